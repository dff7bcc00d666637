// The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.
#include "problems/stepper/nonlinear_system.h"

#include <utility>

#include "problems/stepper/validation.h"

namespace smcbench {

using stepper_detail::Fail;

void NonlinearSignSystem::Validate() const {
  constexpr const char* kOwner = "NonlinearSignSystem";
  if (n < 1) Fail(kOwner, "n must be >= 1, got " + std::to_string(n));
  if (m < 1) Fail(kOwner, "m must be >= 1, got " + std::to_string(m));
  if (!g) Fail(kOwner, "g is not set");
  if (!h) Fail(kOwner, "h is not set");
  if (!h_jacobian) Fail(kOwner, "h_jacobian is not set");
  if (f && !f_jacobian) Fail(kOwner, "f is set but f_jacobian is not (the implicit scheme needs the Jacobian)");
  if (!f && f_jacobian) Fail(kOwner, "f_jacobian is set but f is not");
}

void AffineGainSignSystem::Validate() const {
  constexpr const char* kOwner = "AffineGainSignSystem";
  using stepper_detail::CheckFinite;
  using stepper_detail::CheckShape;
  using stepper_detail::CheckSize;
  if (B.rows() < 1 || B.cols() < 1) Fail(kOwner, "B is empty (it must be n x m with n, m >= 1)");
  const Eigen::Index nn = B.rows(), mm = B.cols();
  CheckFinite(kOwner, "B", B);
  if (E.size() != 0) {
    CheckShape(kOwner, "E", E, nn, nn);
    CheckFinite(kOwner, "E", E);
  }
  if (c.size() != 0) {
    CheckSize(kOwner, "c", c, nn);
    ValidateFinite(kOwner, "c", c);
  }
  if (!A.empty()) {
    if (static_cast<Eigen::Index>(A.size()) != mm) {
      Fail(kOwner, "A holds " + std::to_string(A.size()) + " matrices but B has m = " + std::to_string(mm) +
                       " columns (one A_i per sign component, or none)");
    }
    for (std::size_t i = 0; i < A.size(); ++i) {
      const std::string field = "A[" + std::to_string(i) + "]";
      CheckShape(kOwner, field.c_str(), A[i], nn, nn);
      CheckFinite(kOwner, field.c_str(), A[i]);
    }
  }
  CheckShape(kOwner, "C", C, mm, nn);
  CheckFinite(kOwner, "C", C);
  if (D.size() != 0) {
    CheckSize(kOwner, "D", D, mm);
    ValidateFinite(kOwner, "D", D);
  }
}

NonlinearSignSystem ToNonlinear(const AffineGainSignSystem& system) {
  system.Validate();
  NonlinearSignSystem out;
  const int n = system.n(), m = system.m();
  out.n = n;
  out.m = m;
  out.description = "class (3): g_i(x) = A_i x + B_i, h(x) = C x + D";
  const DenseMatrix E = system.E.size() ? system.E : DenseMatrix::Zero(n, n);
  const Vector c = system.c.size() ? system.c : Vector::Zero(n);
  const bool has_f = system.E.size() != 0 || system.c.size() != 0 || static_cast<bool>(system.forcing);
  if (has_f) {
    out.f = [E, c, forcing = system.forcing](double t, const Vector& x, Eigen::Ref<Vector> f) {
      if (forcing) {
        forcing(t, f);
        f += c;
      } else {
        f = c;
      }
      f.noalias() += E.lazyProduct(x);
    };
    out.f_jacobian = [E](double, const Vector&, Eigen::Ref<DenseMatrix> J) { J = E; };
  }
  const bool has_A = !system.A.empty();
  // A stored side by side, [A_1 ... A_m] (n × nm), so g(x) and ∇g·s are plain loops without allocation.
  // Products are coefficient-based (lazyProduct): the systems are small and Eigen's dynamic gemv dispatch would
  // cost more than the arithmetic.
  DenseMatrix A_all(n, has_A ? static_cast<Eigen::Index>(n) * m : 0);
  for (int i = 0; has_A && i < m; ++i) A_all.middleCols(static_cast<Eigen::Index>(i) * n, n) = system.A[i];
  const DenseMatrix B = system.B;
  out.g = [A_all, B, n, m, has_A](const Vector& x, Eigen::Ref<DenseMatrix> G) {
    G = B;
    if (has_A) {
      for (int i = 0; i < m; ++i) {
        G.col(i).noalias() += A_all.middleCols(static_cast<Eigen::Index>(i) * n, n).lazyProduct(x);
      }
    }
  };
  if (has_A) {
    // (∇g·s)_{kp} = Σ_l ∂g_kl/∂x_p s_l = Σ_l (A_l)_{kp} s_l, `eq:NL-trois2`.
    out.g_jacobian_s = [A_all, n, m](const Vector&, const Vector& s, Eigen::Ref<DenseMatrix> J) {
      J.setZero();
      for (int i = 0; i < m; ++i) J += s[i] * A_all.middleCols(static_cast<Eigen::Index>(i) * n, n);
    };
  }
  const DenseMatrix C = system.C;
  const Vector D = system.D.size() ? system.D : Vector::Zero(m);
  out.h = [C, D](const Vector& x, Eigen::Ref<Vector> y) {
    y = D;
    y.noalias() += C.lazyProduct(x);
  };
  out.h_jacobian = [C](const Vector&, Eigen::Ref<DenseMatrix> H) { H = C; };
  return out;
}

}  // namespace smcbench

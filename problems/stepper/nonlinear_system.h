// The nonlinear sliding-mode systems of the report (Acary–Brogliato 2009): class (4), `eq:quatre`,
//     x' ∈ f(t, x) − g(x) Sgn(h(x)),   g: Rⁿ → R^{n×m},  h: Rⁿ → Rᵐ,
// given by callables with their Jacobians, and class (3), `eq:trois`, g_i(x) = A_i x + B_i, h_i(x) = C_i x + D_i,
// as a special case built from matrices.
// The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "problems/stepper/linear_system.h"
#include "solvers/core/types.h"

namespace smcbench {

// x' ∈ f(t, x) − g(x) Sgn(h(x)) (`eq:quatre`, written `sept-bis-bis` as x' = f − g s, y = h(x), s ∈ Sgn(y)).
// Every callable writes into a pre-sized output and must not allocate if the caller wants an allocation-free
// time loop; none may resize its output. The stepper calls them with the exact sizes below.
struct NonlinearSignSystem {
  using VectorField = std::function<void(double t, const Vector& x, Eigen::Ref<Vector> out)>;
  using MatrixField = std::function<void(double t, const Vector& x, Eigen::Ref<DenseMatrix> out)>;
  using StateMatrix = std::function<void(const Vector& x, Eigen::Ref<DenseMatrix> out)>;
  using StateVector = std::function<void(const Vector& x, Eigen::Ref<Vector> out)>;
  using ContractedJacobian = std::function<void(const Vector& x, const Vector& s, Eigen::Ref<DenseMatrix> out)>;

  int n = 0;  // states
  int m = 0;  // sign components (sliding surfaces)
  VectorField f;             // f(t, x), n; null means f = 0
  MatrixField f_jacobian;    // ∇ₓf(t, x), n×n; required when f is set
  StateMatrix g;             // g(x), n×m
  // ∇ₓg(x) contracted with s (the report's "simple contracted tensor product", `eq:NL00`):
  // out(k, p) = Σ_l ∂g_kl/∂x_p s_l, n×n. Null means g is constant (∇g = 0).
  ContractedJacobian g_jacobian_s;
  StateVector h;             // h(x), m
  StateMatrix h_jacobian;    // ∇ₓh(x), m×n
  std::string description;

  // n ≥ 1, m ≥ 1, g, h, h_jacobian set, f_jacobian set iff f is. InvalidInputError naming the field.
  void Validate() const;
};

// Class (3), `eq:trois`: x' ∈ E x + c + c(t) − Σ_i (A_i x + B_i) sgn(C_i x + D_i), i = 1..m, i.e. class (4) with
// f(t, x) = E x + c + c(t), g(x) = [A_1 x + B_1, ..., A_m x + B_m] (`eq:NL-trois`), ∇g·s = Σ_i s_i A_i
// (`eq:NL-trois2`), h(x) = C x + D, ∇h = C (`eq:NL-trois1`). With every A_i = 0 it is class (2), `eq:deux`.
struct AffineGainSignSystem {
  DenseMatrix E;               // n×n; empty means 0 (n is then taken from B)
  Vector c;                    // n; empty means 0
  Forcing forcing;             // c(t), null means 0
  std::vector<DenseMatrix> A;  // m matrices n×n; empty vector means every A_i = 0
  DenseMatrix B;               // n×m, column i is B_i
  DenseMatrix C;               // m×n, row i is C_i
  Vector D;                    // m; empty means 0

  int n() const { return static_cast<int>(B.rows()); }
  int m() const { return static_cast<int>(B.cols()); }
  // Sizes and finiteness; InvalidInputError "AffineGainSignSystem: A[1] is 2x3 but must be 2x2".
  void Validate() const;
};

// Validates and converts; the callables own copies of the matrices.
NonlinearSignSystem ToNonlinear(const AffineGainSignSystem& system);

}  // namespace smcbench

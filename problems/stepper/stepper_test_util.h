// Test helpers for the stepper: a reference box-MLCP solver that does not depend on any backend in progress, and
// the linear scenes of docs/scenes.md as systems.
// The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.
#pragma once

#include <cmath>
#include <limits>

#include "problems/stepper/discretization.h"
#include "solvers/core/solver.h"

namespace smcbench::stepper_test {

// Exact small box-MLCP solver by enumeration of the 3^m active sets (free / at l / at u), m ≤ 4, with
// fixed-capacity matrices so it never allocates. Among the index sets whose solution is feasible it returns the
// one with the smallest natural residual. For a 1×1 problem with a free index it returns −q/M, a single
// division: the Lemma (yahoo) test relies on s_{k+1} = x_k/h being computed exactly that way.
class ReferenceSolver final : public Solver {
 public:
  const SolverInfo& info() const override {
    static const SolverInfo kInfo{"reference", "test-only enumeration of the 3^m active sets", "", true, false,
                                  false, true, false, 4};
    return kInfo;
  }

 protected:
  void DoSolve(const BoxMLCP& problem, const SolverOptions&, SolveResult* result) override {
    using Mat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 4, 4>;
    using Vec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 4, 1>;
    const int m = problem.size();
    if (m > 4 || problem.is_sparse()) {
      result->status = SolveStatus::kSizeLimit;
      result->message = "reference solver: m <= 4 dense only";
      return;
    }
    const DenseMatrix& M = problem.dense_matrix();
    const Vector& q = problem.q();
    const Vector& l = problem.l();
    const Vector& u = problem.u();
    int codes = 1;
    for (int i = 0; i < m; ++i) codes *= 3;
    double best = std::numeric_limits<double>::infinity();
    Vec z(m), best_z(m), w(m);
    int free_index[4];
    for (int code = 0; code < codes; ++code) {
      int c = code, nf = 0;
      bool bounded_ok = true;
      for (int i = 0; i < m; ++i, c /= 3) {
        const int d = c % 3;
        if (d == 0) {
          free_index[nf++] = i;
        } else {
          z[i] = d == 1 ? l[i] : u[i];
          if (!std::isfinite(z[i])) bounded_ok = false;
        }
      }
      if (!bounded_ok) continue;
      if (nf > 0) {
        Mat A(nf, nf);
        Vec b(nf);
        for (int a = 0; a < nf; ++a) {
          b[a] = -q[free_index[a]];
          for (int i = 0, cc = code; i < m; ++i, cc /= 3) {
            if (cc % 3 != 0) b[a] -= M(free_index[a], i) * z[i];
          }
          for (int e = 0; e < nf; ++e) A(a, e) = M(free_index[a], free_index[e]);
        }
        Eigen::FullPivLU<Mat> lu(A);
        if (!lu.isInvertible()) continue;
        const Vec zf = lu.solve(b);
        for (int a = 0; a < nf; ++a) z[free_index[a]] = zf[a];
      }
      double r = 0.0;
      for (int i = 0; i < m; ++i) {
        w[i] = q[i];
        for (int j = 0; j < m; ++j) w[i] += M(i, j) * z[j];
      }
      for (int i = 0; i < m; ++i) {
        const double projected = std::min(std::max(z[i] - w[i], l[i]), u[i]);
        r = std::max(r, std::abs(z[i] - projected));
      }
      if (r < best) {
        best = r;
        best_z = z;
      }
    }
    if (!std::isfinite(best)) {
      result->status = SolveStatus::kSingular;
      result->message = "reference solver: every active set is singular";
      return;
    }
    for (int i = 0; i < m; ++i) result->z[i] = best_z[i];
    result->iterations = codes;
    result->status = SolveStatus::kSolved;
  }
};

inline DenseMatrix Mat(std::initializer_list<std::initializer_list<double>> rows) {
  const auto r = static_cast<Eigen::Index>(rows.size());
  const auto c = static_cast<Eigen::Index>(rows.begin()->size());
  DenseMatrix A(r, c);
  Eigen::Index i = 0;
  for (const auto& row : rows) {
    Eigen::Index j = 0;
    for (double v : row) A(i, j++) = v;
    ++i;
  }
  return A;
}

inline Vector Vec(std::initializer_list<double> values) {
  Vector v(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (double x : values) v[i++] = x;
  return v;
}

// S1 `sign`: x' ∈ −sgn(x).
inline LinearSignSystem SignScene() {
  LinearSignSystem s;
  s.E = Mat({{0.0}});
  s.B = Mat({{1.0}});
  s.C = Mat({{1.0}});
  return s;
}

// S2 `galias-yu-2007`: x' = [[0,1],[0,−c1]] x − [0; α] sgn([c1 1] x), c1 = α = 1.
inline LinearSignSystem GaliasYuScene() {
  LinearSignSystem s;
  s.E = Mat({{0.0, 1.0}, {0.0, -1.0}});
  s.B = Mat({{0.0}, {1.0}});
  s.C = Mat({{1.0, 1.0}});
  return s;
}

// S3 `multi-surface`: f = 0, B = C = [[1, 2], [2, −1]].
inline LinearSignSystem MultiSurfaceScene() {
  LinearSignSystem s;
  s.E = DenseMatrix::Zero(2, 2);
  s.B = Mat({{1.0, 2.0}, {2.0, -1.0}});
  s.C = s.B;
  return s;
}

// S4 `filippov`: f = 0, B = [[1, −2], [2, 1]], C = I.
inline LinearSignSystem FilippovScene() {
  LinearSignSystem s;
  s.E = DenseMatrix::Zero(2, 2);
  s.B = Mat({{1.0, -2.0}, {2.0, 1.0}});
  s.C = DenseMatrix::Identity(2, 2);
  return s;
}

// S5 `zoh-siso`: F = [[0, 1], [−a1, −a2]], a1 = −2, a2 = 2, G = [0; 1], C = [1 1], α = 1.
inline ZohSmcSystem ZohSisoScene() {
  ZohSmcSystem s;
  s.F = Mat({{0.0, 1.0}, {2.0, -2.0}});
  s.G = Mat({{0.0}, {1.0}});
  s.C = Mat({{1.0, 1.0}});
  return s;
}

// S6 `zoh-mimo`.
inline ZohSmcSystem ZohMimoScene() {
  ZohSmcSystem s;
  s.F = Mat({{0.0, 0.0, 1.0}, {1.0, 1.0, 1.0}, {-1.0, -3.0, 1.0}});
  s.G = Mat({{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}});
  s.C = Mat({{1.0, 0.0, 1.0}, {0.0, 1.0, 1.0}});
  return s;
}

// S7 `lyapunov`: x' = −x − u + α sin t, u ∈ sgn(x), α = 0.1.
inline LinearSignSystem LyapunovScene(double alpha = 0.1) {
  LinearSignSystem s;
  s.E = Mat({{-1.0}});
  s.B = Mat({{1.0}});
  s.C = Mat({{1.0}});
  s.forcing = [alpha](double t, Eigen::Ref<Vector> g) { g[0] = alpha * std::sin(t); };
  return s;
}

// S8 `observer`: state (x, e, x_s, x_s'), parasitic second-order actuator with time constant τ, gain k.
inline LinearSignSystem ObserverScene(double tau, double k = 1.0) {
  LinearSignSystem s;
  const double it2 = 1.0 / (tau * tau);
  s.E = Mat({{0, 0, 0, 0}, {k, -k, -k, 0}, {0, 0, 0, 1}, {it2, 0, -it2, -2.0 / tau}});
  s.B = Mat({{1.0}, {0.0}, {0.0}, {0.0}});
  s.C = Mat({{1.0, -1.0, 0.0, 0.0}});
  return s;
}

}  // namespace smcbench::stepper_test

// A nonlinear box MCP with a planted unique solution and every kind of row, for the tests of the Siconos MCP
// rewriting and adapters.
#pragma once

#include <random>

#include "solvers/core/problem.h"

namespace smcbench {
namespace test_support {

// F(z) = A z + 0.3 z³ + b on rows of every kind (fixed, free, lower, upper, box: at a bound or inside) with A's
// symmetric part positive definite, so the solution z* (planted) is unique.
class PlantedMcp final : public MCP {
 public:
  PlantedMcp(const Vector& l, const Vector& u, const Vector& z_star, const Vector& F_star, bool sparse)
      : MCP(l, u, "planted"), sparse_(sparse) {
    const int n = static_cast<int>(l.size());
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> any(-1.0, 1.0);
    DenseMatrix B(n, n), C(n, n);
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        B(i, j) = any(rng);
        C(i, j) = any(rng);
      }
    }
    A_ = B * B.transpose() / n + DenseMatrix::Identity(n, n) + 0.5 * (C - C.transpose());
    b_ = F_star - A_ * z_star - 0.3 * z_star.array().cube().matrix();
  }
  void Evaluate(const Vector& z, Vector* F) const override {
    *F = A_ * z + 0.3 * z.array().cube().matrix() + b_;
  }
  JacobianKind jacobian_kind() const override { return sparse_ ? JacobianKind::kSparse : JacobianKind::kDense; }
  void JacobianDense(const Vector& z, DenseMatrix* J) const override {
    *J = A_;
    J->diagonal().array() += 0.9 * z.array().square();
  }
  void JacobianSparse(const Vector& z, SparseMatrix* J) const override {
    DenseMatrix D;
    JacobianDense(z, &D);
    *J = D.sparseView();
  }

 private:
  bool sparse_;
  DenseMatrix A_;
  Vector b_;
};

struct Planted {
  Vector l, u, z_star, F_star;
};

// Rows: fixed, free, lower at 0, lower inside, upper at u, upper inside, box at l, box at u, box inside.
inline Planted EveryRowKind() {
  Planted p;
  p.l.resize(9);
  p.u.resize(9);
  p.z_star.resize(9);
  p.F_star.resize(9);
  p.l << 0.5, -kInf, 0, 0, -kInf, -kInf, -1, -1, -1;
  p.u << 0.5, kInf, kInf, kInf, 2, 2, 1, 1, 1;
  p.z_star << 0.5, 0.7, 0, 1.5, 2, -0.5, -1, 1, 0.3;
  p.F_star << 0.8, 0, 1.2, 0, -0.7, 0, 0.4, -2.0, 0;
  return p;
}

}  // namespace test_support
}  // namespace smcbench

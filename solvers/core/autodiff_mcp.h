// An MCP whose Jacobian is F's own derivative by forward-mode automatic differentiation (Eigen's unsupported
// AutoDiff module, libeigen3-dev): the user writes F once, as a template on the scalar type, and no J by hand.
//   auto mcp = MakeAutoDiffMcp(l, u, [](const auto* z, auto* F) {
//     F[0] = z[0] * z[0] + z[1] - 2.0;   // every F_i written, with + − × ÷ and the std/Eigen functions
//     F[1] = exp(z[0]) - z[1];           // (sqrt, exp, log, sin, cos, pow, abs, ...) found by ADL
//   });
// The Jacobian is exact to rounding (no step to choose, unlike central differences: solvers/core/mcp_derivatives.h).
// A derivative at a kink (|z| at 0) is the one-sided derivative Eigen's AutoDiff gives. Each J call allocates (the
// derivative vectors are dynamic unless N, the size, is given at compile time): for users' problems, not hot paths.
#pragma once

#include <Eigen/Core>  // before AutoDiff, which uses Eigen::internal without including it
#include <unsupported/Eigen/AutoDiff>

#include <string>
#include <utility>

#include "solvers/core/problem.h"

namespace smcbench {

// Function: callable as f(const T* z, T* F) for T = double and T = Eigen::AutoDiffScalar<...>, writing F[0..n).
// N: the size if known at compile time (fixed-size derivatives, no allocation inside the arithmetic), else Dynamic.
template <class Function, int N = Eigen::Dynamic>
class AutoDiffMCP final : public MCP {
 public:
  using Derivatives = Eigen::Matrix<double, N, 1>;
  using Scalar = Eigen::AutoDiffScalar<Derivatives>;

  AutoDiffMCP(Vector l, Vector u, Function f, std::string name = "autodiff")
      : MCP(std::move(l), std::move(u), std::move(name)), f_(std::move(f)) {
    if (N != Eigen::Dynamic && size() != N) {
      throw InvalidInputError("AutoDiffMCP: the template size N = " + std::to_string(N) + " but l has " +
                              std::to_string(size()) + " entries");
    }
  }

  void Evaluate(const Vector& z, Vector* F) const override { f_(z.data(), F->data()); }

  void JacobianDense(const Vector& z, DenseMatrix* J) const override {
    const int n = size();
    Eigen::Matrix<Scalar, Eigen::Dynamic, 1> x(n), F(n);
    for (int j = 0; j < n; ++j) x[j] = Scalar(z[j], n, j);  // z_j with the derivative e_j
    // An F_i set to a constant keeps an empty derivative vector: it reads as a zero row.
    for (int i = 0; i < n; ++i) F[i] = Scalar(0.0);
    f_(x.data(), F.data());
    if (J->rows() != n || J->cols() != n) J->resize(n, n);
    for (int i = 0; i < n; ++i) {
      const auto& d = F[i].derivatives();
      if (d.size() == n) {
        J->row(i) = d.transpose();
      } else {
        J->row(i).setZero();
      }
    }
  }

 private:
  Function f_;
};

// The AutoDiffMCP of f over the box [l, u], its class deduced from the lambda.
template <int N = Eigen::Dynamic, class Function>
AutoDiffMCP<Function, N> MakeAutoDiffMcp(Vector l, Vector u, Function f, std::string name = "autodiff") {
  return AutoDiffMCP<Function, N>(std::move(l), std::move(u), std::move(f), std::move(name));
}

}  // namespace smcbench

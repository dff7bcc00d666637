// Derivatives of an MCP's F without a hand-written Jacobian, and a check of a hand-written one: central differences
// with a step scaled per component, and a derivative test (in the spirit of Ipopt's derivative_test) that compares
// J(z) with them at one point and names the worst entry. Automatic differentiation of a templated F is in
// solvers/core/autodiff_mcp.h. Not for hot paths: both allocate and call F 2n times.
#pragma once

#include <string>

#include "solvers/core/problem.h"

namespace smcbench {

// ∂F/∂z at z by central differences, column j from F(z ± h_j e_j), h_j = ε^{1/3} max(1, |z_j|) (ε = 2.2e-16; the
// step that balances the O(h²) truncation against the O(ε/h) rounding). Where z_j ± h_j would leave [l_j, u_j]
// the difference is one-sided inward (forward near a lower bound, backward near an upper one, step ε^{1/2}
// max(1, |z_j|)) if that fits in the box, so F is evaluated in the box only (many F are undefined outside it).
// J is resized to n × n.
void CentralDifferenceJacobian(const MCP& problem, const Vector& z, DenseMatrix* J);

struct JacobianCheckOptions {
  // An entry is wrong when |J_ij − D_ij| > tolerance · max(1, |D_ij|), D the central differences (Ipopt's
  // derivative_test_tol is 1e-4 with forward differences; central ones are more accurate, the default is the same).
  double tolerance = 1e-4;
};

struct JacobianCheck {
  bool ok = true;                 // every entry within the tolerance (and every value finite)
  double max_error = 0.0;         // max_ij |J_ij − D_ij| / max(1, |D_ij|)
  int row = -1, col = -1;         // the worst entry (−1: J and D agree exactly)
  double analytic = 0.0;          // J at the worst entry
  double finite_difference = 0.0; // D at the worst entry
  int wrong_entries = 0;          // entries beyond the tolerance
  // "" when ok; otherwise one sentence: "derivative check at the start: J[1, 0] = 3 but central differences give
  // 2 (relative error 0.5 > 1e-4; 2 of 4 entries differ)".
  std::string message;
};

// Compares the problem's Jacobian at z (the kind it advertises: dense, or sparse made dense) with
// CentralDifferenceJacobian. InvalidInputError when z is not of size n or not finite, or the tolerance is not > 0.
JacobianCheck CheckMcpJacobian(const MCP& problem, const Vector& z, const JacobianCheckOptions& options = {});

}  // namespace smcbench

// A box MCP rewritten in the shape of Siconos' MixedComplementarityProblem: n1 equations G(x) = 0 first, then n2
// rows 0 ≤ x ⟂ H(x) ≥ 0, no general bounds. Exact in both directions; no Siconos header needed.
//
// The nonlinear counterpart of standard_form.h's mixed form. Each row i of the box MCP with F = F(z):
//   fixed  (l = u):            eliminated, z_i = l_i;
//   free   (l = −∞, u = +∞):   equation variable, z_i = x_a, G_a = F_i(z) = 0;
//   lower  (l finite, u = ∞):  z_i = l_i + x_a, 0 ≤ x_a ⟂ F_i(z) ≥ 0;
//   upper  (l = −∞, u finite): z_i = u_i − x_a, 0 ≤ x_a ⟂ −F_i(z) ≥ 0;
//   box    (both finite):      z_i = l_i + x_a and a multiplier y_k ≥ 0 of the upper bound:
//                              0 ≤ x_a ⟂ F_i(z) + y_k ≥ 0,  0 ≤ y_k ⟂ (u_i − l_i) − x_a ≥ 0.
// So two finite bounds are exact too (the relay → LCP doubling): at a solution y_k = max(0, −F_i(z)), and
// z_i = u_i exactly when y_k > 0 or F_i = 0 at the bound. With z = z̄ + S x (z̄ = l, u or 0, S = diag(±1)):
//   F_std(x, y) = [S F(z̄ + S x) + E y;  (u − l)_K − Eᵀ x],   ∇F_std = [[S J S, E], [−Eᵀ, 0]],
// over the variables (free rows, then lower/upper/box rows in their original order, then one multiplier per box
// row). As an MCP (free bounds on the n1 equation variables, [0, ∞) on the rest) it is what Siconos receives, and
// what the tests solve with our own backends to check the correspondence.
#pragma once

#include <string>
#include <vector>

#include "solvers/core/problem.h"

namespace smcbench {

class McpStandardForm final : public MCP {
 public:
  // Keeps a reference to original, which must outlive this form.
  explicit McpStandardForm(const MCP& original);

  int num_equations() const { return num_equations_; }  // n1: the free rows, first
  int num_complementarity() const { return size() - num_equations_; }  // n2

  // x (and the box multipliers y) for a point z of the original: x = S(z − z̄), y = max(0, −F(z)) on box rows.
  void FromOriginal(const Vector& z, Vector* x) const;
  // z of the original for x; fixed rows get l. Nothing is clipped.
  void ToOriginal(const Vector& x, Vector* z) const;

  // F_std and its (dense) Jacobian. A sparse original Jacobian is densified. A wrong-size original Jacobian fills
  // J with NaN and records the reason (jacobian_error).
  void Evaluate(const Vector& x, Vector* F) const override;
  void JacobianDense(const Vector& x, DenseMatrix* J) const override;
  const std::string& jacobian_error() const { return jacobian_error_; }

 private:
  struct Layout;
  static Layout MakeLayout(const MCP& original);
  McpStandardForm(const MCP& original, const Layout& layout);

  const MCP& original_;
  int num_equations_ = 0;
  std::vector<int> row_of_;         // primary variable → original row
  std::vector<int> var_of_;         // original row → primary variable, −1 for fixed rows
  std::vector<int> multiplier_of_;  // original row → multiplier variable, −1 unless a box row
  std::vector<double> sign_;        // per primary variable: +1, or −1 for upper rows
  Vector base_;                     // z̄ per original row
  int primaries_ = 0;
  mutable Vector z_, F_;            // scratch: the original's point and F
  mutable DenseMatrix J_;
  mutable SparseMatrix Js_;
  mutable std::string jacobian_error_;
};

}  // namespace smcbench

// The box-MLCP rewritten in the two shapes Siconos' solvers take: a box problem without fixed rows (Siconos'
// RelayProblem: lb ≤ z ≤ ub, both finite) and a standard MLCP with the equality rows first (Siconos'
// MixedLinearComplementarityProblem: w₁ = 0 for free variables, 0 ≤ x ⊥ w₂ ≥ 0 for the rest), which is an LCP
// when there are no free rows. Exact in both directions; no Siconos header needed.
//
// Mixed form (the reduction of lemke_solver.h without its Schur-complement step). Each row i of the box-MLCP
//   fixed  (l = u):            eliminated, z_i = l_i;
//   free   (l = −∞, u = +∞):   equality variable, z_i = x_i, (Mz + q)_i = 0;
//   lower  (l finite, u = ∞):  z_i = l_i + x_i, x_i ≥ 0 ⊥ (Mz + q)_i ≥ 0;
//   upper  (l = −∞, u finite): z_i = u_i − x_i, x_i ≥ 0 ⊥ −(Mz + q)_i ≥ 0;
//   box    (both finite):      z_i = l_i + x_i and a multiplier y_k ≥ 0 of the upper bound (the relay → LCP
//                              doubling): x_i ⊥ (Mz + q)_i + y_k ≥ 0,  y_k ⊥ (u_i − l_i) − x_i ≥ 0.
// With z = z̄ + S x (z̄ = l, u or 0 as above, S = diag(±1)) the standard problem is
//   M_std = [[S M S, E], [−Eᵀ, 0]],  q_std = [S (q + M z̄); u_K − l_K]
// over the variables (free rows, then lower/upper/box rows in their original order, then one multiplier per box
// row; E has one unit column per box row). Solutions correspond one to one.
//
// Box form: the non-fixed rows only, z_i = x_i, with q + M z̄ carrying the fixed rows' contribution.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "solvers/core/problem.h"

namespace smcbench {

class StandardForm {
 public:
  enum class Kind { kBox, kMixed };
  enum class RowKind : std::uint8_t { kFixed, kFree, kLower, kUpper, kBox };

  // Counts by row kind, without building anything (O(n)).
  struct RowCounts {
    int fixed = 0, free = 0, lower = 0, upper = 0, box = 0;
    int unbounded() const { return free + lower + upper; }  // rows with an infinite bound
  };
  static RowCounts Count(const Vector& l, const Vector& u);

  // Rebuilds the rewritten problem from a dense problem. Kind::kBox needs every non-fixed row finite on both
  // sides (else std::logic_error: callers check Count() first). Reuses storage when the sizes repeat.
  void Build(const BoxMLCP& problem, Kind kind);

  Kind kind() const { return kind_; }
  int size() const { return static_cast<int>(q_.size()); }  // unknowns of the rewritten problem
  int num_equalities() const { return num_equalities_; }    // kMixed: free rows (first in the ordering)
  int num_complementarity() const { return size() - num_equalities_; }
  const DenseMatrix& M() const { return M_; }  // column-major, as Siconos' dense NumericsMatrix
  const Vector& q() const { return q_; }
  const Vector& lower() const { return lower_; }  // kBox only
  const Vector& upper() const { return upper_; }  // kBox only

  // x of the rewritten problem for a box-MLCP point z (warm starts): x = S(z − z̄), box multipliers y = (Mz + q)⁻.
  void FromBox(const BoxMLCP& problem, const Vector& z, Vector* x);
  // z of the box-MLCP for x; fixed rows get l. Nothing is clipped: a point outside [l, u] stays outside.
  void ToBox(const BoxMLCP& problem, const Vector& x, Vector* z) const;

 private:
  Kind kind_ = Kind::kMixed;
  int num_equalities_ = 0;
  std::vector<int> row_of_;       // rewritten variable (primary) → box-MLCP row
  std::vector<int> var_of_;       // box-MLCP row → primary variable, −1 for fixed rows
  std::vector<int> multiplier_of_;  // box-MLCP row → multiplier variable, −1 unless a box row in kMixed
  std::vector<double> sign_;      // per primary variable: +1, or −1 for upper rows
  Vector base_;                   // z̄ per box-MLCP row
  DenseMatrix M_;
  Vector q_, lower_, upper_;
  Vector w_;                      // scratch for FromBox
};

std::string_view ToString(StandardForm::RowKind kind);

}  // namespace smcbench

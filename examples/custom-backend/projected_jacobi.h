// An out-of-tree smcbench backend: projected (damped) Jacobi for the box-constrained MLCP, derived from the public
// smcbench::Solver. Everything smcbench's own backends get from the base class (option checks, warm starts, row
// equilibration, timing, the exact polish, the merit function and the rule for "solved") it gets too; it implements
// only its iteration in DoSolve.
//
// One iteration, with every row updated from the same old z (Jacobi, unlike PSOR's Gauss–Seidel):
//     z ← Π_[l,u]( z − ω D⁻¹ (M z + q) ),   D = diag(M).
// For symmetric positive definite M this is projected gradient descent on ½zᵀMz + qᵀz in the metric D, which
// converges for 0 < ω < 2/λ_max(D⁻¹M); for strictly diagonally dominant M with positive diagonal it is a contraction
// in the ∞-norm for 0 < ω ≤ 1. The automatic ω (omega = 0, the default) is 1/‖D⁻¹M‖∞, which is ≤ 1 and below
// 2/λ_max in both cases. Other matrices may make it cycle or diverge: that is reported, never claimed as solved.
//
// Stopping rule: the natural residual ‖z − Π(z − (Mz + q))‖∞ ≤ tol·(1 + min(‖z‖∞, ‖q‖∞)), the base's verdict on
// the (row-equilibrated) problem it is given. Statuses when it does not get there: kIterationLimit (budget, default
// 100000 iterations), kStalled (the best residual did not halve within stall_iterations), kDiverged (‖z‖∞ beyond
// divergence_threshold·(1 + ‖z⁰‖∞ + ‖q‖∞/min M_ii)), kNumericalFailure (NaN/Inf), kTimeLimit, and kNotApplicable
// when a row with l_i < u_i has M_ii ≤ 0.
#pragma once

#include <string>

#include <smcbench/smcbench.h>

namespace example {

struct ProjectedJacobiOptions {
  double omega = 0.0;                  // relaxation ω in (0, 2); 0 = automatic, 1/‖D⁻¹M‖∞
  int stall_iterations = 5000;         // stalled if the best residual does not halve within this many (0: off)
  double divergence_threshold = 1e10;  // > 1

  // True if every field is usable; otherwise *why names the field and the accepted range.
  bool IsValid(std::string* why) const;
};

class ProjectedJacobiSolver final : public smcbench::Solver {
 public:
  static constexpr const char* kName = "pjacobi";
  static constexpr int kDefaultMaxIterations = 100000;

  const smcbench::SolverInfo& info() const override;

 protected:
  void DoSolve(const smcbench::BoxMLCP& problem, const smcbench::SolverOptions& options,
               smcbench::SolveResult* result) override;
  void BindOptions(smcbench::OptionBinder* binder) override;
  bool ValidateBackendOptions(std::string* why) const override;

 private:
  ProjectedJacobiOptions options_;
  smcbench::Vector step_;  // ω / M_ii per row (0 on fixed rows l_i = u_i); kept to avoid allocating per solve
  smcbench::Vector w_;     // M z + q
};

}  // namespace example

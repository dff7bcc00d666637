// Projected successive over-relaxation (PSOR) for the box-constrained MLCP: projected Gauss–Seidel sweeps with
// relaxation ω, Cottle–Pang–Stone, "The Linear Complementarity Problem" (1992), §5.2, extended from z ≥ 0 to the
// box [l,u] (the projection is the only change).
//
// One sweep visits the rows in order i = 0, …, n−1 (PsorOptions::sweep: or n−1, …, 0, or both in turn) and sets
//     z_i ← Π_[l_i,u_i]( z_i − ω (M z + q)_i / M_ii ),
// always using the newest z (Gauss–Seidel). ω = 1 is projected Gauss–Seidel. With ω = 1 the first forward sweep
// from any start solves a lower triangular M with positive diagonal exactly (it is the forward substitution), the
// first backward sweep an upper triangular one (the back substitution); the symmetric sweep (forward, then
// backward: projected SSOR) does not depend on the row order on symmetric M.
//
// Convergence (what the theory promises, and what it does not):
//  * M symmetric positive definite, 0 < ω < 2: PSOR is a relaxed coordinate descent on the strictly convex QP
//    ½zᵀMz + qᵀz over the box and converges to its unique solution (CPS §5.2; for symmetric positive
//    semidefinite M see Luo & Tseng, JOTA 1992).
//  * M an H-matrix with positive diagonal (e.g. strictly diagonally dominant): the projected iteration is a
//    contraction in a weighted ∞-norm for 0 < ω ≤ 1 (and for ω slightly above 1, depending on ρ(|D⁻¹(M−D)|)).
//  * Anything else (nonsymmetric, not dominant) may cycle or diverge. That is reported as kStalled / kDiverged
//    / kIterationLimit with the residual reached, never as a solution.
//
// Implementation choices (why):
//  * w = M z + q is kept up to date incrementally: after a change δ of z_i, w += δ·M(:,i). This is the natural
//    access pattern of both column-major dense M and CSC sparse M (no row-major copy, no cache of the problem,
//    no per-problem setup beyond an O(nnz) scan for the diagonal), a row whose z_i does not move costs O(1)
//    instead of a row dot product, and the merit function ‖z − Π(z − w)‖∞ is then an O(n) pass, so it can be
//    evaluated after every sweep instead of costing an extra O(nnz) product. Rounding drift in w is bounded by
//    recomputing w exactly every `refresh_interval` sweeps, and "solved" is only declared after a check against
//    an exactly recomputed w.
//  * Dense problems with n ≤ 4 run a fixed-size kernel (fully unrolled, no dynamic-size overhead).
//  * Workspace (1/M_ii steps) is a member resized only when n changes: repeated solves do not allocate.
//
// Safeguards: a diagonal entry M_ii ≤ min_diagonal·max|M_jk| (zero, tiny or negative) on a row with l_i < u_i
// makes the method inapplicable (kNotApplicable, naming the index) before any sweep; a non-finite iterate or
// ‖z‖∞ beyond divergence_threshold·(1 + ‖z⁰‖∞ + ‖q‖∞ / min_i M_ii) is kDiverged; a sweep that changes nothing
// although the residual is above tolerance (an exact floating-point fixed point), or no halving of the best
// residual within stall_sweeps sweeps, is kStalled; the sweep budget (default 10000) is kIterationLimit.
// result->iterations counts sweeps.
//
// Subspace step (the idea of PGS with subspace minimization: Morales, Nocedal & Smelyanskiy, "An algorithm for the
// fast solution of symmetric linear complementarity problems", Numer. Math. 111, 2008): projected sweeps identify
// the active set long before they converge on ill-conditioned M (small h, cond 1e6: thousands of sweeps). When the
// bound pattern has been stable and the remaining sweeps, predicted from the residual's rate, would cost more than
// one LU of the free block, the free rows are solved exactly on that pattern (the base's polish kernel,
// polish.h). The answer is accepted by the same stopping test as a sweep's, so it changes the cost, never the
// verdict; a pattern that is not the solution's only costs that one solve. Details "subspace_tries" and
// "subspace_steps" (accepted).
//
// Stopping test: the base's verdict on the problem PSOR is given (row-equilibrated by Solver's base): its natural
// residual, in units of z, at most tol·(1 + ‖z‖∞) and tol·(1 + ‖q‖∞). "Converged" means right in units of z,
// whatever the size of M; scaled residuals are reported in the messages.
#pragma once

#include <memory>
#include <string>

#include "solvers/core/backend_options.h"
#include "solvers/core/solver.h"

namespace smcbench {

struct PsorOptions {
  // Values of sweep (`--set psor.sweep=NAME`): the order in which one sweep visits the rows.
  enum SweepOrder : int {
    // "forward": i = 0, …, n−1 (CPS §5.2). One sweep is the forward substitution on lower triangular M.
    kForwardSweep = 0,
    // "backward": i = n−1, …, 0. One sweep is the back substitution on upper triangular M.
    kBackwardSweep = 1,
    // "symmetric": forward, then backward, counted as one sweep (projected SSOR): on symmetric M neither row
    // order is favoured.
    kSymmetricSweep = 2,
  };

  // Relaxation factor ω ∈ (0, 2). 1 is projected Gauss–Seidel.
  double omega = 1.0;
  SweepOrder sweep = kForwardSweep;
  // Sweeps between evaluations of the merit function (≥ 1). It costs O(n) thanks to the incremental w.
  int check_interval = 1;
  // Sweeps between exact recomputations of w = M z + q, which bound the drift of the incremental update (≥ 1).
  int refresh_interval = 64;
  // Diverged once ‖z‖∞ > divergence_threshold · (1 + ‖z⁰‖∞ + ‖q‖∞ / min_i M_ii) (> 1).
  double divergence_threshold = 1e10;
  // Stalled if the best residual has not dropped below stall_factor × its value stall_sweeps sweeps ago.
  // stall_sweeps = 0 disables this test (the iteration budget still applies).
  int stall_sweeps = 1000;
  double stall_factor = 0.5;  // in (0, 1)
  // A row with l_i < u_i needs M_ii > min_diagonal · max|M_jk| (relative, in [0, 1)).
  double min_diagonal = 1e-12;
  // The subspace step (dense 5 ≤ n ≤ 512): once the active set the natural map reads off the sweeps (which rows
  // sit at l, at u, inside) has not changed for subspace_sweeps merit checks, and the sweeps still needed at the observed rate would cost more than
  // one factorization, PSOR solves that pattern's reduced system exactly and keeps the answer only if it passes the
  // stopping test; a failed try doubles the wait. 0 disables it (plain PSOR).
  int subspace_sweeps = 3;

  // True if every field is usable; otherwise *why names the field and the accepted range.
  bool IsValid(std::string* why) const;
};

class PsorSolver final : public BackendWithOptions<PsorOptions> {
 public:
  // Default iteration budget (sweeps) when SolverOptions::max_iterations ≤ 0.
  static constexpr int kDefaultMaxSweeps = 10000;

  PsorSolver();
  explicit PsorSolver(const PsorOptions& options);
  ~PsorSolver() override;
  PsorSolver(const PsorSolver&) = delete;
  PsorSolver& operator=(const PsorSolver&) = delete;

  const SolverInfo& info() const override;

 protected:
  void DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) override;
  void BindOptions(OptionBinder* binder) override;
  bool ValidateBackendOptions(std::string* why) const override;

 private:
  // The backward and symmetric sweeps, on the general dense and the sparse kernel only (no fixed-size one: their
  // use is larger triangular and symmetric M), out of line: the default forward path compiles as without them.
  [[gnu::noinline]] void IterateBackwardOrSymmetric(const BoxMLCP& problem, const SolverOptions& options,
                                                    SolveResult* result);
  template <PsorOptions::SweepOrder Order, typename Columns>
  void Iterate(const Columns& columns, const BoxMLCP& problem, const SolverOptions& options, SolveResult* result);
  template <PsorOptions::SweepOrder Order>
  void IterateDense(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result);

  Vector step_;  // ω / M_ii per row (0 for fixed rows l_i = u_i); sized once per n
  Vector w_;     // M z + q, updated incrementally
  struct SubspaceWorkspace;  // the subspace step's storage (dense n > 4 only), made on first use, sized once per n
  std::unique_ptr<SubspaceWorkspace> subspace_;
};

}  // namespace smcbench

// Block principal pivoting for box-MLCPs (`bpp`): the active-set method of Júdice & Pires (A block principal pivoting
// algorithm for large-scale strictly monotone linear complementarity problems, Comput. Oper. Res. 21, 1994) applied
// directly to the box z ∈ [l, u] on its n variables, as Kostreva's block pivoting (Block pivot methods for solving
// the complementarity problem, Linear Algebra Appl. 21, 1978) generalizes to bounded variables: every row is free,
// at l or at u, so there is no doubling of a box row into an x and a multiplier y (Lemke's 2n reduction).
//
// One iteration solves the current active set exactly with the shared kernel (active_set.h: bound rows at their
// bound, z_F = −M_FF⁻¹(q_F + M_FB z_B) by LU with partial pivoting) and computes w = M z + q. A row is infeasible
// when it is free with z_i outside [l_i, u_i] (it moves to the bound it crossed), at l with w_i < 0 or at u with
// w_i > 0 (it becomes free). A solution is a set with no infeasible row. The pivot rule is Júdice–Pires':
//   - while the number of infeasible rows falls below its best so far, every infeasible row changes (block pivot);
//   - otherwise up to block_steps_without_progress further block pivots are allowed (p̄ = 3, as Júdice–Pires and
//     Kim & Park, SIAM J. Sci. Comput. 33, 2011, use);
//   - then only the infeasible row of least index changes (Murty's Bard-type scheme, Opsearch 11, 1974), until the
//     count falls below its best again. For an LCP with a P-matrix the least-index single pivots cannot cycle and
//     end at the solution (Murty 1974; Murty, Linear Complementarity, 1988, §4.2); that is what makes the method
//     finite there. For rows with two finite bounds we know of no such proof: the method then relies on the
//     iteration budget, and SolverInfo::exact is false.
// Safeguards: a singular (pivot ≤ pivot_tolerance, in units of the row-equilibrated M) or non-finite free block
// reached by a block pivot is left again and a single pivot taken from the previous set instead; a singular first
// guess is replaced by every row at a bound; any other singular block ends the solve as kSingular (never for a
// P-matrix). The budget (default max(2^16, 20·n) active sets;
// Murty's method may need 2^n on his own worst cases) ends it as kIterationLimit, the time limit as kTimeLimit.
//
// Signs are tested with the margin ½·tolerance·(1 + min(‖z‖∞, ‖q‖∞)) in units of z (Solver hands DoSolve the
// row-equilibrated problem), so a set accepted here passes the base's merit function; free values within the
// margin outside the box are clipped onto it.
//
// Start: the warm start's active set when SolverOptions::warm_start is given (z_i at or beyond a bound: at that
// bound, strictly inside: free), else the natural-map set at Π(0) with a Jacobi-scaled w (t_i = z_i − w_i/M_ii), so
// a 1×1 problem is solved by its first set. A warm start from the solution's own active set solves in one
// iteration. Nothing is remembered between solves (the session's reused active set does that).
//
// Dense M: free blocks up to 64 rows are factored by dense_lu, larger ones by Eigen's blocked in-place LU on the same
// storage (as newton does); nothing is allocated after the first solve of a size, except inside Eigen's level-3
// kernels, which take scratch beyond 128 KiB from malloc (free blocks above about 300 rows). Sparse M: each free
// block is gathered and factored by Eigen's SparseLU (SparseFreeBlock), which allocates. Every set is refactored from
// scratch (no low-rank updates of the factors; no Cholesky for symmetric M, whose symmetry the row equilibration
// hides). iterations = active sets solved; details block_pivots, single_pivots, singular_blocks.
#pragma once

#include <string>
#include <vector>

#include "solvers/core/active_set.h"
#include "solvers/core/backend_options.h"
#include "solvers/core/solver.h"

namespace smcbench {

struct BppOptions {
  // Block pivots allowed while the number of infeasible rows does not fall below its best (Júdice–Pires' p̄).
  // 0: the least-index single pivot as soon as a block step fails to improve.
  int block_steps_without_progress = 3;
  // A pivot of the free block's LU must exceed this (the block is a part of the row-equilibrated M, max |M_ij| = 1);
  // smaller pivots make the block singular.
  double pivot_tolerance = 1e-14;
  // Work safeguard: the solve ends as kIterationLimit ("handed over") once this many least-index single pivots
  // were taken, instead of running Murty's scheme to its end (finite on P-matrix LCPs, but it may take thousands
  // of sets on strongly nonsymmetric M where lemke needs tens of pivots). −1: no limit beyond the iteration budget.
  // auto gives its own bpp instance a limit proportional to n (docs/auto.md), so a bpp that leaves its block phase
  // hands the problem to the next candidate before it costs more than that candidate would.
  int max_single_pivots = -1;

  // True if every field is usable; otherwise *why names the field and the accepted range.
  bool IsValid(std::string* why) const;
};

// Default budget of active sets when SolverOptions::max_iterations ≤ 0: max(2^16, 20·n).
inline constexpr int kBppDefaultMinIterations = 1 << 16;

class BppSolver final : public BackendWithOptions<BppOptions> {
 public:
  BppSolver() = default;
  explicit BppSolver(const BppOptions& options) : BackendWithOptions(options) {}

  const SolverInfo& info() const override;

 protected:
  void DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) override;
  void BindOptions(OptionBinder* binder) override;
  bool ValidateBackendOptions(std::string* why) const override;

 private:
  // The iterations on dense (Sparse = false) or sparse M.
  template <bool Sparse>
  void Pivot(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result);
  // z for the current active set_ (bound rows placed, free rows solved); false when the free block is singular or
  // its solution not finite.
  template <bool Sparse>
  bool SolveActiveSet(const BoxMLCP& problem, double* z);

  ActiveSetWorkspace dense_;                  // the kernel's scratch (block, rhs, state, free rows, pivots)
  std::vector<signed char> previous_state_;   // the set before the last pivot, to step back from a singular block
  std::vector<int> infeasible_;               // rows to change this iteration
  Vector w_;                                  // M z + q of the current set
  // Sparse M only: the free block's factors and its right-hand side and solution.
  SparseFreeBlock sparse_block_;
  Vector sparse_rhs_, sparse_x_, placed_;
};

}  // namespace smcbench

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
// a 1×1 problem is solved by its first set. On a dense M of at least 32 rows that is symmetric up to the base's row
// scaling (M = D S, S symmetric, checked once per matrix) with a positive diagonal, guess_sweeps (3) projected Gauss–Seidel sweeps
// from Π(0) come first and the set is read off their iterate the same way: on SPD M they converge, and they halve
// the sets at m ≥ 64 (docs/auto.md); on nonsymmetric M of that size they are skipped (measured: they help relays, cost
// LCPs and mixed bounds). From 5 to 31 rows they also come first on a box (every row with a choice has both bounds
// finite: the projected iterate cannot run off whatever M is) with a positive diagonal whose M is neither symmetric up
// to the row scaling nor strictly diagonally dominant by rows nor skew-dominant (checked once per matrix): there the
// natural map at Π(0) can be far from the answer's set (the small-h P-matrix relay of condition 1e6 at m = 8: 9
// sets, 2 after the sweeps), while on symmetric or dominant M it usually is the answer's set and the sweeps would
// only cost, and on skew-dominant M they do not converge (issue 34,
// docs/auto.md); the sweeps there stop early at a sweep that moves nothing, and an answer from such a solve with a
// free row is not polished again when the polish would read the same set off z. A warm start from the solution's own
// active set solves in one iteration. Nothing is remembered between solves (the session's reused active set does
// that).
//
// Dense M of 12 to 15 rows that is symmetric up to the base's row scaling with a positive diagonal: from the third
// set on (the first two by the inline LU), each set is solved by a Cholesky factor of (R⁻¹ M)_FF that keeps the leading rows of the last set's factor (prefix_cholesky.h), the
// inline LU taking over for the rest of the solve when a block is not positive definite (option cholesky); an
// answer the polish would only solve again is not polished (as below). Detail reused_cholesky_rows.
// Dense M of at least 16 rows (below, every set is factored inline): the first set's free block is factored (dense_lu up to 64 rows, Eigen's blocked in-place LU above); each
// later set is solved from those factors by a Schur-complement update for the rows that entered or left the free
// set (updated_free_block.h: the bordered system of Gill–Murray–Saunders–Wright), until the difference exceeds a
// quarter of the factored block (at most 128 rows), the Schur complement's LU has a pivot below 1e-10 of its
// largest entry, or a value is not finite: then the set is factored from scratch and becomes the reference. So a
// singular free block is always judged by a fresh LU, and an answer solved by an update whose free rows' w does not
// vanish to the sign margin is factored and solved again (detail refactored_answers). factor_updates = false
// refactors every set (the method as published). Nothing is allocated after the first solve of a size, except
// inside Eigen's level-3 kernels (the blocked LU, the update's triangular solves and products), which take scratch
// beyond 128 KiB from malloc (free blocks above about 300 rows). Sparse M: each free block is gathered and factored
// by Eigen's SparseLU (SparseFreeBlock), which allocates; no updates, no sweeps. Dense M of at least 16 rows that is
// symmetric up to the base's row scaling (M = R S, as the base hands bpp a symmetric M row-equilibrated) with a
// positive diagonal: the reference blocks are factored by Cholesky of (R⁻¹ M)_FF, the LU taking over for the rest of
// the solve when one is not positive definite (option cholesky). When the answer's set was factored afresh (not
// updated), no value was clipped and the base's polish would read the same set off z, bpp tells the base so
// (Solver::NotePolishRedundant): the polish, which would factor that block once more, is skipped when z passes. On
// the Cholesky path an answer solved by an update is factored once more by Cholesky when the base would polish it
// (n ≤ kMaxPolishDenseSize): half the flops of the polish's LU, which it then replaces (detail final_cholesky; the
// same set, not counted as another); there, too, a set reached by a block pivot is factored afresh rather than
// updated (its update plus that final Cholesky cost more than one Cholesky; single pivots are still updated). iterations = active sets solved; details block_pivots, single_pivots,
// singular_blocks, and for dense M factorizations (fresh LUs or Cholesky factorizations) and updated_sets;
// cholesky_factorizations, final_cholesky, refactored_answers and swept_guess (1) when nonzero.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "solvers/core/active_set.h"
#include "solvers/core/backend_options.h"
#include "solvers/core/solver.h"
#include "solvers/pivoting/prefix_cholesky.h"
#include "solvers/pivoting/updated_free_block.h"

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
  // auto gives its own bpp instance a limit proportional to n (single_pivots_per_row; docs/auto.md), so a bpp that
  // leaves its block phase hands the problem to the next candidate before it costs more than that candidate would.
  int max_single_pivots = -1;
  // The same limit in proportion to the problem: max(4, ⌈single_pivots_per_row · n⌉) single pivots, when > 0 and
  // max_single_pivots is −1. auto sets 0.25 (measured: auto_rule_measure handover, docs/auto.md).
  double single_pivots_per_row = -1.0;
  // Dense M: solve each active set after the first by a Schur-complement update of the last factored free block
  // (updated_free_block.h) instead of refactoring it; a set too far from it, or whose update is ill-conditioned,
  // is factored from scratch. false: every set factored from scratch (the method as published).
  bool factor_updates = true;
  // Dense M of at least 32 rows, cold start: projected Gauss–Seidel sweeps from Π(0) before the first set is read
  // off (0: the Jacobi-scaled natural map at Π(0) alone). Only where they converge for every problem of the class: M symmetric
  // (up to the base's row scaling) with a positive diagonal; elsewhere they are skipped (measured: on nonsymmetric
  // P-matrices they help relays and cost LCPs and mixed bounds more sets, docs/auto.md). From 5 to 31 rows: on a box
  // whose M is neither symmetric (up to the row scaling) nor strictly diagonally dominant (issue 34, docs/auto.md).
  int guess_sweeps = 3;
  // Dense M of at least UpdatedFreeBlock::kMinRows rows that is symmetric up to the base's row scaling with a
  // positive diagonal: factor the free blocks by Cholesky of the symmetric (R⁻¹ M)_FF (half the LU's flops), the LU
  // taking over for the rest of the solve when one is not positive definite (updated_free_block.h). false: LU only.
  bool cholesky = true;

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

  // The first active set from guess_sweeps projected Gauss–Seidel sweeps (dense M) from z0 = Π(0) (nullptr: Π(0)
  // computed here): true when it was read off into state. on_box: the caller checked BoxWithPositiveDiagonal; otherwise M must be symmetric up to the row
  // scaling (checked here).
  bool SweptGuess(const BoxMLCP& problem, const double* z0, signed char* state, bool on_box);
  // Whether every row with a choice (l < u) of the dense M has both bounds finite and M_ii > 0 (O(n), every cold
  // solve of 5 to 31 rows whose M is not symmetric): the sweeps' iterate then stays in the box whatever M is.
  bool BoxWithPositiveDiagonal(const BoxMLCP& problem) const;
  // Whether the sweeps should choose the first set of a small box (kMinBoxSweptRows): the dense M is not strictly
  // diagonally dominant by rows (M_ii > Σ_j≠i |M_ij|) and its skew part does not outweigh its symmetric part
  // (kMaxSweptSkewRatio, Frobenius norms); decided once per matrix_id.
  bool SweepsChooseTheFirstSet(const BoxMLCP& problem);

  // Whether the dense M is D·S for a positive diagonal D and a symmetric S (a symmetric M after row scaling) with a
  // positive diagonal, decided once per matrix_id (O(n²) then; row_ratio_ and inv_row_ratio_ hold d_i / d_0 and its
  // inverse when true).
  bool SymmetricUpToRowScaling(const BoxMLCP& problem);
  // Dense M, n ≥ kMinRows, a solved set whose free block was just factored afresh (not updated) and nothing clipped:
  // true when the active set the base's polish reads off z (ClassifyRowsForPolish) is this set, so the polish would
  // factor the same block again for the same answer (Solver::NotePolishRedundant).
  bool PolishWouldRepeat(const BoxMLCP& problem, const double* z, const signed char* state);

  ActiveSetWorkspace dense_;                  // the kernel's scratch (block, rhs, state, free rows, pivots)
  std::vector<signed char> previous_state_;   // the set before the last pivot, to step back from a singular block
  std::vector<int> infeasible_;               // rows to change this iteration
  Vector w_;                                  // M z + q of the current set
  UpdatedFreeBlock updated_;                  // dense M of ≥ kMinRows rows: the free block's factors, updated
  int small_factorizations_ = 0;              // dense M of fewer rows: the sets factored this solve
  PrefixCholesky prefix_;                     // dense symmetric M of fewer rows: the free blocks' Cholesky
  bool small_cholesky_ = false;               // this solve may factor its small blocks by prefix_ (until one fails)
  int small_cholesky_sets_ = 0;               // of small_factorizations_, the sets prefix_ solved
  Vector guess_;                              // SweptGuess's iterate
  Vector row_ratio_, inv_row_ratio_;          // SymmetricUpToRowScaling's d_i / d_0 and d_0 / d_i
  std::vector<signed char> polish_state_;     // PolishWouldRepeat's classification
  Vector polish_w_;                           // and its w
  std::uint64_t symmetry_id_ = 0;             // the matrix_id SymmetricUpToRowScaling last decided, and its answer
  bool symmetric_ = false;
  std::uint64_t sweep_first_id_ = 0;          // the matrix_id SweepsChooseTheFirstSet last decided, and its answer
  bool sweep_first_ = false;
  Vector dominance_sums_;                     // its off-diagonal row sums
  // Sparse M only: the free block's factors and its right-hand side and solution.
  SparseFreeBlock sparse_block_;
  Vector sparse_rhs_, sparse_x_, placed_;
};

}  // namespace smcbench

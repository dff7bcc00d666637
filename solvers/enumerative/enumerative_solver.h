// The exact reference backend: exhaustive enumeration of the active sets of the box-MLCP, with a guided
// first phase and rank-revealing least-norm solves on singular free blocks.
//
// Every row i is put in one state: at its lower bound (z_i = l_i, needs w_i ≥ 0), at its upper bound
// (z_i = u_i, needs w_i ≤ 0) or free (M_FF z_F = −(q_F + M_FB z_B), needs l_i ≤ z_i ≤ u_i). A solution of the
// box-MLCP is exactly a state assignment whose linear system has a solution meeting those sign conditions, so
// trying every assignment either finds one or proves there is none: the total enumeration of complementary
// bases (Murty 1988, Linear Complementarity, Linear and Nonlinear Programming, ch. 1; Júdice 1994, Algorithms
// for linear complementarity problems, in Algorithms for Continuous Optimization, NATO ASI C 434, on
// enumerative methods). Rows with l = −∞, u = +∞ are always free and rows with l = u always fixed, so an LCP row
// has 2 states and a finite box row 3.
//
// Search order. (1) The natural-map active set at the starting point (warm start, else Π(0)), Jacobi-scaled
// so that a 1×1 problem is solved exactly; (2) guided steps: the natural-map active set at the previous
// candidate, i.e. block principal pivoting (Júdice & Pires 1994) / the primal-dual active-set step
// (Hintermüller, Ito & Kunisch 2002), until a set repeats; (3) every active set, nearest-first (by Hamming
// distance) around the last guess, least confident rows first. Step (3) alone makes the method exact. It starts at
// the set step (2) stopped on, a repeat: a guided set within one row of that start is counted but not examined again
// (it was refuted already; only its determinant's sign is taken, for the certificate below).
//
// Each candidate: LU with partial pivoting of M_FF (closed forms for 1×1, 2×2); if a pivot falls below
// rank_tolerance · max|M_FF| the block is treated as singular and solved by column-pivoted QR plus a second
// QR, giving the least-norm solution about Π(0) of the rank-cut system, so consistent singular blocks are not
// skipped (before that, the plain LU solution is tried: a small pivot does not make a candidate wrong). z_F must
// lie within its bounds up to τ (see feasibility_scale), is clipped onto them, and the candidate is accepted when
// the merit function passes — BoxMLCP::NaturalResidual, relative and in units of z, the test of Solver::Finish;
// on bound rows it is the sign violation of w. Solver::Solve hands the search the row-equilibrated problem, so
// every threshold here is in units of z. Siconos' lcp_enum, by contrast, skips a basis only on an
// exactly zero LAPACK pivot and accepts any solution with no entry below −1e-6 (NaN and 1e13-sized garbage
// included), which is why it fails, platform-dependently, on lcp_enum_fails.dat (296 of its 512 bases are
// singular).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "solvers/core/backend_options.h"
#include "solvers/core/solver.h"

namespace smcbench {

struct EnumerativeOptions {
  // Largest number of rows with a choice of state (LCP: n; free and fixed rows do not count). Larger problems
  // are refused with kSizeLimit before any work: the search is exponential in this number.
  int size_limit = 20;
  // Largest number of active sets the exhaustive search may need (product of the per-row choice counts: 2^n
  // for an LCP, 3^n for a relay/box problem). Larger problems are refused with kSizeLimit before any work.
  // Default 3^16: an n = 16 relay problem, or an LCP at the size_limit (2^20).
  int max_candidates = 43046721;
  // Sign and bound tests accept violations up to
  //   τ = max(feasibility_scale · n · ε · (‖M‖∞ ‖z‖∞ + ‖q‖∞),  tolerance · (1 + ‖q‖∞)),
  // i.e. roundoff of the block solve or what the merit test itself tolerates; the merit function decides.
  double feasibility_scale = 1e3;
  // A free block whose LU pivot falls below rank_tolerance · max|M_FF| is treated as (numerically) singular: its
  // plain LU solution is tried, then column-pivoted QR with rank cut-off rank_tolerance · |R_00| gives the
  // least-norm solution and, for rank k − 1, the line of solutions searched for a point meeting every condition.
  double rank_tolerance = 1e-12;
  // Try least-norm solutions of consistent singular free blocks (else such blocks are skipped, and the search can
  // no longer prove infeasibility: a skipped block could hold a solution).
  bool solve_singular_blocks = true;
  // Guided steps before the exhaustive search: each next active set is the natural-map active set at the
  // last candidate (block principal pivoting). Stops early at a repeated set; 0 goes straight to the
  // exhaustive search. They add at most this many sets to the count.
  int guided_steps = 16;

  bool IsValid(std::string* why) const;
};

// Exhaustive active-set enumeration. iterations = number of active sets examined (guided ones included; a set
// may be examined in both phases). Outcomes: kSolved (the merit function accepts z); kSizeLimit (before any work);
// kIterationLimit (options.max_iterations sets examined; ≤ 0 means no budget beyond the full search); kTimeLimit;
// and, once every active set was examined without a solution, kInfeasible only with a certificate:
//   - each set refuted with a margin: z_F out of its box, or a sign condition of w violated, by more than
//     100·τ_B, τ_B = max(τ, feasibility_scale·n·ε·(‖M‖∞‖z‖∞ + ‖q‖∞)·growth), growth = max|M_FF| over the
//     smallest LU pivot (the block solve's error); a singular block (pivot below rank_tolerance) only on its
//     whole solution set: a rank k − 1 block on its line of solutions, with a threshold that grows along the line
//     (the single solution of a nearly singular block may lie far out) unless M_FF v = 0 holds exactly, a deeper
//     deficiency only by a row that does not see z_F (zero entries on the free columns); no block skipped or
//     overflowed;
//   - a class that can lack a solution: not every bound finite, M + Mᵀ not positive definite, and the signs of
//     the free blocks' determinants not all alike (which would make the problem a P-matrix one).
// Otherwise kNumericalFailure, "not a proof of infeasibility", with the reasons. Details: active_sets_total (size
// of the full search), guided_sets, singular_blocks.
// Problems with m ≤ 4 rows first try the guessed set on a fixed-size fast path (loops unrolled at compile time,
// values in registers, cached factors or inverses of the free blocks, division-free guess and acceptance tests).
class EnumerativeSolver final : public BackendWithOptions<EnumerativeOptions> {
 public:
  EnumerativeSolver() = default;
  explicit EnumerativeSolver(const EnumerativeOptions& options) : BackendWithOptions(options) {}

  // The fast path's factors of the free blocks M_FF, one per free set (bitmask of rows), for the M identified
  // by matrix_id (BoxMLCP::matrix_id()). Fixed size: m ≤ 4, no allocation.
  struct BlockCache {
    static constexpr int kMaxRows = 4;
    enum State : signed char { kUnknown, kFactored, kSingular };
    struct Entry {
      State state = kUnknown;
      double a[kMaxRows * kMaxRows];  // FactorBlock's output, leading dimension n
      int piv[kMaxRows];
      int k = 0;  // rows in the free set
      // 2×2 blocks with κ∞ ≤ kInverseConditionLimit also keep their inverse, scattered into an n×n matrix that is
      // zero outside the free rows and columns: the solve is then a mat-vec with compile-time indices, kept in
      // registers, instead of two chained divisions on the critical path of a time step.
      bool has_inverse = false;
      double inverse[kMaxRows * kMaxRows];
    };
    static constexpr double kInverseConditionLimit = 1e4;
    std::uint64_t matrix_id = 0;  // 0: empty
    int n = 0;
    double rank_tolerance = 0.0;
    double active_sets_total = 0.0;  // the detail: size of the full search for this M, l, u
    Entry entries[1 << kMaxRows];
  };

  const SolverInfo& info() const override;

 protected:
  void DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) override;
  void BindOptions(OptionBinder* binder) override;
  bool ValidateBackendOptions(std::string* why) const override;

 private:
  // The search, with the row count fixed at compile time (N = 1..4) or read at run time (N = 0).
  template <int N>
  void Search(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result);
  // The search's phases and the state they share (enumerative_solver.cc).
  template <int N>
  class ActiveSetSearch;
  // The fixed-size fast path (N = 1..4): only the guessed active set; false if it does not solve the problem.
  template <int N>
  bool SolveFast(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result);
  // Sizes the workspace for n rows and that many guided steps; allocates only when they grow or n changes.
  void Reserve(int n, int guided_steps);

  // Workspace for the run-time-size path (the fixed-size path keeps its buffers on the stack).
  int workspace_n_ = -1;
  int workspace_history_ = 0;
  std::vector<double> real_work_;
  std::vector<int> int_work_;
  BlockCache block_cache_;  // keyed on the problem's matrix_id(): rebuilt when M changes
};

}  // namespace smcbench

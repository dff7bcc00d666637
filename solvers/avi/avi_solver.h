// Solving an AVI with any box backend, through the exact reduction of avi_reduction.h: the backend solves the
// normalized reduced box-MLCP z = (λ, μ̃, ν̃) with the usual base-class work (equilibration, polish, the merit
// function), and the answer is mapped back and judged by the AVI verdict (avi_verdict.h).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "solvers/avi/affine_vi.h"
#include "solvers/avi/avi_reduction.h"
#include "solvers/avi/avi_verdict.h"
#include "solvers/core/result.h"
#include "solvers/core/session.h"
#include "solvers/core/solver.h"

namespace smcbench {

struct AviResult {
  // The backend's status on the reduction (its refusals included), except that a "solved" failing the AVI rule
  // (PassesAviTolerance) is kInaccurate: status solved ⇒ the verdict's residual parts pass.
  SolveStatus status = SolveStatus::kNotRun;
  std::string message;                        // why, for anything but solved
  std::string_view solver;                    // the backend's registered name
  AviSolution solution;                       // λ, μ, ν as stated, mapped back from the backend's z
  int iterations = 0;
  double solve_seconds = 0.0;
  SolveResult reduced;      // the backend's whole result on the normalized reduction (z, w, residuals, details)
  AviJudgement judgement;   // the AVI verdict (expected outcome from ExpectedAviOutcome, the given reference)
  bool solved() const { return status == SolveStatus::kSolved; }
};

// A backend that works on P directly (Cao–Ferris' pivoting on the polytope) rather than on the reduction. SolveAvi
// calls it instead of Solver::Solve, then does the shared work itself: the multipliers when the backend gives none
// (AviMultipliersAt), the residual and the rule for "solved" (a claim the verdict's residuals reject becomes
// kInaccurate, as in the box base class), the timing.
class DirectAviBackend {
 public:
  virtual ~DirectAviBackend() = default;
  // Must set result->status (and message when not solved), result->iterations, and solution->lambda (size n);
  // solution->mu and nu when the method has them (as stated), else left empty. options are valid.
  virtual void SolveAviDirect(const AffineVI& avi, const SolverOptions& options, AviSolution* solution,
                              SolveResult* result) = 0;
};

// Multipliers for a given λ: rows of (H, K) within 1e-9·(1 + ‖λ‖∞) of active (each row divided by its largest
// coefficient) may carry μ_i ≥ 0, the others 0, and Hᵀμ + Eᵀν = Mλ + q is solved by least squares (column-pivoted
// QR); when that gives a clearly negative μ_i (a degenerate vertex with several choices), a phase-1 simplex finds
// a nonnegative one and the least squares is repeated on its support. Best effort: the verdict judges the result.
AviSolution AviMultipliersAt(const AffineVI& avi, const Vector& lambda);

// Solves avi with solver: through the reduction, or directly for a DirectAviBackend. options.warm_start may be
// empty, λ alone (size n: multipliers start at 0) or (λ, μ, ν) as stated (size n + m + p); any other size reaches
// the backend, which reports it (kInvalidOptions). Never throws for a valid AVI (as Solver::Solve). Allocates: it
// builds the reduction on every call (AviSession does not).
AviResult SolveAvi(const AffineVI& avi, Solver& solver, const SolverOptions& options = {},
                   const AviReference* reference = nullptr);

// Prepare once, solve many (a time-stepper with a polytope law: M, H, K, E, f fixed, q new every step): the
// normalized reduction is built once and solved through one box session (solvers/core/session.h) whose q is replaced
// in place, so repeated solves allocate nothing after the first (for a backend with info().allocation_free; pinned
// by avi_test). As the box path of a time-stepper, a solve may start from the previous answer: the session first
// tries the reduction's last active set (SessionOptions::reuse_active_set, 0 iterations when it holds), and the
// backend starts from the warm start given to Solve. The rule for "solved" is SolveAvi's; the verdict against a
// reference is JudgeAvi's business. Solves through the reduction only (a DirectAviBackend is called by SolveAvi).
// The solver must outlive the session.
class AviSession {
 public:
  // options.warm_start as SolveAvi's (empty, λ alone, or (λ, μ, ν) as stated): the start of every Solve given none.
  AviSession(const AffineVI& avi, Solver& solver, const SolverOptions& options = {},
             const SessionOptions& session = {});

  // Solves the AVI with q (size n, finite: InvalidInputError naming the index otherwise, as AffineVI::set_q).
  // warm_start: null, or an answer as stated to start the backend from, typically the previous solve's solution()
  // (λ and its multipliers): mapped into the reduction's z = (λ, μ̃_i = μ_i h_i/σ, ν̃_j = ν_j e_j/σ) (avi_reduction.h)
  // in a buffer of the session, without allocating; empty μ or ν start at 0, other sizes are InvalidInputError
  // naming the field. A reused active set whose answer fails the AVI rule is dropped and the backend called.
  SolveStatus Solve(const Eigen::Ref<const Vector>& q, const AviSolution* warm_start = nullptr);
  // The last answer as stated (λ, μ, ν), valid when the backend returned a z of the reduction's size.
  const AviSolution& solution() const { return solution_; }
  // The backend's result on the reduction (status, message, z = (λ, μ̃, ν̃), residuals, details; detail "path":
  // SessionPath, whether the reused active set answered).
  const SolveResult& result() const { return result_; }
  // The reduction, its q the last solve's.
  const AviReduction& reduction() const { return reduction_; }
  // Solves answered by the reused active set, and in all (SolveSession::reused, calls).
  std::int64_t reused() const { return session_.reused(); }
  std::int64_t calls() const { return session_.calls(); }

 private:
  // *warm_start (as stated) into warm_z_ (units of the reduction).
  void MapWarmStart(const AviSolution& warm_start);

  AviReduction reduction_;
  SolverOptions options_;
  SolveSession session_;
  Vector reduced_q_;  // q̃ of the reduction, its tail (−K̃, −f̃) fixed
  Vector warm_z_;     // the mapped warm start (n + m + p)
  SolveResult result_;
  AviSolution solution_;
};

}  // namespace smcbench

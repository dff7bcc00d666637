// Solving an AVI with any box backend, through the exact reduction of avi_reduction.h: the backend solves the
// normalized reduced box-MLCP z = (λ, μ̃, ν̃) with the usual base-class work (equilibration, polish, the merit
// function), and the answer is mapped back and judged by the AVI verdict (avi_verdict.h).
#pragma once

#include <string>
#include <string_view>

#include "solvers/avi/affine_vi.h"
#include "solvers/avi/avi_reduction.h"
#include "solvers/avi/avi_verdict.h"
#include "solvers/core/result.h"
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

// Solves avi with solver: through the reduction, or directly for a DirectAviBackend. options.warm_start may be empty, λ alone (size n: multipliers start at 0) or (λ, μ, ν)
// as stated (size n + m + p); any other size reaches the backend, which reports it (kInvalidOptions). Never throws
// for a valid AVI (as Solver::Solve). Allocates: it builds the reduction on every call.
AviResult SolveAvi(const AffineVI& avi, Solver& solver, const SolverOptions& options = {},
                   const AviReference* reference = nullptr);

}  // namespace smcbench

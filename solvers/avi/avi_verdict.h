// How an answer (λ, μ, ν) to an AVI is judged, and its certified reference: the box verdict (solvers/core/verdict.h)
// applied to the normalized reduction (avi_reduction.h), plus primal feasibility and the forward error of λ where
// λ is unique. docs/avi.md states the rule; this file is its one home.
#pragma once

#include <vector>

#include "solvers/avi/affine_vi.h"
#include "solvers/avi/avi_reduction.h"
#include "solvers/core/matrix_class.h"
#include "solvers/core/verdict.h"
#include "solvers/reference/certify.h"

namespace smcbench {

// A reference solution of an AVI: Certify (extended precision) on its normalized reduction, and what is known of
// the uniqueness of λ. The multipliers need not be unique (more active rows than unknowns, a vertex of a
// degenerate polytope); only λ's uniqueness matters for the forward error.
struct AviReference {
  ReferenceSolution reduced;   // of the normalized reduction: z* = (λ*, μ̃*, ν̃*), its certificate and condition
  AviSolution solution;        // λ*, μ*, ν* as stated (empty unless reduced.verified())
  // M + Mᵀ positive definite (Cholesky with margin, matrix_class.h): the AVI is strictly monotone, so at most one λ
  // solves it, whatever P is.
  MatrixClassAnswer strictly_monotone = MatrixClassAnswer::kNotDecided;
  // λ* is the only solution's λ: strictly monotone, or the reduction's z* certified unique (an exhaustive
  // enumeration that met one solution and no singular block).
  bool lambda_unique = false;
  bool verified() const { return reduced.verified(); }
};

// candidates: points to start from (a planted solution, backends' answers; wrong sizes and non-finite entries are
// ignored by Certify, empty μ or ν read as 0). The reduction must have at most options.max_size rows (n + m + p),
// else the certificate is kNone. Never throws for a valid AVI.
AviReference CertifyAvi(const AffineVI& avi, const std::vector<AviSolution>& candidates,
                        const CertifyOptions& options = {});

// Everything the AVI verdict computed.
struct AviJudgement {
  Verdict verdict = Verdict::kFailed;
  // The natural residual of the normalized reduction at (λ, μ̃, ν̃), recomputed here (Residual of BoxMLCP): rel is
  // relative to 1 + ‖(q̃, K̃, f̃)‖∞, scaled is relative to 1 + ‖(λ, μ̃, ν̃)‖∞. Both scale-free: they do
  // not change when (M, q) are scaled together or a row of (H, K) or (E, f) is scaled by a positive number.
  Residual residual;
  // max over rows of (K̃_i − H̃_iλ)⁺ and |Ẽ_jλ − f̃_j| (each row divided by its largest coefficient, so in units of
  // λ), relative to 1 + ‖λ‖∞.
  double primal_infeasibility = kInf;
  // max over rows of |min(μ̃_i, H̃_iλ − K̃_i)| and |Ẽ_jλ − f̃_j|, relative to 1 + ‖λ‖∞: the complementarity rows of
  // the residual in units of λ. Why besides `residual`: the multipliers grow like ‖q̃‖ (like 1/h when M = O(h), as
  // in a time step), and a residual relative to 1 + ‖(λ, μ̃, ν̃)‖∞ would let λ leave its face by tol·‖μ̃‖∞.
  // It bounds primal_infeasibility (for μ̃ ≥ 0).
  double complementarity = kInf;
  // The forward error is judged only where λ is unique (AviReference::lambda_unique) and a reference verified:
  // when M is singular and λ is not unique (twisting: several λ give the same state x), the residual rule alone
  // decides and these stay NaN.
  bool forward_error_applicable = false;
  double forward_error = kNaN;       // ‖λ − λ*‖∞
  double forward_error_rel = kNaN;   // forward_error / max(1, ‖λ*‖∞)
  double forward_allowance = kNaN;   // 10·max(1, κ)·tol·(1 + ‖λ*‖∞), κ the reference's condition (verdict.h)
};

// The AVI verdict, with the meaning of Judge (verdict.h):
//   solved:     Judge's residual rule (rel ≤ tol and scaled ≤ tol) on the normalized reduction at the answer,
//               complementarity ≤ tol and primal_infeasibility ≤ tol (PassesAviTolerance); else wrongly claimed
//               (also on an expected-infeasible AVI). Where the forward error applies, ‖λ − λ*‖∞ ≤
//               forward_allowance, else inaccurate.
//   infeasible: wrongly refused when the AVI is known solvable (expected solvable, or a verified reference),
//               correctly refused when expected infeasible, else failed.
//   otherwise:  correctly refused on an expected-infeasible AVI, else failed.
// An answer of the wrong size has residual +∞ (so "solved" with it is wrongly claimed); empty μ or ν read as 0.
AviJudgement JudgeAvi(const AffineVI& avi, ExpectedOutcome expected, const AviReference* reference,
                      SolveStatus status, const AviSolution& answer, double tolerance);

// The two parts of the AVI rule in units of λ (AviJudgement::primal_infeasibility and complementarity) at z =
// (λ, μ̃, ν̃) of a normalized reduction, both relative to 1 + ‖λ‖∞; +∞ on NaN. No allocation (AviSession's per-step
// rule).
struct AviFaceResidual {
  double primal_infeasibility = kInf;
  double complementarity = kInf;
};
AviFaceResidual ComputeAviFaceResidual(const AviReduction& reduction, const Vector& z);

// The residual part of the AVI rule: residual.rel, residual.scaled, complementarity and primal_infeasibility all
// ≤ tolerance (NaN never passes). SolveAvi sets its status by it, JudgeAvi its verdict.
inline bool PassesAviTolerance(const AviJudgement& j, double tolerance) {
  return PassesBoxMlcpTolerance(j.residual, tolerance) && j.complementarity <= tolerance &&
         j.primal_infeasibility <= tolerance;
}

// What a correct backend does: on a bounded P an AVI always has a solution (Hartman–Stampacchia): kSolvable; on an
// unbounded or undecided P it may have none: kUnknown.
ExpectedOutcome ExpectedAviOutcome(const AffineVI& avi);

}  // namespace smcbench

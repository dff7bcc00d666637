// The one verdict: how a backend's answer on a box-MLCP is judged, used by Solver (solvers/core), the replay
// engine, the suites' tests, the reports and Python. "Solved" must mean right in the units the user reads (z):
// see docs/verdict.md for the rule in two sentences and why each part is there.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "solvers/core/problem.h"
#include "solvers/core/status.h"

namespace smcbench {

// What a correct backend does on the problem.
enum class ExpectedOutcome : std::uint8_t {
  kUnknown = 0,     // not known (captured or peer problems nobody has classified): any honest answer is fine
  kSolvable = 1,    // a solution exists; "solved" is the right answer, any other status is a failure (not wrong)
  kInfeasible = 2,  // no solution exists; every non-solved status is a correct refusal, "solved" is wrong
};
std::string_view ToString(ExpectedOutcome value);  // "unknown", "solvable", "infeasible"
std::optional<ExpectedOutcome> ExpectedOutcomeFromString(std::string_view text);

// What a certified reference solution proves (solvers/reference/certify.h computes it in extended precision).
// Append-only, explicit values: stored in .smcps files.
enum class Certificate : std::uint8_t {
  kNone = 0,        // no reference was computed (too large, sparse, or not asked for)
  kUnique = 1,      // z* verified with margins, strictly complementary, and the only solution
  kDegenerate = 2,  // z* verified and the only solution, but some row is at a bound with w_i = 0 (not strict)
  kNonUnique = 3,   // z* verified, but other solutions exist: z* is one of them, forward error is not defined
  kNoneFound = 4,   // no candidate active set could be verified (not a proof that none exists)
  kIsolated = 5,    // z* verified with a nonsingular free block (locally unique; possibly degenerate); global
                    // uniqueness not established (not a P-matrix, too many active sets to enumerate)
};
std::string_view ToString(Certificate value);  // "none", "unique", "degenerate", "non-unique", "none found", "isolated"
std::optional<Certificate> CertificateFromString(std::string_view text);

// A reference solution and what it proves. condition = μ = ‖(D_F⁻¹ M_FF)⁻¹‖∞ at z*'s active set F (rows strictly
// inside their bounds; the larger over the choices for degenerate rows), D the row scales (BoxMLCP::row_scale):
// how much an error in the equilibrated residual can move z. 0 when F is empty.
struct ReferenceSolution {
  Certificate certificate = Certificate::kNone;
  Vector z;                // z* rounded to double (empty unless the certificate verified one)
  double condition = 0.0;  // μ above
  // Proved in interval arithmetic (solvers/reference/enclosure.h): an exact solution lies within this distance
  // (∞-norm) of z. NaN when not proved (not verified, n > 64, degenerate rows, a free block too ill-conditioned) or
  // not attempted; not stored in .smcps files (AttachReferences recomputes it).
  double proved_radius = kNaN;
  // With a proved radius: M + Mᵀ proved positive definite as well (enclosure.h), so that solution is the only one.
  bool proved_unique = false;
  bool verified() const {
    return certificate == Certificate::kUnique || certificate == Certificate::kDegenerate ||
           certificate == Certificate::kNonUnique || certificate == Certificate::kIsolated;
  }
  // The forward error is defined only when z* is the only solution.
  bool unique() const { return certificate == Certificate::kUnique || certificate == Certificate::kDegenerate; }
};

// How a backend's answer is judged. Append-only, explicit values (stored in results).
enum class Verdict : std::uint8_t {
  kSolved = 0,            // success where success is possible
  kCorrectlyRefused = 1,  // not solved, and the problem has no solution
  kFailed = 2,            // not solved although the problem is solvable (or not known to be unsolvable)
  kWronglyClaimed = 3,    // status solved but a residual is above tolerance, or the problem has no solution
  kInaccurate = 4,        // status solved, residuals pass, but ‖z − z*‖∞ exceeds what the conditioning allows
  kWronglyRefused = 5,    // status infeasible (a claim that no solution exists) on a problem that has one
};
std::string_view ToString(Verdict verdict);  // "solved", "correctly refused", "failed", "WRONGLY CLAIMED", ...
// The inverse of ToString (exact text), empty for any other text.
std::optional<Verdict> VerdictFromString(std::string_view text);
// Wrong answers: wrongly claimed, inaccurate (a wrong z reported as solved) and wrongly refused. Must be 0.
inline bool IsWrong(Verdict v) {
  return v == Verdict::kWronglyClaimed || v == Verdict::kInaccurate || v == Verdict::kWronglyRefused;
}

// The forward-error allowance C·max(1, μ)·tol·(1 + ‖z*‖∞): at z*'s active set an equilibrated residual r moves z by
// at most μ‖r‖∞, and "solved" bounds ‖r‖∞ by tol·(1 + ‖z‖∞); C = 10 covers ‖z‖ against ‖z*‖ and rounding.
inline constexpr double kForwardErrorFactor = 10.0;
double ForwardErrorAllowance(const ReferenceSolution& reference, double tolerance);

// Everything the verdict computed, for records and JSON.
struct Judgement {
  Verdict verdict = Verdict::kFailed;
  Residual residual;                  // recomputed from z here (never the backend's)
  double forward_error = kNaN;        // ‖z − z*‖∞ when the reference is unique, else NaN
  double forward_error_rel = kNaN;    // forward_error / max(1, ‖z*‖∞)
  double forward_allowance = kNaN;    // ForwardErrorAllowance, when the forward error is defined
};

// Judges status and z on problem against the expected outcome and the reference (may be null):
//   solved:     residual_rel ≤ tol and residual_scaled ≤ tol, recomputed here; and, with a unique reference,
//               ‖z − z*‖∞ ≤ ForwardErrorAllowance; else wrongly claimed (residuals) or inaccurate (forward error).
//               On an expected-infeasible problem "solved" is wrongly claimed.
//   infeasible: a claim that no solution exists: wrongly refused when the problem is known solvable (expected
//               solvable, or a verified reference), correctly refused when expected infeasible, else failed.
//   otherwise:  correctly refused on an expected-infeasible problem, else failed.
Judgement Judge(const BoxMLCP& problem, ExpectedOutcome expected, const ReferenceSolution* reference,
                SolveStatus status, const Vector& z, double tolerance);

// The verdict on a nonlinear MCP, with the same meaning as Judge: the residuals are recomputed from z here (F and
// the Jacobian at z: McpMerit), "solved" requires the scale-free residual (Residual::scaled, McpScaledResidual) ≤ tol
// and nothing else of the residuals: Residual::rel (relative to 1 + ‖F(Π(0))‖∞) is kept as information, since a
// positive scaling of F's rows changes it and must not change a verdict. The forward error is judged against the
// nearest verified reference when references_complete (every solution is listed), else against the first reference
// certified unique; references may be empty. It is measured in the variables' units c (MCP::variable_scale; empty:
// 1): forward_error = max_i |z_i − z*_i|/c_i, allowance 10·max(1, μ)·tol·(1 + max_i |z*_i|/c_i), μ =
// ‖(D⁻¹ J_FF C_F)⁻¹‖∞ at z* (the box's condition with M = J C), so the verdict survives a change of units.
Judgement JudgeMCP(const MCP& problem, ExpectedOutcome expected, const std::vector<ReferenceSolution>& references,
                   bool references_complete, SolveStatus status, const Vector& z, double tolerance);

}  // namespace smcbench

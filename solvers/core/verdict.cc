#include "solvers/core/verdict.h"

#include <algorithm>
#include <string>

#include "solvers/core/mcp_merit.h"
#include "solvers/core/solver.h"

namespace smcbench {

std::string_view ToString(ExpectedOutcome value) {
  switch (value) {
    case ExpectedOutcome::kSolvable:
      return "solvable";
    case ExpectedOutcome::kInfeasible:
      return "infeasible";
    case ExpectedOutcome::kUnknown:
      break;
  }
  return "unknown";
}

std::optional<ExpectedOutcome> ExpectedOutcomeFromString(std::string_view text) {
  for (ExpectedOutcome e : {ExpectedOutcome::kUnknown, ExpectedOutcome::kSolvable, ExpectedOutcome::kInfeasible}) {
    if (ToString(e) == text) return e;
  }
  return std::nullopt;
}

std::string_view ToString(Certificate value) {
  switch (value) {
    case Certificate::kUnique:
      return "unique";
    case Certificate::kDegenerate:
      return "degenerate";
    case Certificate::kNonUnique:
      return "non-unique";
    case Certificate::kNoneFound:
      return "none found";
    case Certificate::kIsolated:
      return "isolated";
    case Certificate::kNone:
      break;
  }
  return "none";
}

std::optional<Certificate> CertificateFromString(std::string_view text) {
  for (Certificate c : {Certificate::kNone, Certificate::kUnique, Certificate::kDegenerate, Certificate::kNonUnique,
                        Certificate::kNoneFound, Certificate::kIsolated}) {
    if (ToString(c) == text) return c;
  }
  return std::nullopt;
}

std::string_view ToString(Verdict verdict) {
  switch (verdict) {
    case Verdict::kSolved:
      return "solved";
    case Verdict::kCorrectlyRefused:
      return "correctly refused";
    case Verdict::kFailed:
      return "failed";
    case Verdict::kWronglyClaimed:
      return "WRONGLY CLAIMED";
    case Verdict::kInaccurate:
      return "INACCURATE";
    case Verdict::kWronglyRefused:
      return "WRONGLY REFUSED";
  }
  return "?";
}

std::optional<Verdict> VerdictFromString(std::string_view text) {
  for (const Verdict v : {Verdict::kSolved, Verdict::kCorrectlyRefused, Verdict::kFailed, Verdict::kWronglyClaimed,
                          Verdict::kInaccurate, Verdict::kWronglyRefused}) {
    if (ToString(v) == text) return v;
  }
  return std::nullopt;
}

double ForwardErrorAllowance(const ReferenceSolution& reference, double tolerance) {
  const double z_norm = reference.z.size() ? reference.z.cwiseAbs().maxCoeff() : 0.0;
  return kForwardErrorFactor * std::max(1.0, reference.condition) * tolerance * (1.0 + z_norm);
}

namespace {
// The verdict from what Judge and JudgeMCP computed: the status, what is known of the problem, whether the returned z
// passes the residual test of its problem type, and the forward error against its allowance (NaN: not judged).
Verdict Classify(SolveStatus status, ExpectedOutcome expected, bool known_solvable, bool residuals_pass,
                 const Judgement& j) {
  if (status == SolveStatus::kSolved) {
    if (expected == ExpectedOutcome::kInfeasible || !residuals_pass) return Verdict::kWronglyClaimed;
    if (j.forward_allowance == j.forward_allowance && !(j.forward_error <= j.forward_allowance)) {
      return Verdict::kInaccurate;
    }
    return Verdict::kSolved;
  }
  if (status == SolveStatus::kInfeasible && known_solvable) return Verdict::kWronglyRefused;
  return expected == ExpectedOutcome::kInfeasible ? Verdict::kCorrectlyRefused : Verdict::kFailed;
}
}  // namespace

Judgement Judge(const BoxMLCP& problem, ExpectedOutcome expected, const ReferenceSolution* reference,
                SolveStatus status, const Vector& z, double tolerance) {
  Judgement j;
  const bool has_z = z.size() == problem.size();
  if (has_z) {
    Vector w;
    j.residual = problem.NaturalResidual(z, &w);
    if (reference != nullptr && reference->unique() && reference->z.size() == z.size()) {
      j.forward_error = (z - reference->z).cwiseAbs().maxCoeff();
      if (!(j.forward_error >= 0.0)) j.forward_error = kInf;  // NaN in z
      j.forward_error_rel = j.forward_error / std::max(1.0, reference->z.cwiseAbs().maxCoeff());
      j.forward_allowance = ForwardErrorAllowance(*reference, tolerance);
    }
  }
  const bool known_solvable =
      expected == ExpectedOutcome::kSolvable || (reference != nullptr && reference->verified());
  j.verdict = Classify(status, expected, known_solvable,
                       has_z && PassesBoxMlcpTolerance(j.residual, tolerance), j);
  return j;
}

namespace {
// max_i |x_i| / c_i (c empty: 1): a length in the variables' units (MCP::variable_scale).
double NormInUnits(const Vector& x, const Vector& c) {
  double m = 0.0;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    const double a = std::abs(x[i]) / (c.size() == x.size() ? c[i] : 1.0);
    if (!(a <= kInf)) return kInf;  // NaN
    m = std::max(m, a);
  }
  return m;
}
}  // namespace

Judgement JudgeMCP(const MCP& problem, ExpectedOutcome expected, const std::vector<ReferenceSolution>& references,
                   bool references_complete, SolveStatus status, const Vector& z, double tolerance) {
  Judgement j;
  const bool has_z = z.size() == problem.size();
  const Vector& c = problem.variable_scale();
  if (has_z) {
    Vector F;
    internal::McpMeritWorkspace workspace;
    std::string why;
    internal::McpMerit(problem, z, &F, &workspace, &j.residual, &why);  // on failure the residual stays +∞: not solved
    // The reference the answer is judged against: the nearest verified one when every solution is listed, else the
    // one certified unique.
    const ReferenceSolution* reference = nullptr;
    double nearest = kInf;
    for (const ReferenceSolution& candidate : references) {
      if (candidate.z.size() != z.size()) continue;
      if (references_complete ? candidate.verified() : candidate.unique()) {
        const double error = NormInUnits(z - candidate.z, c);
        if (reference == nullptr || error < nearest) {
          reference = &candidate;
          nearest = error;
        }
        if (!references_complete) break;
      }
    }
    if (reference != nullptr) {
      // ForwardErrorAllowance measured in the variables' units: with c = 1 it is exactly the box's.
      const double z_star_norm = NormInUnits(reference->z, c);
      j.forward_error = nearest;
      j.forward_error_rel = nearest / std::max(1.0, z_star_norm);
      j.forward_allowance =
          kForwardErrorFactor * std::max(1.0, reference->condition) * tolerance * (1.0 + z_star_norm);
    }
  }
  bool known_solvable = expected == ExpectedOutcome::kSolvable;
  for (const ReferenceSolution& reference : references) known_solvable = known_solvable || reference.verified();
  j.verdict = Classify(status, expected, known_solvable, has_z && PassesMcpTolerance(j.residual, tolerance), j);
  return j;
}

}  // namespace smcbench

#include "solvers/avi/avi_verdict.h"

#include <algorithm>
#include <cmath>

namespace smcbench {
namespace {

double InfNorm(const Vector& v) { return v.size() ? v.cwiseAbs().maxCoeff() : 0.0; }

bool SizesFit(const AffineVI& avi, const AviSolution& s) {
  return s.lambda.size() == avi.size() && (s.mu.size() == 0 || s.mu.size() == avi.inequality_count()) &&
         (s.nu.size() == 0 || s.nu.size() == avi.equality_count());
}

}  // namespace

AviReference CertifyAvi(const AffineVI& avi, const std::vector<AviSolution>& candidates,
                        const CertifyOptions& options) {
  AviReference out;
  out.strictly_monotone = ClassifySymmetricPartPositiveDefinite(avi.M()).answer;
  const AviReduction reduction = ReduceToBoxMlcp(avi, AviReductionScaling::kNormalized);
  std::vector<Vector> points;
  for (const AviSolution& c : candidates) {
    if (SizesFit(avi, c)) points.push_back(JoinReducedSolution(reduction, c));
  }
  CertifyOptions certify = options;
  // With constraint rows the reduced matrix has a zero diagonal block: not a P-matrix, no need to test it.
  if (!certify.p_matrix && avi.inequality_count() + avi.equality_count() > 0) certify.p_matrix = false;
  out.reduced = Certify(reduction.problem, points, certify);
  if (out.reduced.verified()) {
    out.solution = SplitReducedSolution(reduction, out.reduced.z);
    out.lambda_unique = out.strictly_monotone == MatrixClassAnswer::kYes || out.reduced.unique();
  }
  return out;
}

AviFaceResidual ComputeAviFaceResidual(const AviReduction& reduction, const Vector& z) {
  const int n = reduction.n, m = reduction.m, p = reduction.p;
  const DenseMatrix& reduced_matrix = reduction.problem.dense_matrix();
  const Vector& reduced_q = reduction.problem.q();
  double infeasibility = 0.0, complementarity = 0.0, lambda_norm = 0.0;
  bool finite = true;
  for (int j = 0; j < n; ++j) {
    lambda_norm = std::max(lambda_norm, std::abs(z[j]));
    finite = finite && std::isfinite(z[j]);
  }
  const auto row_times_lambda = [&](int row) {  // H̃_iλ or Ẽ_jλ: the first n columns of the reduced row
    double sum = 0.0;
    for (int j = 0; j < n; ++j) sum += reduced_matrix(row, j) * z[j];
    return sum;
  };
  for (int i = 0; i < m; ++i) {  // row n + i of the reduction: H̃_iλ − K̃_i, its multiplier z[n + i] = μ̃_i
    const double slack = row_times_lambda(n + i) + reduced_q[n + i];
    infeasibility = std::max(infeasibility, -slack);
    complementarity = std::max(complementarity, std::abs(std::min(z[n + i], slack)));
    finite = finite && std::isfinite(z[n + i]) && std::isfinite(slack);
  }
  for (int j = 0; j < p; ++j) {
    const int row = n + m + j;
    const double violation = std::abs(row_times_lambda(row) + reduced_q[row]);
    infeasibility = std::max(infeasibility, violation);
    complementarity = std::max(complementarity, violation);
    finite = finite && std::isfinite(z[row]) && std::isfinite(violation);
  }
  if (!finite) return {};
  return {infeasibility / (1.0 + lambda_norm), complementarity / (1.0 + lambda_norm)};
}

ExpectedOutcome ExpectedAviOutcome(const AffineVI& avi) {
  return avi.boundedness() == PolytopeBoundedness::kBounded ? ExpectedOutcome::kSolvable : ExpectedOutcome::kUnknown;
}

AviJudgement JudgeAvi(const AffineVI& avi, ExpectedOutcome expected, const AviReference* reference,
                      SolveStatus status, const AviSolution& answer, double tolerance) {
  AviJudgement out;
  const bool known_solvable =
      expected == ExpectedOutcome::kSolvable || (reference != nullptr && reference->verified());
  if (status == SolveStatus::kInfeasible) {
    out.verdict = known_solvable ? Verdict::kWronglyRefused
                                 : (expected == ExpectedOutcome::kInfeasible ? Verdict::kCorrectlyRefused
                                                                             : Verdict::kFailed);
  } else if (status != SolveStatus::kSolved) {
    out.verdict = expected == ExpectedOutcome::kInfeasible ? Verdict::kCorrectlyRefused : Verdict::kFailed;
  }
  if (!SizesFit(avi, answer)) {
    if (status == SolveStatus::kSolved) out.verdict = Verdict::kWronglyClaimed;
    return out;
  }
  const AviReduction reduction = ReduceToBoxMlcp(avi, AviReductionScaling::kNormalized);
  const Vector z = JoinReducedSolution(reduction, answer);
  // The box verdict on the reduction: its residual rule and its handling of the expected outcome.
  const Judgement box = Judge(reduction.problem, expected, nullptr, status, z, tolerance);
  out.residual = box.residual;
  const AviFaceResidual face = ComputeAviFaceResidual(reduction, z);
  out.primal_infeasibility = face.primal_infeasibility;
  out.complementarity = face.complementarity;
  const Vector& lambda = answer.lambda;
  if (status == SolveStatus::kSolved) {
    out.verdict = box.verdict;
    if (out.verdict == Verdict::kSolved && !PassesAviTolerance(out, tolerance)) out.verdict = Verdict::kWronglyClaimed;
  }
  if (reference != nullptr && reference->verified() && reference->lambda_unique) {
    const Vector& star = reference->solution.lambda;
    out.forward_error_applicable = true;
    out.forward_error = (lambda - star).cwiseAbs().maxCoeff();
    if (std::isnan(out.forward_error)) out.forward_error = kInf;
    out.forward_error_rel = out.forward_error / std::max(1.0, InfNorm(star));
    out.forward_allowance =
        kForwardErrorFactor * std::max(1.0, reference->reduced.condition) * tolerance * (1.0 + InfNorm(star));
    if (out.verdict == Verdict::kSolved && !(out.forward_error <= out.forward_allowance)) {
      out.verdict = Verdict::kInaccurate;
    }
  }
  return out;
}

}  // namespace smcbench

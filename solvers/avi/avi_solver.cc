#include "solvers/avi/avi_solver.h"

#include <chrono>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace smcbench {

namespace {

// Rows within this distance of their bound (in units of λ, relative to 1 + ‖λ‖∞) may carry a multiplier.
constexpr double kActiveRowTolerance = 1e-9;

// Least squares for the multipliers of the rows in `active` (indices into H) and of every row of E.
void SolveMultipliers(const AffineVI& avi, const std::vector<int>& active, const Vector& target, AviSolution* out) {
  const int n = avi.size(), k = static_cast<int>(active.size()), p = avi.equality_count();
  DenseMatrix A(n, k + p);
  for (int c = 0; c < k; ++c) A.col(c) = avi.H().row(active[static_cast<std::size_t>(c)]).transpose();
  if (p > 0) A.rightCols(p) = avi.E().transpose();
  out->mu = Vector::Zero(avi.inequality_count());
  out->nu = Vector::Zero(p);
  if (k + p == 0) return;
  const Vector x = A.colPivHouseholderQr().solve(target);
  for (int c = 0; c < k; ++c) out->mu[active[static_cast<std::size_t>(c)]] = x[c];
  out->nu = x.tail(p);
}

// The AVI's rule for "solved" (PassesAviTolerance) on a backend's claim: the box rule its Solve applied to the
// reduction does not see λ leave its face by tol·‖μ̃‖∞ (avi_verdict.h, AviJudgement::complementarity).
void ApplyAviRule(const AffineVI& avi, double tolerance, const AviSolution& solution, SolveResult* result) {
  if (result->status != SolveStatus::kSolved) return;
  const AviJudgement j = JudgeAvi(avi, ExpectedOutcome::kUnknown, nullptr, SolveStatus::kSolved, solution, tolerance);
  if (PassesAviTolerance(j, tolerance)) return;
  result->status = SolveStatus::kInaccurate;
  result->message = "the backend reported success but the AVI residual is above the tolerance " +
                    std::to_string(tolerance) + " (normalized reduction: " + std::to_string(j.residual.rel) +
                    " relative, " + std::to_string(j.residual.scaled) + " scaled; complementarity in units of λ " +
                    std::to_string(j.complementarity) + ")";
}

// The shared work after a DirectAviBackend: multipliers, the merit function of the normalized reduction at the
// answer (into result's z, w and residuals), the rule for "solved".
void ConcludeDirect(const AffineVI& avi, const AviReduction& reduction, const SolverOptions& options,
                    AviSolution* solution, SolveResult* result) {
  const int total = reduction.n + reduction.m + reduction.p;
  if (solution->lambda.size() != avi.size() || !solution->lambda.allFinite()) {
    if (result->status == SolveStatus::kSolved) {
      result->status = SolveStatus::kNumericalFailure;
      result->message = "the backend returned a λ of the wrong size or with non-finite entries";
    }
    return;
  }
  if (solution->mu.size() != avi.inequality_count() || solution->nu.size() != avi.equality_count()) {
    *solution = AviMultipliersAt(avi, solution->lambda);
  }
  result->z = JoinReducedSolution(reduction, *solution);
  result->w.resize(total);
  const Residual r = reduction.problem.NaturalResidual(result->z, &result->w);
  result->residual_abs = r.abs;
  result->residual_rel = r.rel;
  result->residual_scaled = r.scaled;
  ApplyAviRule(avi, options.tolerance, *solution, result);
}

// options with its warm start (empty, λ alone, or (λ, μ, ν) as stated) in the reduction's units z = (λ, μ̃, ν̃); any
// other size is left for the backend to report (kInvalidOptions), as Solver::Solve does.
SolverOptions ReducedOptions(const AviReduction& reduction, const SolverOptions& options) {
  const int n = reduction.n, total = n + reduction.m + reduction.p;
  SolverOptions reduced = options;
  const Vector& w = options.warm_start;
  if (w.size() == n && total != n) {
    reduced.warm_start = JoinReducedSolution(reduction, {w, {}, {}});
  } else if (w.size() == total) {
    reduced.warm_start = JoinReducedSolution(reduction, {w.head(n), w.segment(n, reduction.m), w.tail(reduction.p)});
  }
  return reduced;
}

}  // namespace

AviSolution AviMultipliersAt(const AffineVI& avi, const Vector& lambda) {
  const int m = avi.inequality_count();
  AviSolution out;
  out.lambda = lambda;
  const Vector target = avi.M() * lambda + avi.q();
  const double threshold = kActiveRowTolerance * (1.0 + lambda.cwiseAbs().maxCoeff());
  std::vector<int> active;
  for (int i = 0; i < m; ++i) {
    const double scale = avi.H().row(i).cwiseAbs().maxCoeff();
    if ((avi.H().row(i).dot(lambda) - avi.K()[i]) / scale <= threshold) active.push_back(i);
  }
  SolveMultipliers(avi, active, target, &out);
  const double mu_scale = 1.0 + (m ? out.mu.cwiseAbs().maxCoeff() : 0.0);
  if (m == 0 || out.mu.minCoeff() >= -kActiveRowTolerance * mu_scale) {
    out.mu = out.mu.cwiseMax(0.0);
    return out;
  }
  // A nonnegative choice: μ_A ≥ 0 with H_Aᵀμ_A + Eᵀν = Mλ + q (ν = ν⁺ − ν⁻ through the free variables of the
  // simplex), then least squares again on its support for full precision.
  const int k = static_cast<int>(active.size()), p = avi.equality_count(), n = avi.size();
  DenseMatrix G = DenseMatrix::Zero(k, k + p);  // μ_A ≥ 0 (ν unconstrained)
  for (int c = 0; c < k; ++c) G(c, c) = 1.0;
  DenseMatrix stationarity(n, k + p);
  for (int c = 0; c < k; ++c) stationarity.col(c) = avi.H().row(active[static_cast<std::size_t>(c)]).transpose();
  if (p > 0) stationarity.rightCols(p) = avi.E().transpose();
  std::vector<int> rows;  // FindPolytopePoint needs nonzero rows
  for (int j = 0; j < n; ++j) {
    if (stationarity.row(j).cwiseAbs().maxCoeff() > 0.0) rows.push_back(j);
  }
  DenseMatrix E(static_cast<Eigen::Index>(rows.size()), k + p);
  Vector f(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    E.row(static_cast<Eigen::Index>(r)) = stationarity.row(rows[r]);
    f[static_cast<Eigen::Index>(r)] = target[rows[r]];
  }
  const PolytopePoint point = FindPolytopePoint(G, Vector::Zero(k), E, f);
  if (!point.found) return out;
  std::vector<int> support;
  for (int c = 0; c < k; ++c) {
    if (point.point[c] > 0.0) support.push_back(active[static_cast<std::size_t>(c)]);
  }
  SolveMultipliers(avi, support, target, &out);
  out.mu = out.mu.cwiseMax(0.0);
  return out;
}

AviResult SolveAvi(const AffineVI& avi, Solver& solver, const SolverOptions& options, const AviReference* reference) {
  AviResult out;
  const AviReduction reduction = ReduceToBoxMlcp(avi, AviReductionScaling::kNormalized);
  if (auto* direct = dynamic_cast<DirectAviBackend*>(&solver)) {
    out.reduced.Reset();
    out.reduced.solver = solver.info().name;
    std::string why;
    if (!options.IsValid(&why)) {
      out.reduced.status = SolveStatus::kInvalidOptions;
      out.reduced.message = why;
    } else {
      const auto start = std::chrono::steady_clock::now();
      direct->SolveAviDirect(avi, options, &out.solution, &out.reduced);
      ConcludeDirect(avi, reduction, options, &out.solution, &out.reduced);
      if (options.measure_time) {
        out.reduced.solve_seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      }
    }
    out.status = out.reduced.status;
    out.message = out.reduced.message;
    out.solver = out.reduced.solver;
    out.iterations = out.reduced.iterations;
    out.solve_seconds = out.reduced.solve_seconds;
    out.judgement = JudgeAvi(avi, ExpectedAviOutcome(avi), reference, out.status, out.solution, options.tolerance);
    return out;
  }
  const int total = reduction.n + reduction.m + reduction.p;
  solver.Solve(reduction.problem, ReducedOptions(reduction, options), &out.reduced);
  if (out.reduced.z.size() == total) out.solution = SplitReducedSolution(reduction, out.reduced.z);
  ApplyAviRule(avi, options.tolerance, out.solution, &out.reduced);
  out.status = out.reduced.status;
  out.message = out.reduced.message;
  out.solver = out.reduced.solver;
  out.iterations = out.reduced.iterations;
  out.solve_seconds = out.reduced.solve_seconds;
  out.judgement = JudgeAvi(avi, ExpectedAviOutcome(avi), reference, out.status, out.solution, options.tolerance);
  return out;
}

AviSession::AviSession(const AffineVI& avi, Solver& solver, const SolverOptions& options,
                       const SessionOptions& session)
    : reduction_(ReduceToBoxMlcp(avi, AviReductionScaling::kNormalized)),
      options_(ReducedOptions(reduction_, options)),
      session_(solver.Prepare(reduction_.problem, options_, session)),
      reduced_q_(reduction_.problem.q()),
      warm_z_(Vector::Zero(reduction_.n + reduction_.m + reduction_.p)) {
  solution_.lambda.resize(reduction_.n);
  solution_.mu.resize(reduction_.m);
  solution_.nu.resize(reduction_.p);
}

void AviSession::MapWarmStart(const AviSolution& warm_start) {
  const int n = reduction_.n, m = reduction_.m, p = reduction_.p;
  const auto check = [](const char* field, const Vector& v, int size, bool may_be_empty) {
    if (v.size() == size || (may_be_empty && v.size() == 0)) return;
    throw InvalidInputError("AviSession: warm_start." + std::string(field) + " has size " + std::to_string(v.size()) +
                            " but the AVI has " + std::to_string(size));
  };
  check("lambda", warm_start.lambda, n, false);
  check("mu", warm_start.mu, m, true);
  check("nu", warm_start.nu, p, true);
  // JoinReducedSolution's map (μ̃ = μ h/σ, ν̃ = ν e/σ), into the session's buffer.
  const bool has_mu = warm_start.mu.size() > 0, has_nu = warm_start.nu.size() > 0;
  for (int j = 0; j < n; ++j) warm_z_[j] = warm_start.lambda[j];
  for (int i = 0; i < m; ++i) {
    warm_z_[n + i] = has_mu ? warm_start.mu[i] * reduction_.inequality_scale[i] / reduction_.sigma : 0.0;
  }
  for (int j = 0; j < p; ++j) {
    warm_z_[n + m + j] = has_nu ? warm_start.nu[j] * reduction_.equality_scale[j] / reduction_.sigma : 0.0;
  }
}

SolveStatus AviSession::Solve(const Eigen::Ref<const Vector>& q, const AviSolution* warm_start) {
  const int n = reduction_.n, m = reduction_.m, p = reduction_.p;
  if (q.size() != n) {
    throw InvalidInputError("AviSession: q has size " + std::to_string(q.size()) + " but the AVI has n = " +
                            std::to_string(n));
  }
  for (int j = 0; j < n; ++j) {
    if (!std::isfinite(q[j])) {
      throw InvalidInputError("AviSession: q[" + std::to_string(j) + "] is " + (std::isnan(q[j]) ? "NaN" : "infinite"));
    }
    reduced_q_[j] = q[j] / reduction_.sigma;  // a division, as ReduceToBoxMlcp: the same bits
  }
  // Read before the solve overwrites solution_ (the usual warm start is the previous solution()).
  if (warm_start != nullptr) MapWarmStart(*warm_start);
  const Vector* warm_z = warm_start != nullptr ? &warm_z_ : nullptr;
  reduction_.problem.set_q(reduced_q_);  // reduction(): the problem as solved (a StepObserver reads it)
  session_.Solve(reduced_q_, &result_, warm_z);
  const bool reused = SessionPathOf(result_) == SessionPath::kReusedActiveSet;
  if (result_.z.size() != n + m + p) return result_.status;
  // The box rule holds for a solved z (Solver::Solve, or the session's reuse test); the AVI's own part, without
  // allocating.
  if (result_.status == SolveStatus::kSolved) {
    AviFaceResidual face = ComputeAviFaceResidual(reduction_, result_.z);
    if (reused && !(face.complementarity <= options_.tolerance && face.primal_infeasibility <= options_.tolerance)) {
      // The last active set passed the box rule but not the AVI's: let the backend solve this q afresh (rare).
      session_.ForgetWarmState();
      session_.Solve(reduced_q_, &result_, warm_z);
      if (result_.z.size() != n + m + p) return result_.status;
      face = ComputeAviFaceResidual(reduction_, result_.z);
    }
    if (result_.status == SolveStatus::kSolved &&
        !(face.complementarity <= options_.tolerance && face.primal_infeasibility <= options_.tolerance)) {
      result_.status = SolveStatus::kInaccurate;
      result_.message = "the backend reported success but the complementarity in units of λ is " +
                        std::to_string(face.complementarity) + " > " + std::to_string(options_.tolerance);
    }
  }
  const Vector& z = result_.z;
  solution_.lambda = z.head(n);
  solution_.mu = reduction_.sigma * z.segment(n, m).cwiseQuotient(reduction_.inequality_scale);
  solution_.nu = reduction_.sigma * z.tail(p).cwiseQuotient(reduction_.equality_scale);
  return result_.status;
}

}  // namespace smcbench

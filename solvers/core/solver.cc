#include "solvers/core/solver.h"

#include <cstdio>
#include <sstream>

namespace smcbench {

bool Solver::Prepare(int n, const Vector& l, const Vector& u, const SolverOptions& options, SolveResult* result) {
  result->Reset();
  result->solver = info().name;
  if (result->z.size() != n) result->z.resize(n);
  if (result->w.size() != n) result->w.resize(n);
  std::string why;
  if (!options.IsValid(&why) || !ValidateBackendOptions(&why)) {
    result->status = SolveStatus::kInvalidOptions;
    result->message = std::move(why);
    result->z.setZero();
    return false;
  }
  if (options.warm_start.size() != 0 && options.warm_start.size() != n) {
    result->status = SolveStatus::kInvalidOptions;
    result->message = "warm_start has size " + std::to_string(options.warm_start.size()) +
                      " but the problem has " + std::to_string(n) + " unknowns";
    result->z.setZero();
    return false;
  }
  if (options.warm_start.size() == n) {
    result->z = options.warm_start;
  } else {
    for (int i = 0; i < n; ++i) result->z[i] = std::min(std::max(0.0, l[i]), u[i]);
  }
  has_deadline_ = options.time_limit_seconds < kInf;
  if (has_deadline_) {
    deadline_ = std::chrono::steady_clock::now() +
                std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                    std::chrono::duration<double>(options.time_limit_seconds));
  }
  return true;
}

void Solver::Finish(double tolerance, std::chrono::steady_clock::time_point start, SolveResult* result) {
  using Clock = std::chrono::steady_clock;
  if (result->status == SolveStatus::kSolved && !(result->residual_rel <= tolerance)) {
    // The rule: the merit function, not the backend, decides what "solved" means.
    std::ostringstream s;
    s << "backend reported success but the natural residual is " << result->residual_rel << " (relative) > "
      << tolerance;
    result->status = SolveStatus::kInaccurate;
    result->message = s.str();
  }
  if (result->status == SolveStatus::kNotRun) {
    result->status = SolveStatus::kNumericalFailure;
    result->message = "backend returned without setting a status";
  }
  result->solve_seconds = start == Clock::time_point{} ? 0.0 : std::chrono::duration<double>(Clock::now() - start).count();
}

namespace {
std::chrono::steady_clock::time_point StartClock(const SolverOptions& options) {
  return options.measure_time ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
}
}  // namespace

void Solver::Solve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) {
  const auto start = StartClock(options);
  const SolverInfo& solver_info = info();
  if (Prepare(problem.size(), problem.l(), problem.u(), options, result)) {
    if (problem.is_sparse() && !solver_info.sparse) {
      // A dense-only backend gets a dense copy (allocates per solve; sparse inputs are not its hot path),
      // unless the copy would be unreasonably large.
      if (problem.size() > kMaxDensifiedSize) {
        result->status = SolveStatus::kNotApplicable;
        result->message = "backend accepts dense M only and n = " + std::to_string(problem.size()) + " > " +
                          std::to_string(kMaxDensifiedSize) + " is too large to densify";
      } else {
        const BoxMLCP dense(problem.ToDense(), problem.q(), problem.l(), problem.u(), problem.name());
        DoSolve(dense, options, result);
        result->SetDetail("densified", 1.0);
      }
    } else if (solver_info.symmetric_only && !problem.IsSymmetric()) {
      result->status = SolveStatus::kNotApplicable;
      result->message = "backend requires symmetric M";
    } else {
      DoSolve(problem, options, result);
    }
  }
  const Residual r = problem.NaturalResidual(result->z, &result->w);
  result->residual_abs = r.abs;
  result->residual_rel = r.rel;
  Finish(options.tolerance, start, result);
}

void Solver::Solve(const MCP& problem, const SolverOptions& options, SolveResult* result) {
  const auto start = StartClock(options);
  const int n = problem.size();
  if (Prepare(n, problem.l(), problem.u(), options, result)) {
    if (!info().mcp) {
      result->status = SolveStatus::kNotApplicable;
      result->message = "backend does not solve nonlinear MCPs";
    } else {
      DoSolveMCP(problem, options, result);
    }
  }
  // Relative scale of an MCP: 1 + ‖F(Π(0))‖∞, the box-MLCP's 1 + ‖q‖∞ when 0 is feasible.
  Vector& F = result->w;
  if (scale_point_.size() != n) scale_point_.resize(n);
  for (int i = 0; i < n; ++i) scale_point_[i] = std::min(std::max(0.0, problem.l()[i]), problem.u()[i]);
  problem.Evaluate(scale_point_, &F);
  const double scale = 1.0 + (F.size() ? F.cwiseAbs().maxCoeff() : 0.0);
  const Residual r = problem.NaturalResidual(result->z, &F, std::isfinite(scale) ? scale : 1.0);
  result->residual_abs = r.abs;
  result->residual_rel = r.rel;
  Finish(options.tolerance, start, result);
}

SolveResult Solver::Solve(const BoxMLCP& problem, const SolverOptions& options) {
  SolveResult result;
  Solve(problem, options, &result);
  return result;
}

SolveResult Solver::Solve(const MCP& problem, const SolverOptions& options) {
  SolveResult result;
  Solve(problem, options, &result);
  return result;
}

void Solver::DoSolveMCP(const MCP&, const SolverOptions&, SolveResult* result) {
  result->status = SolveStatus::kNotApplicable;
  result->message = "backend does not solve nonlinear MCPs";
}

void Solver::BindOptions(OptionBinder*) {}

bool Solver::ValidateBackendOptions(std::string*) const { return true; }

bool Solver::SetOption(std::string_view name, std::string_view value, std::string* error) {
  OptionBinder binder;
  BindOptions(&binder);
  const std::string previous = binder.ValueText(name);
  if (!binder.Set(name, value, error)) return false;
  std::string why;
  if (!ValidateBackendOptions(&why)) {
    // A rejected value is never kept: the backend stays exactly as it was.
    std::string ignored;
    binder.Set(name, previous, &ignored);
    *error = "invalid value for option '" + std::string(name) + "': " + why;
    return false;
  }
  return true;
}

std::string Solver::OptionsHelp() {
  OptionBinder binder;
  BindOptions(&binder);
  return binder.Help();
}

bool Solver::TimeLimitReached() const {
  return has_deadline_ && std::chrono::steady_clock::now() >= deadline_;
}

}  // namespace smcbench

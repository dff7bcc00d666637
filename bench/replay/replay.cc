#include "bench/replay/replay.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "bench/replay/sample_times.h"
#include "solvers/registry/backend_settings.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

std::string JoinTags(const std::vector<std::string>& tags) {
  std::string out;
  for (const auto& t : tags) out += (out.empty() ? "" : ",") + t;
  return out;
}

ReplayRecord Describe(const ProblemSet& set, const LibraryProblem& p, std::string_view solver) {
  ReplayRecord r;
  r.suite = set.name;
  r.problem = p.id;
  r.solver = std::string(solver);
  r.size = p.size();
  r.sparse = p.sparse();
  r.tags = JoinTags(p.tags);
  r.expected = p.expected;
  return r;
}

// The verdict and the numbers it rests on: residuals recomputed from z by Judge (never the backend's own claim),
// the forward error against the problem's certified reference where that proves z* unique.
void Fill(const LibraryProblem& p, const SolveResult& result, double tolerance, ReplayRecord* r) {
  const Judgement j = Judge(p, result.status, result.z, tolerance);
  const bool has_z = result.z.size() == p.size();
  r->status = result.status;
  r->message = result.message;
  r->iterations = result.iterations;
  r->residual_abs = has_z ? j.residual.abs : result.residual_abs;
  r->residual_rel = has_z ? j.residual.rel : result.residual_rel;
  r->residual_scaled = has_z ? j.residual.scaled : result.residual_scaled;
  r->forward_error = j.forward_error;
  r->forward_error_rel = j.forward_error_rel;
  r->forward_allowance = j.forward_allowance;
  r->certificate = std::string(ToString(p.reference.certificate));
  r->reference_radius = p.reference.proved_radius;
  r->reference_proved_unique = p.reference.proved_unique;
  r->tolerance = tolerance;
  r->verdict = j.verdict;
  r->backend_code = result.backend_code;
}

}  // namespace

std::vector<std::size_t> SweepProblemIndices(std::size_t problems, int sweep_problems) {
  std::vector<std::size_t> out;
  if (sweep_problems <= 0) return out;
  const std::size_t n = std::min(problems, static_cast<std::size_t>(sweep_problems));
  for (std::size_t i = 0; i < n; ++i) out.push_back(n == problems ? i : (2 * i + 1) * problems / (2 * n));
  return out;
}

void TimeSolves(Solver* solver, const BoxMLCP& problem, const SolverOptions& options, const ReplayOptions& replay,
                SolveResult* result, ReplayRecord* record) {
  SessionOptions session_options;
  session_options.reuse_active_set = replay.reuse_active_set;
  SolveSession session = solver->Prepare(problem, options, session_options);
  const Eigen::Ref<const Vector> q = problem.q();
  const auto solve = [&] { session.Solve(q, result); };
  if (replay.reuse_active_set) {  // warm by request: the repeats may be answered by the reused active set
    replay_internal::SampleSolveTimes(solve, result, replay, record);
    if (record->mode == "cold") record->mode = "cached";
    return;
  }
  replay_internal::SampleSolveTimes(solve, result, replay, record, [&] { return session.ForgetWarmState(); });
}

std::vector<std::unique_ptr<Solver>> CreateReplaySolvers(const ReplayOptions& options,
                                                         std::vector<std::string>* names) {
  if (names->empty()) {
    for (auto n : SolverNames()) names->emplace_back(n);
  }
  std::vector<std::unique_ptr<Solver>> solvers;
  for (const auto& n : *names) solvers.push_back(CreateSolver(n));  // unknown: InvalidInputError listing names
  try {
    ApplyBackendSettings(options.settings, solvers);  // the one --set parser: solvers/registry/backend_settings.h
  } catch (const InvalidInputError& e) {
    throw InvalidInputError(std::string("bench: ") + e.what());
  }
  if (!(options.tolerance > 0.0) || !(options.time_limit_seconds > 0.0) || options.repetitions < 1 ||
      !(options.min_sample_seconds >= 0.0) || !(options.max_seconds_per_pair > 0.0)) {
    throw InvalidInputError("bench: tolerance, time limit, repetitions and sample times must be positive");
  }
  return solvers;
}

std::vector<std::string> BackendsWith(const std::vector<std::string>& names, bool SolverInfo::*capability) {
  std::vector<std::string> all = names;
  if (all.empty()) {
    for (auto n : SolverNames()) all.emplace_back(n);
  }
  std::vector<std::string> out;
  for (const std::string& n : all) {
    if (CreateSolver(n)->info().*capability) out.push_back(n);
  }
  return out;
}

SolverOptions ReplaySolverOptions(const ReplayOptions& options, double tolerance) {
  SolverOptions o;
  o.tolerance = tolerance;
  o.time_limit_seconds = options.time_limit_seconds;
  o.measure_time = false;
  o.polish = options.polish;
  return o;
}

ReplayRecord ReplayOne(const ProblemSet& set, const LibraryProblem& p, Solver* solver, const std::string& solver_name,
                       const ReplayOptions& options, const std::string& mode, double tolerance) {
  const SolverOptions o = ReplaySolverOptions(options, tolerance);
  ReplayRecord r = Describe(set, p, solver_name);
  r.mode = mode;
  ReplayOptions timing = options;
  if (mode == "sweep") timing.repetitions = std::min(options.repetitions, 3);
  SolveResult result;
  TimeSolves(solver, p.problem, o, timing, &result, &r);
  Fill(p, result, tolerance, &r);
  return r;
}

}  // namespace smcbench

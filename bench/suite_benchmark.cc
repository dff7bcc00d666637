// The replay suites of `smcbench bench` as Google Benchmark benchmarks: one per problem × backend, named
// "suite/<problem id>/<backend>", so --benchmark_filter, repetitions and the standard JSON output apply to exactly
// the problems the report is about (built as `smcbench bench` builds them, certified references attached). Cold
// start, tolerance 1e-10, judged by the one verdict (solvers/core/verdict.h): a wrong answer (wrongly claimed,
// inaccurate, wrongly refused) or a failure is reported as an error (never as a fast time); a correct refusal of
// a problem whose expected outcome is "infeasible" is the right answer and is timed.
// Suites: SMCBENCH_SUITES (comma-separated names `smcbench bench --suite` takes: paper, families, hard, siconos,
// scale, tiny or a .smcps file; default "paper,families,hard"; "siconos" and "hard" read SMCBENCH_SICONOS_DIR,
// default the checkout's tests/data/siconos: problems/io/data_dirs.h).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "solvers/registry/registry.h"
#include "problems/suites/catalogue.h"

namespace smcbench {
namespace {

std::vector<std::unique_ptr<ProblemSet>>& Sets() {
  static std::vector<std::unique_ptr<ProblemSet>> sets;  // kept alive for the benchmarks' lifetime
  return sets;
}

void SolveBenchmark(benchmark::State& state, const LibraryProblem* problem, std::string solver_name) {
  auto solver = CreateSolver(solver_name);
  SolverOptions options;
  options.tolerance = 1e-10;
  options.time_limit_seconds = 10;
  options.measure_time = false;
  // Through a cold session, as the replay engine times (bench/replay/replay.h): the backend's own algorithm per call.
  SessionOptions cold;
  cold.reuse_active_set = false;
  SolveSession session = solver->Prepare(problem->problem, options, cold);
  const Vector& q = problem->problem.q();
  SolveResult result;
  session.Solve(q, &result);  // warm-up sizes the workspace
  const Judgement judgement = Judge(*problem, result.status, result.z, options.tolerance);
  if (IsWrong(judgement.verdict) || judgement.verdict == Verdict::kFailed) {
    state.SkipWithError(
        (std::string(ToString(judgement.verdict)) + ": " + std::string(ToString(result.status))).c_str());
    return;
  }
  for (auto _ : state) {
    session.Solve(q, &result);
    benchmark::DoNotOptimize(result.z.data());
    benchmark::ClobberMemory();
  }
  state.counters["iterations"] = result.iterations;
  state.counters["residual_rel"] = judgement.residual.rel;
  state.counters["residual_scaled"] = judgement.residual.scaled;
  // Only where the certified reference proves z* unique (a NaN counter would break the JSON output).
  if (!std::isnan(judgement.forward_error)) state.counters["forward_error"] = judgement.forward_error;
  state.counters["m"] = problem->size();
}

void RegisterAll() {
  const char* env = std::getenv("SMCBENCH_SUITES");
  const SuiteRequest request;  // its siconos_dir: $SMCBENCH_SICONOS_DIR, else this build's collection
  std::stringstream names(env ? env : "paper,families,hard");
  for (std::string name; std::getline(names, name, ',');) {
    Sets().push_back(std::make_unique<ProblemSet>(BuildSuite(name, request)));
  }
  for (const auto& set : Sets()) {
    for (const LibraryProblem& p : set->problems) {
      for (auto solver : SolverNames()) {
        const std::string bench_name = "suite/" + p.id + "/" + std::string(solver);
        benchmark::RegisterBenchmark(bench_name.c_str(), SolveBenchmark, &p, std::string(solver))
            ->Unit(benchmark::kNanosecond);
      }
    }
  }
}

}  // namespace
}  // namespace smcbench

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  try {
    smcbench::RegisterAll();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "suite_benchmark: %s\n", e.what());
    return 1;
  }
  benchmark::AddCustomContext("tolerance", "1e-10 on the relative and the row-equilibrated natural residual");
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

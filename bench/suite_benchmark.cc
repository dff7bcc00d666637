// The replay suites of `smcbench bench` as Google Benchmark benchmarks: one per problem × backend, named
// "suite/<problem id>/<backend>", so --benchmark_filter, repetitions and the standard JSON output apply to exactly
// the problems the report is about. Cold start, tolerance 1e-10; a solve that is not "solved" is reported as an
// error (never as a fast time), except on problems whose expected outcome is "infeasible", where the refusal is
// the right answer and is timed.
// Suites: SMCBENCH_SUITES (comma-separated: paper, families, hard, siconos, scale; default "paper,families,hard";
// "siconos" reads SMCBENCH_SICONOS_DIR, default ../shared/peer-data/siconos).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "problems/library/capture.h"
#include "problems/suites/families.h"
#include "problems/suites/hard_cases.h"
#include "solvers/registry/registry.h"
#include "tools/smcbench/bench_command.h"

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
  SolveResult result;
  solver->Solve(problem->problem, options, &result);  // warm-up sizes the workspace
  const Verdict verdict = Judge(*problem, result.status, result.z, options.tolerance).verdict;
  if (verdict != Verdict::kSolved && verdict != Verdict::kCorrectlyRefused) {
    state.SkipWithError((std::string(ToString(verdict)) + ": " + std::string(ToString(result.status))).c_str());
    return;
  }
  for (auto _ : state) {
    solver->Solve(problem->problem, options, &result);
    benchmark::DoNotOptimize(result.z.data());
    benchmark::ClobberMemory();
  }
  state.counters["iterations"] = result.iterations;
  state.counters["residual_rel"] = result.residual_rel;
  state.counters["m"] = problem->size();
}

void RegisterAll() {
  const char* env = std::getenv("SMCBENCH_SUITES");
  const char* dir = std::getenv("SMCBENCH_SICONOS_DIR");
  const std::string siconos_dir = dir ? dir : "../shared/peer-data/siconos";
  std::stringstream names(env ? env : "paper,families,hard");
  for (std::string name; std::getline(names, name, ',');) {
    if (name == "paper") {
      Sets().push_back(std::make_unique<ProblemSet>(CapturePaperSuite()));
    } else if (name == "families") {
      Sets().push_back(std::make_unique<ProblemSet>(FamiliesSuite()));
    } else if (name == "hard") {
      Sets().push_back(std::make_unique<ProblemSet>(HardSuite(siconos_dir)));
    } else if (name == "siconos") {
      Sets().push_back(std::make_unique<ProblemSet>(SiconosSuite(siconos_dir)));
    } else if (name == "scale") {
      Sets().push_back(std::make_unique<ProblemSet>(ScaleSuite()));
    } else {
      throw InvalidInputError("suite_benchmark: unknown suite '" + name + "' in SMCBENCH_SUITES");
    }
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
  benchmark::AddCustomContext("tolerance", "1e-10 relative natural residual");
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

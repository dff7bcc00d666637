// Times every backend on seeded random problems of size m = 1 … 1024 (SPD and nonsymmetric P-matrix; LCP and
// relay bounds), cold start, tolerance 1e-10. One benchmark per backend × family × bounds × size, with counters
// for iterations, both residuals (relative, row-equilibrated) and the forward error against the planted
// solution (these are P-matrix problems: the planted z* is the only solution); a solve that fails is reported as
// an error, never as a fast time.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <iterator>
#include <string>

#include "solvers/generators/random_problems.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

constexpr int kSizes[] = {1, 2, 4, 8, 16, 64, 256, 1024};

// The largest size a backend is timed at, from its capabilities: its size limit (enum refuses larger problems by
// design) and the size above which one solve takes seconds (SolverInfo::practical_size_limit: ipopt).
int MaxSize(const SolverInfo& info) {
  int max_size = kSizes[std::size(kSizes) - 1];
  if (info.default_size_limit > 0) max_size = std::min(max_size, info.default_size_limit);
  if (info.practical_size_limit > 0) max_size = std::min(max_size, info.practical_size_limit);
  return max_size;
}

void SolveBenchmark(benchmark::State& state, std::string solver_name, GeneratorOptions g) {
  const GeneratedProblem gen = GenerateProblem(g);
  auto solver = CreateSolver(solver_name);
  SolverOptions options;
  options.tolerance = 1e-10;
  options.time_limit_seconds = 60;
  SolveResult result;
  solver->Solve(gen.problem, options, &result);  // warm-up sizes the workspace
  if (!result.solved()) {
    state.SkipWithError((std::string(ToString(result.status)) + ": " + result.message).c_str());
    return;
  }
  for (auto _ : state) {
    solver->Solve(gen.problem, options, &result);
    benchmark::DoNotOptimize(result.z.data());
    benchmark::ClobberMemory();
  }
  if (!result.solved()) {
    state.SkipWithError((std::string(ToString(result.status)) + ": " + result.message).c_str());
    return;
  }
  state.counters["iterations"] = result.iterations;
  state.counters["residual_rel"] = result.residual_rel;
  state.counters["residual_scaled"] = result.residual_scaled;
  state.counters["forward_error"] = (result.z - gen.z_star).cwiseAbs().maxCoeff();
  state.counters["m"] = g.size;
}

// A prepared session (Solver::Prepare) solving the same problem again and again, the clock off (the benchmark
// times the loop): "cold" = the backend's algorithm from Π(0) every call (reuse off), "warm" = the previous
// answer's active set tried first (the default). What `smcbench solve --repeat N [--warm]` measures per call.
void SessionBenchmark(benchmark::State& state, std::string solver_name, GeneratorOptions g, bool warm) {
  const GeneratedProblem gen = GenerateProblem(g);
  auto solver = CreateSolver(solver_name);
  SolverOptions options;
  options.tolerance = 1e-10;
  options.measure_time = false;
  SessionOptions session_options;
  session_options.reuse_active_set = warm;
  SolveSession session = solver->Prepare(gen.problem, options, session_options);
  SolveResult result;
  const Vector& q = gen.problem.q();
  session.Solve(q, &result);
  if (!result.solved()) {
    state.SkipWithError((std::string(ToString(result.status)) + ": " + result.message).c_str());
    return;
  }
  for (auto _ : state) {
    session.Solve(q, &result);
    benchmark::DoNotOptimize(result.z.data());
    benchmark::ClobberMemory();
  }
  if (!result.solved()) {
    state.SkipWithError((std::string(ToString(result.status)) + ": " + result.message).c_str());
    return;
  }
  state.counters["reused"] = static_cast<double>(session.reused()) / static_cast<double>(session.calls());
  state.counters["forward_error"] = (result.z - gen.z_star).cwiseAbs().maxCoeff();
  state.counters["m"] = g.size;
}

void RegisterAll() {
  for (auto solver : SolverNames()) {
    const SolverInfo info = CreateSolver(solver)->info();
    for (MatrixFamily family : {MatrixFamily::kSymmetricPositiveDefinite, MatrixFamily::kNonsymmetricPMatrix}) {
      for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay}) {
        for (int m : kSizes) {
          if (m > MaxSize(info)) continue;
          GeneratorOptions g;
          g.family = family;
          g.bounds = bounds;
          g.size = m;
          g.seed = 2026;
          const std::string name = "solve/" + std::string(solver) + "/" + ToString(family) + "-" +
                                   ToString(bounds) + "/" + std::to_string(m) + "/";
          auto* b = benchmark::RegisterBenchmark(name.c_str(), SolveBenchmark, std::string(solver), g);
          b->Unit(benchmark::kNanosecond);
          if (m >= 256) b->Iterations(m >= 1024 ? 3 : 20);
          // A backend slow enough to have a practical size limit (ipopt: an interior point per call) is timed by the
          // solve/ benchmarks only.
          if (m > 16 || info.practical_size_limit > 0) continue;
          for (bool warm : {false, true}) {
            const std::string session_name = "session/" + std::string(solver) + "/" + ToString(family) + "-" +
                                             ToString(bounds) + "/" + std::to_string(m) + "/" +
                                             (warm ? "warm" : "cold");
            benchmark::RegisterBenchmark(session_name.c_str(), SessionBenchmark, std::string(solver), g, warm)
                ->Unit(benchmark::kNanosecond);
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace smcbench

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  smcbench::RegisterAll();
  benchmark::AddCustomContext("tolerance", "1e-10 on the relative and the row-equilibrated natural residual");
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

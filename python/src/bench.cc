// smcbench.bench: a benchmark run from Python through the engine `smcbench bench` runs (bench/run: MakeBenchPlan,
// RunShard), its results written as `bench` writes them (results.json and results.csv, bench/replay/results_io.h),
// which __init__.py reads back into a DataFrame: the columns are results.csv's by construction.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <map>
#include <set>
#include <string>
#include <vector>

#include "bench/replay/results_io.h"
#include "bench/run/bench_plan.h"
#include "bench/run/run_shard.h"

namespace py = pybind11;

namespace smcbench::python {
namespace {

// Runs the suites (names or problem-set files) on the backends and writes out_dir/results.{json,csv}. Every bad
// input is an InvalidInputError before anything runs or is written. No stepper studies: the DataFrame holds the
// replay records only (cold, sweep, and warm-track rows when warm).
void Bench(const std::vector<std::string>& suites, const std::vector<std::string>& solvers,
           const std::vector<std::string>& settings, double tolerance, int repetitions, double time_limit,
           double backend_budget, double job_budget, double sequence_budget, bool quick, bool polish, bool warm, const std::string& siconos_dir,
           const std::vector<std::string>& problems, const std::string& out_dir) {
  BenchRequest request;
  request.suites = suites;
  request.problems = problems;
  if (suites.empty()) throw InvalidInputError("bench: suites is empty (give a suite name or a problem-set file)");
  request.solvers = solvers;
  request.settings = settings;
  if (!siconos_dir.empty()) request.siconos_dir = siconos_dir;
  request.tolerance = tolerance;
  request.repetitions = repetitions;
  request.time_limit_seconds = time_limit;
  request.backend_budget_seconds = backend_budget;
  request.job_budget_seconds = job_budget;
  request.sequence_budget_seconds = sequence_budget;
  request.quick = quick;
  request.polish = polish;
  request.warm = warm;
  request.stepper = StepperStudyChoice::kNever;
  // The run touches no Python object: other Python threads may run meanwhile.
  py::gil_scoped_release release;
  const BenchPlan plan = MakeBenchPlan(request);
  std::map<std::size_t, JobLine> done;
  RunShard(plan, ShardSelection{}, {}, [&](const JobLine& line) { done[line.job] = line; });
  BenchResults results = PlanResults(plan, done);
  results.command = "smcbench.bench (Python)";
  WriteBenchResults(results, out_dir);
}

}  // namespace

void BindBench(py::module_& m) {
  using namespace pybind11::literals;
  m.def("_bench", &Bench, "suites"_a, "solvers"_a, "settings"_a, "tol"_a, "repetitions"_a, "time_limit"_a,
        "backend_budget"_a, "job_budget"_a, "sequence_budget"_a, "quick"_a, "polish"_a, "warm"_a, "siconos_dir"_a, "problems"_a, "out_dir"_a,
        "Run a benchmark as `smcbench bench` does and write out_dir/results.{json,csv} (see smcbench.bench).");
}

}  // namespace smcbench::python

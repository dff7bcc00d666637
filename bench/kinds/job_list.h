// The job list of a run: every suite's jobs as its problem kind lists them (KindSuite::Jobs), numbered, named and
// estimated here the same way for every kind, then the warm jobs and the stepper job. The order is the order of a
// single run's results, and the shards (AssignShards) depend on it.
#pragma once

#include <vector>

#include "bench/kinds/problem_kind.h"
#include "bench/replay/jobs.h"

namespace smcbench {

// Every job of a run, in the order a single run writes its results: per suite (in the plan's order: box suites,
// then MCP, then AVI, then any other kind's) its jobs on the backends of its kind (request.kind_solvers, default
// request.solvers), BenchJob::suite indexing suites; then the warm jobs (suite, sequence, backend of
// request.solvers); then the stepper job. The box kind lists per suite the cold jobs (problem, then backend), the
// floor jobs (problem; with request.floor), the generic sparse path (problem), the sweep (SweepProblemIndices,
// backend, tolerance); the others per unit (problem, or MCP problem × start) each backend, then the floor.
std::vector<BenchJob> ListBenchJobs(const std::vector<PlanSuite>& suites, const ReplayOptions& options,
                                    const JobListRequest& request);

}  // namespace smcbench

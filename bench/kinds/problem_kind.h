// One interface per kind of problem (box-MLCP, MCP, AVI, or a kind a caller adds), so that the plan, the job list,
// the shard runner and the manifest never branch on the kind: a new kind implements ProblemKind and KindSuite and
// is passed in BenchRequest::kinds, and no dispatcher changes.
//
// ProblemKind builds suites of its kind by name; KindSuite is one built suite in a plan, and answers everything the
// dispatcher asks of it: what it is (the manifest's line), its jobs and their estimates, a job replayed into a
// record, its floor, and the record of a job its backend's budget stopped.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "bench/kinds/problem_filter.h"
#include "bench/replay/jobs.h"
#include "bench/replay/replay.h"
#include "bench/replay/results_io.h"
#include "bench/replay/warm_track.h"

namespace smcbench {

class Solver;

// What a suite's jobs run on: a problem, or (an MCP's) one problem from one of its starts.
struct SuiteUnit {
  std::size_t problem = 0;  // index of the problem in its suite
  std::string problem_id;
  bool has_start = false;   // the unit is problem × start (job ids "problem@start")
  std::size_t start = 0;
  std::string start_label;
};

// One job of a suite before the job list numbers it.
struct SuiteJob {
  JobKind kind = JobKind::kCold;  // kCold, kSweep or kFloor
  SuiteUnit unit;
  std::string solver;
  double tolerance = 0.0;
};

// One suite of a plan, of some kind.
class KindSuite {
 public:
  virtual ~KindSuite() = default;

  virtual std::string kind() const = 0;  // the ProblemKind's name
  virtual std::string name() const = 0;  // the suite's name ("paper", "mcp", "avi", ...)
  // What results.json and the manifest say of it: name, description, problems, checksum (no records).
  virtual SuiteResults Describe() const = 0;
  // Its units in job order, and what a backend past its budget is said to miss ("problems", "problem x start").
  virtual std::vector<SuiteUnit> Units() const = 0;
  virtual std::string UnitsNoun() const { return "problems"; }
  // Its jobs on these backends, in the order a single run writes them. The default: per unit, each backend, then
  // (with floor and some backend) the floor job. The box kind orders its own (cold, floor, generic path, sweep).
  virtual std::vector<SuiteJob> Jobs(const std::vector<std::string>& backends, const ReplayOptions& options,
                                     bool floor) const;
  // The manifest's "kind" of a cold job on solver: "cold" unless an older name must stay ("mcp", "avi",
  // "generic-sparse"), so that manifests written before the kinds existed still merge and resume.
  virtual std::string ColdJobName(const std::string& /*solver*/) const { return "cold"; }
  // Estimated seconds of a job (bench/replay/jobs.h: the Estimate*JobSeconds of the kind).
  virtual double EstimateSeconds(const SuiteJob& job, const ReplayOptions& options, const BackendCost& cost,
                                 const JobBudgets& budgets) const = 0;
  // A cold or sweep job replayed, timed and judged (solver: the job's backend, created by the runner).
  virtual ReplayRecord Replay(const BenchJob& job, Solver* solver, const ReplayOptions& options) const = 0;
  // A floor job: one factorization of the unit's matrix, timed as a cold solve (bench/replay/floor.h).
  virtual ReplayRecord Floor(const BenchJob& job, const ReplayOptions& options) const = 0;
  // The record of a job that did not run (status time limit, verdict failed, infinite residuals, message), which
  // the runner marks as cut.
  virtual ReplayRecord NotRun(const BenchJob& job, const std::string& message) const = 0;
};

using PlanSuite = std::shared_ptr<const KindSuite>;

// What building a suite needs of the bench request.
struct SuiteBuildRequest {
  std::string siconos_dir;
  bool quick = false;
  bool certify = true;
  bool warm = true;                  // build the suite's warm sequences (box suites that have them)
  std::vector<std::string> solvers;  // the backends named (empty: every registered one)
};

// A suite built by its kind.
struct BuiltSuite {
  PlanSuite suite;                      // null when the filter kept none of its problems
  std::vector<WarmSequence> warm;       // its warm sequences (filtered, certified), with request.warm
  std::string first_id;                 // its first problem, filtered or not (the no-match error's example)
  std::string line;                     // for the log: size, time taken, certificates
  std::string warm_line;                // for the log, after every suite's line: its warm track
};

// One kind of problem: which suites it builds, how, and which backends run them.
class ProblemKind {
 public:
  virtual ~ProblemKind() = default;
  virtual std::string name() const = 0;  // "box", "mcp", "avi"
  // Whether this kind builds the suite named (a built-in name, or a file of its kind).
  virtual bool Builds(const std::string& suite_name) const = 0;
  // The suite of that name, its problems kept by filter (applied before references are computed), validated and
  // certified (with request.certify). InvalidInputError for a suite that cannot be built or holds no problem.
  virtual BuiltSuite Build(const std::string& suite_name, const SuiteBuildRequest& request,
                           ProblemFilter* filter) const = 0;
  // The backends of its jobs among the run's (resolved names), and the log line when there are none.
  virtual std::vector<std::string> Backends(const std::vector<std::string>& solvers) const = 0;
  virtual std::string NoBackendsLine() const { return ""; }
};

using ProblemKinds = std::vector<std::shared_ptr<const ProblemKind>>;

}  // namespace smcbench

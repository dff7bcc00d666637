// Benchmark results on disk: one JSON document per `smcbench bench` run (the environment that produced it, every
// record) plus a CSV of the replay records for spreadsheets. The report reads the JSON back.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/replay/replay.h"
#include "bench/replay/stepper_study.h"
#include "bench/replay/warm_track.h"

namespace smcbench {

// What produced the numbers: git SHA, compiler and flags, build type, machine (CPU model, cores, kernel), library
// versions (Eigen, SuiteSparse/UMFPACK, Ipopt, nlohmann-json, Siconos if built), date. Never throws.
// build_revision: the revision the running binary was built from (the CLI's GitRevision(), passed down as data so
// bench/ needs nothing from tools/), recorded as "build_revision"; "git_sha" is the checkout's HEAD at run time.
nlohmann::json BenchEnvironment(const std::string& build_revision = "");

// The fields of an environment that say which build made the numbers (build_revision, version, compiler, flags,
// build type, assertions, libraries), leaving out the machine and the date: results to be merged must agree on them.
nlohmann::json BuildIdentity(const nlohmann::json& environment);

// One replay record as results.json holds it, and back (InvalidInputError naming the field).
nlohmann::json ReplayRecordToJson(const ReplayRecord& record);
ReplayRecord ReplayRecordFromJson(const nlohmann::json& record);
// The time-stepper studies as results.json holds them, and back.
nlohmann::json StepperStudyToJson(const StepperStudy& study);
StepperStudy StepperStudyFromJson(const nlohmann::json& study);
// One warm-track record (the replay record plus "warm": source and counts), and back.
nlohmann::json WarmRecordToJson(const WarmRecord& record);
WarmRecord WarmRecordFromJson(const nlohmann::json& record);

struct SuiteResults {
  std::string suite;        // "paper", "families", ...
  std::string description;
  int problems = 0;
  // ProblemSetContentChecksum (problems/suites/catalogue.h) of the problems run, references attached; empty in
  // older results that did not record it.
  std::string checksum;
  ReplayResults replay;
  std::vector<WarmRecord> warm = {};  // mode "warm": one per warm sequence of the suite × backend (warm_track.h)
  // Its ProblemKind's name ("box", "mcp", "avi", ...: bench/kinds/problem_kind.h), which chooses its report section;
  // empty in results and manifests written before it was recorded (the section is then found as it was before).
  std::string kind = {};
};

struct BenchResults {
  std::string command;      // the command line that produced them
  bool polish = true;       // SolverOptions::polish of every solve (false: `bench --no-polish`, raw algorithms)
  // The options the run measured under, as its manifest records them (bench/run/bench_plan.h: PlanOptionsJson:
  // backends, settings, tolerance, budgets, the --problem globs, ...); null in results written before they were.
  nlohmann::json options;
  std::vector<SuiteResults> suites;
  bool has_stepper = false;
  StepperStudy stepper;
};

nlohmann::json ToJson(const BenchResults& results, const nlohmann::json& environment);
// Inverse of ToJson (environment ignored). InvalidInputError naming the field on a malformed document.
BenchResults BenchResultsFromJson(const nlohmann::json& document);
// Writes dir/results.json and dir/results.csv (dir created). InvalidInputError if it cannot. Without environment:
// BenchEnvironment() of this process.
void WriteBenchResults(const BenchResults& results, const std::string& dir);
void WriteBenchResults(const BenchResults& results, const std::string& dir, const nlohmann::json& environment);
// Reads dir/results.json. InvalidInputError naming the file if missing or malformed.
BenchResults ReadBenchResults(const std::string& dir, nlohmann::json* environment = nullptr);

}  // namespace smcbench

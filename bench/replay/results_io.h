// Benchmark results on disk: one JSON document per `smcbench bench` run (the environment that produced it, every
// record) plus a CSV of the replay records for spreadsheets. The report reads the JSON back.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "bench/replay/replay.h"
#include "bench/replay/stepper_study.h"

namespace smcbench {

// What produced the numbers: git SHA, compiler and flags, build type, machine (CPU model, cores, kernel), library
// versions (Eigen, SuiteSparse/UMFPACK, Ipopt, nlohmann-json, Siconos if built), date. Never throws.
nlohmann::json BenchEnvironment();

struct SuiteResults {
  std::string suite;        // "paper", "families", ...
  std::string description;
  int problems = 0;
  ReplayResults replay;
};

struct BenchResults {
  std::string command;      // the command line that produced them
  bool polish = true;       // SolverOptions::polish of every solve (false: `bench --no-polish`, raw algorithms)
  std::vector<SuiteResults> suites;
  bool has_stepper = false;
  StepperStudy stepper;
};

nlohmann::json ToJson(const BenchResults& results, const nlohmann::json& environment);
// Inverse of ToJson (environment ignored). InvalidInputError naming the field on a malformed document.
BenchResults BenchResultsFromJson(const nlohmann::json& document);
// Writes dir/results.json and dir/results.csv (dir created). InvalidInputError if it cannot.
void WriteBenchResults(const BenchResults& results, const std::string& dir);
// Reads dir/results.json. InvalidInputError naming the file if missing or malformed.
BenchResults ReadBenchResults(const std::string& dir, nlohmann::json* environment = nullptr);

}  // namespace smcbench

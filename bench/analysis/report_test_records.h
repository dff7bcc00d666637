// The analysis tests' hand-made records: a cold record whose status follows its verdict, and the report of a suite
// written to a fresh folder.
#pragma once

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <unistd.h>

#include "bench/analysis/report_markdown.h"
#include "bench/replay/results_io.h"

namespace smcbench::report_test {

namespace fs = std::filesystem;

inline std::string ReadText(const fs::path& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// A cold record whose status follows the verdict unless given.
inline ReplayRecord Rec(const std::string& problem, const std::string& solver, Verdict v, double t, int size = 2,
                 SolveStatus status = SolveStatus::kNotRun) {
  ReplayRecord r;
  r.suite = "s";
  r.problem = problem;
  r.solver = solver;
  r.verdict = v;
  r.status = status != SolveStatus::kNotRun ? status
             : v == Verdict::kSolved || v == Verdict::kWronglyClaimed || v == Verdict::kInaccurate
                 ? SolveStatus::kSolved
                 : SolveStatus::kIterationLimit;
  r.time_median = t;
  r.size = size;
  r.samples = 3;
  r.residual_rel = v == Verdict::kSolved ? 1e-12 : 1.0;
  r.residual_scaled = v == Verdict::kSolved ? 2e-12 : 1.0;
  return r;
}

inline fs::path ReportDir(const std::string& name) {
  return fs::temp_directory_path() / ("smcbench-report-" + name + "-" + std::to_string(::getpid()));
}

// Writes results holding suite to a fresh folder ReportDir(name) and returns the report's markdown; the folder is
// removed unless keep (the caller then reads the figures' files and removes it).
inline std::string ReportOf(const SuiteResults& suite, const std::string& name, bool plots = false, bool keep = false) {
  const fs::path dir = ReportDir(name);
  fs::remove_all(dir);
  BenchResults results;
  results.command = "test";
  results.suites = {suite};
  WriteBenchResults(results, dir.string(), nlohmann::json::object());
  const std::string md = WriteBenchReport(dir.string(), plots);
  if (!keep) fs::remove_all(dir);
  return md;
}

// Three problems: lemke solves all, psor two (an iteration limit on the third), enum refuses all three on size

}  // namespace smcbench::report_test

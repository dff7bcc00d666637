// The report's tables as data — named columns, rows of numbers or text — so Python can make them pandas DataFrames
// (smcbench.report_tables) from the same pure functions the markdown is rendered from.
#pragma once

#include <string>
#include <variant>
#include <vector>

#include "bench/replay/results_io.h"

namespace smcbench {

// One cell: a number (counts, seconds, ratios; NaN where the report leaves a blank or a "–") or text.
using TableCell = std::variant<double, std::string>;

// A table: its name, its columns (named as the report's markdown names them), its rows (one cell per column).
struct ReportTable {
  std::string name;
  std::vector<std::string> columns;
  std::vector<std::vector<TableCell>> rows;
};

// The tables of a run, over the cold records the report's tables use (no "cached" or "cut" records), in this order:
// "summary" (per class: SummarizeClasses), "failures" (per backend: FailuresPerBackend), then with a column "suite"
// first: "backends" (SummarizeSuite; every backend, also those the report lists apart as having solved nothing),
// "statuses" (records per backend and status), "audit" (AuditClaims), "bands" (FastestCorrectPerBand), "ladder"
// (BuildToleranceLadder, one row per backend and tolerance), "sweep" (SweepRows), "peers" (OursAgainstPeersPerBand,
// one row per band, track and library) and "profiles" (PerformanceRatios, one row per backend and problem).
std::vector<ReportTable> ReportTables(const BenchResults& results);

}  // namespace smcbench

// The renderers of a comparison (compare_runs.h: CompareRuns, CompareRunFolders): compare.md, compare.json and the
// short table for a terminal, apart from the statistics that make the comparison.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

#include "bench/compare/compare_runs.h"

namespace smcbench {

// compare.md: the runs side by side (their differences named, a warning when the machines differ), how they were
// compared (noise floor, drift), verdict changes, then the ratio table (one row per group: times, raw and
// normalized ratio, interval, median iterations, flag). figure_stem: the ratio figure's file stem to link (empty:
// none).
std::string CompareMarkdown(const RunComparison& comparison, const CompareOptions& options, const std::string& label_a,
                            const std::string& label_b, const std::string& figure_stem);

// compare.json: the same as data (format "smcbench-compare/1"): the runs side by side and their differences, the
// method and its parameters, the noise floor, the flag limit, the drift, the verdict changes and the groups (raw and
// ÷ drift ratio, interval, median iterations, flag "slower" / "faster" / "none"), and whether B regressed.
nlohmann::json CompareJson(const RunComparison& comparison, const CompareOptions& options, const std::string& label_a,
                           const std::string& label_b);

// The short table for a terminal: counts, the verdict changes (at most max_changes), and the groups (all when at most
// max_groups, else only the flagged ones).
std::string CompareSummaryText(const RunComparison& comparison, const CompareOptions& options,
                               std::size_t max_changes = 10, std::size_t max_groups = 30);

}  // namespace smcbench

// `smcbench report --history FILE`: the perf gate's history (tools/perf-check --history appends one line per figure
// to results/history.csv) as DIR/history.md — every figure's instructions per unit over the runs — and
// DIR/history.png: per backend, the geometric mean over its figures of instructions relative to the first run.
#pragma once

#include <string>

namespace smcbench {

// Returns the markdown. InvalidInputError if the history cannot be read or is empty, or plots are asked for and
// gnuplot is missing or fails.
std::string WritePerfHistoryReport(const std::string& history_csv, const std::string& dir, bool plots);

}  // namespace smcbench

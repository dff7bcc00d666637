// `smcbench report DIR`: turns a bench run's results.json into DIR/report.md with PNG plots — per suite and
// backend the verdict counts (wrong answers apart), the statuses the backends returned, success rate, shifted
// geometric mean time (failure penalty stated beside it), worst residuals (relative and row-equilibrated) and worst
// forward error, the backends that solved nothing listed apart with their reason, the fastest correct backend per
// size band, the audit of the backends' own success flags, the tolerance ladder, Dolan–Moré performance profiles,
// time against the forward error and against the residual reached (tolerance sweep), the time-stepper's
// work-precision diagrams and warm/cold table, the scale family's growth exponent, and for an MCP suite its own
// section. The tables come from the analysis layer (suite_tables.h, class_tables.h, peer_tables.h, sweep_tables.h);
// this is their markdown and gnuplot renderer.
#pragma once

#include <string>

#include "bench/analysis/class_tables.h"
#include "bench/analysis/plot_style.h"
#include "bench/analysis/suite_tables.h"
#include "bench/replay/results_io.h"

namespace smcbench {

// The verdict in two sentences a user can check by hand (the report's text and `smcbench bench --help`).
extern const char* const kVerdictInTwoSentences;

// The report's warning when compared times come from shared hosts: records measured while other bench jobs ran on
// their host (ReplayRecord::concurrent_jobs > 1) or records from more than one host. Empty when neither.
std::string SharedHostWarning(const BenchResults& results);

// Writes dir/report.md (and PNGs when plots is true and gnuplot is on PATH). Returns the markdown.
// InvalidInputError if results are missing or gnuplot is required but absent.
std::string WriteBenchReport(const std::string& dir, bool plots);

}  // namespace smcbench

// The report's markdown sections, one writer per table or figure, called in order by WriteBenchReport
// (report_markdown.cc): each computes its table from the analysis layer (suite_tables.h, class_tables.h,
// peer_tables.h, sweep_tables.h) and prints it. Namespace markdown: the layout of report.md, not a public API.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <set>
#include <string>

#include "bench/analysis/peer_tables.h"
#include "bench/replay/results_io.h"

namespace smcbench::markdown {

// The opening, the summary per class and per backend, the failure list, the appendix (markdown_summary.cc).
void WriteHeader(std::ostream& md, const std::string& dir, const BenchResults& results, const nlohmann::json& env);
void WriteSummary(std::ostream& md, const BenchResults& results);
void WriteFailureList(std::ostream& md, const BenchResults& results);
void WriteVerdictAppendix(std::ostream& md, const BenchResults& results);

// A box suite's tables (markdown_suite.cc); the backend table, floor line and counts serve the MCP, AVI and warm
// sections too.
std::string CertificateCounts(const SuiteResults& suite);
std::string ProvedCounts(const SuiteResults& suite);
void WriteSuiteSummary(std::ostream& md, const SuiteResults& suite);
void WriteBackendTableOnly(std::ostream& md, const SuiteResults& suite);
void WriteBackendTable(std::ostream& md, const SuiteResults& suite);
void WriteFloorLine(std::ostream& md, const SuiteResults& suite);
void WriteSolvedNothing(std::ostream& md, const SuiteResults& suite);
void WriteStatusesAndClaims(std::ostream& md, const SuiteResults& suite);
void WriteBandWinners(std::ostream& md, const SuiteResults& suite);
void WriteWrongAnswers(std::ostream& md, const SuiteResults& suite);

// Against other backends and libraries, the tolerance ladder and sweep, the scale table (markdown_comparisons.cc).
void WriteSparsePathComparison(std::ostream& md, const SparsePathComparison& c);
void WriteSiconosComparison(std::ostream& md, const SiconosComparison& c);
void WritePeerRatios(std::ostream& md, const SuiteResults& suite);
void WriteToleranceLadder(std::ostream& md, const SuiteResults& suite);
void WriteToleranceSweep(std::ostream& md, const SuiteResults& suite, const std::string& dir, bool plots);
void WriteScaleTable(std::ostream& md, const SuiteResults& suite);

// The MCP and AVI suites' own sections (markdown_kinds.cc).
void WriteMcpSection(std::ostream& md, const SuiteResults& suite, const std::string& dir, bool plots);
void WriteAviSection(std::ostream& md, const SuiteResults& suite, const std::string& dir, bool plots);

// Per size band, the warm track, the time-stepper (markdown_warm.cc).
void WritePerBand(std::ostream& md, const SuiteResults& suite, const std::string& dir, bool plots,
                  const std::string& what);
void WriteWarmTrack(std::ostream& md, const SuiteResults& suite, const std::string& dir, bool plots);
void WriteWarmStart(std::ostream& md, const StepperStudy& st);
void WriteWorkPrecision(std::ostream& md, const StepperStudy& st, const std::string& dir, bool plots);

}  // namespace smcbench::markdown

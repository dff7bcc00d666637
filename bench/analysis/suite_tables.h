// Per suite and backend, as plain structs computed by pure functions over a suite's records: the verdict counts,
// success and shifted geometric mean time (SummarizeSuite), the fastest correct backend per size band, the audit of
// the backends' own success flags, the Dolan–Moré ratios, the size-band and warm-track views of a suite, the growth
// exponent. The report's tables are rendered from these (report_markdown.h).
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "bench/replay/results_io.h"
#include "bench/replay/size_band.h"

namespace smcbench {

// The most common way a backend's records that are not correct ended: what the report says instead of a time.
struct FailureReason {
  SolveStatus status = SolveStatus::kNotRun;
  int count = 0;              // records not correct with that status
  std::string message;        // the most common message among them (ties: the first met)
  int message_count = 0;      // records with that status and that message
  double median_time = kNaN;  // median of their per-solve times (seconds)
};

struct BackendSummary {
  std::string solver;
  int problems = 0, solved = 0, correctly_refused = 0, failed = 0;
  int wrongly_claimed = 0, inaccurate = 0, wrongly_refused = 0;  // the wrong answers (IsWrong)
  double success_rate = 0.0;     // (solved + correctly refused) / problems
  double shifted_geomean = 0.0;  // seconds; see SummarizeSuite
  // Over the records with verdict solved: max relative residual, max row-equilibrated residual, and max forward
  // error ‖z − z*‖∞ over those whose problem has a unique reference. NaN when not defined (nothing solved, no
  // reference): the report prints a blank, never a 0 that looks like a perfect answer.
  double worst_residual = kNaN;
  double worst_residual_scaled = kNaN;
  double worst_forward_error = kNaN;
  int forward_error_defined = 0;  // solved records with a forward error
  std::map<SolveStatus, int> statuses;  // records per status the backend returned
  FailureReason failure;                // over the records that are not correct (count 0: none)
  int wrong() const { return wrongly_claimed + inaccurate + wrongly_refused; }
  int correct() const { return solved + correctly_refused; }
};

// True for a suite of the MCP kind (SuiteResults::kind "mcp"; in older results, records that are problem × start):
// the report's MCP section.
bool IsMcpSuite(const SuiteResults& suite);
// True for a suite of the AVI kind (kind "avi"; in older results, the suite named `avi`): the report's AVI section.
bool IsAviSuite(const SuiteResults& suite);

// Shifted geometric mean of the per-problem median times, shift 1e-6 s, a problem the backend does not get right
// counted at kFailurePenaltyFactor × the slowest correct time on that problem (time_limit_seconds if nobody got it
// right). For an MCP suite a problem is a problem × start, here and in PerformanceRatios.
std::vector<BackendSummary> SummarizeSuite(const SuiteResults& suite, double time_limit_seconds = 10.0);
// The same over any subset of one suite's cold records (a size band, ...): penalties from that subset alone.
std::vector<BackendSummary> SummarizeRecords(const std::vector<ReplayRecord>& records,
                                             double time_limit_seconds = 10.0);
inline constexpr double kFailurePenaltyFactor = 10.0;

// True when the backend goes in the report's "solved nothing" list instead of the timing table: it solved no
// problem of the suite while another backend solved at least one (then its SGM would be its penalty alone).
bool SolvedNothing(const BackendSummary& backend, const std::vector<BackendSummary>& suite);

// The fastest correct backend of one size band: among the backends with no wrong answer in the band, those with
// the most correct answers, and of them the smallest shifted geometric mean over the band (SummarizeRecords).
struct BandWinner {
  SizeBand band = SizeBand::kTiny;
  int problems = 0;          // instances in the band
  std::string solver;        // empty when every backend gave a wrong answer in the band
  int correct = 0;           // its correct answers in the band
  double shifted_geomean = kNaN;
  int fastest_on = 0;        // instances where its time was the smallest of the correct answers
  std::string runner_up;     // the next backend in the same order (empty if none)
  int runner_up_correct = 0;
  double runner_up_geomean = kNaN;
};
// One entry per band that has records, smallest band first.
std::vector<BandWinner> FastestCorrectPerBand(const SuiteResults& suite, double time_limit_seconds = 10.0);

// What the backend itself said: its library's own return code where the record has one (ReplayRecord::backend_code,
// 0 = success), else its status is solved.
bool ClaimedSolved(const ReplayRecord& record);

// Audit of the backends' own success flags over a suite's cold records: a claim is right when ClaimedSolved ⇔ our
// verdict is solved.
struct ClaimAudit {
  std::string solver;
  int records = 0, right = 0;
  int false_success = 0;     // claimed solved, our verdict is not solved
  int false_failure = 0;     // claimed not solved (a failure code), our verdict is solved
  int with_return_code = 0;  // records judged on the library's own return code rather than the status
};
std::vector<ClaimAudit> AuditClaims(const SuiteResults& suite);

// The most common ending of records that are not correct: its status, its most common message, the median time.
FailureReason MostCommonFailureOf(const std::vector<const ReplayRecord*>& not_correct);

// Dolan–Moré: for each backend, ρ(τ) = fraction of problems solved within τ × the best time on that problem.
// Returns, per backend, the ratios r_p = t_p / min_s t_p (∞ for problems it does not solve), sorted.
std::vector<std::pair<std::string, std::vector<double>>> PerformanceRatios(const SuiteResults& suite);

// The cold records of one size band of a suite (suite name "<suite> <band's ShortName>", the same description), so
// every table and profile of a suite can be given per band.
SuiteResults SizeBandSlice(const SuiteResults& suite, SizeBand band);
// The suite's warm-track records (SuiteResults::warm) as the records of a suite named "<suite> warm": each warm
// sequence × backend one record (time per step), so the cold tables, profiles and band winners apply to them.
SuiteResults WarmTrackAsSuite(const SuiteResults& suite);

// Least-squares slope of log(time) against log(size) over the solved records of one backend (NaN if < 2 sizes).
double GrowthExponent(const SuiteResults& suite, const std::string& solver);

// The suite without its records whose timed solves could not all start cold (mode "cached"), which no cold table or
// profile may compare; *cached receives "backend on problem" for each.
SuiteResults WithoutCachedRecords(const SuiteResults& suite, std::vector<std::string>* cached);
// The suite without its records cut by a time budget (mode "cut"), which have no verdict and so belong in no table;
// *cut receives them.
SuiteResults WithoutCutRecords(const SuiteResults& suite, std::vector<ReplayRecord>* cut);

}  // namespace smcbench

// A box suite's tables in markdown: heading and references, backends, floor, solved nothing, statuses and the audit,
// band winners, wrong answers (markdown_sections.h).
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "bench/analysis/class_tables.h"
#include "bench/analysis/markdown_cells.h"
#include "bench/analysis/markdown_sections.h"
#include "bench/analysis/peer_tables.h"
#include "bench/analysis/record_facts.h"
#include "bench/analysis/report_figures.h"
#include "bench/analysis/suite_tables.h"
#include "bench/analysis/sweep_tables.h"
#include <optional>

#include "solvers/core/verdict.h"

namespace smcbench::markdown {

// "3 unique, 2 non-unique": what the certified references prove, counted per problem (every backend's record
// carries its problem's).
std::string CertificateCounts(const SuiteResults& suite) {
  std::map<std::string, std::string> certificate_of;
  for (const auto& r : suite.replay.records) certificate_of.emplace(r.problem, r.certificate);
  std::map<std::string, int> certificates;
  for (const auto& [problem, certificate] : certificate_of) ++certificates[certificate];
  std::string certified;
  for (const auto& [certificate, count] : certificates) {
    certified += (certified.empty() ? "" : ", ") + std::to_string(count) + " " + certificate;
  }
  return certified;
}

// "; 5 of the 7 verified proved by an interval enclosure (3 the only solution: M + Mᵀ proved positive definite),
// an exact solution within 2.2e-16 of z*": how many verified references an interval proof confirms
// (ReplayRecord::reference_radius, reference_proved_unique; solvers/reference/enclosure.h), counted per problem,
// with the largest radius; empty when the suite has no verified reference.
std::string ProvedCounts(const SuiteResults& suite) {
  std::map<std::string, const ReplayRecord*> record_of;
  for (const auto& r : suite.replay.records) record_of.emplace(r.problem, &r);
  int verified = 0, proved = 0, proved_unique = 0;
  double radius = 0.0;
  for (const auto& [problem, r] : record_of) {
    const std::optional<Certificate> certificate = CertificateFromString(r->certificate);
    if (!certificate) continue;
    ReferenceSolution reference;
    reference.certificate = *certificate;
    if (!reference.verified()) continue;
    ++verified;
    if (std::isnan(r->reference_radius)) continue;
    ++proved;
    proved_unique += r->reference_proved_unique ? 1 : 0;
    radius = std::max(radius, r->reference_radius);
  }
  if (verified == 0) return {};
  std::string text = "; " + std::to_string(proved) + " of the " + std::to_string(verified) +
                     " verified proved by an interval enclosure";
  if (proved_unique > 0) {
    text += " (" + std::to_string(proved_unique) + " the only solution: M + Mᵀ proved positive definite)";
  }
  if (proved > 0) text += ", an exact solution within " + G(radius) + " of z*";
  return text;
}

// The suite's heading and its table of verdict counts, success, SGM time and worst errors per backend.
void WriteSuiteSummary(std::ostream& md, const SuiteResults& suite) {
  const std::string certified = CertificateCounts(suite);
  md << "## Suite `" << suite.suite << "`: " << suite.description << "\n\n"
     << suite.problems << " problems; certified references: " << (certified.empty() ? "–" : certified)
     << " (forward errors are judged on the unique and degenerate ones)" << ProvedCounts(suite) << ".\n\n";
  WriteBackendTable(md, suite);
}

// The failure-penalty convention, in the words the report prints beside every table and figure that uses it.
const char* const kPenaltyConvention =
    "SGM time = shifted geometric mean (shift 1 µs) of the per-problem median times, where a problem the backend "
    "did not get right (failed, or a wrong answer) counts as 10× the slowest correct time on that problem, or as "
    "10 s when no backend got it right: a failure never costs less than the slowest success (qpbenchmark's "
    "convention, with 10× the slowest correct time in place of the time limit).";

// What the floor is, under a suite's first table: the factorizations timed and their times, or that the run
// measured none (results written before the floor, or a run without box, MCP or AVI jobs).
void WriteFloorLine(std::ostream& md, const SuiteResults& suite) {
  if (suite.replay.floor.empty()) {
    md << "Floor not measured in this run (no floor records in results.json): no time is given against one "
          "factorization of M.\n\n";
    return;
  }
  std::map<std::string, int> methods;  // "dense Cholesky" → problems
  std::vector<double> times;
  for (const ReplayRecord& r : suite.replay.floor) {
    std::string method = r.message.substr(r.message.find(": ") == std::string::npos ? 0 : r.message.find(": ") + 2);
    method = method.substr(0, method.find(" of a "));
    ++methods[method];
    if (r.samples > 0) times.push_back(r.time_median);
  }
  std::sort(times.begin(), times.end());
  std::string list;
  for (const auto& [method, count] : methods) list += (list.empty() ? "" : ", ") + method + " on " + std::to_string(count);
  md << "**Floor** (column *time / floor*): one factorization of each problem's matrix (" << list
     << "; an MCP's Jacobian at its start, an AVI's reduced box-MLCP), timed in this run with the cold protocol "
        "(same repetitions, the median): what a direct method pays at least once. *time / floor* is a backend's "
        "median, over the problems it got right, of its time over that problem's floor (n problems). Floor times: "
        "median "
     << (times.empty() ? "–" : Seconds(MedianOfSorted(times))) << " ["
     << (times.empty() ? "–" : Seconds(times.front())) << " – " << (times.empty() ? "–" : Seconds(times.back()))
     << "] over " << suite.replay.floor.size() << " problems.\n\n";
}

// Per backend: verdict counts, success, SGM time and worst errors (SummarizeSuite), and its time over the floor
// when the run measured one. Backends that solved nothing are listed apart (WriteSolvedNothing): their SGM would be
// the penalty alone.
void WriteBackendTableOnly(std::ostream& md, const SuiteResults& suite) {
  const std::vector<BackendSummary> summary = SummarizeSuite(suite);
  const std::map<std::string, double> floor = FloorTimes(suite);
  md << "| backend | solved | correctly refused | failed | **wrongly claimed** | **inaccurate** | **wrongly "
        "refused** | success | SGM time | worst residual (solved) | worst residual (eq.) | worst forward error "
        "(solved) |"
     << (floor.empty() ? "" : " time / floor |") << "\n|---|---|---|---|---|---|---|---|---|---|---|---|"
     << (floor.empty() ? "" : "---|") << "\n";
  for (const BackendSummary& b : summary) {
    if (SolvedNothing(b, summary)) continue;
    md << "| " << b.solver << " | " << b.solved << " | " << b.correctly_refused << " | " << b.failed << " | "
       << Count(b.wrongly_claimed) << " | " << Count(b.inaccurate) << " | " << Count(b.wrongly_refused) << " | "
       << G(100.0 * b.success_rate, 3) << "% | " << Seconds(b.shifted_geomean) << " | " << Blank(b.worst_residual)
       << " | " << Blank(b.worst_residual_scaled) << " | ";
    // Nothing solved: blank; solved, but no problem with a unique reference: "–".
    if (b.solved > 0) md << G(b.worst_forward_error);
    if (b.forward_error_defined) md << " (" << b.forward_error_defined << " with z*)";
    md << " |";
    if (!floor.empty()) md << " " << FloorRatioCell(FloorRatios(suite.replay.records, floor, b.solver)) << " |";
    md << "\n";
  }
  md << "\n";
}

void WriteBackendTable(std::ostream& md, const SuiteResults& suite) {
  WriteBackendTableOnly(md, suite);
  md << kPenaltyConvention << " Worst residuals and forward error are over the solved answers (blank: none "
     << "solved; –: no solved problem has a unique certified reference).\n\n";
  WriteFloorLine(md, suite);
}

// The backends that solved nothing while others solved something, each with its most common ending.
void WriteSolvedNothing(std::ostream& md, const SuiteResults& suite) {
  const std::vector<BackendSummary> summary = SummarizeSuite(suite);
  std::vector<const BackendSummary*> none;
  for (const BackendSummary& b : summary) {
    if (SolvedNothing(b, summary)) none.push_back(&b);
  }
  if (none.empty()) return;
  md << "**Solved nothing** in this suite (left out of the table above: their SGM would be the failure penalty "
        "alone). The most common ending, with its message and the median time it took:\n\n"
        "| backend | problems | correctly refused | failed | wrong | most common ending |\n|---|---|---|---|---|---|\n";
  for (const BackendSummary* b : none) {
    md << "| " << b->solver << " | " << b->problems << " | " << b->correctly_refused << " | " << b->failed << " | "
       << Count(b->wrong()) << " | " << FailureText(b->failure, b->problems) << " |\n";
  }
  md << "\n";
}

// Per backend, how many records ended with each status the backend returned (one column per status met in the
// suite), then the audit of claims (AuditClaims): whether its own success flag agreed with our verdict.
void WriteStatusesAndClaims(std::ostream& md, const SuiteResults& suite) {
  const std::vector<BackendSummary> summary = SummarizeSuite(suite);
  const std::vector<ClaimAudit> audit = AuditClaims(suite);
  std::set<SolveStatus> met;
  for (const BackendSummary& b : summary) {
    for (const auto& [status, count] : b.statuses) met.insert(status);
  }
  md << "**Statuses returned and the audit of claims**: how each backend's answers ended in its own words, and "
        "whether its success flag was right — a claim is right when it says solved exactly when our verdict is "
        "solved. The flag is the external library's own (Siconos' `info` = 0, Bullet's and DART's success flag; column "
        "`backend_code` of results.csv, 0 = success) where the record has one, before our base layer re-judged the answer (with the polish on, a false failure can be a "
        "short stop our polish finished); else the status.\n\n| backend | ";
  for (SolveStatus s : met) md << "`" << ToString(s) << "` | ";
  md << "flag right | false success (said solved, is not) | false failure (said failed, is solved) | flag from the "
        "return code |\n|---|";
  for (std::size_t i = 0; i < met.size() + 4; ++i) md << "---|";
  md << "\n";
  for (std::size_t k = 0; k < summary.size(); ++k) {
    const BackendSummary& b = summary[k];
    const ClaimAudit& a = audit[k];  // both in the order the backends first appear in the records
    md << "| " << b.solver << " | ";
    for (SolveStatus s : met) {
      const auto it = b.statuses.find(s);
      md << (it == b.statuses.end() ? 0 : it->second) << " | ";
    }
    md << Fraction(a.right, a.records) << " | " << Count(a.false_success) << " | " << a.false_failure << " | "
       << a.with_return_code << "/" << a.records << " |\n";
  }
  md << "\n";
}

// The fastest correct backend per size band (FastestCorrectPerBand), with the evidence: its correct answers, SGM,
// on how many problems it was the fastest, and the runner-up.
void WriteBandWinners(std::ostream& md, const SuiteResults& suite) {
  const std::vector<BandWinner> winners = FastestCorrectPerBand(suite);
  if (winners.empty()) return;
  const std::map<std::string, double> floor = FloorTimes(suite);
  md << "**Fastest correct backend per size band**: among the backends with no wrong answer in the band, those "
        "with the most correct answers, and of them the smallest SGM time over the band (penalty as above, from the "
        "band's problems alone)"
     << (floor.empty() ? "" : "; *fastest / floor*: its median time over the floor on the band's problems it got right")
     << ":\n\n| size band | problems | fastest correct | correct | SGM time | fastest on | "
        "runner-up | its correct | its SGM time | runner-up / fastest |"
     << (floor.empty() ? "" : " fastest / floor |") << "\n|---|---|---|---|---|---|---|---|---|---|"
     << (floor.empty() ? "" : "---|") << "\n";
  for (const BandWinner& w : winners) {
    md << "| " << ToString(w.band) << " | " << w.problems << " | ";
    if (w.solver.empty()) {
      md << "none (every backend gave a wrong answer) | | | | | | | |" << (floor.empty() ? "" : " |") << "\n";
      continue;
    }
    md << "**" << w.solver << "** | " << w.correct << "/" << w.problems << " | " << Seconds(w.shifted_geomean)
       << " | " << w.fastest_on << " | " << w.runner_up << " | "
       << (w.runner_up.empty() ? "" : std::to_string(w.runner_up_correct) + "/" + std::to_string(w.problems))
       << " | " << (w.runner_up.empty() ? "" : Seconds(w.runner_up_geomean)) << " | "
       << (w.runner_up.empty() ? "" : G(w.runner_up_geomean / w.shifted_geomean) + "×") << " |";
    if (!floor.empty()) {
      std::vector<ReplayRecord> band;
      for (const ReplayRecord& r : suite.replay.records) {
        if (SizeBandOf(r.size) == w.band) band.push_back(r);
      }
      md << " " << FloorRatioCell(FloorRatios(band, floor, w.solver)) << " |";
    }
    md << "\n";
  }
  md << "\n";
}

// Every wrong answer, so a reader can check it (the first few per suite; results.csv has them all).
void WriteWrongAnswers(std::ostream& md, const SuiteResults& suite) {
  std::vector<const ReplayRecord*> wrong;
  for (const auto& r : suite.replay.records) {
    if (IsWrong(r.verdict)) wrong.push_back(&r);
  }
  if (wrong.empty()) return;
  constexpr std::size_t kListed = 30;
  md << "Wrong answers (" << wrong.size() << (wrong.size() > kListed ? ", the first 30" : "")
     << "):\n\n| problem | backend | verdict | status | residual | residual (eq.) | forward error | "
        "allowance | certificate |\n|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < std::min(wrong.size(), kListed); ++i) {
    const ReplayRecord& r = *wrong[i];
    md << "| " << r.problem << " | " << r.solver << " | " << ToString(r.verdict) << " | " << ToString(r.status)
       << " | " << G(r.residual_rel) << " | " << G(r.residual_scaled) << " | " << G(r.forward_error) << " | "
       << G(r.forward_allowance) << " | " << r.certificate << " |\n";
  }
  md << "\n";
}

}  // namespace smcbench::markdown

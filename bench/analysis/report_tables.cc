// The report's tables as data: report_tables.h.
#include "bench/analysis/report_tables.h"

#include <string>
#include <string_view>

#include "bench/analysis/class_tables.h"
#include "bench/analysis/peer_tables.h"
#include "bench/analysis/suite_tables.h"
#include "bench/analysis/sweep_tables.h"

namespace smcbench {
namespace {

ReportTable Table(const std::string& name, std::vector<std::string> columns) {
  ReportTable t;
  t.name = name;
  t.columns = std::move(columns);
  return t;
}

TableCell Number(double v) { return v; }
TableCell Text(std::string_view s) { return std::string(s); }

// The run's suites as the report's tables see them: without the records cut by a budget or timed warm.
std::vector<SuiteResults> TabledSuites(const BenchResults& results) {
  std::vector<SuiteResults> out;
  for (const SuiteResults& suite : results.suites) {
    std::vector<std::string> cached;
    std::vector<ReplayRecord> cut;
    out.push_back(WithoutCachedRecords(WithoutCutRecords(suite, &cut), &cached));
  }
  return out;
}

void AddSummary(const BenchResults& results, std::vector<ReportTable>* tables) {
  ReportTable t = Table("summary", {"class", "size band", "problems", "fastest correct", "its correct", "its SGM time",
                                    "fastest / floor", "floor problems", "most reliable", "its correct (reliable)",
                                    "its wrong"});
  for (const ClassSummary& c : SummarizeClasses(results)) {
    t.rows.push_back({Text(ClassName(c.problem_class)), Text(ToString(c.problem_class.band)), Number(c.problems),
                      Text(c.fastest), Number(c.fastest_correct), Number(c.fastest_sgm), Number(c.fastest_over_floor),
                      Number(c.floor_instances), Text(c.most_reliable), Number(c.reliable_correct),
                      Number(c.reliable_wrong)});
  }
  tables->push_back(std::move(t));
  ReportTable f = Table("failures", {"backend", "records", "not correct", "wrong", "most common cause",
                                     "cause records", "cause message", "cause median time"});
  for (const BackendFailures& b : FailuresPerBackend(results)) {
    f.rows.push_back({Text(b.solver), Number(b.records), Number(b.not_correct), Number(b.wrong),
                      Text(b.cause.count ? std::string(ToString(b.cause.status)) : std::string()),
                      Number(b.cause.count), Text(b.cause.message), Number(b.cause.median_time)});
  }
  tables->push_back(std::move(f));
}

void AddBackends(const SuiteResults& suite, ReportTable* backends, ReportTable* statuses, ReportTable* audit) {
  const std::vector<BackendSummary> summary = SummarizeSuite(suite);
  const std::map<std::string, double> floor = FloorTimes(suite);
  for (const BackendSummary& b : summary) {
    const std::vector<double> over_floor = FloorRatios(suite.replay.records, floor, b.solver);
    backends->rows.push_back(
        {Text(suite.suite), Text(b.solver), Number(b.problems), Number(b.solved), Number(b.correctly_refused),
         Number(b.failed), Number(b.wrongly_claimed), Number(b.inaccurate), Number(b.wrongly_refused),
         Number(b.success_rate), Number(b.shifted_geomean), Number(b.worst_residual), Number(b.worst_residual_scaled),
         Number(b.worst_forward_error), Number(MedianOfSorted(over_floor)), Number(SolvedNothing(b, summary))});
    for (const auto& [status, count] : b.statuses) {
      statuses->rows.push_back({Text(suite.suite), Text(b.solver), Text(ToString(status)), Number(count)});
    }
  }
  for (const ClaimAudit& a : AuditClaims(suite)) {
    audit->rows.push_back({Text(suite.suite), Text(a.solver), Number(a.records), Number(a.right),
                           Number(a.false_success), Number(a.false_failure), Number(a.with_return_code)});
  }
}

void AddBands(const SuiteResults& suite, ReportTable* bands) {
  for (const BandWinner& w : FastestCorrectPerBand(suite)) {
    bands->rows.push_back({Text(suite.suite), Text(ToString(w.band)), Number(w.problems), Text(w.solver),
                           Number(w.correct), Number(w.shifted_geomean), Number(w.fastest_on), Text(w.runner_up),
                           Number(w.runner_up_correct), Number(w.runner_up_geomean)});
  }
}

void AddSweep(const SuiteResults& suite, ReportTable* ladder, ReportTable* sweep) {
  const ToleranceLadder l = BuildToleranceLadder(suite);
  for (const ToleranceLadder::Row& row : l.rows) {
    for (std::size_t k = 0; k < l.tolerances.size(); ++k) {
      ladder->rows.push_back({Text(suite.suite), Text(row.solver), Number(l.tolerances[k]), Number(row.correct[k]),
                              Number(row.problems[k])});
    }
  }
  for (const SweepRow& r : SweepRows(suite)) {
    sweep->rows.push_back({Text(suite.suite), Text(r.solver), Number(r.tolerance), Number(r.forward_error),
                           Number(static_cast<double>(r.with_reference)), Number(r.residual),
                           Number(r.residual_scaled), Number(r.time), Number(r.solved),
                           Number(static_cast<double>(r.problems))});
  }
}

void AddPeersAndProfiles(const SuiteResults& suite, ReportTable* peers, ReportTable* profiles) {
  for (const PeerRatioRow& row : OursAgainstPeersPerBand(suite)) {
    for (const auto& [library, r] : row.by_peer) {
      peers->rows.push_back({Text(suite.suite), Text(ToString(row.band)), Text(row.warm ? "warm" : "cold"),
                             Text(library), Number(MedianOfSorted(r)), Number(r.front()), Number(r.back()),
                             Number(static_cast<double>(r.size()))});
    }
  }
  for (const auto& [solver, ratios] : PerformanceRatios(suite)) {
    for (double r : ratios) profiles->rows.push_back({Text(suite.suite), Text(solver), Number(r)});
  }
}

}  // namespace

std::vector<ReportTable> ReportTables(const BenchResults& results) {
  std::vector<ReportTable> tables;
  AddSummary(results, &tables);
  ReportTable backends = Table("backends", {"suite", "backend", "problems", "solved", "correctly refused", "failed",
                                            "wrongly claimed", "inaccurate", "wrongly refused", "success",
                                            "SGM time", "worst residual (solved)", "worst residual (eq.)",
                                            "worst forward error (solved)", "time / floor", "solved nothing"});
  ReportTable statuses = Table("statuses", {"suite", "backend", "status", "records"});
  ReportTable audit = Table("audit", {"suite", "backend", "records", "flag right", "false success", "false failure",
                                      "flag from the return code"});
  ReportTable bands = Table("bands", {"suite", "size band", "problems", "fastest correct", "correct", "SGM time",
                                      "fastest on", "runner-up", "its correct", "its SGM time"});
  ReportTable ladder = Table("ladder", {"suite", "backend", "tolerance", "correct", "problems"});
  ReportTable sweep = Table("sweep", {"suite", "backend", "tolerance", "forward error (median)", "with z*",
                                      "achieved residual (median)", "achieved residual, eq. (median)",
                                      "time (median)", "solved", "problems"});
  ReportTable peers = Table("peers", {"suite", "size band", "track", "library", "median ratio", "min", "max",
                                      "problems"});
  ReportTable profiles = Table("profiles", {"suite", "backend", "ratio"});
  for (const SuiteResults& suite : TabledSuites(results)) {
    AddBackends(suite, &backends, &statuses, &audit);
    AddBands(suite, &bands);
    AddSweep(suite, &ladder, &sweep);
    AddPeersAndProfiles(suite, &peers, &profiles);
  }
  for (ReportTable* t : {&backends, &statuses, &audit, &bands, &ladder, &sweep, &peers, &profiles}) {
    tables.push_back(std::move(*t));
  }
  return tables;
}

}  // namespace smcbench

// The report's tables as data (ReportTables): every row has one cell per column, and the numbers are the typed
// tables' (SummarizeSuite, AuditClaims, FastestCorrectPerBand) on a hand-made suite.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "bench/analysis/report_tables.h"
#include "bench/analysis/report_test_records.h"

namespace smcbench {
namespace {

using namespace report_test;

const ReportTable& Named(const std::vector<ReportTable>& tables, const std::string& name) {
  for (const ReportTable& t : tables) {
    if (t.name == name) return t;
  }
  throw std::runtime_error("no table " + name);
}

double Cell(const ReportTable& t, std::size_t row, const std::string& column) {
  for (std::size_t c = 0; c < t.columns.size(); ++c) {
    if (t.columns[c] == column) return std::get<double>(t.rows.at(row).at(c));
  }
  throw std::runtime_error("no column " + column);
}

TEST(ReportTables, OneCellPerColumnAndTheNumbersOfTheTypedTables) {
  SuiteResults s;
  s.suite = "mine";
  s.description = "two problems";
  s.problems = 2;
  s.replay.records = {Rec("p1", "lemke", Verdict::kSolved, 2e-6), Rec("p2", "lemke", Verdict::kSolved, 4e-6),
                      Rec("p1", "psor", Verdict::kSolved, 1e-6), Rec("p2", "psor", Verdict::kFailed, 1e-6)};
  BenchResults results;
  results.suites = {s};
  const std::vector<ReportTable> tables = ReportTables(results);
  std::vector<std::string> names;
  for (const ReportTable& t : tables) {
    names.push_back(t.name);
    for (const auto& row : t.rows) EXPECT_EQ(row.size(), t.columns.size()) << t.name;
  }
  EXPECT_EQ(names, (std::vector<std::string>{"summary", "failures", "backends", "statuses", "audit", "bands", "ladder",
                                             "sweep", "peers", "profiles"}));
  const ReportTable& backends = Named(tables, "backends");
  ASSERT_EQ(backends.rows.size(), 2u);
  EXPECT_EQ(std::get<std::string>(backends.rows[0][1]), "lemke");
  EXPECT_EQ(Cell(backends, 0, "solved"), 2);
  EXPECT_EQ(Cell(backends, 1, "failed"), 1);
  EXPECT_DOUBLE_EQ(Cell(backends, 1, "success"), 0.5);
  EXPECT_DOUBLE_EQ(Cell(backends, 0, "SGM time"), SummarizeSuite(s)[0].shifted_geomean);
  const ReportTable& audit = Named(tables, "audit");
  EXPECT_EQ(Cell(audit, 1, "records"), 2);
  const ReportTable& bands = Named(tables, "bands");
  ASSERT_EQ(bands.rows.size(), 1u);
  EXPECT_EQ(std::get<std::string>(bands.rows[0][3]), "lemke");  // the only one with both right
  EXPECT_EQ(Named(tables, "profiles").rows.size(), 4u);          // two backends × two problems someone solved
  EXPECT_EQ(Named(tables, "failures").rows.size(), 2u);
}

}  // namespace
}  // namespace smcbench

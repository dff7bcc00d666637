// The report per size band: a suite's band slices and warm track as suites, ours against each library's best per
// band cold and warm, the per-band tables and the warm track in the report, and the AVI section's counts.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "bench/analysis/peer_tables.h"
#include "bench/analysis/report_markdown.h"
#include "bench/analysis/report_test_records.h"
#include "bench/replay/results_io.h"
#include "bench/replay/size_band.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

using namespace report_test;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Not;

WarmRecord Warm(const std::string& sequence, const std::string& solver, Verdict v, double t, int size, int changes,
                int reused, int fallbacks) {
  WarmRecord w;
  w.record = Rec(sequence, solver, v, t, size);
  w.record.mode = "warm";
  w.source = WarmSource::kTrajectory;
  w.counts.steps = 8;
  w.counts.steps_solved = v == Verdict::kSolved ? 8 : 3;
  w.counts.active_set_changes = changes;
  w.counts.iterations = 20;
  w.counts.reuse = !IsExternalBackendName(solver);
  w.counts.reused_steps = reused;
  w.counts.fallbacks = fallbacks;
  return w;
}

// Two bands (m = 2 and m = 64), ours (lemke, newton) against siconos-lcp-lemke and bullet-dantzig, cold and warm,
// with times chosen so that the winner flips between the bands: lemke is fastest at m = 2, newton at m = 64.
SuiteResults TwoBandSuite() {
  SuiteResults suite;
  suite.suite = "s";
  suite.description = "two bands";
  suite.problems = 4;
  for (const char* p : {"a", "b"}) {
    suite.replay.records.push_back(Rec(p, "lemke", Verdict::kSolved, 1e-6, 2));
    suite.replay.records.push_back(Rec(p, "newton", Verdict::kSolved, 4e-6, 2));
    suite.replay.records.push_back(Rec(p, "siconos-lcp-lemke", Verdict::kSolved, 3e-6, 2));
    suite.replay.records.push_back(Rec(p, "bullet-dantzig", Verdict::kSolved, 0.5e-6, 2));
  }
  for (const char* p : {"c", "d"}) {
    suite.replay.records.push_back(Rec(p, "lemke", Verdict::kSolved, 1e-3, 64));
    suite.replay.records.push_back(Rec(p, "newton", Verdict::kSolved, 1e-4, 64));
    suite.replay.records.push_back(Rec(p, "siconos-lcp-lemke", Verdict::kSolved, 4e-4, 64));
    suite.replay.records.push_back(Rec(p, "bullet-dantzig", Verdict::kFailed, 1e-4, 64));
  }
  suite.warm.push_back(Warm("s/warm/small", "lemke", Verdict::kSolved, 2e-7, 2, 1, 6, 1));
  suite.warm.push_back(Warm("s/warm/small", "bullet-dantzig", Verdict::kSolved, 6e-7, 2, 1, 0, 0));
  suite.warm.push_back(Warm("s/warm/mid", "newton", Verdict::kSolved, 2e-5, 64, 3, 4, 3));
  suite.warm.push_back(Warm("s/warm/mid", "siconos-lcp-lemke", Verdict::kSolved, 1e-4, 64, 3, 0, 0));
  suite.warm.push_back(Warm("s/warm/mid", "bullet-dantzig", Verdict::kFailed, 1e-5, 64, 0, 0, 0));
  return suite;
}

TEST(BenchReportBands, SlicesAndWarmSuiteKeepTheirRecords) {
  const SuiteResults suite = TwoBandSuite();
  const SuiteResults small = SizeBandSlice(suite, SizeBand::kTiny);
  EXPECT_EQ(small.problems, 2);
  EXPECT_EQ(small.replay.records.size(), 8u);
  EXPECT_EQ(small.suite, "s m<=4");
  EXPECT_EQ(SizeBandSlice(suite, SizeBand::kLarge).replay.records.size(), 0u);
  const SuiteResults warm = WarmTrackAsSuite(suite);
  EXPECT_EQ(warm.problems, 2);
  EXPECT_EQ(warm.replay.records.size(), 5u);
  // The fastest correct warm backend per band: lemke at m ≤ 4, newton at 5–64 (bullet failed there).
  const std::vector<BandWinner> winners = FastestCorrectPerBand(warm);
  ASSERT_EQ(winners.size(), 2u);
  EXPECT_EQ(winners[0].solver, "lemke");
  EXPECT_EQ(winners[1].solver, "newton");
}

TEST(BenchReportBands, PeerRatiosHaveAColdAndAWarmRowPerBand) {
  const std::vector<PeerRatioRow> rows = OursAgainstPeersPerBand(TwoBandSuite());
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0].band, SizeBand::kTiny);
  EXPECT_FALSE(rows[0].warm);
  // Cold m = 2: ours best 1 µs; siconos 3 µs → 3×, bullet 0.5 µs → 0.5× (on both problems).
  EXPECT_THAT(rows[0].by_peer.at("siconos"), ElementsAre(3.0, 3.0));
  EXPECT_THAT(rows[0].by_peer.at("bullet"), ElementsAre(0.5, 0.5));
  EXPECT_TRUE(rows[1].warm);
  EXPECT_EQ(rows[1].band, SizeBand::kTiny);
  EXPECT_DOUBLE_EQ(rows[1].by_peer.at("bullet").at(0), 3.0);  // 6e-7 / 2e-7
  EXPECT_EQ(rows[2].band, SizeBand::kSmall);
  EXPECT_FALSE(rows[2].warm);
  EXPECT_DOUBLE_EQ(rows[2].by_peer.at("siconos").at(0), 4.0);  // 4e-4 / 1e-4
  EXPECT_EQ(rows[2].by_peer.count("bullet"), 0u);              // bullet failed at m = 64: no ratio
  EXPECT_TRUE(rows[3].warm);
  EXPECT_DOUBLE_EQ(rows[3].by_peer.at("siconos").at(0), 5.0);  // 1e-4 / 2e-5
}

TEST(BenchReportBands, ReportHasPerBandTablesTheWarmTrackAndTheRatioTable) {
  const std::string md = ReportOf(TwoBandSuite(), "bands");
  EXPECT_THAT(md, HasSubstr("**Per size band (cold)**"));
  EXPECT_THAT(md, HasSubstr("*cold, m ≤ 4* (2 problems)"));
  EXPECT_THAT(md, HasSubstr("*cold, 5 ≤ m ≤ 64* (2 problems)"));
  EXPECT_THAT(md, HasSubstr("### Warm track of suite `s`"));
  EXPECT_THAT(md, HasSubstr("*warm, m ≤ 4* (1 problems)"));
  EXPECT_THAT(md, HasSubstr("| s/warm/mid | trajectory | 64 | 8 | 3 | newton | 20 µs | 20 | newton | 4 / 3 | 2/3 |"));
  EXPECT_THAT(md, HasSubstr("| 5 ≤ m ≤ 64 | cold | | 4× [4 – 4] (2) |"));
  EXPECT_THAT(md, HasSubstr("| 5 ≤ m ≤ 64 | warm | | 5× [5 – 5] (1) |"));
  EXPECT_THAT(md, HasSubstr("| m ≤ 4 | cold | 0.5× [0.5 – 0.5] (2) | 3× [3 – 3] (2) |"));
}

// The AVI section: verdict counts and the median time over correct answers per backend, correct answers per
// family (the id's second part), a wrong answer listed first among the failures, in bold.
TEST(ReportAvi, SectionCountsVerdictsPerBackendAndFamily) {
  SuiteResults s;
  s.suite = "avi";
  s.description = "AVIs";
  s.problems = 3;
  s.replay.records = {Rec("avi/planted/n2/s1", "lemke", Verdict::kSolved, 1e-6),
                      Rec("avi/planted/n4/s1", "lemke", Verdict::kSolved, 3e-6),
                      Rec("avi/infeasible/halfline", "lemke", Verdict::kCorrectlyRefused, 2e-6),
                      Rec("avi/planted/n2/s1", "bad", Verdict::kFailed, 1e-6),
                      Rec("avi/planted/n4/s1", "bad", Verdict::kWronglyClaimed, 1e-6),
                      Rec("avi/infeasible/halfline", "bad", Verdict::kCorrectlyRefused, 5e-6)};
  for (ReplayRecord& r : s.replay.records) r.suite = "avi";
  const std::string md = ReportOf(s, "avi");
  EXPECT_THAT(md, HasSubstr("## AVI suite `avi`: AVIs"));
  EXPECT_THAT(md, HasSubstr("(1 infeasible, 2 planted)"));
  EXPECT_THAT(md, HasSubstr("| lemke | 3 | 2 | 1 | 0 | 0 | 0 | 0 | 2 µs |"));
  EXPECT_THAT(md, HasSubstr("| bad | 3 | 0 | 1 | **1** | 0 | 0 | 1 | 5 µs |"));
  EXPECT_THAT(md, HasSubstr("| backend | planted | infeasible | \n"));
  EXPECT_THAT(md, HasSubstr("| bad | 0/2 | 1/1 | \n"));
  const auto failures = md.find("Where the backends fail (2 AVI × backend");
  ASSERT_NE(failures, std::string::npos);
  EXPECT_LT(md.find("| bad | **WRONGLY CLAIMED** |", failures), md.find("| failed |", failures));
  EXPECT_EQ(md.find("## Suite `avi`"), std::string::npos);  // not the box suite's section
}

}  // namespace
}  // namespace smcbench

// The class summary and the failures per backend: class_tables.h.
#include "bench/analysis/class_tables.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <string_view>
#include <tuple>

#include "bench/analysis/record_facts.h"
#include "bench/replay/jobs.h"

namespace smcbench {
namespace {

std::vector<std::string> SplitTags(const std::string& tags) {
  std::vector<std::string> out;
  std::size_t begin = 0;
  while (begin <= tags.size()) {
    const std::size_t end = std::min(tags.find(',', begin), tags.size());
    if (end > begin) out.push_back(tags.substr(begin, end - begin));
    begin = end + 1;
  }
  return out;
}

bool Has(const std::vector<std::string>& tags, std::string_view tag) {
  return std::find(tags.begin(), tags.end(), tag) != tags.end();
}

int MatrixOrder(const std::string& matrix) {
  static const char* const kOrder[] = {"SPD", "nonsymmetric P", "general", "sparse", "MCP", "AVI"};
  for (int i = 0; i < 6; ++i) {
    if (matrix == kOrder[i]) return i;
  }
  return 6;
}

int BoundsOrder(const std::string& bounds) {
  static const char* const kOrder[] = {"LCP", "relay", "mixed", "untagged"};
  for (int i = 0; i < 4; ++i) {
    if (bounds == kOrder[i]) return i;
  }
  return 4;
}

}  // namespace

ProblemClass ClassOfRecord(const ReplayRecord& r, bool mcp, bool avi) {
  return ProblemClass{MatrixClassOf(r, mcp, avi), SizeBandOf(r.size), BoundsClassOf(r)};
}

std::string MatrixClassOf(const ReplayRecord& record, bool mcp_suite, bool avi_suite) {
  const std::vector<std::string> tags = SplitTags(record.tags);
  if (mcp_suite || Has(tags, kMcpSuiteTag)) return "MCP";
  if (avi_suite || Has(tags, kAviSuiteTag)) return "AVI";
  if (Has(tags, "sparse") || (record.sparse && record.solver != kGenericSparsePath)) return "sparse";
  if (Has(tags, "spd") || (Has(tags, "symmetric") && Has(tags, "positive_definite"))) return "SPD";
  for (const std::string& t : tags) {
    if (t == "pmatrix" || t == "p_matrix" || t == "diagdom" || t.rfind("nonsym", 0) == 0) return "nonsymmetric P";
  }
  return "general";
}

std::string BoundsClassOf(const ReplayRecord& record) {
  const std::vector<std::string> tags = SplitTags(record.tags);
  if (Has(tags, "lcp")) return "LCP";
  if (Has(tags, "relay")) return "relay";
  if (Has(tags, "mixed") || Has(tags, "mlcp") || Has(tags, "box")) return "mixed";
  return "untagged";
}

bool ProblemClass::operator<(const ProblemClass& o) const {
  return std::make_tuple(MatrixOrder(matrix), matrix, BoundsOrder(bounds), bounds, static_cast<int>(band)) <
         std::make_tuple(MatrixOrder(o.matrix), o.matrix, BoundsOrder(o.bounds), o.bounds, static_cast<int>(o.band));
}

bool ProblemClass::operator==(const ProblemClass& o) const {
  return matrix == o.matrix && band == o.band && bounds == o.bounds;
}

std::string ClassName(const ProblemClass& c) { return c.matrix + " · " + c.bounds; }

std::map<std::string, double> FloorTimes(const SuiteResults& suite) {
  std::map<std::string, double> out;
  for (const ReplayRecord& r : suite.replay.floor) {
    if (r.status == SolveStatus::kSolved && r.samples > 0) out[InstanceOf(r)] = r.time_median;
  }
  return out;
}

std::vector<double> FloorRatios(const std::vector<ReplayRecord>& records, const std::map<std::string, double>& floor,
                                const std::string& solver) {
  std::vector<double> out;
  for (const ReplayRecord& r : records) {
    if (r.solver != solver || !IsCorrect(r) || r.samples == 0) continue;
    const auto it = floor.find(InstanceOf(r));
    if (it != floor.end() && it->second > 0.0) out.push_back(r.time_median / it->second);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<ReplayRecord> PooledColdRecords(const BenchResults& results, std::map<std::string, double>* floor) {
  std::vector<ReplayRecord> out;
  for (const SuiteResults& suite : results.suites) {
    const bool mcp = IsMcpSuite(suite), avi = IsAviSuite(suite);
    for (ReplayRecord r : suite.replay.records) {
      if (r.mode == "cached") continue;
      // The suite's kind travels in the tags (MatrixClassOf reads them).
      if (mcp || avi) r.tags = (r.tags.empty() ? "" : r.tags + ",") + (mcp ? kMcpSuiteTag : kAviSuiteTag);
      r.problem = suite.suite + "/" + r.problem;
      out.push_back(std::move(r));
    }
    if (floor) {
      for (const auto& [instance, t] : FloorTimes(suite)) (*floor)[suite.suite + "/" + instance] = t;
    }
  }
  return out;
}

std::vector<ClassSummary> SummarizeClasses(const BenchResults& results, double time_limit_seconds) {
  std::map<std::string, double> floor;
  const std::vector<ReplayRecord> pooled = PooledColdRecords(results, &floor);
  std::map<ProblemClass, std::vector<ReplayRecord>> by_class;
  for (const ReplayRecord& r : pooled) {
    by_class[ClassOfRecord(r, false, false)].push_back(r);
  }
  std::vector<ClassSummary> out;
  for (const auto& [problem_class, records] : by_class) {
    ClassSummary row;
    row.problem_class = problem_class;
    std::set<std::string> instances;
    for (const ReplayRecord& r : records) instances.insert(InstanceOf(r));
    row.problems = static_cast<int>(instances.size());
    const std::vector<BackendSummary> summary = SummarizeRecords(records, time_limit_seconds);
    const BackendSummary* fastest = nullptr;
    const BackendSummary* reliable = nullptr;
    for (const BackendSummary& b : summary) {
      if (b.wrong() == 0 && b.correct() > 0 && (!fastest || b.shifted_geomean < fastest->shifted_geomean)) {
        fastest = &b;
      }
      if (!reliable || std::make_tuple(-b.correct(), b.wrong(), b.shifted_geomean) <
                           std::make_tuple(-reliable->correct(), reliable->wrong(), reliable->shifted_geomean)) {
        reliable = &b;
      }
    }
    if (fastest) {
      row.fastest = fastest->solver;
      row.fastest_correct = fastest->correct();
      row.fastest_sgm = fastest->shifted_geomean;
      const std::vector<double> ratios = FloorRatios(records, floor, fastest->solver);
      row.fastest_over_floor = MedianOfSorted(ratios);
      row.floor_instances = static_cast<int>(ratios.size());
    }
    if (reliable) {
      row.most_reliable = reliable->solver;
      row.reliable_correct = reliable->correct();
      row.reliable_wrong = reliable->wrong();
    }
    out.push_back(std::move(row));
  }
  return out;
}

std::vector<BackendFailures> FailuresPerBackend(const BenchResults& results) {
  const std::vector<ReplayRecord> pooled = PooledColdRecords(results, nullptr);
  std::vector<BackendFailures> out;
  std::map<std::string, std::size_t> index;
  std::map<std::string, std::vector<const ReplayRecord*>> not_correct;
  for (const ReplayRecord& r : pooled) {
    auto [it, inserted] = index.emplace(r.solver, out.size());
    if (inserted) {
      out.emplace_back();
      out.back().solver = r.solver;
    }
    BackendFailures& b = out[it->second];
    ++b.records;
    if (IsCorrect(r)) continue;
    ++b.not_correct;
    b.wrong += IsWrong(r.verdict);
    not_correct[r.solver].push_back(&r);
    const ProblemClass c = ClassOfRecord(r, false, false);
    b.entries.push_back({InstanceOf(r), ClassName(c) + " · " + std::string(ShortName(c.band)), r.status, r.verdict,
                         r.message});
  }
  for (BackendFailures& b : out) {
    if (b.not_correct > 0) b.cause = MostCommonFailureOf(not_correct[b.solver]);
  }
  return out;
}

}  // namespace smcbench

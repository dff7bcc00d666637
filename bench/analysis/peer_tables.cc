// The peer ratio tables: peer_tables.h.
#include "bench/analysis/peer_tables.h"

#include <algorithm>

#include "bench/analysis/record_facts.h"
#include "bench/replay/jobs.h"
#include "solvers/registry/registry.h"

namespace smcbench {

std::vector<PeerRatioRow> OursAgainstPeersPerBand(const SuiteResults& suite) {
  std::vector<PeerRatioRow> out;
  const auto rows = [&](const std::vector<ReplayRecord>& records, bool warm) {
    // problem → fastest correct time of ours, and of each peer family; problem → size.
    std::map<std::string, double> ours;
    std::map<std::string, std::map<std::string, double>> peers;
    std::map<std::string, int> sizes;
    for (const ReplayRecord& r : records) {
      if (r.verdict != Verdict::kSolved || r.solver == "newton-sparse-path") continue;
      const std::string key = InstanceOf(r);
      sizes[key] = r.size;
      if (!IsExternalBackendName(r.solver)) {
        auto [it, inserted] = ours.emplace(key, r.time_median);
        if (!inserted) it->second = std::min(it->second, r.time_median);
        continue;
      }
      const std::string family = r.solver.substr(0, r.solver.find('-'));
      auto [it, inserted] = peers[family].emplace(key, r.time_median);
      if (!inserted) it->second = std::min(it->second, r.time_median);
    }
    std::map<SizeBand, PeerRatioRow> by_band;
    for (const auto& [family, times] : peers) {
      for (const auto& [key, t] : times) {
        if (!ours.count(key)) continue;
        PeerRatioRow& row = by_band[SizeBandOf(sizes.at(key))];
        row.band = SizeBandOf(sizes.at(key));
        row.warm = warm;
        row.by_peer[family].push_back(t / ours.at(key));
      }
    }
    for (auto& [band, row] : by_band) {
      for (auto& [family, ratios] : row.by_peer) std::sort(ratios.begin(), ratios.end());
    }
    return by_band;
  };
  std::vector<ReplayRecord> warm_records;
  for (const WarmRecord& w : suite.warm) warm_records.push_back(w.record);
  std::map<SizeBand, PeerRatioRow> cold = rows(suite.replay.records, false), warm = rows(warm_records, true);
  for (SizeBand band : kSizeBands) {
    if (cold.count(band)) out.push_back(cold.at(band));
    if (warm.count(band)) out.push_back(warm.at(band));
  }
  return out;
}

std::vector<PeerClassRow> OursAgainstPeersPerClass(const SuiteResults& suite) {
  const bool mcp = IsMcpSuite(suite), avi = IsAviSuite(suite);
  const std::map<std::string, double> floor = FloorTimes(suite);
  std::map<std::string, double> ours;                               // instance → our fastest correct time
  std::map<std::string, std::map<std::string, double>> peers;       // family → instance → its fastest
  std::map<std::string, ProblemClass> class_of;
  for (const ReplayRecord& r : suite.replay.records) {
    if (r.verdict != Verdict::kSolved || r.solver == kGenericSparsePath || r.mode == "cached") continue;
    const std::string key = InstanceOf(r);
    class_of.emplace(key, ClassOfRecord(r, mcp, avi));
    std::map<std::string, double>& times =
        IsExternalBackendName(r.solver) ? peers[r.solver.substr(0, r.solver.find('-'))] : ours;
    auto [it, inserted] = times.emplace(key, r.time_median);
    if (!inserted) it->second = std::min(it->second, r.time_median);
  }
  std::map<ProblemClass, PeerClassRow> rows;
  for (const auto& [family, times] : peers) {
    for (const auto& [key, t] : times) {
      if (!ours.count(key)) continue;
      PeerClassRow& row = rows[class_of.at(key)];
      row.problem_class = class_of.at(key);
      row.by_peer[family].push_back(t / ours.at(key));
    }
  }
  for (const auto& [key, t] : ours) {
    const auto f = floor.find(key);
    if (f == floor.end() || !(f->second > 0.0)) continue;
    PeerClassRow& row = rows[class_of.at(key)];
    row.problem_class = class_of.at(key);
    row.ours_over_floor.push_back(t / f->second);
  }
  std::vector<PeerClassRow> out;
  for (auto& [c, row] : rows) {
    for (auto& [family, ratios] : row.by_peer) std::sort(ratios.begin(), ratios.end());
    std::sort(row.ours_over_floor.begin(), row.ours_over_floor.end());
    out.push_back(std::move(row));
  }
  return out;
}

SparsePathComparison CompareWithSparsePath(const SuiteResults& suite) {
  std::map<std::string, double> best, generic;
  std::map<std::string, int> sizes;
  for (const auto& r : suite.replay.records) {
    if (r.verdict != Verdict::kSolved) continue;
    if (r.solver == "newton-sparse-path") {
      generic[r.problem] = r.time_median;
    } else {
      auto [it, inserted] = best.emplace(r.problem, r.time_median);
      if (!inserted) it->second = std::min(it->second, r.time_median);
      sizes[r.problem] = r.size;
    }
  }
  SparsePathComparison c;
  for (const auto& [problem, t] : generic) {
    if (!best.count(problem)) continue;
    c.speedups.push_back(t / best.at(problem));
    // Arithmetic floor: one m×m factorization and two mat-vecs, m³/3 + 4m² flops, at one flop per nanosecond
    // (scalar code at ~1–3 GHz).
    const double m = sizes.at(problem);
    c.over_floor.push_back(best.at(problem) / ((m * m * m / 3.0 + 4.0 * m * m) * 1e-9));
  }
  std::sort(c.speedups.begin(), c.speedups.end());
  std::sort(c.over_floor.begin(), c.over_floor.end());
  return c;
}

SiconosComparison CompareWithSiconos(const SuiteResults& suite) {
  std::map<std::string, double> ours, theirs, theirs_through_worker;
  std::map<std::string, int> sizes;
  for (const auto& r : suite.replay.records) {
    if (r.verdict != Verdict::kSolved || r.solver == "newton-sparse-path") continue;
    const bool siconos = r.solver.rfind("siconos-", 0) == 0;
    if (!siconos && IsExternalBackendName(r.solver)) continue;  // another library (bullet-*, dart-*): not ours
    auto& side = !siconos ? ours : r.timed_in_worker ? theirs_through_worker : theirs;
    auto [it, inserted] = side.emplace(r.problem, r.time_median);
    if (!inserted) it->second = std::min(it->second, r.time_median);
    sizes[r.problem] = r.size;
  }
  const auto by_size = [&](const std::map<std::string, double>& external) {
    std::map<int, std::vector<double>> ratios;
    for (const auto& [problem, t] : external) {
      if (ours.count(problem)) ratios[sizes.at(problem)].push_back(t / ours.at(problem));
    }
    for (auto& [m, r] : ratios) std::sort(r.begin(), r.end());
    return ratios;
  };
  return {by_size(theirs), by_size(theirs_through_worker)};
}

}  // namespace smcbench

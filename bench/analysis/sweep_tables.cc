// The tolerance sweep's tables: sweep_tables.h.
#include "bench/analysis/sweep_tables.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>

#include "bench/analysis/record_facts.h"

namespace smcbench {

ToleranceLadder BuildToleranceLadder(const SuiteResults& suite) {
  ToleranceLadder ladder;
  std::set<double> tolerances;
  for (const auto& r : suite.replay.sweep) tolerances.insert(r.tolerance);
  ladder.tolerances.assign(tolerances.rbegin(), tolerances.rend());
  for (const std::string& solver : SolversIn(suite.replay.sweep)) {
    ToleranceLadder::Row row;
    row.solver = solver;
    row.correct.assign(ladder.tolerances.size(), 0);
    row.problems.assign(ladder.tolerances.size(), 0);
    for (const auto& r : suite.replay.sweep) {
      if (r.solver != solver) continue;
      const auto k = static_cast<std::size_t>(
          std::find(ladder.tolerances.begin(), ladder.tolerances.end(), r.tolerance) - ladder.tolerances.begin());
      ++row.problems[k];
      row.correct[k] += IsCorrect(r);
    }
    ladder.rows.push_back(std::move(row));
  }
  return ladder;
}

std::vector<SweepRow> SweepRows(const SuiteResults& suite) {
  std::map<std::pair<std::string, double>, std::vector<const ReplayRecord*>> groups;  // (backend, −tolerance)
  for (const auto& r : suite.replay.sweep) groups[{r.solver, -r.tolerance}].push_back(&r);
  std::vector<SweepRow> rows;
  for (const auto& [key, rs] : groups) {
    std::vector<double> res, res_scaled, fwd, t, t_fwd;
    SweepRow row;
    row.solver = key.first;
    row.tolerance = -key.second;
    row.problems = rs.size();
    for (const auto* r : rs) {
      res.push_back(std::isfinite(r->residual_rel) ? r->residual_rel : 1e300);
      res_scaled.push_back(std::isfinite(r->residual_scaled) ? r->residual_scaled
                                                             : std::isnan(r->residual_scaled) ? kNaN : 1e300);
      t.push_back(r->time_median);
      if (!std::isnan(r->forward_error)) {
        fwd.push_back(std::isfinite(r->forward_error) ? r->forward_error : 1e300);
        t_fwd.push_back(r->time_median);
      }
      row.solved += r->verdict == Verdict::kSolved;
    }
    row.residual = MedianDefined(res);
    row.residual_scaled = MedianDefined(res_scaled);
    row.time = MedianDefined(t);
    row.forward_error = MedianDefined(fwd);
    row.with_reference = fwd.size();
    row.time_with_reference = MedianDefined(t_fwd);
    rows.push_back(row);
  }
  return rows;
}

}  // namespace smcbench

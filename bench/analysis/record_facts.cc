// The record facts of the report's tables: record_facts.h.
#include "bench/analysis/record_facts.h"

#include <algorithm>
#include <cmath>

namespace smcbench {

std::string InstanceOf(const ReplayRecord& r) { return r.start.empty() ? r.problem : r.problem + "@" + r.start; }

bool IsCorrect(const ReplayRecord& r) {
  return r.verdict == Verdict::kSolved || r.verdict == Verdict::kCorrectlyRefused;
}

std::vector<std::string> SolversIn(const std::vector<ReplayRecord>& records) {
  std::vector<std::string> out;
  for (const auto& r : records) {
    if (std::find(out.begin(), out.end(), r.solver) == out.end()) out.push_back(r.solver);
  }
  return out;
}

double MedianOfSorted(const std::vector<double>& sorted) {
  return sorted.empty() ? kNaN : sorted[sorted.size() / 2];
}

double MedianDefined(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return std::isnan(x); }), v.end());
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

double MaxDefined(double a, double b) { return std::isnan(a) ? b : std::isnan(b) ? a : std::max(a, b); }

double LogLogSlope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const std::size_t n = x.size();
  if (n < 2) return std::nan("");
  for (std::size_t i = 0; i < n; ++i) {
    const double a = std::log(x[i]), b = std::log(y[i]);
    sx += a, sy += b, sxx += a * a, sxy += a * b;
  }
  const double d = n * sxx - sx * sx;
  return d > 0 ? (n * sxy - sx * sy) / d : std::nan("");
}


}  // namespace smcbench

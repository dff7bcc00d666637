#include "bench/kinds/problem_kind.h"

#include "bench/replay/floor.h"
#include "solvers/core/glob_match.h"

namespace smcbench {

ProblemFilter::ProblemFilter(std::vector<std::string> globs_in)
    : globs(std::move(globs_in)), matched(globs.size(), 0) {}

bool ProblemFilter::Keeps(std::string_view id) {
  if (globs.empty()) return true;
  bool keep = false;
  for (std::size_t g = 0; g < globs.size(); ++g) {
    if (GlobMatch(globs[g], id)) keep = true, matched[g] = 1;  // every glob asked: each learns that it matched
  }
  return keep;
}

std::vector<std::string> ProblemFilter::Unmatched() const {
  std::vector<std::string> out;
  for (std::size_t g = 0; g < globs.size(); ++g) {
    if (!matched[g]) out.push_back(globs[g]);
  }
  return out;
}

std::vector<SuiteJob> KindSuite::Jobs(const std::vector<std::string>& backends, const ReplayOptions& options,
                                      bool floor) const {
  std::vector<SuiteJob> jobs;
  for (const SuiteUnit& unit : Units()) {
    for (const std::string& solver : backends) jobs.push_back({JobKind::kCold, unit, solver, options.tolerance});
    if (floor && !backends.empty()) jobs.push_back({JobKind::kFloor, unit, kFloorSolver, options.tolerance});
  }
  return jobs;
}

}  // namespace smcbench

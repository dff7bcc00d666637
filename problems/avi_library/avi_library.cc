// AviProblemSet's validation (avi_library.h).
#include "problems/avi_library/avi_library.h"

#include <set>

namespace smcbench {

void AviProblemSet::Validate() const {
  std::set<std::string> ids;
  for (std::size_t k = 0; k < problems.size(); ++k) {
    const AviLibraryProblem& p = problems[k];
    const std::string where = "AviProblemSet '" + name + "': problem " + std::to_string(k) +
                              (p.id.empty() ? std::string() : " ('" + p.id + "')");
    if (p.id.empty()) throw InvalidInputError(where + ": id is empty");
    if (!ids.insert(p.id).second) throw InvalidInputError(where + ": id is a duplicate");
    if (!p.problem) throw InvalidInputError(where + ": problem is null");
    if (p.reference.verified() && p.reference.solution.lambda.size() != p.problem->size()) {
      throw InvalidInputError(where + ": reference.solution.lambda has size " +
                              std::to_string(p.reference.solution.lambda.size()) + ", the problem has n = " +
                              std::to_string(p.problem->size()));
    }
    if (p.reference.verified() && p.expected == ExpectedOutcome::kInfeasible) {
      throw InvalidInputError(where + ": expected is infeasible but reference is a verified solution");
    }
  }
}

}  // namespace smcbench

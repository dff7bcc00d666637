// McpProblemSet's validation (mcp_library.h).
#include "problems/mcp/mcp_library.h"

#include <set>

namespace smcbench {

void McpProblemSet::Validate() const {
  std::set<std::string> ids;
  for (std::size_t k = 0; k < problems.size(); ++k) {
    const McpLibraryProblem& p = problems[k];
    const std::string where = "McpProblemSet '" + name + "': problem " + std::to_string(k) +
                              (p.id.empty() ? std::string() : " ('" + p.id + "')");
    if (p.id.empty()) throw InvalidInputError(where + ": id is empty");
    if (!ids.insert(p.id).second) throw InvalidInputError(where + ": id is a duplicate");
    if (!p.problem) throw InvalidInputError(where + ": problem is null");
    const int n = p.problem->size();
    if (p.starts.empty()) throw InvalidInputError(where + ": starts is empty (every problem needs at least one)");
    if (p.start_labels.size() != p.starts.size()) {
      throw InvalidInputError(where + ": start_labels has " + std::to_string(p.start_labels.size()) +
                              " entries but starts has " + std::to_string(p.starts.size()));
    }
    for (std::size_t s = 0; s < p.starts.size(); ++s) {
      if (p.starts[s].size() != n) {
        throw InvalidInputError(where + ": starts[" + std::to_string(s) + "] has size " +
                                std::to_string(p.starts[s].size()) + ", the problem has n = " + std::to_string(n));
      }
      if (!p.starts[s].allFinite()) {
        throw InvalidInputError(where + ": starts[" + std::to_string(s) + "] has a NaN or infinite entry");
      }
      if (p.start_labels[s].empty())
        throw InvalidInputError(where + ": start_labels[" + std::to_string(s) + "] is empty");
    }
    for (std::size_t r = 0; r < p.references.size(); ++r) {
      const Vector& z = p.references[r].z;
      if (p.references[r].verified() && z.size() != n) {
        throw InvalidInputError(where + ": references[" + std::to_string(r) + "].z has size " +
                                std::to_string(z.size()) + ", the problem has n = " + std::to_string(n));
      }
    }
  }
}

}  // namespace smcbench

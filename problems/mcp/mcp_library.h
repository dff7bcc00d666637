// The MCP half of the problem library: nonlinear complementarity problems with what a benchmark needs (stable id,
// the literature's starting points, the outcome a correct backend must produce, certified references). A nonlinear
// F cannot be stored as data: an MCP of the library is a named built-in (F and its Jacobian in C++, templated on the
// scalar type so that references are refined in extended precision), rebuilt from its id; user MCPs come from
// Python callables or C++ subclasses of MCP.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "solvers/core/problem.h"
#include "solvers/core/verdict.h"

namespace smcbench {

// One MCP of a suite with every published starting point: a problem × start is one benchmark job.
struct McpLibraryProblem {
  // Stable across runs and machines: "mcp/<family>/<parameters>", e.g. "mcp/classic/kojshin" or
  // "mcp/obstacle/n1024". Unique within a set.
  std::string id;
  // Where it came from: "literature:<short citation>", "generated:<family>", "capture:<scene>".
  std::string source;
  std::shared_ptr<const MCP> problem;
  // The published starting points (at least one), each with a label ("start1", "z0=0", ...), same order.
  std::vector<Vector> starts;
  std::vector<std::string> start_labels;
  std::vector<std::string> tags;  // "classic", "family", "hard", "degenerate", "several-solutions", "sparse", ...
  ExpectedOutcome expected = ExpectedOutcome::kUnknown;
  // Certified reference solutions (solvers/reference/mcp_certify.h). One entry for a problem with a unique
  // solution; several when the problem has several known ones.
  std::vector<ReferenceSolution> references;
  // True when `references` lists every solution of the problem (proved, or established in the literature): an
  // answer is then judged by its forward error against the nearest one. False: forward errors are judged only
  // against a reference certified unique.
  bool references_complete = false;
  std::map<std::string, std::string> metadata;  // anything else worth keeping, as text

  int size() const { return problem ? problem->size() : 0; }
  bool sparse() const { return problem && problem->jacobian_kind() == MCP::JacobianKind::kSparse; }
};

// The name of the built-in suite (`bench --suite mcp`) and of its records' suite.
inline constexpr const char* kMcpSuiteName = "mcp";

struct McpProblemSet {
  std::string name;         // kMcpSuiteName, or a user's name
  std::string description;  // one line
  std::vector<McpLibraryProblem> problems;

  // InvalidInputError naming the id: empty or duplicate ids, a null problem, no starts, a start or reference of the
  // wrong size, start labels not matching the starts.
  void Validate() const;
};

}  // namespace smcbench

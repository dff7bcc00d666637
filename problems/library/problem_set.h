// The problem library's data model: box-MLCPs with the metadata a benchmark needs (stable id, where the problem
// came from, matrix-class tags, seed, the outcome a correct backend must produce, a known solution). Suites,
// generators, captured trajectories and the on-disk format (problem_set_io.h) all speak this one type.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "solvers/core/problem.h"
#include "solvers/core/status.h"
#include "solvers/core/verdict.h"

namespace smcbench {

// A matrix property that may be known to hold, known not to hold, or not known (P-matrix checks are exponential).
enum class Tristate : std::uint8_t { kUnknown = 0, kNo = 1, kYes = 2 };
std::string_view ToString(Tristate value);  // "unknown", "no", "yes"

struct MatrixTags {
  Tristate symmetric = Tristate::kUnknown;
  Tristate positive_definite = Tristate::kUnknown;  // of the symmetric part: xᵀMx > 0 for x ≠ 0
  Tristate p_matrix = Tristate::kUnknown;           // every principal minor > 0 (unique solution for every q)
};

struct LibraryProblem {
  // Stable across runs and machines: "<suite>/<family>/<parameters>", e.g. "families/spd-relay/m16/s3" or
  // "paper/galias-yu-2007/implicit/h0.3/k12". Unique within a set.
  std::string id;
  // Where it came from: "generated:<generator>", "siconos:<relative path>", "capture:<scene>".
  std::string source;
  BoxMLCP problem;
  MatrixTags matrix;
  std::vector<std::string> tags;  // free labels: "degenerate", "murty", "h-sweep", "near-singular", ...
  std::optional<std::uint64_t> seed;
  ExpectedOutcome expected = ExpectedOutcome::kUnknown;
  // A known solution (planted z*, or the z the capturing run used); empty if none.
  Vector solution;
  // Anything else worth keeping (capture: scene, method, h, theta, step), as text.
  std::map<std::string, std::string> metadata;
  // The certified reference solution (solvers/reference/certify.h), when one was computed.
  ReferenceSolution reference;

  int size() const { return problem.size(); }
  bool sparse() const { return problem.is_sparse(); }
};

// A library problem with no tags, seed, solution or metadata and an unknown expected outcome (aggregate
// initialization would have to name every field).
inline LibraryProblem MakeLibraryProblem(std::string id, std::string source, BoxMLCP problem) {
  return LibraryProblem{std::move(id), std::move(source), std::move(problem), MatrixTags{}, {}, std::nullopt,
                        ExpectedOutcome::kUnknown, Vector(), {}, ReferenceSolution{}};
}

// A name or id taken from a file, made safe to quote in a one-line error message: control and non-ASCII bytes as
// \xNN, cut to max_bytes of input with "..." after (ids come from files, and a message must stay one line).
std::string QuoteForMessage(std::string_view text, std::size_t max_bytes = 200);

struct ProblemSet {
  std::string name;         // "paper", "families", "hard", "siconos", "scale", or a capture's name
  std::string description;  // one line
  std::vector<LibraryProblem> problems;

  // Throws InvalidInputError naming the id if two problems share an id, an id is empty, a solution has the
  // wrong size, a reference's certificate is not a known value, or its z* does not match the certificate (size n
  // when verified, else empty).
  void Validate() const;
};

// The verdict (solvers/core/verdict.h) for a result on a library problem: its expected outcome and reference.
inline Judgement Judge(const LibraryProblem& problem, SolveStatus status, const Vector& z, double tolerance) {
  return Judge(problem.problem, problem.expected, &problem.reference, status, z, tolerance);
}

}  // namespace smcbench

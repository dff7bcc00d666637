// Helpers shared by the suite generators (families.cc, hard_cases.cc): a reproducible RNG, number formatting for
// ids and metadata, the planted (z*, w*) of one row, and LibraryProblem construction. Not a public API.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>

#include "problems/library/problem_set.h"
#include "solvers/core/number_text.h"
#include "solvers/generators/seeded_random.h"

namespace smcbench::suites_detail {

// The reproducible RNG of solvers/generators (same seed, same numbers on every platform).
using Random = SeededRandom;

// A step size for ids: "0.1", "0.01", "0.001", "1e-04", ... ("%g", stable and short).
inline std::string StepText(double h) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%g", h);
  return buffer;
}

// The state of a planted row: strictly inside its bounds with w = 0, at l with w > 0, at u with w < 0.
enum class PlantedState { kInside, kAtLower, kAtUpper };

struct PlantedRow {
  double z;
  double w;
};

// z*, w* of a row of bounds [l, u] in the given state (the bound must be finite for kAtLower / kAtUpper):
// |w| ∈ [0.1, 1.1] at a bound; inside, z at least 10% of a finite box (or 0.1) away from each finite bound.
inline PlantedRow PlantRow(double l, double u, PlantedState state, Random& rng) {
  switch (state) {
    case PlantedState::kAtLower:
      return {l, rng.Uniform(0.1, 1.1)};
    case PlantedState::kAtUpper:
      return {u, -rng.Uniform(0.1, 1.1)};
    case PlantedState::kInside:
      break;
  }
  const bool has_l = l > -kInf;
  const bool has_u = u < kInf;
  if (has_l && has_u) return {l + (u - l) * rng.Uniform(0.1, 0.9), 0.0};
  if (has_l) return {l + rng.Uniform(0.1, 2.0), 0.0};
  if (has_u) return {u - rng.Uniform(0.1, 2.0), 0.0};
  return {rng.Uniform(-2.0, 2.0), 0.0};
}

// A LibraryProblem with every field set (the aggregate has no default for BoxMLCP); the problem is named by its id.
inline LibraryProblem MakeProblem(std::string id, std::string source, BoxMLCP problem, MatrixTags matrix,
                                  ExpectedOutcome expected) {
  problem.set_name(id);
  LibraryProblem p = MakeLibraryProblem(std::move(id), std::move(source), std::move(problem));
  p.matrix = matrix;
  p.expected = expected;
  return p;
}

}  // namespace smcbench::suites_detail

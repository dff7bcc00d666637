// The box-MLCP problem kind: the library's problem sets (paper, families, hard, siconos, scale, tiny, or a
// problem-set file) as suites of a plan, each with its cold, floor, generic-sparse-path and sweep jobs and its warm
// sequences, replayed by ReplayOne.
#pragma once

#include <memory>

#include "bench/kinds/problem_kind.h"
#include "problems/library/problem_set.h"

namespace smcbench {

// The suite names the box kind builds (any other readable file that is not an AVI set is a box problem-set file).
inline constexpr const char* kBoxSuiteNames[] = {"paper", "families", "hard", "siconos", "scale", "tiny"};

std::shared_ptr<const ProblemKind> BoxProblemKind();

// A box suite of a plan. With generic_sparse_path, a suite named "paper" also runs its problems with M stored
// sparse through newton's UMFPACK path (kGenericSparsePath, a cold job of that pseudo-backend).
PlanSuite MakeBoxSuite(ProblemSet set, bool generic_sparse_path = false);

// The problem set of a box suite; InvalidInputError for a suite of another kind.
const ProblemSet& BoxSet(const KindSuite& suite);

// Box suites of these sets (no generic path): what a caller with problem sets gives ListBenchJobs.
std::vector<PlanSuite> BoxSuites(std::vector<ProblemSet> sets);

}  // namespace smcbench

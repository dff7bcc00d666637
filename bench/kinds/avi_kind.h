// The affine variational inequality kind: the `avi` suite or an AVI set file, each AVI × box backend replayed by
// ReplayAviOne through SolveAvi's reduction (manifest kind "avi", as before the kinds).
#pragma once

#include <memory>

#include "bench/kinds/problem_kind.h"
#include "problems/avi_library/avi_library.h"

namespace smcbench {

std::shared_ptr<const ProblemKind> AviProblemKind();

PlanSuite MakeAviSuite(AviProblemSet set);

// The problem set of an AVI suite; InvalidInputError for a suite of another kind.
const AviProblemSet& AviSet(const KindSuite& suite);

}  // namespace smcbench

// The problem kinds a run knows without being told (BenchRequest::kinds empty): box, MCP, AVI, in the order their
// suites and jobs come in a plan.
#pragma once

#include "bench/kinds/problem_kind.h"

namespace smcbench {

ProblemKinds BuiltinProblemKinds();

}  // namespace smcbench

#include "bench/kinds/builtin_kinds.h"

#include "bench/kinds/avi_kind.h"
#include "bench/kinds/box_kind.h"
#include "bench/kinds/mcp_kind.h"

namespace smcbench {

ProblemKinds BuiltinProblemKinds() { return {BoxProblemKind(), McpProblemKind(), AviProblemKind()}; }

}  // namespace smcbench

// Built instead of dart_solver.cc when DART is absent (or SMCBENCH_WITH_DART=OFF): the registry then lists no
// dart-* backend.
#include "solvers/siconos/external_backends.h"

namespace smcbench {

void AppendDartBackends(std::vector<ExternalBackend>*) {}

}  // namespace smcbench

// Built instead of the Siconos adapters when Siconos Numerics is absent (or SMCBENCH_WITH_SICONOS=OFF): the
// registry then lists no external backend.
#include "solvers/siconos/external_backends.h"

namespace smcbench {

void AppendExternalBackends(std::vector<ExternalBackend>*) {}

}  // namespace smcbench

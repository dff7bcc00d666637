// Built instead of bullet_solver.cc when Bullet's double-precision build is absent (or SMCBENCH_WITH_BULLET=OFF):
// the registry then lists no bullet-* backend.
#include "solvers/siconos/external_backends.h"

namespace smcbench {

void AppendBulletBackends(std::vector<ExternalBackend>*) {}

}  // namespace smcbench

// pjacobi-smcbench: the smcbench command line with the example backend "pjacobi" registered, so that
// `pjacobi-smcbench bench --solver pjacobi --solver lemke ...` benchmarks it beside ours, in the same results and
// report. The whole program is: register, then run smcbench's own command line (smcbench::cli).
#include <cstdlib>
#include <iostream>
#include <memory>

#include <smcbench/smcbench.h>

#include "projected_jacobi.h"
#include "tools/smcbench/commands.h"

int main(int argc, char** argv) {
  // The scenes (used by `simulate` and the time-stepper studies of `bench`) are those of the installed package,
  // unless the user chose others.
  ::setenv("SMCBENCH_SCENES_DIR", SMCBENCH_INSTALLED_SCENES_DIR, /*overwrite=*/0);
  smcbench::RegisterSolver(example::ProjectedJacobiSolver::kName,
                           [] { return std::make_unique<example::ProjectedJacobiSolver>(); });
  return smcbench::RunCli(argc, argv, std::cout, std::cerr);
}

// pjacobi-conformance: runs smcbench's conformance checks (the ones every built-in backend passes) on the example
// backend. Exit status 0 when they pass, 1 with one line per failure otherwise.
#include <iostream>
#include <memory>

#include <smcbench/smcbench.h>

#include "projected_jacobi.h"

int main() {
  smcbench::ConformanceOptions options;
  // Projected Jacobi converges for SPD and diagonally dominant M; on the nonsymmetric P-matrices it may stop with
  // an honest failure status (any answer it calls solved is still checked against the planted solution).
  options.must_solve = [](const smcbench::ConformanceCase& c) {
    return c.family != smcbench::MatrixFamily::kNonsymmetricPMatrix;
  };
  const smcbench::ConformanceReport report =
      smcbench::CheckConformance([] { return std::make_unique<example::ProjectedJacobiSolver>(); }, options);
  std::cout << "pjacobi conformance: " << smcbench::ToString(report) << "\n";
  return report.passed() ? 0 : 1;
}

// The smallest program against an installed smcbench: solve a 2×2 relay problem with Lemke's method and check the
// answer against the solution worked out by hand.
#include <cmath>
#include <iostream>

#include <smcbench/smcbench.h>

int main() {
  // M = [[2, 1], [1, 2]], q = (-2, 4), -1 <= z <= 1. At z* = (1, -1): M z* + q = (-1, 3), so row 1 sits at its
  // upper bound with (Mz + q)_1 <= 0 and row 2 at its lower bound with (Mz + q)_2 >= 0: z* solves it, and it is
  // the only solution (M is positive definite).
  smcbench::DenseMatrix M(2, 2);
  M << 2, 1, 1, 2;
  smcbench::Vector q(2);
  q << -2, 4;
  auto solver = smcbench::CreateSolver("lemke");
  auto result = solver->Solve(smcbench::BoxMLCP::Relay(M, q));
  std::cout << "smcbench " << smcbench::Version() << ": " << smcbench::ToString(result.status) << ", z = ("
            << result.z[0] << ", " << result.z[1] << ")\n";
  const bool right = result.solved() && std::abs(result.z[0] - 1) < 1e-12 && std::abs(result.z[1] + 1) < 1e-12;
  return right ? 0 : 1;
}

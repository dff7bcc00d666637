// The continuous-time sliding-mode systems the linear time-stepper integrates: class (2) of the report
// (Acary–Brogliato 2009, `eq:deux`) with affine f, and the ZOH-sampled plant with the equivalent-control-based
// SMC of section "Extension to ZOH discretized systems" (`ZOH1`–`eq:ZOHZOH2`).
#pragma once

#include <functional>

#include "solvers/core/problem.h"
#include "solvers/core/types.h"

namespace smcbench {

// Time-dependent forcing g(t): writes g(t) into g (size n, already sized). Called once per step (the value at
// t_k is cached), so it may be slow-ish but must not allocate if the caller wants an allocation-free loop.
using Forcing = std::function<void(double t, Eigen::Ref<Vector> g)>;

// x' ∈ E x + g + g(t) − B Sgn(C x + D)  (`eq:deux` with f(t,x) = E x + g + g(t)); Sgn componentwise,
// sgn(0) = [−1, 1]. x ∈ Rⁿ, m sliding surfaces.
struct LinearSignSystem {
  DenseMatrix E;     // n×n
  DenseMatrix B;     // n×m
  DenseMatrix C;     // m×n
  Vector D;          // m; empty means 0
  Vector g;          // n; constant forcing, empty means 0
  Forcing forcing;   // time-dependent forcing, null means 0

  int n() const { return static_cast<int>(E.rows()); }
  int m() const { return static_cast<int>(C.rows()); }
  // Throws InvalidInputError naming the field ("LinearSignSystem: B has 3 rows but E is 2x2") on size
  // mismatch, empty E or C, or a NaN/infinite entry.
  void Validate() const;
};

// x' = F x + G u with the ECB-SMC u = −(CG)⁻¹(C F x + α Sgn(C x)), α > 0 (report, Example ECB-SMC and
// `ZOH1`). G is n×m, C m×n with CG invertible.
struct ZohSmcSystem {
  DenseMatrix F;  // n×n
  DenseMatrix G;  // n×m
  DenseMatrix C;  // m×n
  double alpha = 1.0;

  int n() const { return static_cast<int>(F.rows()); }
  int m() const { return static_cast<int>(C.rows()); }
  // Sizes, finiteness, α > 0, and CG invertible (InvalidInputError "ZohSmcSystem: CG is singular ...").
  void Validate() const;
};

// The continuous closed loop of a ZOH-SMC system as a class-(2) system (report, Example ECB-SMC):
// x' = (F − G(CG)⁻¹CF) x − α G(CG)⁻¹ Sgn(C x), i.e. E = F − G(CG)⁻¹CF, B = α G(CG)⁻¹, D = 0.
// Lets the same plant be run with Euler (θ-method) or ZOH (S5/S6 of SCENES.md compare both).
LinearSignSystem ClosedLoop(const ZohSmcSystem& system);

}  // namespace smcbench

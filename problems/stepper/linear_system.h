// The continuous-time sliding-mode systems the linear time-stepper integrates: class (2) of the report
// (Acary–Brogliato 2009, `eq:deux`) with affine f, and the ZOH-sampled plant with the equivalent-control-based
// SMC of section "Extension to ZOH discretized systems" (`ZOH1`–`eq:ZOHZOH2`).
// The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "solvers/core/problem.h"
#include "solvers/core/types.h"

namespace smcbench {

// Time-dependent forcing g(t): writes g(t) into g (size n, already sized). Called once per step (the value at
// t_k is cached), so it may be slow-ish but must not allocate if the caller wants an allocation-free loop.
using Forcing = std::function<void(double t, Eigen::Ref<Vector> g)>;

// The set-valued law s ∈ P of the one-step problem when it is not the box [−1, 1]^m: a polytope
// P = {s : H s ≥ K} (Siconos' NormalConeNSL; implicit twisting's parallelogram). The implicit step is then the AVI
// 0 ∈ M s + q + N_P(s) (solvers/avi, docs/avi.md) instead of the box-MLCP; with H = [I; −I], K = −1 it is the box.
// Empty H: the box. Non-emptiness of P is checked where the AVI is built (AffineVI).
struct PolytopeLaw {
  DenseMatrix H;  // r×m
  Vector K;       // r

  bool empty() const { return H.size() == 0; }
  // Shapes (m columns, K of H's rows, at least one row) and finiteness; InvalidInputError naming owner and field.
  void Validate(const char* owner, int m) const;
};

// x' ∈ E x + g + g(t) − B Sgn(C x + D)  (`eq:deux` with f(t,x) = E x + g + g(t)); Sgn componentwise,
// sgn(0) = [−1, 1]. x ∈ Rⁿ, m sliding surfaces.
struct LinearSignSystem {
  DenseMatrix E;     // n×n
  DenseMatrix B;     // n×m
  DenseMatrix C;     // m×n
  Vector D;          // m; empty means 0
  Vector g;          // n; constant forcing, empty means 0
  Forcing forcing;   // time-dependent forcing, null means 0
  // A time-dependent term of the relation, y = C x + D + e(t) (Siconos' ParallelInverter): writes e(t) into a vector
  // of size m; null means 0. A constant e belongs in D. The implicit step's q takes e(t_{k+1}).
  Forcing relation_offset;
  // The relay u = −s entering through B is the system's control input (S1: x' ∈ −sgn x is the controller
  // u = −sgn(x) on x' = u): runs then report u_k = −s_{k+1} (trajectory columns u1..um, the input summary keys).
  bool control_input = false;
  // s ∈ P instead of s ∈ [−1, 1]^m (y ∈ N_P(s), the polytope's generalization of s ∈ Sgn(y)); empty: the box.
  PolytopeLaw law;

  int n() const { return static_cast<int>(E.rows()); }
  int m() const { return static_cast<int>(C.rows()); }
  // Throws InvalidInputError naming the field ("LinearSignSystem: B has 3 rows but E is 2x2") on size
  // mismatch, empty E or C, or a NaN/infinite entry.
  void Validate() const;
};

// Siconos' equivalent-control SMC (control/src/Controller/CommonSMC.cpp computeUeq, LinearSMC, ExplicitLinearSMC):
// u_k = u_eq,k + u_s,k with u_eq,k = −(CG)⁻¹CF((1 − θ) x_k + θ x̃_{k+1}), x̃_{k+1} = e^{Fh} x_k + Ψ G u_eq,k the ZOH
// prediction under u_eq alone (Ψ = ∫₀ʰ e^{Fτ}dτ), and the switching part u_s ∈ −α Sgn(C x_{k+1}) (implicit: the
// relay one-step problem on [−α, α]) or u_s = −α sgn(C x_k) (explicit), applied through G itself. θ = 0.5 is Siconos'
// default; θ = 0 is an explicit equivalent control, and with CG = I the paper's scheme.
struct EquivalentControl {
  double theta = 0.5;
};

// A disturbance on the plant, unknown to the controller: x' = F x + G u + W d(t) with
// d(t) = constant + Σ_j amplitude_j sin(omega_j t + phase_j) (q components). W = G is a matched disturbance.
struct DisturbanceSinusoid {
  Vector amplitude;    // q
  double omega = 1.0;  // rad per unit time
  double phase = 0.0;  // rad
};
struct Disturbance {
  DenseMatrix W;       // n×q; empty: no disturbance
  Vector constant;     // q; empty means 0
  std::vector<DisturbanceSinusoid> sinusoids;

  bool empty() const { return W.size() == 0; }
  // w(t) = W d(t) into w (size n; allocation-free).
  void Evaluate(double t, Eigen::Ref<Vector> w) const;
};

// x' = F x + G u with the ECB-SMC u = −(CG)⁻¹(C F x + α Sgn(C x)), α > 0 (report, Example ECB-SMC and
// `ZOH1`). G is n×m, C m×n with CG invertible.
struct ZohSmcSystem {
  DenseMatrix F;  // n×n
  DenseMatrix G;  // n×m
  DenseMatrix C;  // m×n
  double alpha = 1.0;
  // Absent: the paper's ECB-SMC above (`ZOH1`); present: Siconos' θ-weighted equivalent control.
  std::optional<EquivalentControl> equivalent_control;
  // Acts on the plant only; the controller does not know it.
  Disturbance disturbance;
  // u = −α s alone, no equivalent part (Siconos' Twisting, RegularTwisting, ExplicitTwisting: the controller applies
  // its multiplier λ = −s directly); CG need not be invertible then. Excludes equivalent_control.
  bool switching_only = false;
  // s ∈ P instead of the box (PolytopeLaw); empty: the box.
  PolytopeLaw law;
  // The sliding variable y = C x + D + e(t) (m; D empty means 0, e null means 0), a surface shifted by a reference
  // the controller knows ahead: the ZOH step at t_k takes e(t_{k+1}), the sample its prediction x_{k+1} lands on
  // (DiscretizeZoh). A constant e belongs in D.
  Vector D;
  Forcing relation_offset;

  int n() const { return static_cast<int>(F.rows()); }
  int m() const { return static_cast<int>(C.rows()); }
  // Sizes, finiteness, α > 0, CG invertible unless switching_only (InvalidInputError "ZohSmcSystem: CG is singular
  // ..."), θ of the equivalent control in [0, 1], the disturbance's shapes (W n×q, constant and every amplitude q,
  // finite), the law's, D's (m, finite).
  void Validate() const;
};

// The continuous closed loop of a ZOH-SMC system as a class-(2) system (report, Example ECB-SMC):
// x' = (F − G(CG)⁻¹CF) x − α G(CG)⁻¹ Sgn(C x), i.e. E = F − G(CG)⁻¹CF, B = α G(CG)⁻¹, D = 0; with Siconos'
// equivalent control the switching part enters through G itself: B = α G. A disturbance becomes the forcing
// g + g(t) = W d(t) (an Euler scheme of the closed loop sees it, unlike the ZOH controller). switching_only:
// E = F, B = α G. The law, D and e(t) of the relation are carried over.
// Lets the same plant be run with Euler (θ-method) or ZOH (S5/S6 of docs/scenes.md compare both).
LinearSignSystem ClosedLoop(const ZohSmcSystem& system);

}  // namespace smcbench

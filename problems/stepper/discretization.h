// Discretizations of the linear sliding-mode systems into the one-step form `eq:TDS1` of the report
// (Acary–Brogliato 2009):
//     x_{k+1} = R x_k + p_k − S s_{k+1},   y_{k+1} = C x_{k+1} + D,   s_{k+1} ∈ Sgn(y_{k+1})   (implicit sign)
// or, for the classical schemes that chatter, s_{k+1} := sgn(y_k) with sgn(0) := 0 (explicit sign).
// With the implicit sign each step is the box-MLCP `eq:TDS3`: z = s_{k+1}, M = C S, q = −(C R x_k + C p_k + D),
// l = −1, u = 1.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

#include "problems/stepper/linear_system.h"

namespace smcbench {

// How s_{k+1} is obtained: from the one-step MLCP (implicit, the report's method) or as sgn(y_k) (explicit).
enum class SignTreatment { kImplicit, kExplicit };

// The four methods of the CLI (`--method implicit|explicit|zoh|zoh-explicit`).
//   kImplicit:    θ-method on f, implicit sign (`eq:TDS4`).
//   kExplicit:    θ-method on f, explicit sign s_{k+1} = sgn(y_k). With θ = 0 this is the classical explicit
//                 Euler scheme (`eq:TDS3-a` with the sign taken at x_k), see DiscretizeExplicitEuler.
//   kZoh:         ZOH of x' = Fx + Gu with the implicit ECB-SMC (`ZOH2`, `ZOH3`, `eq:TDS4-a`).
//   kZohExplicit: ZOH with the explicit ECB-SMC s_k = sgn(C x_k) (`ZOH1`).
enum class Method { kImplicit, kExplicit, kZoh, kZohExplicit };
// "implicit", "explicit", "zoh", "zoh-explicit".
std::string_view ToString(Method method);
std::optional<Method> MethodFromString(std::string_view name);

// The data of one step, `eq:TDS1`. Built once per (system, h, θ, method); the time loop only reads it.
//   p_k = p + P (θ g(t_{k+1}) + (1 − θ) g(t_k))   when a time-dependent forcing is present (θ-weighted, as
//   Siconos' Euler–Moreau integrator does); otherwise p_k = p.
struct OneStepData {
  DenseMatrix R;  // n×n
  DenseMatrix S;  // n×m
  DenseMatrix C;  // m×n
  Vector D;       // m (zero when the system has none)
  Vector p;       // n, the constant part of p_k
  DenseMatrix P;  // n×n, h (I − hθE)⁻¹; empty when there is no time-dependent forcing
  Forcing forcing;            // null when there is none
  double forcing_theta = 1.0; // θ used to weight g(t_k), g(t_{k+1})
  double h = 0.0;
  SignTreatment sign = SignTreatment::kImplicit;
  std::string description;    // e.g. "theta=1, implicit sign", "zoh, explicit sign"

  int n() const { return static_cast<int>(R.rows()); }
  int m() const { return static_cast<int>(C.rows()); }
  bool has_forcing() const { return static_cast<bool>(forcing); }
  // M = C S of `eq:TDS3` (allocates; the stepper calls it once).
  DenseMatrix OneStepMatrix() const { return C * S; }
  // Sizes, finiteness, h > 0, θ ∈ [0, 1]; InvalidInputError naming the field.
  void Validate() const;
};

// θ-method on f, `eq:TDS4`, θ ∈ [0, 1] (θ = 1 implicit Euler, θ = 0 semi-implicit, θ = ½ trapezoidal on f):
//   R = (I − hθE)⁻¹(I + h(1−θ)E),  S = h(I − hθE)⁻¹B,  p = h(I − hθE)⁻¹ g,  P = h(I − hθE)⁻¹.
// The report prints p = (I − hθE)⁻¹ g: the factor h is missing there. Integrating x' = Ex + g over one step,
// x_{k+1} − x_k = h(θ E x_{k+1} + (1−θ) E x_k + g) − hB s, so (I − hθE) x_{k+1} = (I + h(1−θ)E) x_k + h g − hB s;
// the tests check this on a 1-D case by hand. Throws InvalidInputError for h ≤ 0, θ ∉ [0, 1], NaN, a malformed
// system, or I − hθE singular (hθ is the inverse of an eigenvalue of E).
OneStepData DiscretizeTheta(const LinearSignSystem& system, double h, double theta, SignTreatment sign);

// The classical explicit Euler scheme: θ = 0 and s_{k+1} = sgn(y_k): x_{k+1} = (I + hE) x_k + h g(t_k) − hB sgn(y_k).
OneStepData DiscretizeExplicitEuler(const LinearSignSystem& system, double h);

// ZOH discretization of x' = Fx + Gu with the ECB-SMC (`ZOH1`, `eq:ZOHGAMMA`):
//   Γ = ∫₀ʰ e^{Fτ}dτ G(CG)⁻¹,  Φ = e^{Fh} − Γ C F,  R = Φ, S = α Γ, p = 0, D = 0.
// e^{Fh} and Γ come from ONE exponential of the (n+m)×(n+m) block matrix h [[F, G(CG)⁻¹], [0, 0]] (Van Loan
// 1978; Moler–Van Loan 2003, method 10), whose top blocks are [e^{Fh}, Γ]; Eigen's MatrixFunctions module
// computes it by scaling and squaring with Padé approximants.
OneStepData DiscretizeZoh(const ZohSmcSystem& system, double h, SignTreatment sign);

// Either kind of linear model a scene may describe.
using LinearModel = std::variant<LinearSignSystem, ZohSmcSystem>;

// Dispatch by method:
//   LinearSignSystem: kImplicit / kExplicit → DiscretizeTheta with the given θ; kZoh* → InvalidInputError
//     (ZOH needs the open-loop plant F, G).
//   ZohSmcSystem: kZoh / kZohExplicit → DiscretizeZoh (θ unused); kImplicit / kExplicit → DiscretizeTheta on
//     ClosedLoop(system) (the Euler discretization of the same closed loop, S5 of SCENES.md).
OneStepData Discretize(const LinearModel& model, Method method, double h, double theta);

// N = round(T / h) steps for a horizon T. InvalidInputError for T < 0 or non-finite, h ≤ 0, or N ≥ 2⁴⁰.
std::int64_t NumSteps(double T, double h);

}  // namespace smcbench

// Discretizations of the linear sliding-mode systems into the one-step form `eq:TDS1` of the report
// (Acary–Brogliato 2009):
//     x_{k+1} = R x_k + p_k − S s_{k+1},   y_{k+1} = C x_{k+1} + D,   s_{k+1} ∈ Sgn(y_{k+1})   (implicit sign)
// or, for the classical schemes that chatter, s_{k+1} := sgn(y_k) with sgn(0) := 0 (explicit sign).
// With the implicit sign each step is the box-MLCP `eq:TDS3`: z = s_{k+1}, M = C S, q = −(C R x_k + C p_k + D),
// l = −1, u = 1.
// The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.
#pragma once

#include <cmath>
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
// Whether each step solves a one-step problem (implicit sign: kImplicit, kZoh); the explicit methods solve none.
constexpr bool IsImplicit(Method method) { return method == Method::kImplicit || method == Method::kZoh; }
// Whether the method samples a ZOH plant (kZoh, kZohExplicit): only these have a held input between samples.
constexpr bool IsZoh(Method method) { return method == Method::kZoh || method == Method::kZohExplicit; }

// The exact forced response of a plant disturbance W d(t) (linear_system.h) over [t_k, t_k + τ) from x = 0, for one
// fixed τ (the step h, or a point between samples: sampled_plant.h):
//   w = constant + Σ_j sin(ω_j t_k + φ_j) cos_part.col(j) + cos(ω_j t_k + φ_j) sin_part.col(j),
// with cos_part.col(j) = ∫₀^τ e^{F(τ−σ)} W a_j cos(ω_j σ) dσ and sin_part.col(j) the same with sin
// (sin(ω(t_k + σ) + φ) = sin(ωt_k + φ) cos ωσ + cos(ωt_k + φ) sin ωσ), and constant = Ψ(τ) W c.
struct DisturbanceResponse {
  Vector constant;       // n; empty: no disturbance
  DenseMatrix cos_part;  // n×J
  DenseMatrix sin_part;  // n×J
  Vector omega;          // J
  Vector phase;          // J

  bool present() const { return constant.size() > 0; }
  // Terms summed per state component (for rounding bounds): the constant and two per sinusoid.
  int terms() const { return present() ? 2 * static_cast<int>(omega.size()) + 1 : 0; }
  // w += the response at t_k (w of size n), allocation-free; nothing when there is no disturbance.
  template <typename W>
  void Add(double t_k, W& w) const {
    if (!present()) return;
    const Eigen::Index n = constant.size();
    for (Eigen::Index i = 0; i < n; ++i) w[i] += constant[i];
    for (Eigen::Index j = 0; j < omega.size(); ++j) {
      const double angle = omega[j] * t_k + phase[j];
      const double sn = std::sin(angle), cs = std::cos(angle);
      for (Eigen::Index i = 0; i < n; ++i) w[i] += sn * cos_part(i, j) + cs * sin_part(i, j);
    }
  }
  // Sizes (n, J) and finiteness; InvalidInputError naming owner and the field.
  void Validate(const char* owner, int n) const;
};

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
  // e(t) of y = C x + D + e(t) (size m; the system's relation_offset), null when there is none: q gets
  // −e(t_{k+1}) and every y_k has e(t_k).
  Forcing relation_offset;
  double forcing_theta = 1.0; // θ used to weight g(t_k), g(t_{k+1})
  double h = 0.0;
  SignTreatment sign = SignTreatment::kImplicit;
  std::string description;    // e.g. "theta=1, implicit sign", "zoh, explicit sign"

  // The control input applied over [t_k, t_{k+1}): u_k = input_x x_k + input_s s_{k+1} (m inputs). Empty (0×0)
  // when the system reports none. ZOH: x_{k+1} = e^{Fh} x_k + Ψ G u_k (+ the disturbance); a class-(2) system with
  // control_input: u_k = −s_{k+1}, x_{k+1} = R x_k + p_k + S u_k.
  DenseMatrix input_x;  // m×n
  DenseMatrix input_s;  // m×m

  // A disturbance the controller does not know (ZOH plants): it enters x_{k+1}, never q (DisturbanceResponse over
  // one step h; empty: none).
  DisturbanceResponse disturbance;

  // s_{k+1} ∈ P = {s : H s ≥ K} instead of the box (the system's PolytopeLaw): the implicit step is the AVI
  // 0 ∈ M s + q + N_P(s) with the same M and q, solved through AviSession (solvers/avi). Empty: the box.
  // Implicit sign only (the explicit sgn(y_k) is the box's).
  PolytopeLaw law;

  int n() const { return static_cast<int>(R.rows()); }
  int m() const { return static_cast<int>(C.rows()); }
  bool has_forcing() const { return static_cast<bool>(forcing); }
  bool has_relation_offset() const { return static_cast<bool>(relation_offset); }
  bool has_input() const { return input_s.rows() > 0; }
  bool has_disturbance() const { return disturbance.present(); }
  bool has_polytope_law() const { return !law.empty(); }
  // w_k at t_k added into w (size n), allocation-free; nothing without a disturbance.
  template <typename W>
  void AddDisturbance(double t_k, W& w) const {
    disturbance.Add(t_k, w);
  }
  // M = C S of `eq:TDS3` (allocates; the stepper calls it once).
  DenseMatrix OneStepMatrix() const { return C * S; }
  // Sizes, finiteness, h > 0, θ ∈ [0, 1], the law's shapes and an implicit sign with it; InvalidInputError naming
  // the field.
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
//   Γ = ∫₀ʰ e^{Fτ}dτ G(CG)⁻¹,  Φ = e^{Fh} − Γ C F,  R = Φ, S = α Γ, p = 0, D = the system's D (0 if none);
//   u_k = −(CG)⁻¹(C F x_k + α s_{k+1}).
// A relation offset e(t) (ZohSmcSystem::relation_offset) is sampled at t_{k+1} in the step taken at t_k:
// q = −(C R x_k + D + e(t_{k+1})), i.e. s_{k+1} ∈ Sgn(C x_{k+1} + D + e(t_{k+1})). Why t_{k+1}: x_{k+1} =
// R x_k − S s_{k+1} is the controller's prediction of the plant at the next sample (exact without a disturbance),
// so the surface is met where the prediction lands; e(t_k) would leave it h·ė behind. Recorded: y_k = C x_k + D +
// e(t_k).
// With system.switching_only (Siconos' Twisting controllers): R = e^{Fh}, S = α ΨG, u_k = −α s_{k+1} (the controller
// predicts the plant exactly; no equivalent part).
// With system.equivalent_control (Siconos' LinearSMC / ExplicitLinearSMC, linear_system.h), K = (CG)⁻¹CF,
// Ψ = ∫₀ʰ e^{Fτ}dτ: the prediction x̃_{k+1} = e^{Fh}x_k + ΨG u_eq with u_eq = −K((1−θ)x_k + θx̃_{k+1}) gives
// x̃_{k+1} = (I + θΨGK)⁻¹(e^{Fh} − (1−θ)ΨGK) x_k =: Ã x_k, u_eq = −L x_k with L = K((1−θ)I + θÃ), and
//   R = e^{Fh} − ΨG L,  S = α ΨG,  u_k = −L x_k − α s_{k+1}.
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
//     ClosedLoop(system) (the Euler discretization of the same closed loop, S5 of docs/scenes.md).
OneStepData Discretize(const LinearModel& model, Method method, double h, double theta);

// N = round(T / h) steps for a horizon T. InvalidInputError for T < 0 or non-finite, h ≤ 0, or N ≥ 2⁴⁰.
std::int64_t NumSteps(double T, double h);

}  // namespace smcbench

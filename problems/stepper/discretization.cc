// The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.
#include "problems/stepper/discretization.h"

#include <cmath>
#include <utility>
#include <unsupported/Eigen/MatrixFunctions>

#include "problems/stepper/discretization_detail.h"
#include "problems/stepper/validation.h"
#include "solvers/core/number_text.h"

namespace smcbench {

using stepper_detail::Fail;

std::string_view ToString(Method method) {
  switch (method) {
    case Method::kImplicit: return "implicit";
    case Method::kExplicit: return "explicit";
    case Method::kZoh: return "zoh";
    case Method::kZohExplicit: return "zoh-explicit";
  }
  return "unknown";
}

std::optional<Method> MethodFromString(std::string_view name) {
  for (Method m : {Method::kImplicit, Method::kExplicit, Method::kZoh, Method::kZohExplicit}) {
    if (ToString(m) == name) return m;
  }
  return std::nullopt;
}

void OneStepData::Validate() const {
  constexpr const char* kOwner = "OneStepData";
  stepper_detail::CheckStep(kOwner, h);
  if (R.rows() == 0) Fail(kOwner, "R is empty");
  if (C.rows() == 0) Fail(kOwner, "C is empty");
  stepper_detail::CheckShape(kOwner, "R", R, n(), n());
  stepper_detail::CheckShape(kOwner, "S", S, n(), m());
  stepper_detail::CheckShape(kOwner, "C", C, m(), n());
  stepper_detail::CheckSize(kOwner, "D", D, m());
  stepper_detail::CheckSize(kOwner, "p", p, n());
  stepper_detail::CheckFinite(kOwner, "R", R);
  stepper_detail::CheckFinite(kOwner, "S", S);
  stepper_detail::CheckFinite(kOwner, "C", C);
  ValidateFinite(kOwner, "D", D);
  ValidateFinite(kOwner, "p", p);
  if (forcing) {
    stepper_detail::CheckShape(kOwner, "P", P, n(), n());
    stepper_detail::CheckFinite(kOwner, "P", P);
    if (!(forcing_theta >= 0.0 && forcing_theta <= 1.0)) {
      Fail(kOwner, "forcing_theta must lie in [0, 1], got " + NumberText(forcing_theta));
    }
  }
  if (input_x.size() || input_s.size()) {
    stepper_detail::CheckShape(kOwner, "input_x", input_x, m(), n());
    stepper_detail::CheckShape(kOwner, "input_s", input_s, m(), m());
    stepper_detail::CheckFinite(kOwner, "input_x", input_x);
    stepper_detail::CheckFinite(kOwner, "input_s", input_s);
  }
  if (has_disturbance()) disturbance.Validate(kOwner, n());
  law.Validate(kOwner, m());
  if (has_polytope_law() && sign != SignTreatment::kImplicit) {
    Fail(kOwner, "law: a polytope law needs an implicit method (implicit or zoh); the explicit sign sgn(y_k) is "
                 "the box's");
  }
}

void DisturbanceResponse::Validate(const char* owner, int n) const {
  if (!present()) return;
  const Eigen::Index J = omega.size();
  stepper_detail::CheckSize(owner, "disturbance.constant", constant, n);
  stepper_detail::CheckShape(owner, "disturbance.cos_part", cos_part, n, J);
  stepper_detail::CheckShape(owner, "disturbance.sin_part", sin_part, n, J);
  stepper_detail::CheckSize(owner, "disturbance.phase", phase, J);
  stepper_detail::CheckFinite(owner, "disturbance.cos_part", cos_part);
  stepper_detail::CheckFinite(owner, "disturbance.sin_part", sin_part);
  ValidateFinite(owner, "disturbance.constant", constant);
  ValidateFinite(owner, "disturbance.omega", omega);
  ValidateFinite(owner, "disturbance.phase", phase);
}

namespace stepper_detail {

OneStepData DiscretizeThetaUnchecked(const LinearSignSystem& system, double h, double theta, SignTreatment sign) {
  const int n = system.n();
  const DenseMatrix I = DenseMatrix::Identity(n, n);
  const Eigen::PartialPivLU<DenseMatrix> lu(I - (h * theta) * system.E);  // I − hθE, `eq:TDS4`
  OneStepData d;
  d.h = h;
  d.sign = sign;
  d.R = lu.solve(I + (h * (1.0 - theta)) * system.E);
  d.S = lu.solve(h * system.B);
  d.C = system.C;
  d.D = system.D.size() ? system.D : Vector::Zero(system.m());
  // p = h (I − hθE)⁻¹ g: the report's `eq:TDS4` omits the h (see the header).
  d.p = system.g.size() ? Vector(lu.solve(h * system.g)) : Vector::Zero(n);
  if (system.forcing) {
    d.P = lu.solve(h * I);
    d.forcing = system.forcing;
    d.forcing_theta = theta;
  }
  d.relation_offset = system.relation_offset;
  d.law = system.law;
  if (system.control_input) {  // u_k = −s_{k+1} through B
    d.input_x = DenseMatrix::Zero(system.m(), n);
    d.input_s = -DenseMatrix::Identity(system.m(), system.m());
  }
  return d;
}

std::pair<DenseMatrix, DenseMatrix> ExpAndIntegral(const DenseMatrix& F, const DenseMatrix& K, double h) {
  const auto n = F.rows(), m = K.cols();
  DenseMatrix block = DenseMatrix::Zero(n + m, n + m);
  block.topLeftCorner(n, n) = h * F;
  block.topRightCorner(n, m) = h * K;
  const DenseMatrix expo = block.exp();
  return {expo.topLeftCorner(n, n), expo.topRightCorner(n, m)};
}

// Per sinusoid j, the forced response over [0, h) to v cos(ωτ) and v sin(ωτ) (v = W a_j) comes from ONE exponential
// of h [[F, v, 0], [0, 0, −ω], [0, ω, 0]] (Van Loan again, with the harmonic oscillator generating (cos ωτ, sin ωτ)
// from (1, 0) and (−sin ωτ, cos ωτ) from (0, 1)).
DisturbanceResponse DiscretizeDisturbance(const DenseMatrix& F, const Disturbance& d, double h) {
  DisturbanceResponse response;
  const auto n = F.rows();
  response.constant = Vector::Zero(n);
  if (d.constant.size()) {
    const DenseMatrix v = d.W * d.constant;
    response.constant = ExpAndIntegral(F, v, h).second.col(0);
  }
  const auto J = static_cast<Eigen::Index>(d.sinusoids.size());
  response.cos_part = DenseMatrix::Zero(n, J);
  response.sin_part = DenseMatrix::Zero(n, J);
  response.omega = Vector::Zero(J);
  response.phase = Vector::Zero(J);
  for (Eigen::Index j = 0; j < J; ++j) {
    const DisturbanceSinusoid& term = d.sinusoids[static_cast<std::size_t>(j)];
    DenseMatrix block = DenseMatrix::Zero(n + 2, n + 2);
    block.topLeftCorner(n, n) = h * F;
    block.block(0, n, n, 1) = h * (d.W * term.amplitude);
    block(n, n + 1) = -h * term.omega;
    block(n + 1, n) = h * term.omega;
    const DenseMatrix expo = block.exp();
    response.cos_part.col(j) = expo.block(0, n, n, 1);
    response.sin_part.col(j) = -expo.block(0, n + 1, n, 1);
    response.omega[j] = term.omega;
    response.phase[j] = term.phase;
  }
  return response;
}

OneStepData DiscretizeZohUnchecked(const ZohSmcSystem& system, double h, SignTreatment sign) {
  const int n = system.n();
  const int m = system.m();
  const DenseMatrix CG = system.C * system.G;
  const Eigen::PartialPivLU<DenseMatrix> cg_lu(CG);  // used only when CG is invertible (not switching_only)
  OneStepData d;
  d.h = h;
  d.sign = sign;
  d.C = system.C;
  d.D = system.D.size() ? system.D : Vector::Zero(m);
  d.p = Vector::Zero(n);
  d.law = system.law;
  d.relation_offset = system.relation_offset;  // e(t_{k+1}) in q: see the header
  if (system.switching_only) {
    // u = −α s alone: the controller's prediction is the plant's ZOH step.
    const auto [expFh, PsiG] = ExpAndIntegral(system.F, system.G, h);
    d.R = expFh;
    d.S = system.alpha * PsiG;
    d.input_x = DenseMatrix::Zero(m, n);
    d.input_s = -system.alpha * DenseMatrix::Identity(m, m);
  } else if (!system.equivalent_control) {
    // K = G (CG)⁻¹, solved as (CG)ᵀ Kᵀ = Gᵀ.
    const DenseMatrix K = CG.transpose().partialPivLu().solve(system.G.transpose()).transpose();
    // Van Loan: exp(h [[F, K], [0, 0]]) = [[e^{Fh}, ∫₀ʰ e^{Fτ}dτ K], [0, I]].
    const auto [expFh, Gamma] = ExpAndIntegral(system.F, K, h);  // Γ: `eq:ZOHGAMMA`
    d.R = expFh - Gamma * (system.C * system.F);                  // Φ
    d.S = system.alpha * Gamma;
    d.input_x = -cg_lu.solve(system.C * system.F);  // u_k = −(CG)⁻¹(CF x_k + α s_{k+1})
    d.input_s = -system.alpha * cg_lu.inverse();
  } else {
    // Siconos' θ-weighted equivalent control (see the header).
    const double theta = system.equivalent_control->theta;
    const DenseMatrix I = DenseMatrix::Identity(n, n);
    const auto [expFh, PsiG] = ExpAndIntegral(system.F, system.G, h);
    const DenseMatrix K = cg_lu.solve(system.C * system.F);  // (CG)⁻¹CF
    const DenseMatrix PsiGK = PsiG * K;
    const DenseMatrix predictor = (I + theta * PsiGK).partialPivLu().solve(expFh - (1.0 - theta) * PsiGK);  // Ã
    const DenseMatrix L = (1.0 - theta) * K + theta * (K * predictor);
    d.R = expFh - PsiG * L;
    d.S = system.alpha * PsiG;
    d.input_x = -L;
    d.input_s = -system.alpha * DenseMatrix::Identity(m, m);
  }
  if (!system.disturbance.empty()) d.disturbance = DiscretizeDisturbance(system.F, system.disturbance, h);
  return d;
}

namespace {
SignTreatment SignOf(Method method) {
  return (method == Method::kImplicit || method == Method::kZoh) ? SignTreatment::kImplicit
                                                                  : SignTreatment::kExplicit;
}
}  // namespace

OneStepData DiscretizeUnchecked(const LinearModel& model, Method method, double h, double theta) {
  if (const auto* zsys = std::get_if<ZohSmcSystem>(&model)) {
    if (IsZoh(method)) return DiscretizeZohUnchecked(*zsys, h, SignOf(method));
    return DiscretizeThetaUnchecked(ClosedLoop(*zsys), h, theta, SignOf(method));
  }
  return DiscretizeThetaUnchecked(std::get<LinearSignSystem>(model), h, theta, SignOf(method));
}

}  // namespace stepper_detail

OneStepData DiscretizeTheta(const LinearSignSystem& system, double h, double theta, SignTreatment sign) {
  constexpr const char* kOwner = "DiscretizeTheta";
  system.Validate();
  stepper_detail::CheckStep(kOwner, h);
  if (!(theta >= 0.0 && theta <= 1.0)) Fail(kOwner, "theta must lie in [0, 1], got " + NumberText(theta));
  const int n = system.n();
  stepper_detail::CheckInvertible(kOwner, "I - h*theta*E", DenseMatrix::Identity(n, n) - (h * theta) * system.E);
  OneStepData d = stepper_detail::DiscretizeThetaUnchecked(system, h, theta, sign);
  d.description = "theta=" + NumberText(theta) + (sign == SignTreatment::kImplicit ? ", implicit sign" : ", explicit sign");
  if (!system.law.empty()) d.description += ", polytope law";
  d.Validate();
  return d;
}

OneStepData DiscretizeExplicitEuler(const LinearSignSystem& system, double h) {
  OneStepData d = DiscretizeTheta(system, h, 0.0, SignTreatment::kExplicit);
  d.description = "explicit Euler";
  return d;
}

OneStepData DiscretizeZoh(const ZohSmcSystem& system, double h, SignTreatment sign) {
  constexpr const char* kOwner = "DiscretizeZoh";
  system.Validate();
  stepper_detail::CheckStep(kOwner, h);
  OneStepData d = stepper_detail::DiscretizeZohUnchecked(system, h, sign);
  if (!d.R.allFinite() || !d.S.allFinite()) {
    Fail(kOwner, "exp(h*[[F, G(CG)^-1], [0, 0]]) overflowed (h*||F|| too large), h = " + NumberText(h));
  }
  d.description = sign == SignTreatment::kImplicit ? "zoh, implicit sign" : "zoh, explicit sign";
  if (system.equivalent_control) {
    d.description += ", equivalent control theta=" + NumberText(system.equivalent_control->theta);
  }
  if (system.switching_only) d.description += ", switching part only";
  if (!system.law.empty()) d.description += ", polytope law";
  if (!system.disturbance.empty()) d.description += ", disturbed";
  if (!d.input_x.allFinite() || !d.input_s.allFinite() ||
      (d.has_disturbance() && (!d.disturbance.cos_part.allFinite() || !d.disturbance.sin_part.allFinite() ||
                               !d.disturbance.constant.allFinite()))) {
    Fail(kOwner, "the equivalent control or the disturbance's discretization is not finite at h = " + NumberText(h));
  }
  d.Validate();
  return d;
}

OneStepData Discretize(const LinearModel& model, Method method, double h, double theta) {
  const bool zoh = method == Method::kZoh || method == Method::kZohExplicit;
  const SignTreatment sign =
      (method == Method::kImplicit || method == Method::kZoh) ? SignTreatment::kImplicit : SignTreatment::kExplicit;
  if (const auto* zsys = std::get_if<ZohSmcSystem>(&model)) {
    if (zoh) return DiscretizeZoh(*zsys, h, sign);
    return DiscretizeTheta(ClosedLoop(*zsys), h, theta, sign);
  }
  if (zoh) {
    Fail("Discretize", "method '" + std::string(ToString(method)) +
                           "' needs a ZOH plant (F, G, C); this model is a class-(2) system (E, B, C, D)");
  }
  return DiscretizeTheta(std::get<LinearSignSystem>(model), h, theta, sign);
}

std::int64_t NumSteps(double T, double h) {
  constexpr const char* kOwner = "NumSteps";
  if (!(T >= 0.0) || !std::isfinite(T)) Fail(kOwner, "T must be a finite horizon >= 0, got " + NumberText(T));
  stepper_detail::CheckStep(kOwner, h);
  const double steps = std::round(T / h);
  if (!(steps < 1099511627776.0)) {  // 2^40: far beyond any run we could store or time
    Fail(kOwner, "T/h = " + NumberText(T / h) + " steps is too many");
  }
  return static_cast<std::int64_t>(steps);
}

}  // namespace smcbench

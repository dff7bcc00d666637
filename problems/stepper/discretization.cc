#include "problems/stepper/discretization.h"

#include <cmath>
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
  return d;
}

OneStepData DiscretizeZohUnchecked(const ZohSmcSystem& system, double h, SignTreatment sign) {
  const int n = system.n();
  const int m = system.m();
  const DenseMatrix CG = system.C * system.G;
  // K = G (CG)⁻¹, solved as (CG)ᵀ Kᵀ = Gᵀ.
  const DenseMatrix K = CG.transpose().partialPivLu().solve(system.G.transpose()).transpose();
  // Van Loan: exp(h [[F, K], [0, 0]]) = [[e^{Fh}, ∫₀ʰ e^{Fτ}dτ K], [0, I]].
  DenseMatrix block = DenseMatrix::Zero(n + m, n + m);
  block.topLeftCorner(n, n) = h * system.F;
  block.topRightCorner(n, m) = h * K;
  const DenseMatrix expo = block.exp();
  const DenseMatrix Gamma = expo.topRightCorner(n, m);  // `eq:ZOHGAMMA`
  OneStepData d;
  d.h = h;
  d.sign = sign;
  d.R = expo.topLeftCorner(n, n) - Gamma * (system.C * system.F);  // Φ
  d.S = system.alpha * Gamma;
  d.C = system.C;
  d.D = Vector::Zero(m);
  d.p = Vector::Zero(n);
  return d;
}

namespace {
bool IsZoh(Method method) { return method == Method::kZoh || method == Method::kZohExplicit; }
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

#include "problems/stepper/linear_system.h"

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "problems/stepper/validation.h"
#include "solvers/core/number_text.h"

namespace smcbench {

void LinearSignSystem::Validate() const {
  constexpr const char* kOwner = "LinearSignSystem";
  if (E.rows() == 0) stepper_detail::Fail(kOwner, "E is empty: the state needs at least one component");
  if (C.rows() == 0) stepper_detail::Fail(kOwner, "C is empty: the system needs at least one sliding surface");
  stepper_detail::CheckShape(kOwner, "E", E, n(), n());
  stepper_detail::CheckShape(kOwner, "B", B, n(), m());
  stepper_detail::CheckShape(kOwner, "C", C, m(), n());
  if (D.size() != 0) stepper_detail::CheckSize(kOwner, "D", D, m());
  if (g.size() != 0) stepper_detail::CheckSize(kOwner, "g", g, n());
  stepper_detail::CheckFinite(kOwner, "E", E);
  stepper_detail::CheckFinite(kOwner, "B", B);
  stepper_detail::CheckFinite(kOwner, "C", C);
  ValidateFinite(kOwner, "D", D);
  ValidateFinite(kOwner, "g", g);
  law.Validate(kOwner, m());
}

void PolytopeLaw::Validate(const char* owner, int m) const {
  if (empty()) return;
  const auto rows = static_cast<int>(H.rows());
  stepper_detail::CheckShape(owner, "law.H", H, rows, m);
  stepper_detail::CheckSize(owner, "law.K", K, rows);
  stepper_detail::CheckFinite(owner, "law.H", H);
  ValidateFinite(owner, "law.K", K);
}

void ZohSmcSystem::Validate() const {
  constexpr const char* kOwner = "ZohSmcSystem";
  if (F.rows() == 0) stepper_detail::Fail(kOwner, "F is empty: the state needs at least one component");
  if (C.rows() == 0) stepper_detail::Fail(kOwner, "C is empty: the system needs at least one sliding surface");
  stepper_detail::CheckShape(kOwner, "F", F, n(), n());
  stepper_detail::CheckShape(kOwner, "G", G, n(), m());
  stepper_detail::CheckShape(kOwner, "C", C, m(), n());
  stepper_detail::CheckFinite(kOwner, "F", F);
  stepper_detail::CheckFinite(kOwner, "G", G);
  stepper_detail::CheckFinite(kOwner, "C", C);
  if (!(alpha > 0.0) || !std::isfinite(alpha)) {
    stepper_detail::Fail(kOwner, "alpha must be a positive finite number, got " + NumberText(alpha));
  }
  // The equivalent control needs (CG)⁻¹ (report, Example ECB-SMC); the switching part alone does not.
  if (!switching_only) stepper_detail::CheckInvertible(kOwner, "CG", C * G);
  if (switching_only && equivalent_control) {
    stepper_detail::Fail(kOwner, "switching_only and equivalent_control exclude each other (u = -alpha s has no "
                                 "equivalent part)");
  }
  law.Validate(kOwner, m());
  if (D.size() != 0) stepper_detail::CheckSize(kOwner, "D", D, m());
  ValidateFinite(kOwner, "D", D);
  if (equivalent_control) {
    const double theta = equivalent_control->theta;
    if (!(theta >= 0.0 && theta <= 1.0)) {
      stepper_detail::Fail(kOwner, "equivalent_control.theta must lie in [0, 1], got " + NumberText(theta));
    }
  }
  if (!disturbance.empty()) {
    const Disturbance& d = disturbance;
    const auto q = static_cast<int>(d.W.cols());
    stepper_detail::CheckShape(kOwner, "disturbance.W", d.W, n(), q);
    stepper_detail::CheckFinite(kOwner, "disturbance.W", d.W);
    if (d.constant.size() != 0) stepper_detail::CheckSize(kOwner, "disturbance.constant", d.constant, q);
    ValidateFinite(kOwner, "disturbance.constant", d.constant);
    for (std::size_t j = 0; j < d.sinusoids.size(); ++j) {
      const std::string field = "disturbance.sinusoids[" + std::to_string(j) + "]";
      const std::string amplitude = field + ".amplitude";
      stepper_detail::CheckSize(kOwner, amplitude.c_str(), d.sinusoids[j].amplitude, q);
      ValidateFinite(kOwner, amplitude.c_str(), d.sinusoids[j].amplitude);
      if (!std::isfinite(d.sinusoids[j].omega) || !std::isfinite(d.sinusoids[j].phase)) {
        stepper_detail::Fail(kOwner, field + ": omega and phase must be finite");
      }
    }
  }
}

void Disturbance::Evaluate(double t, Eigen::Ref<Vector> w) const {
  w.setZero();
  if (empty()) return;
  const Eigen::Index n = W.rows(), q = W.cols();
  for (Eigen::Index c = 0; c < q; ++c) {
    double d = constant.size() ? constant[c] : 0.0;
    for (const DisturbanceSinusoid& term : sinusoids) d += term.amplitude[c] * std::sin(term.omega * t + term.phase);
    for (Eigen::Index i = 0; i < n; ++i) w[i] += W(i, c) * d;
  }
}

LinearSignSystem ClosedLoop(const ZohSmcSystem& system) {
  system.Validate();
  LinearSignSystem out;
  if (system.switching_only) {
    out.E = system.F;
    out.B = system.alpha * system.G;
  } else {
    const DenseMatrix CG = system.C * system.G;
    const DenseMatrix G_CGinv = CG.transpose().partialPivLu().solve(system.G.transpose()).transpose();  // G(CG)⁻¹
    out.E = system.F - G_CGinv * system.C * system.F;
    out.B = system.equivalent_control ? DenseMatrix(system.alpha * system.G) : DenseMatrix(system.alpha * G_CGinv);
  }
  out.C = system.C;
  out.law = system.law;
  out.D = system.D.size() ? system.D : Vector::Zero(system.m());
  out.relation_offset = system.relation_offset;
  out.control_input = false;  // u = −(CG)⁻¹(CF x + α s) mixes x_k and x_{k+1} under a θ-method: not reported
  if (!system.disturbance.empty()) {
    const Disturbance& d = system.disturbance;
    if (d.constant.size() && !d.constant.isZero(0.0)) out.g = d.W * d.constant;
    if (!d.sinusoids.empty()) {
      // g(t) = Σ_j (W a_j) sin(ω_j t + φ_j), the directions W a_j formed once: no allocation per call.
      std::vector<std::pair<Vector, std::pair<double, double>>> terms;
      for (const DisturbanceSinusoid& term : d.sinusoids) {
        terms.push_back({d.W * term.amplitude, {term.omega, term.phase}});
      }
      out.forcing = [terms = std::move(terms)](double t, Eigen::Ref<Vector> g) {
        g.setZero();
        for (const auto& [direction, frequency] : terms) {
          g += direction * std::sin(frequency.first * t + frequency.second);
        }
      };
    }
  }
  return out;
}

}  // namespace smcbench

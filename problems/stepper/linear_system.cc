#include "problems/stepper/linear_system.h"

#include <cmath>
#include <string>

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
  // The equivalent control needs (CG)⁻¹ (report, Example ECB-SMC).
  stepper_detail::CheckInvertible(kOwner, "CG", C * G);
}

LinearSignSystem ClosedLoop(const ZohSmcSystem& system) {
  system.Validate();
  const DenseMatrix CG = system.C * system.G;
  const DenseMatrix G_CGinv = CG.transpose().partialPivLu().solve(system.G.transpose()).transpose();  // G(CG)⁻¹
  LinearSignSystem out;
  out.E = system.F - G_CGinv * system.C * system.F;
  out.B = system.alpha * G_CGinv;
  out.C = system.C;
  out.D = Vector::Zero(system.m());
  return out;
}

}  // namespace smcbench

// The discretization formulas without input validation, for the rebuild-every-step path, which validates once
// and then re-discretizes every step (as a general simulator would) without paying for the checks again.
#pragma once

#include "problems/stepper/discretization.h"

namespace smcbench::stepper_detail {

// Preconditions: the inputs passed the checks of the public Discretize* functions. description is left empty.
OneStepData DiscretizeThetaUnchecked(const LinearSignSystem& system, double h, double theta, SignTreatment sign);
OneStepData DiscretizeZohUnchecked(const ZohSmcSystem& system, double h, SignTreatment sign);
OneStepData DiscretizeUnchecked(const LinearModel& model, Method method, double h, double theta);

}  // namespace smcbench::stepper_detail

// The discretization formulas without input validation, for the rebuild-every-step path, which validates once
// and then re-discretizes every step (as a general simulator would) without paying for the checks again; and the
// exponentials they are made of, which the sampled-data plant (sampled_plant.h) evaluates at points between samples.
#pragma once

#include <utility>

#include "problems/stepper/discretization.h"

namespace smcbench::stepper_detail {

// Preconditions: the inputs passed the checks of the public Discretize* functions. description is left empty.
OneStepData DiscretizeThetaUnchecked(const LinearSignSystem& system, double h, double theta, SignTreatment sign);
OneStepData DiscretizeZohUnchecked(const ZohSmcSystem& system, double h, SignTreatment sign);
OneStepData DiscretizeUnchecked(const LinearModel& model, Method method, double h, double theta);

// [e^{Fτ}, ∫₀^τ e^{Fσ}dσ K] from ONE exponential of τ [[F, K], [0, 0]] (Van Loan 1978; Moler–Van Loan 2003, method
// 10): its top blocks. Eigen's MatrixFunctions (scaling and squaring with Padé approximants).
std::pair<DenseMatrix, DenseMatrix> ExpAndIntegral(const DenseMatrix& F, const DenseMatrix& K, double tau);
// The exact forced response of d over [t_k, t_k + τ) (DisturbanceResponse, discretization.h); d not empty.
DisturbanceResponse DiscretizeDisturbance(const DenseMatrix& F, const Disturbance& d, double tau);

}  // namespace smcbench::stepper_detail

// The super-twisting algorithm (Levant 1993) on a plant of relative degree 1 in the sliding variable σ, discretized
// implicitly (Brogliato, Polyakov & Efimov, "The implicit discretization of the supertwisting sliding-mode control
// algorithm", IEEE TAC 65(8), 2020) or by explicit Euler:
//     σ' = u + d(t),   u = −k₁ |σ|^{1/2} sgn σ + v,   v' = −k₂ sgn σ          (d: a disturbance the controller
//                                                                              does not know)
// The state is x = (σ, v), one surface (m = 1), y = σ.
//   Implicit (backward Euler of the undisturbed closed loop, BPE 2020): σ̂ = σ_k + h(−k₁|σ̂|^{1/2} sgn σ̂ + v_{k+1}),
//     v_{k+1} = v_k − h k₂ s, s ∈ Sgn(σ̂). With w = σ_k + h v_k this is one scalar generalized equation
//         0 ∈ σ̂ + h k₁ |σ̂|^{1/2} sgn σ̂ + h² k₂ Sgn(σ̂) − w,
//     solved by its closed form (SolveSuperTwistingStep) or as an MCP (SuperTwistingStepMcp). The controller applies
//     u_k = (σ̂ − σ_k)/h = −k₁|σ̂|^{1/2} sgn σ̂ + v_{k+1}; the plant then gives σ_{k+1} = σ_k + h u_k + ∫ d = σ̂ + ∫ d
//     (computed so: σ_k + h u_k would leave the rounding of the division and product).
//     A sliding step of the closed form (|w| ≤ h² k₂: σ̂ = 0, s = w/(h² k₂)) has v_{k+1} = v_k − h k₂ s = −σ_k/h by
//     the same algebra; the stepper computes it so, since v_k − h k₂ (w/b) leaves a rounding tail of ~1e-16 |v_k|
//     that a run of sliding steps shrinks into subnormals instead of 0 (docs/smc.md, "Higher-order sliding modes").
//   Explicit Euler: u_k = −k₁|σ_k|^{1/2} sgn σ_k + v_k, v_{k+1} = v_k − h k₂ sgn σ_k (sgn 0 = 0).
// The plant is integrated exactly over a step (σ' = u + d with u held: σ_{k+1} = σ_k + h u_k + ∫_{t_k}^{t_{k+1}} d).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "problems/stepper/linear_stepper.h"
#include "problems/stepper/trajectory.h"
#include "solvers/core/problem.h"
#include "solvers/core/solver.h"

namespace smcbench {

// d(t) = constant + Σ_j amplitude_j sin(omega_j t + phase_j).
struct ScalarDisturbance {
  struct Sinusoid {
    double amplitude = 0.0;
    double omega = 1.0;
    double phase = 0.0;
  };
  double constant = 0.0;
  std::vector<Sinusoid> sinusoids;

  double Value(double t) const;
  // ∫_{t0}^{t1} d(t) dt in closed form (allocation-free).
  double Integral(double t0, double t1) const;
  // A Lipschitz constant of d: Σ_j |amplitude_j omega_j| (the bound L on |d'| of the gain conditions).
  double Lipschitz() const;
  bool zero() const { return constant == 0.0 && sinusoids.empty(); }
};

struct SuperTwistingSystem {
  double k1 = 1.0;  // gain of the |σ|^{1/2} term, ≥ 0
  double k2 = 1.0;  // gain of the integral (v) term, > 0
  ScalarDisturbance disturbance;

  // InvalidInputError naming the field: k1 < 0, k2 ≤ 0, a non-finite entry.
  void Validate() const;
};

// How the implicit step's generalized equation is solved.
enum class SuperTwistingSolution { kClosedForm, kMcp };

// The unique solution of 0 ∈ σ̂ + a|σ̂|^{1/2} sgn σ̂ + b Sgn(σ̂) − w (a = h k₁ ≥ 0, b = h² k₂ > 0) with its selection
// s ∈ Sgn(σ̂): |w| ≤ b gives σ̂ = 0, s = w/b; otherwise σ̂ = sgn(w) r², s = sgn(w), r > 0 the root of
// r² + a r + b = |w|, r = 2(|w| − b) / (a + sqrt(a² + 4(|w| − b))) (the form without cancellation).
struct SuperTwistingStepSolution {
  double sigma = 0.0;      // σ̂
  double selection = 0.0;  // s ∈ Sgn(σ̂)
  bool sliding = false;    // |w| ≤ b: σ̂ = 0 with s = w/b (not an r² that underflowed to 0, where s = ±1)
};
SuperTwistingStepSolution SolveSuperTwistingStep(double w, double a, double b);

// The same generalized equation as a mixed complementarity problem over z = (r, s), r = sgn(σ̂)|σ̂|^{1/2} free and
// s ∈ [−1, 1] (the change of variable makes F continuously differentiable: ∂(r|r|)/∂r = 2|r|):
//   F(z) = ( r|r| + a r + b s − w ,  −r ),   ∇F = [[2|r| + a, b], [−1, 0]]  (nonsingular for b > 0).
// −F₂ = r ∈ N_[−1,1](s) is s ∈ Sgn(r) = Sgn(σ̂). SetStep() changes w; evaluations do not allocate.
class SuperTwistingStepMcp final : public MCP {
 public:
  SuperTwistingStepMcp(double a, double b);
  void SetStep(double w) { w_ = w; }
  double w() const { return w_; }
  void Evaluate(const Vector& z, Vector* F) const override;
  void JacobianDense(const Vector& z, DenseMatrix* J) const override;

 private:
  double a_, b_, w_ = 0.0;
};

struct SuperTwistingOptions {
  SuperTwistingSolution solution = SuperTwistingSolution::kClosedForm;
  // solver options (kMcp), warm start (kMcp starts from the previous (r, s)), record, sink, t0, on_failure.
  StepperOptions stepper;
};

// Runs num_steps steps from x0 = (σ_0, v_0) with the implicit (sign kImplicit) or explicit Euler (kExplicit)
// discretization into *out: x = (σ, v), s = the selection of Sgn(σ̂) (implicit) or sgn(σ_{k−1}) (explicit),
// y = σ, u = the control held over [t_k, t_{k+1}). kMcp needs a solver that solves MCPs (else InvalidInputError);
// kClosedForm and the explicit scheme use none. The closed-form and explicit loops do not allocate per step.
void RunSuperTwisting(const SuperTwistingSystem& system, SignTreatment sign, double h, const Vector& x0,
                      std::int64_t num_steps, Solver* solver, const SuperTwistingOptions& options, Trajectory* out);

// Convergence time and steady-state precision of σ, accumulated while the run goes (a sink) or from a recorded run:
//   convergence_step: the first step k after which |σ_j| ≤ band for every j ≥ k (−1: never);
//   tail: rows k ≥ tail_from = num_steps − ⌊num_steps / 2⌋ (the second half of the run);
//   max_abs_sigma_tail = max |σ_k|, max_abs_sigma_dot_tail = max |σ_{k+1} − σ_k| / h over the tail.
struct SuperTwistingPrecision {
  double band = 0.0;
  std::int64_t convergence_step = -1;
  std::int64_t tail_from = 0;
  double max_abs_sigma_tail = 0.0;
  double max_abs_sigma_dot_tail = 0.0;
};
class SuperTwistingPrecisionAccumulator final : public TrajectorySink {
 public:
  SuperTwistingPrecisionAccumulator(double band, std::int64_t num_steps, double h);
  void OnRows(const TrajectoryBlock& block) override;
  void Add(std::int64_t k, double sigma);
  SuperTwistingPrecision Result() const;

 private:
  double h_;
  std::int64_t last_outside_ = -1;  // the last row with |σ| > band, −1 if none
  std::int64_t last_row_ = -1;
  bool any_row_ = false;
  double previous_ = 0.0;
  SuperTwistingPrecision result_;
};
// InvalidInputError if the trajectory was not recorded.
SuperTwistingPrecision ComputeSuperTwistingPrecision(const Trajectory& trajectory, double band);

}  // namespace smcbench

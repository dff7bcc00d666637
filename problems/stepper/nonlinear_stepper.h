// The time-stepper for the nonlinear classes (3) and (4) of the report (Acary–Brogliato 2009, `eq:trois`,
// `eq:quatre`), discretized by the θ/γ scheme `eq:toto1` with the optional ρ-shift of `neuf`:
//     (1 + hρ)(x_{k+1} − x_k) = h f(x_{k+θ}, t_{k+θ}) − h g(x_{k+γ}) s_{k+1},   s_{k+1} ∈ Sgn(h(x_{k+1})),
// x_{k+θ} = θ x_{k+1} + (1−θ) x_k, x_{k+γ} = γ x_{k+1} + (1−γ) x_k, t_{k+θ} = θ t_{k+1} + (1−θ) t_k (the report
// prints (1−θ) t_{k+1}, a typo: that would make t_{k+θ} = t_{k+1} for every θ).
// Each step is the MCP `eq:MCP3` in z = (x_{k+1}, s_{k+1}), x free, s ∈ [−1, 1], solved by one of two paths:
//   Algorithm 1 (`Algo:EulerSliding-MCP`): the MCP itself (OneStepMCP, Jacobian `eq:JacMCLP`) handed to a
//     Solver that solves nonlinear MCPs (the registry's "newton").
//   Algorithm 2 (`Algo:EulerSliding-MCLP`): an outer Newton loop (Josephy–Newton on the same MCP: F linearized in
//     x, exact in s) whose every iteration is the m×m relay box-MLCP `eq:NL14`/`eq:NL15`, x eliminated by the
//     Schur complement as the linear case does:
//       M_α = (1 + hρ) I − hθ ∇f(x^α_{k+θ}, t_{k+θ}) + hγ ∇g(x^α_{k+γ})·s^α          (`eq:NL9`)
//       W = h ∇h(x^α) M_α⁻¹ g(x^α_{k+γ}),   b = h(x^α) + ∇h(x^α) M_α⁻¹ r_α,           (`eq:NL15`)
//       r_α = (1 + hρ)(x_k − x^α) + h f(x^α_{k+θ}, t_{k+θ}),
//     box-MLCP z = s^{α+1}, M = W, q = −b, l = −1, u = 1 (so y^{α+1} = b − W s^{α+1} = −(w − v)), solved by ANY
//     backend; then x^{α+1} = x^α + M_α⁻¹ (r_α − h g s^{α+1}) (`eq:NL11`). Started from (x_k, s_k) (`eq:NL7`).
//     Eliminating x keeps every row a relay row, which every backend handles (psor needs W_ii > 0: the report's
//     "C B > 0" condition, here ∇h g > 0, for small h); the (n+m) free-row form would give psor a zero diagonal.
// Both paths stop on the same merit function, the relative natural residual of OneStepMCP (relative to
// 1 + ‖F(Π(0))‖∞, exactly as Solver::Solve(MCP) measures it), so they agree to that tolerance.
// The report's `eq:JacMCLP` prints the lower-left block as +∇h; F's second block is −h(x), so it is −∇h.
// `eq:disctrois`/`eq:discquatre` print the ρ-shift with the signs swapped (−ρ x_k, +ρ x_{k+1} on the right-hand
// side, which makes the hypomonotone part worse); `neuf` has them right and is what is implemented.
// The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "problems/stepper/discretization.h"
#include "problems/stepper/linear_stepper.h"
#include "problems/stepper/nonlinear_system.h"
#include "problems/stepper/trajectory.h"
#include "solvers/core/solver.h"

namespace smcbench {

// The θ/γ scheme `eq:toto1` plus the ρ-shift of `neuf`.
struct NonlinearScheme {
  double h = 0.0;      // time step, > 0
  double theta = 1.0;  // θ ∈ [0, 1] on f (0: explicit f)
  double gamma = 1.0;  // γ ∈ [0, 1] on g (0: g evaluated at x_k)
  // ρ ≥ 0: adds hρ x_{k+1} to the implicit side and hρ x_k to the explicit side (`neuf`). O(h²) per step;
  // ρ ≥ the hypomonotonicity constant makes the one-step operator strongly monotone (unique solution).
  double rho = 0.0;
  // kImplicit: s_{k+1} ∈ Sgn(h(x_{k+1})), the report's method. kExplicit: s_{k+1} = sgn(h(x_k)) with sgn(0) := 0
  // (the classical scheme that chatters); x_{k+1} then solves the smooth equation above by Newton's method (one
  // iteration, exact up to rounding, when θ = γ = 0).
  SignTreatment sign = SignTreatment::kImplicit;

  // h > 0 finite, θ, γ ∈ [0, 1], ρ ≥ 0 finite; InvalidInputError "NonlinearScheme: theta must be in [0, 1]...".
  void Validate() const;
  // "theta=1, gamma=1, rho=0, implicit sign".
  std::string Description() const;
};

// Which solution path an implicit step takes. kClosedForm is for the super-twisting scenes (super_twisting.h), whose
// scalar one-step generalized equation has one; the nonlinear stepper refuses it.
enum class NonlinearAlgorithm { kMcp, kNewtonMlcp, kClosedForm };
// "mcp" (Algorithm 1), "newton-mlcp" (Algorithm 2), "closed-form".
std::string_view ToString(NonlinearAlgorithm algorithm);
std::optional<NonlinearAlgorithm> NonlinearAlgorithmFromString(std::string_view name);

struct NonlinearStepperOptions {
  // solver: options of every backend call (Algorithm 1: the MCP solve; Algorithm 2: each inner MLCP solve);
  // warm_start: Algorithm 1 starts the MCP solve from (x_k, s_k), Algorithm 2 starts each MLCP from s^α (the
  // Newton loop itself always starts from (x_k, s_k), `eq:NL7`); on_failure, record, t0, sink and subnormals as in
  // the linear stepper (kZeroState zeroes the subnormal components of an implicit step's accepted x_{k+1});
  // observer receives every inner MLCP of Algorithm 2 (step k, Newton iteration α), nothing for Algorithm 1.
  StepperOptions stepper;
  NonlinearAlgorithm algorithm = NonlinearAlgorithm::kNewtonMlcp;
  // Algorithm 2 (and the explicit-sign Newton): stop when the relative natural residual of OneStepMCP is
  // ≤ newton_tolerance (the same merit and scale Algorithm 1's backend is judged by).
  double newton_tolerance = 1e-10;
  // Newton iterations per step (each one MLCP solve). Exhausting it makes the step kIterationLimit.
  int newton_max_iterations = 50;

  bool IsValid(std::string* why) const;
};

// The one-step MCP `eq:MCP3`: z = (x_{k+1}, s_{k+1}) ∈ Rⁿ × [−1, 1]ᵐ,
//   F(z) = ( (1 + hρ)(x − x_k) − h f(x_{k+θ}, t_{k+θ}) + h g(x_{k+γ}) s ,  −h(x) ),
//   ∇F = [[(1 + hρ) I − hθ ∇f + hγ ∇g·s,  h g], [−∇h, 0]]   (`eq:JacMCLP`, sign of the lower block corrected).
// SetStep() selects (t_k, x_k). Evaluations reuse mutable workspace: no allocation, not thread-safe.
class OneStepMCP final : public MCP {
 public:
  // Validates system and scheme (InvalidInputError). Keeps its own copy of both.
  OneStepMCP(NonlinearSignSystem system, const NonlinearScheme& scheme);

  const NonlinearSignSystem& system() const { return system_; }
  const NonlinearScheme& scheme() const { return scheme_; }
  int n() const { return system_.n; }
  int m() const { return system_.m; }

  // The step from t_k, x_k to t_{k+1} = t_k + h. x_k must have size n (not checked: hot path).
  void SetStep(double t_k, const Vector& x_k);
  double t_k() const { return t_k_; }
  const Vector& x_k() const { return x_k_; }

  void Evaluate(const Vector& z, Vector* F) const override;
  void JacobianDense(const Vector& z, DenseMatrix* J) const override;

  // The scale Solver::Solve(MCP) divides by: 1 + ‖F(Π_[l,u](0))‖∞ (Π(0) = (0, 0)); 1 if that is not finite.
  double ResidualScale() const;

  // Algorithm 2's linearization at (x, s) = (x^α, s^α) (`eq:NL9`–`eq:NL15`): writes M_α (n×n), g(x^α_{k+γ})
  // (n×m), r_α (n), h(x^α) (m) and ∇h(x^α) (m×n) into pre-sized outputs.
  void Linearize(const Vector& x, const Vector& s, DenseMatrix* M, DenseMatrix* G, Vector* r, Vector* y,
                 DenseMatrix* H) const;

 private:
  // x_{k+θ}, x_{k+γ}, t_{k+θ} for the state x = x_{k+1}.
  void Blend(const Eigen::Ref<const Vector>& x) const;

  NonlinearSignSystem system_;
  NonlinearScheme scheme_;
  double t_k_ = 0.0;
  Vector x_k_;
  mutable Vector x_, s_, x_theta_, x_gamma_, f_, y_, zero_, F0_;
  mutable DenseMatrix G_, Jf_, Jg_, H_;
};

// Per-run numbers of the Newton loop (Algorithm 2 or the explicit-sign Newton); all zero for Algorithm 1.
struct NewtonStats {
  std::vector<int> iterations;  // per recorded step k (entry 0 is 0); empty when the run does not record
  std::int64_t total_iterations = 0;
  int max_iterations = 0;
};

class NonlinearStepper {
 public:
  // Validates (InvalidInputError naming the field) and sizes every workspace once.
  NonlinearStepper(NonlinearSignSystem system, const NonlinearScheme& scheme);
  ~NonlinearStepper();
  NonlinearStepper(NonlinearStepper&&) noexcept;
  NonlinearStepper& operator=(NonlinearStepper&&) noexcept;

  const NonlinearScheme& scheme() const;
  const NonlinearSignSystem& system() const;
  // The one-step MCP of the last step run (Algorithm 1's problem).
  const OneStepMCP& problem() const;

  // Runs num_steps steps from x0 at t = options.stepper.t0 into *out (storage reused across runs). Trajectory row
  // k holds t_k, x_k, the s_k that produced x_k (row 0: s = 0) and y_k = h(x_k); per step, iterations are the
  // backend's (Algorithm 2: summed over the Newton iterations; explicit sign: 0) and residual is the relative
  // natural residual of OneStepMCP at the accepted (x_{k+1}, s_{k+1}) (explicit sign: of its x rows only).
  // solver: Algorithm 1 needs a backend that solves MCPs (kNotApplicable per step otherwise), Algorithm 2 any
  // box-MLCP backend; may be null only for an explicit-sign scheme.
  // InvalidInputError for bad arguments (x0 size/NaN, num_steps < 0, null solver, invalid options, f/g/h or a
  // Jacobian non-finite at x0). A step that is not solved is a status in *out (first_failed_step = k is the step
  // producing x_k, first_failure_message names it), never an exception: backend failure (its status), Newton
  // budget exhausted (kIterationLimit), M_α singular (kSingular), non-finite values (kNumericalFailure/kDiverged).
  void Run(const Vector& x0, std::int64_t num_steps, Solver* solver, const NonlinearStepperOptions& options,
           Trajectory* out);
  Trajectory Run(const Vector& x0, std::int64_t num_steps, Solver* solver,
                 const NonlinearStepperOptions& options = {});

  // Newton iterations of the last run.
  const NewtonStats& newton_stats() const;

  struct Workspace;  // implementation detail

 private:
  std::unique_ptr<Workspace> ws_;
};

}  // namespace smcbench

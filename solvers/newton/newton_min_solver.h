// `newton-min`: semismooth Newton on the min (natural-map) function z − Π_[l,u](z − F(z)), the other classic NCP
// function (Pang 1990, Qi 1993, Facchinei–Pang 2003 §9.1; Siconos' NewtonMin), for box-MLCPs and nonlinear MCPs. Here
// beside `newton` (Fischer–Burmeister) because each of its steps is an active-set Newton step (unit rows at the
// bounds, J on the free rows), exact for an LCP once the set is right, and it fails differently: the min function is
// not differentiable, so the pure method cycles or follows Newton on F out of its basin. Every step is therefore
// checked on FB's merit, with FB's Newton step and then the merit's gradient as fallbacks; there is no proximal
// restart, so a minimizer of the merit that is not a solution ends in `stalled` (Billups' example; Josephy's NCP
// from x = 10·1, which `newton` solves).
#pragma once

#include <memory>
#include <string>

#include "solvers/core/backend_options.h"
#include "solvers/core/solver.h"
#include "solvers/newton/semismooth_newton_solver.h"

namespace smcbench {

struct NewtonMinOptions {
  // Values of globalization (`--set newton-min.globalization=NAME`).
  enum Globalization : int {
    // "fb-line-search": Armijo on the Fischer–Burmeister merit, min-Newton direction when it is a sufficient
    // descent direction for it, else the merit's steepest descent (Siconos' min_FBLSA idea).
    kFischerBurmeisterLineSearch = 0,
    // "none": full min-Newton steps, no merit function (the textbook local method; can cycle or diverge).
    kNoGlobalization = 1,
  };

  // Values of merit_scaling: the row scales d of G = c∘F/d, the F that the active-set choice and the merit see.
  enum MeritScaling : int {
    // "jacobian-rows": d = McpRowScales(J(z₀), c), the verdict's row scales at the start. The run, and so the
    // outcome, is the same after any positive scaling of F's rows or change of the variables' units.
    kJacobianRowScaling = 0,
    // "none": d = 1, F as the problem states it. Not invariant; on problems stated in natural units it can avoid
    // minimizers of the merit that the start's scales create (Josephy's NCP from x = 10·1 is solved).
    kNoRowScaling = 1,
  };

  Globalization globalization = kFischerBurmeisterLineSearch;
  MeritScaling merit_scaling = kJacobianRowScaling;
  // Armijo constant σ in Psi(z + t d) ≤ Psi(z) + σ t ∇Psiᵀd.
  double armijo_sigma = 1e-4;
  // Backtracking factor β: t ∈ {1, β, β², ...}.
  double backtrack_factor = 0.5;
  // Trial step lengths per line search before it is declared failed.
  int max_backtracks = 40;
  // When the min-Newton step is rejected, try the Newton step of the FB function itself (De Luca–Facchinei–Kanzow
  // 1996) before −∇Psi: where the two functions disagree on the active set, gradient steps alone can crawl (Josephy's
  // NCP from x = 10·1, in the tests).
  bool fischer_burmeister_step = true;
  // A Newton direction d is used only if ∇Psiᵀd ≤ −ρ‖d/c‖^p (DFK 1996; c the variables' units), else the next choice.
  double descent_rho = 1e-8;
  double descent_power = 2.1;
  // Stalled when the merit has not fallen below stagnation_ratio × its value stagnation_window iterations earlier:
  // there is no proximal restart here, so crawling gradient steps towards a merit minimizer that is not a solution
  // would only spend the budget.
  static constexpr int kMaxStagnationWindow = 64;
  int stagnation_window = 30;
  double stagnation_ratio = 0.5;
  // Dense LU of the free rows, or UMFPACK on the full system (unit rows at the bounds); the same choices as
  // `newton`'s linear_solver: auto = dense for dense data and sparse data up to dense_max_size unknowns.
  NewtonOptions::LinearSolver linear_solver = NewtonOptions::kAutoLinearSolver;
  int dense_max_size = 64;

  // True if every field is usable; otherwise *why names the field and the accepted range.
  bool IsValid(std::string* why) const;
};

// Solves a box-MLCP (F = Mz + q, dense or sparse M) or a nonlinear MCP. Works in the units of the verdict: rows of F
// divided by d = McpRowScales(J(z₀), c) at the start (merit_scaling) and variables in the problem's units c, in
// which every step, norm and test is measured. So the iterates are unchanged, up to rounding, by a change of units
// stated through MCP::variable_scale and (merit_scaling jacobian-rows) by a positive scaling of F's rows. Stops when
// the scale-free residual McpScaledResidual(z, F, l, u, McpRowScales(J(z), c), c) ≤ tolerance (a box-MLCP, which
// arrives row-equilibrated, also needs its natural residual ≤ tolerance·(1 + ‖q‖∞), the base's second test).
// iterations = Newton iterations, default budget 200 (options.max_iterations ≤ 0). A failure returns the iterate
// with the smallest scale-free residual seen, and says it in the message. Details: "newton_steps" (min-Newton),
// "fb_newton_steps", "gradient_steps", "backtracks", "factorizations", "max_system_size".
class NewtonMinSolver final : public BackendWithOptions<NewtonMinOptions> {
 public:
  NewtonMinSolver();
  explicit NewtonMinSolver(const NewtonMinOptions& options);
  ~NewtonMinSolver() override;
  NewtonMinSolver(const NewtonMinSolver&) = delete;
  NewtonMinSolver& operator=(const NewtonMinSolver&) = delete;

  const SolverInfo& info() const override;

  static constexpr int kDefaultMaxIterations = 200;

 protected:
  void DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) override;
  void DoSolveMCP(const MCP& problem, const SolverOptions& options, SolveResult* result) override;
  void BindOptions(OptionBinder* binder) override;
  bool ValidateBackendOptions(std::string* why) const override;

 private:
  struct Workspace;  // iterate, Jacobian copies, dense LU buffer and UMFPACK state, reused across solves
  void SetUpSolve(int n, const Vector& l, const Vector& u, bool native_sparse);
  void RunAndConclude(const SolverOptions& options, SolveResult* result);
  std::unique_ptr<Workspace> ws_;
};

}  // namespace smcbench

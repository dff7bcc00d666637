// Semismooth (generalized) Newton method on Billups' box Fischer–Burmeister reformulation, for box-MLCPs and
// nonlinear MCPs: De Luca–Facchinei–Kanzow 1996 (Math. Prog. 75) globalized by an Armijo (optionally
// Grippo–Lampariello–Lucidi non-monotone) line search on Psi = ½‖Phi‖², with a gradient-step fallback and a
// proximal-perturbation safeguard against non-solution stationary points of Psi (Billups 1995, ch. 3).
// Dense Jacobians use a reduced LU on the rows that are not trivially active; sparse ones use UMFPACK.
#pragma once

#include <memory>
#include <string>

#include "solvers/core/backend_options.h"
#include "solvers/core/solver.h"

namespace smcbench {

struct NewtonOptions {
  // Values of linear_solver (`--set newton.linear_solver=NAME`; the old numbers 0–2 are still read).
  enum LinearSolver : int {
    kAutoLinearSolver = 0,    // "auto": dense LU for dense data and small sparse data, else UMFPACK
    kDenseLinearSolver = 1,   // "dense": always dense (sparse data are copied to a dense matrix)
    kSparseLinearSolver = 2,  // "sparse": always UMFPACK (dense data converted per solve / MCP iteration)
  };
  static constexpr int kMaxNonmonotoneMemory = 32;

  // Armijo constant σ in Psi(z + t d) ≤ Psi_ref + σ t ∇Psiᵀd (DFK 1996 use 1e-4).
  double armijo_sigma = 1e-4;
  // Backtracking factor β: t ∈ {1, β, β², ...}.
  double backtrack_factor = 0.5;
  // Trial step lengths per line search before it is declared failed.
  int max_backtracks = 40;
  // Grippo–Lampariello–Lucidi memory: Psi_ref = max of the last M merit values. 1 = monotone Armijo (default:
  // on strongly nonsymmetric random problems M = 3..10 needed more iterations and at M = 10 cycled at n ≥ 256).
  int nonmonotone_memory = 1;
  // The same memory for nonlinear MCPs (docs/auto.md, "Nonlinear MCPs"): there the monotone search follows the
  // narrow valleys of Psi that an economy's price floors make, one short step at a time.
  int mcp_nonmonotone_memory = 5;
  // Nonlinear MCP, dense linear algebra: a crash phase of up to this many min-map Newton steps first (the natural
  // map's active set, the free rows' Newton system, the step projected onto the box), each kept only when it at
  // least halves Psi; the first one that does not ends the phase. A linear MCP whose start shows the solution's
  // active set is solved by one such step. 0 = none.
  int crash_steps = 5;
  // Nonlinear MCP: G = D⁻¹F is scaled by the row scales D of ∇F at the start. When the row scales of ∇G at an
  // iterate leave [1/100, 100] (∇F changed by orders of magnitude, as at an economy's price floor), D is refreshed
  // there and the line-search memory restarted (at most 8 times per solve): otherwise Psi can fall while the
  // verdict's residual grows (Mathiesen's economy from Π(0)).
  bool row_scale_refresh = true;
  // stagnation_window and proximal_lambda for nonlinear MCPs: on Kojima–Shindo's and Josephy's NCPs from MCPLIB's
  // starts 6 and 3, a shorter window and a smaller first λ leave the merit function's basins sooner (71 and 83
  // iterations become 25 and 26; docs/auto.md, "Nonlinear MCPs").
  int mcp_stagnation_window = 5;
  double mcp_proximal_lambda = 0.3;
  // DFK 1996 sufficient-descent test for the Newton direction: ∇Psiᵀd ≤ −ρ‖d‖^p; if it fails, the
  // regularized step and then −∇Psi are tried.
  double descent_rho = 1e-8;
  double descent_power = 2.1;
  // Use −∇Psi when neither the Newton nor the regularized step is accepted. If false, such an iteration ends
  // the solve (kSingular if no direction passed its descent test, kStalled if the line search failed).
  bool gradient_fallback = true;
  // kAutoLinearSolver, kDenseLinearSolver or kSparseLinearSolver.
  LinearSolver linear_solver = kAutoLinearSolver;
  // kAutoLinearSolver: sparse data with at most this many unknowns are factorized densely.
  int dense_max_size = 64;
  // Dense only: rows with |Db_i| ≤ threshold·|Da_i| are treated as trivially active (Db_i := 0), so their
  // step is −Phi_i/Da_i and they drop out of the LU. 0 = drop only exact zeros (an exact Newton step).
  double reduction_threshold = 1e-10;
  // Dense LCP with (numerically) symmetric M: the reduced matrix M_RR + diag(Da/Db) + λI is symmetric, so try
  // Cholesky first (half the flops of LU) and fall back to LU when it is not positive definite.
  bool use_cholesky = true;
  // Reformulate with s_i·F_i, s_i = 1/max(1, max_j |∂F_i/∂z_j|) at the starting point: the FB function is not
  // scale invariant, and rows much larger than the box make the line search crawl. Solutions are unchanged.
  bool row_scaling = true;
  // When the Newton system is singular, or its direction fails the descent test or the line search, retry once
  // with ∇F + μI, μ = regularization·min(1, ‖Phi‖₂), before falling back to −∇Psi. 0 disables the retry.
  double regularization = 1.0;
  // Proximal-perturbation safeguard (Billups 1995): when the line search fails or Psi stagnates at a
  // non-solution, solve F(z) + λ(z − z̄) = 0-type perturbed problems and restart Newton from their solutions.
  bool proximal_safeguard = true;
  int max_proximal_rounds = 30;
  // Initial λ = proximal_lambda · max(1, ‖∇F(z)‖∞). Halved after each successful round, ×10 after a failure.
  double proximal_lambda = 1.0;
  // Stagnation: Psi did not fall below stagnation_ratio × its value stagnation_window iterations earlier.
  int stagnation_window = 10;
  double stagnation_ratio = 0.9;
  // Newton iterations allowed to one perturbed problem (the unperturbed run after it uses the global budget).
  int proximal_inner_iterations = 50;

  // True if every field is usable; otherwise *why names the field and the accepted range.
  bool IsValid(std::string* why) const;
};

// Solves a box-MLCP (F = Mz + q) or a nonlinear MCP. iterations = Newton iterations (each takes one step along
// a Newton, regularized or gradient direction), summed over proximal rounds; default budget 200
// (options.max_iterations ≤ 0). A failure returns the iterate with the smallest stopping measure seen (the relative
// natural residual of a box-MLCP, the scale-free residual of an MCP, which is solved in its stated units).
// Details: "backtracks", "gradient_steps", "proximal_rounds", "regularized_steps",
// "factorizations", "max_system_size", "crash_steps" (accepted min-map steps of the crash phase),
// "nonmonotone_steps" (accepted steps that raised Psi, allowed by the non-monotone memory).
class SemismoothNewtonSolver final : public BackendWithOptions<NewtonOptions> {
 public:
  SemismoothNewtonSolver();
  explicit SemismoothNewtonSolver(const NewtonOptions& options);
  ~SemismoothNewtonSolver() override;
  SemismoothNewtonSolver(const SemismoothNewtonSolver&) = delete;
  SemismoothNewtonSolver& operator=(const SemismoothNewtonSolver&) = delete;

  const SolverInfo& info() const override;

  static constexpr int kDefaultMaxIterations = 200;

 protected:
  void DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) override;
  void DoSolveMCP(const MCP& problem, const SolverOptions& options, SolveResult* result) override;
  void BindOptions(OptionBinder* binder) override;
  bool ValidateBackendOptions(std::string* why) const override;

 private:
  struct Workspace;  // vectors, dense LU buffer and UMFPACK state, reused across solves
  // The two halves DoSolve and DoSolveMCP share (the .cc file says what each sets up).
  void SetUpSolve(int n, const Vector& l, const Vector& u, bool native_sparse);
  void RunAndConclude(const SolverOptions& options, SolveResult* result);
  std::unique_ptr<Workspace> ws_;
};

}  // namespace smcbench

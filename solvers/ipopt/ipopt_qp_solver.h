// Ipopt backend: the box-MLCP as a convex QP (symmetric PSD M) or as a complementarity-gap NLP (any other M),
// solved by Ipopt's primal-dual interior-point filter method (Wächter & Biegler 2006) with exact derivatives,
// followed by an OSQP-style active-set polish. The formulations are documented at the top of the .cc file; a
// nonlinear MCP gets the same gap program with F in place of Mz + q (ipopt_mcp.{h,cc}).
#pragma once

#include <memory>
#include <string>

#include "solvers/core/backend_options.h"
#include "solvers/core/solver.h"
#include "solvers/ipopt/ipopt_mcp.h"

namespace smcbench {

struct IpoptOptions {
  // How the box-MLCP is posed to Ipopt (detail "formulation" records what was used).
  enum Formulation : int {
    kAuto = 0,  // convex QP if M is symmetric PSD, else the gap NLP
    kQp = 1,    // QP even if M is not PSD (M must be symmetric): any KKT point of it still solves the MLCP
    kGap = 2,   // the complementarity-gap NLP for every M
  };
  // Ipopt option "linear_solver". Only MUMPS ships with Debian's Ipopt; the HSL codes are loaded at run time
  // (libhsl.so) and give kInvalidOptions when it is missing.
  enum LinearSolver : int { kMumps = 0, kMa27 = 1, kMa57 = 2, kMa77 = 3, kMa86 = 4, kMa97 = 5, kPardiso = 6 };
  enum MuStrategy : int { kMonotone = 0, kAdaptive = 1 };
  // The Hessian of the Lagrangian of the MCP's gap program (ipopt_mcp.cc): F's second derivatives are not
  // available, so either the exact Hessian of the bilinear gap alone (exact when F is affine) or Ipopt's
  // limited-memory quasi-Newton approximation of the whole Lagrangian.
  enum McpHessian : int { kGapHessian = 0, kLimitedMemory = 1 };

  // The options with named values (`--set ipopt.formulation=gap`; the old numbers are still read).
  Formulation formulation = kAuto;
  // Ipopt "tol": its scaled NLP error. The solve also stops as soon as our merit function holds at an iterate.
  double tol = 1e-10;
  // Ipopt "max_iter", used when SolverOptions::max_iterations <= 0. Iterations counted are Ipopt's.
  int max_iter = 3000;
  MuStrategy mu_strategy = kAdaptive;
  // Ipopt "mehrotra_algorithm" for the convex-QP formulation only (Ipopt recommends it for convex QPs).
  bool mehrotra = false;
  LinearSolver linear_solver = kMumps;
  // Ipopt "print_level" (0..12) used when SolverOptions::verbosity >= 2; verbosity 1 caps it at 3 (summary),
  // verbosity 0 silences Ipopt completely (no journal at all, banner suppressed).
  int print_level = 5;
  // M is symmetric when |M_ij - M_ji| <= symmetry_tolerance * max|M_ij|.
  double symmetry_tolerance = 1e-12;
  // Symmetric M is treated as PSD when Cholesky of M + delta*I succeeds, delta = psd_tolerance * ||M||_inf,
  // i.e. lambda_min(M) > -delta.
  double psd_tolerance = 1e-9;
  // Active-set polish after Ipopt (see the .cc file); kept only when it lowers the natural residual.
  bool polish = true;
  // Re-identify the active set from the polished point and re-solve, at most this many times.
  int polish_rounds = 3;
  // Try the polish during the Ipopt iterations, once the iterate's relative natural residual is below
  // early_polish_threshold and its active set differs from the last try; stop Ipopt when it succeeds.
  bool early_polish = true;
  double early_polish_threshold = 1e-3;
  // Try the polish from the warm start before running Ipopt (cheap re-solve of a slightly changed problem).
  bool polish_warm_start = false;
  // Nonlinear MCPs (ipopt_mcp.cc). The polish options above apply to the MCP's Newton refinement as well.
  McpHessian mcp_hessian = kGapHessian;
  // Newton steps of one MCP refinement (each re-identifies the active set and linearizes F there).
  int mcp_newton_steps = 20;

  bool IsValid(std::string* why) const;
};

class IpoptQpSolver final : public BackendWithOptions<IpoptOptions> {
 public:
  IpoptQpSolver();
  ~IpoptQpSolver() override;
  IpoptQpSolver(const IpoptQpSolver&) = delete;
  IpoptQpSolver& operator=(const IpoptQpSolver&) = delete;

  const SolverInfo& info() const override;

 protected:
  void DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) override;
  // The gap program of the MCP with exact first derivatives of F (ipopt_mcp.cc).
  void DoSolveMCP(const MCP& problem, const SolverOptions& options, SolveResult* result) override;
  void BindOptions(OptionBinder* binder) override;
  bool ValidateBackendOptions(std::string* why) const override;

 private:
  struct Impl;  // Ipopt application, TNLPs, classification cache and polish workspace (Ipopt types stay in .cc)
  bool Expired() const { return TimeLimitReached(); }

  std::unique_ptr<Impl> impl_;
  std::unique_ptr<IpoptMcpSession> mcp_;  // created on the first MCP solve
};

}  // namespace smcbench

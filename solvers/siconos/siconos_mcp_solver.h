// Siconos Numerics' nonlinear MCP solvers as backends: `siconos-mcp-newton-fb` (mcp_newton_FB_FBLSA) and
// `siconos-mcp-newton-min` (mcp_newton_min_FBLSA), given the box MCP rewritten exactly in Siconos' form
// (mcp_standard_form.h: free rows as equations, shifted/negated one-sided rows, box rows doubled with an
// upper-bound multiplier) and judged by our verdict like every backend.
//
// In process, unlike the box adapters (siconos_solver.h): an MCP's F and J are C++ callbacks into the caller's
// objects, which the kept worker process (forked before the problem existed) cannot call. So a Siconos crash on an
// MCP ends the process and a Siconos call cannot be interrupted: the time limit is checked before the call and
// when it returns (kTimeLimit if it passed without a solution). Detail in_process is always 1.
//
// What is checked before Siconos runs (a status, never a call): F finite and J of size n×n at the start
// (kNumericalFailure naming the entry or the size), the rewritten size ≤ max_size (kSizeLimit). Our callbacks
// never let an exception through Siconos' C code: it becomes NaN entries for Siconos, and is rethrown to the caller
// once Siconos returned (an exception from F is the caller's, not a status).
//
// Status from Siconos' `info` (detail siconos_info; its own error, the 2-norm of the min-map residual of the
// rewritten problem plus that of its equations, as siconos_error): a non-finite z is kNumericalFailure; info 0 with
// our scale-free residual above the tolerance is kInaccurate (their claim kept in the message, never trusted over
// the verdict); info 1 is kIterationLimit at the iteration budget, else kStalled (its line search gave up); any other
// info is kNumericalFailure. A Jacobian that changes size during the run is kNumericalFailure naming it.
//
// Options mapped from ours: tolerance → Siconos' dparam[TOL] = max(tol/√N, 10·N·ε) (N the rewritten size; its
// test is a 2-norm, in the problem's own units: it neither implies nor is implied by our scale-free test, which
// decides); max_iterations > 0 → iparam[MAX_ITER], else Siconos' default; verbosity ≥ 2 → Siconos verbose; the
// warm start reaches Siconos through the rewriting (box multipliers from F's sign).
#pragma once

#include <cstdio>
#include <memory>
#include <vector>

#include "solvers/core/backend_options.h"
#include "solvers/core/solver.h"
#include "solvers/siconos/external_backends.h"

namespace smcbench {

enum class SiconosMcpMethod : int {
  kNewtonFb = 0,   // mcp_newton_FB_FBLSA
  kNewtonMin = 1,  // mcp_newton_min_FBLSA
};

struct SiconosMcpOptions {
  // Largest rewritten problem (unknowns N; a box row counts 2) sent to Siconos, whose MCP methods are dense and run
  // in process, where our time limit cannot interrupt them: a dense factorization per iteration stays well under a
  // second at this size.
  int max_size = 512;

  bool IsValid(std::string* why) const;
};

class SiconosMcpSolver final : public BackendWithOptions<SiconosMcpOptions> {
 public:
  explicit SiconosMcpSolver(SiconosMcpMethod method);
  ~SiconosMcpSolver() override;
  SiconosMcpSolver(const SiconosMcpSolver&) = delete;
  SiconosMcpSolver& operator=(const SiconosMcpSolver&) = delete;

  const SolverInfo& info() const override;
  SiconosMcpMethod method() const { return method_; }

 protected:
  // Box-MLCPs are refused (kNotApplicable): Siconos' MLCP and LCP adapters take them.
  void DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) override;
  void DoSolveMCP(const MCP& problem, const SolverOptions& options, SolveResult* result) override;
  void BindOptions(OptionBinder* binder) override;
  bool ValidateBackendOptions(std::string* why) const override;

 private:
  SiconosMcpMethod method_;
  std::vector<double> x_, F_;  // Siconos' unknowns (start in, answer out) and its F at the answer
  std::FILE* stdio_sink_ = nullptr;  // /dev/null as a C stream, opened on the first quiet solve
};

// Appends siconos-mcp-newton-fb and siconos-mcp-newton-min (AppendExternalBackends calls it).
void AppendSiconosMcpBackends(std::vector<ExternalBackend>* backends);

}  // namespace smcbench

// Ipopt on a nonlinear MCP: the complementarity-gap program with exact first derivatives of F, then a local Newton
// refinement on the identified active set; the program and its choices are documented at the top of the .cc file.
// IpoptQpSolver::DoSolveMCP runs it (the `ipopt` backend); Ipopt types stay in the .cc file.
#pragma once

#include <functional>
#include <memory>

#include "solvers/core/options.h"
#include "solvers/core/problem.h"
#include "solvers/core/result.h"

namespace smcbench {

struct IpoptOptions;

class IpoptMcpSession {
 public:
  // time_up: true once the caller's time limit has passed (Solver::TimeLimitReached).
  explicit IpoptMcpSession(std::function<bool()> time_up);
  ~IpoptMcpSession();
  IpoptMcpSession(const IpoptMcpSession&) = delete;
  IpoptMcpSession& operator=(const IpoptMcpSession&) = delete;

  // result->z holds the starting point (sizes and options checked by the base). Sets status, message, z,
  // iterations and the details listed in the .cc file.
  void Solve(const MCP& problem, const SolverOptions& options, const IpoptOptions& ipopt, SolveResult* result);

  struct Impl;  // the program, Ipopt's application and the workspaces (defined in the .cc file only)

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace smcbench

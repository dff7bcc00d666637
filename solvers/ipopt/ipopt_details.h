// The codes an ipopt solve leaves among its SolveResult details, each set and read through its CodeDetail
// (solvers/core/result.h), so that JSON and Python print them by name and no caller compares a stored number.
#pragma once

#include <string_view>

#include "solvers/core/result.h"
#include "solvers/ipopt/ipopt_qp_solver.h"

namespace smcbench {

// Detail "formulation" of a box-MLCP solve: how the problem was posed to Ipopt (the .cc file's formulations).
enum class IpoptFormulation : int {
  kNone = 0,      // answered before Ipopt ran (solved at the start, or by the polished warm start)
  kConvexQp = 1,  // the QP of a symmetric PSD M (up to a positive row scaling)
  kGapNlp = 2,    // the complementarity-gap NLP
  kForcedQp = 3,  // the QP forced on a symmetric non-PSD M (formulation=qp): a KKT point still solves the MLCP
};
std::string_view ToString(IpoptFormulation formulation);  // "none", "convex-qp", "gap-nlp", "forced-qp"
inline constexpr CodeDetail<IpoptFormulation, 4> kIpoptFormulationDetail{"formulation"};

// Detail "early_stop" of a box-MLCP solve: what ended it before Ipopt's own convergence test.
enum class IpoptEarlyStop : int {
  kNone = 0,
  kMeritAtIterate = 1,  // an Ipopt iterate met the merit function
  kEarlyPolish = 2,     // the polish of an iterate solved the problem
  kWarmPolish = 3,      // the polish of the warm start solved it before Ipopt ran
};
std::string_view ToString(IpoptEarlyStop stop);  // "none", "merit-at-iterate", "early-polish", "warm-polish"
inline constexpr CodeDetail<IpoptEarlyStop, 4> kIpoptEarlyStopDetail{"early_stop"};

// Detail "early_stop" of a nonlinear MCP solve (its refinement is a Newton step on the active set, not a polish).
enum class IpoptMcpEarlyStop : int {
  kNone = 0,
  kMeritAtIterate = 1,     // an Ipopt iterate met the merit function
  kRefinedIterate = 2,     // the refinement of an iterate solved the problem
  kSolvedAtStart = 3,      // the start point already solved it
  kRefinedWarmStart = 4,   // the refinement of the warm start solved it before Ipopt ran
};
// "none", "merit-at-iterate", "refined-iterate", "solved-at-start", "refined-warm-start"
std::string_view ToString(IpoptMcpEarlyStop stop);
inline constexpr CodeDetail<IpoptMcpEarlyStop, 5> kIpoptMcpEarlyStopDetail{"early_stop"};

// Detail "mcp_hessian" of a nonlinear MCP solve: the option's value that was used ("gap", "limited-memory").
std::string_view ToString(IpoptOptions::McpHessian hessian);
inline constexpr CodeDetail<IpoptOptions::McpHessian, 2> kIpoptMcpHessianDetail{"mcp_hessian"};

}  // namespace smcbench

#include "solvers/ipopt/ipopt_details.h"

namespace smcbench {

std::string_view ToString(IpoptFormulation formulation) {
  switch (formulation) {
    case IpoptFormulation::kNone: return "none";
    case IpoptFormulation::kConvexQp: return "convex-qp";
    case IpoptFormulation::kGapNlp: return "gap-nlp";
    case IpoptFormulation::kForcedQp: return "forced-qp";
  }
  return "";
}

std::string_view ToString(IpoptEarlyStop stop) {
  switch (stop) {
    case IpoptEarlyStop::kNone: return "none";
    case IpoptEarlyStop::kMeritAtIterate: return "merit-at-iterate";
    case IpoptEarlyStop::kEarlyPolish: return "early-polish";
    case IpoptEarlyStop::kWarmPolish: return "warm-polish";
  }
  return "";
}

std::string_view ToString(IpoptMcpEarlyStop stop) {
  switch (stop) {
    case IpoptMcpEarlyStop::kNone: return "none";
    case IpoptMcpEarlyStop::kMeritAtIterate: return "merit-at-iterate";
    case IpoptMcpEarlyStop::kRefinedIterate: return "refined-iterate";
    case IpoptMcpEarlyStop::kSolvedAtStart: return "solved-at-start";
    case IpoptMcpEarlyStop::kRefinedWarmStart: return "refined-warm-start";
  }
  return "";
}

std::string_view ToString(IpoptOptions::McpHessian hessian) {
  switch (hessian) {
    case IpoptOptions::kGapHessian: return "gap";
    case IpoptOptions::kLimitedMemory: return "limited-memory";
  }
  return "";
}

}  // namespace smcbench

// PLACEHOLDER: replaced by the real backend.
#include "solvers/ipopt/ipopt_qp_solver.h"
namespace smcbench {
const SolverInfo& IpoptQpSolver::info() const { static const SolverInfo kInfo{"ipopt", "placeholder", "", true}; return kInfo; }
void IpoptQpSolver::DoSolve(const BoxMLCP&, const SolverOptions&, SolveResult* result) { result->status = SolveStatus::kNotApplicable; }
}  // namespace smcbench

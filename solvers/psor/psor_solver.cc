// PLACEHOLDER: replaced by the real backend.
#include "solvers/psor/psor_solver.h"
namespace smcbench {
const SolverInfo& PsorSolver::info() const { static const SolverInfo kInfo{"psor", "placeholder", "", true}; return kInfo; }
void PsorSolver::DoSolve(const BoxMLCP&, const SolverOptions&, SolveResult* result) { result->status = SolveStatus::kNotApplicable; }
}  // namespace smcbench

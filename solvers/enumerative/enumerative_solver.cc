// PLACEHOLDER: replaced by the real backend.
#include "solvers/enumerative/enumerative_solver.h"
namespace smcbench {
const SolverInfo& EnumerativeSolver::info() const { static const SolverInfo kInfo{"enumerative", "placeholder", "", true}; return kInfo; }
void EnumerativeSolver::DoSolve(const BoxMLCP&, const SolverOptions&, SolveResult* result) { result->status = SolveStatus::kNotApplicable; }
}  // namespace smcbench

// PLACEHOLDER: replaced by the real backend.
#include "solvers/lemke/lemke_solver.h"
namespace smcbench {
const SolverInfo& LemkeSolver::info() const { static const SolverInfo kInfo{"lemke", "placeholder", "", true}; return kInfo; }
void LemkeSolver::DoSolve(const BoxMLCP&, const SolverOptions&, SolveResult* result) { result->status = SolveStatus::kNotApplicable; }
}  // namespace smcbench

// PLACEHOLDER: replaced by the real backend.
#include "solvers/newton/semismooth_newton_solver.h"
namespace smcbench {
const SolverInfo& SemismoothNewtonSolver::info() const { static const SolverInfo kInfo{"newton", "placeholder", "", true}; return kInfo; }
void SemismoothNewtonSolver::DoSolve(const BoxMLCP&, const SolverOptions&, SolveResult* result) { result->status = SolveStatus::kNotApplicable; }
}  // namespace smcbench

// PLACEHOLDER: replaced by the real backend.
#pragma once
#include "solvers/core/solver.h"
namespace smcbench {
class LemkeSolver final : public Solver {
 public:
  const SolverInfo& info() const override;
 protected:
  void DoSolve(const BoxMLCP&, const SolverOptions&, SolveResult* result) override;
};
}  // namespace smcbench

#include "solvers/avi/avi_solver.h"

#include <utility>

namespace smcbench {

AviResult SolveAvi(const AffineVI& avi, Solver& solver, const SolverOptions& options, const AviReference* reference) {
  AviResult out;
  const AviReduction reduction = ReduceToBoxMlcp(avi, AviReductionScaling::kNormalized);
  const int n = reduction.n, total = n + reduction.m + reduction.p;
  SolverOptions reduced_options = options;
  if (options.warm_start.size() == n && total != n) {
    reduced_options.warm_start = JoinReducedSolution(reduction, {options.warm_start, {}, {}});
  } else if (options.warm_start.size() == total) {
    const Vector& w = options.warm_start;
    reduced_options.warm_start = JoinReducedSolution(
        reduction, {w.head(n), w.segment(n, reduction.m), w.tail(reduction.p)});
  }
  solver.Solve(reduction.problem, reduced_options, &out.reduced);
  out.status = out.reduced.status;
  out.message = out.reduced.message;
  out.solver = out.reduced.solver;
  out.iterations = out.reduced.iterations;
  out.solve_seconds = out.reduced.solve_seconds;
  if (out.reduced.z.size() == total) out.solution = SplitReducedSolution(reduction, out.reduced.z);
  out.judgement = JudgeAvi(avi, ExpectedAviOutcome(avi), reference, out.status, out.solution, options.tolerance);
  return out;
}

}  // namespace smcbench

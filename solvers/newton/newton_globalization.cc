// The shared globalization of the two semismooth Newtons (newton_globalization.h).
#include "solvers/newton/newton_globalization.h"

#include <sstream>

namespace smcbench {
namespace newton {

void ReportExit(Exit exit, const char* detail, int iterations, int budget, int rounds, const char* measure,
                double residual, SolveResult* result) {
  if (exit == Exit::kConverged) {
    result->status = SolveStatus::kSolved;
    return;
  }
  std::ostringstream s;
  switch (exit) {
    case Exit::kConverged:
      break;
    case Exit::kBudget:
      result->status = SolveStatus::kIterationLimit;
      s << "iteration limit (" << budget << ") reached";
      break;
    case Exit::kStalled:
    case Exit::kStagnated:
      result->status = SolveStatus::kStalled;
      s << detail;
      break;
    case Exit::kSingular:
      result->status = SolveStatus::kSingular;
      s << detail;
      break;
    case Exit::kNumericalFailure:
      result->status = SolveStatus::kNumericalFailure;
      s << detail;
      break;
    case Exit::kTimeLimit:
      result->status = SolveStatus::kTimeLimit;
      s << "time limit reached";
      break;
    case Exit::kDiverged:
      result->status = SolveStatus::kDiverged;
      s << detail;
      break;
  }
  s << " after " << iterations << " iterations";
  if (rounds > 0) s << "; " << rounds << " proximal-perturbation rounds did not recover";
  s << "; best " << measure << " " << residual;
  result->message = s.str();
}

}  // namespace newton
}  // namespace smcbench

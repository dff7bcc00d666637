// The shared globalization of the two semismooth Newtons (newton_globalization.h).
#include "solvers/newton/newton_globalization.h"

#include <sstream>

namespace smcbench {
namespace newton {
namespace {

// *why = the parts streamed one after the other (when why is given); false.
template <class... Parts>
bool Invalid(std::string* why, const Parts&... parts) {
  if (why) {
    std::ostringstream s;
    (s << ... << parts);
    *why = s.str();
  }
  return false;
}

}  // namespace

bool ExplainArmijoRule(const ArmijoRule& rule, std::string* why) {
  if (!(rule.sigma > 0.0 && rule.sigma < 0.5)) return Invalid(why, "armijo_sigma must be in (0, 0.5), got ", rule.sigma);
  if (!(rule.backtrack_factor > 0.0 && rule.backtrack_factor < 1.0))
    return Invalid(why, "backtrack_factor must be in (0, 1), got ", rule.backtrack_factor);
  if (rule.max_backtracks < 1 || rule.max_backtracks > 200)
    return Invalid(why, "max_backtracks must be in [1, 200], got ", rule.max_backtracks);
  return true;
}

bool ExplainDescentTest(double rho, double power, std::string* why) {
  if (!(rho > 0.0) || !std::isfinite(rho)) return Invalid(why, "descent_rho must be a positive finite number, got ", rho);
  if (!(power > 2.0) || !std::isfinite(power))
    return Invalid(why, "descent_power must be > 2 (DFK 1996 require p > 2), got ", power);
  return true;
}

static_assert(MeritWindow::kMaxWindow == 64, "ValidStagnation states the bound");

bool ExplainStagnation(int window, double ratio, std::string* why) {
  if (window < 1 || window > MeritWindow::kMaxWindow)
    return Invalid(why, "stagnation_window must be in [1, ", MeritWindow::kMaxWindow, "], got ", window);
  if (!(ratio > 0.0 && ratio < 1.0)) return Invalid(why, "stagnation_ratio must be in (0, 1), got ", ratio);
  return true;
}

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

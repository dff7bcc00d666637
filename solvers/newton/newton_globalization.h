// The globalization the two semismooth Newtons share (`newton`, semismooth_newton_solver.cc, and `newton-min`,
// newton_min_solver.cc): how a run ends and how that is reported, the DFK sufficient-descent test, Armijo
// backtracking on a merit function (with the Grippo–Lampariello–Lucidi non-monotone reference), the stagnation
// window on the merit, the step-collapse and divergence tests, and the best iterate by the stopping measure.
// Each solver keeps its own reformulation, merit function, directions and linear algebra; what is here knows only
// numbers and vectors, so it is tested on its own (newton_globalization_test.cc).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "solvers/core/result.h"
#include "solvers/core/types.h"

namespace smcbench {
namespace newton {

// How one run of a Newton loop ended.
enum class Exit {
  kConverged,
  kBudget,     // the loop's own iteration budget (which may be the global one)
  kStalled,    // line search failed along every direction, or the step collapsed
  kStagnated,  // the merit did not decrease enough over the stagnation window
  kSingular,   // no direction: the Newton systems singular and ∇Psi = 0 (or no fallback)
  kNumericalFailure,
  kTimeLimit,
  kDiverged,
};

// A failure that no safeguard (proximal round, restart) should try to recover from.
inline bool IsHardFailure(Exit e) {
  return e == Exit::kNumericalFailure || e == Exit::kTimeLimit || e == Exit::kDiverged;
}

// result->status and, for an exit that is not convergence, result->message: "<why> after N iterations[; R
// proximal-perturbation rounds did not recover]; best <measure> <residual>" (rounds > 0 adds the middle part; the
// budget and the time limit say so in place of detail).
void ReportExit(Exit exit, const char* detail, int iterations, int budget, int rounds, const char* measure,
                double residual, SolveResult* result);

// De Luca–Facchinei–Kanzow 1996 sufficient-descent test gd ≤ −ρ‖d‖^p (p > 2) for a Newton direction d with
// gd = ∇Psiᵀd. The power is evaluated only when the bounds ‖d‖² ≥ ‖d‖^p (‖d‖ ≤ 1) and ‖d‖³ ≥ ‖d‖^p (‖d‖ ≥ 1,
// p ≤ 3) do not decide it.
inline bool SufficientDescent(double gd, double norm_d, double rho, double p) {
  if (!(gd < 0.0)) return false;
  const double n2 = norm_d * norm_d;
  if (p <= 3.0 && gd <= -rho * (norm_d <= 1.0 ? n2 : n2 * norm_d)) return true;
  return gd <= -rho * std::pow(norm_d, p);
}

// Armijo's rule: accept t when Psi(z + t d) ≤ psi_ref + σ t gd, trying t = 1, β, β², … (max_backtracks + 1 trials).
struct ArmijoRule {
  double sigma = 1e-4;            // σ ∈ (0, ½)
  double backtrack_factor = 0.5;  // β ∈ (0, 1)
  int max_backtracks = 40;
};

// The checks of the options both solvers share, each with the option names and ranges in *why on failure. They
// run at every Solve(): the test is inline, only the message is built out of line.
// armijo_sigma ∈ (0, ½), backtrack_factor ∈ (0, 1), max_backtracks ∈ [1, 200];
bool ExplainArmijoRule(const ArmijoRule& rule, std::string* why);
inline bool ValidArmijoRule(const ArmijoRule& rule, std::string* why) {
  if (rule.sigma > 0.0 && rule.sigma < 0.5 && rule.backtrack_factor > 0.0 && rule.backtrack_factor < 1.0 &&
      rule.max_backtracks >= 1 && rule.max_backtracks <= 200) {
    return true;
  }
  return ExplainArmijoRule(rule, why);
}
// descent_rho > 0 finite, descent_power > 2 finite (DFK 1996);
bool ExplainDescentTest(double rho, double power, std::string* why);
inline bool ValidDescentTest(double rho, double power, std::string* why) {
  if (rho > 0.0 && std::isfinite(rho) && power > 2.0 && std::isfinite(power)) return true;
  return ExplainDescentTest(rho, power, why);
}
// stagnation_window ∈ [1, MeritWindow::kMaxWindow], stagnation_ratio ∈ (0, 1) (MeritWindow is below).
bool ExplainStagnation(int window, double ratio, std::string* why);
inline bool ValidStagnation(int window, double ratio, std::string* why) {
  if (window >= 1 && window <= 64 && ratio > 0.0 && ratio < 1.0) return true;
  return ExplainStagnation(window, ratio, why);
}

// Backtracking line search along a direction d with gd = ∇Psiᵀd < 0 from the reference merit psi_ref (Psi(z), or the
// non-monotone reference). merit_at(t, &psi_t) evaluates the trial point z + t d (the caller keeps it, e.g. in zt
// and F(zt)) and returns false when F is not finite there. On success *psi_out and *t_out hold the accepted trial's
// merit and step, and the trial point is the last one merit_at evaluated. *all_nan: every trial's F was not finite.
// Each rejected trial adds one to *backtracks.
template <class MeritAt>
bool ArmijoBacktrack(const ArmijoRule& rule, double psi_ref, double gd, MeritAt&& merit_at, double* psi_out,
                     double* t_out, bool* all_nan, int* backtracks) {
  double t = 1.0;
  *all_nan = true;
  for (int j = 0; j <= rule.max_backtracks; ++j) {
    double psi = 0.0;
    if (merit_at(t, &psi)) {
      *all_nan = false;
      if (psi <= psi_ref + rule.sigma * t * gd) {
        *psi_out = psi;
        *t_out = t;
        return true;
      }
    }
    ++*backtracks;
    t *= rule.backtrack_factor;
  }
  return false;
}

// Grippo–Lampariello–Lucidi (1986) non-monotone reference: the largest of the last `memory` merit values (memory 1 =
// monotone Armijo, the reference is Psi(z)).
class NonmonotoneReference {
 public:
  static constexpr int kMaxMemory = 32;

  // Forgets every value but psi; memory ∈ [1, kMaxMemory] (the caller validates it).
  void Reset(int memory, double psi) {
    memory_ = memory;
    Reset(psi);
  }
  void Reset(double psi) {
    count_ = 0;
    next_ = 0;
    Push(psi);
  }
  void Push(double psi) {
    values_[next_] = psi;
    next_ = (next_ + 1) % memory_;
    count_ = std::min(count_ + 1, memory_);
  }
  double Reference() const {
    double r = values_[0];
    for (int k = 1; k < count_; ++k) r = std::max(r, values_[k]);
    return r;
  }
  int memory() const { return memory_; }

 private:
  std::array<double, kMaxMemory> values_{};
  int memory_ = 1;
  int count_ = 0, next_ = 0;
};

// Stagnation of the merit: a ring of its values at the last window + 1 iterations. Stagnated(k, psi, ratio) is true
// when psi at iteration k has not fallen below ratio × the value recorded at iteration k − window (so only once
// k ≥ window; the caller records every iteration from 0 on).
class MeritWindow {
 public:
  static constexpr int kMaxWindow = 64;  // ValidStagnation's bound

  void SetWindow(int window) { window_ = window; }  // window ∈ [1, kMaxWindow] (the caller validates it)
  int window() const { return window_; }
  void Record(int k, double psi) { values_[k % (window_ + 1)] = psi; }
  bool Stagnated(int k, double psi, double ratio) const {
    return k >= window_ && psi > ratio * values_[(k - window_) % (window_ + 1)];
  }
  // Every slot to v (kInf: no comparison with what was recorded before can report stagnation).
  void Fill(double v) { values_.fill(v); }

 private:
  std::array<double, kMaxWindow + 1> values_{};
  int window_ = 10;
};

// False when the accepted point `to` equals `from` to rounding (every |to_i − from_i| ≤ 2ε|from_i|): the step length
// collapsed.
inline bool StepMoved(const Vector& from, const Vector& to) {
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  const int n = static_cast<int>(from.size());
  bool moved = false;
  for (int i = 0; i < n && !moved; ++i) moved = std::abs(to[i] - from[i]) > 2.0 * kEps * std::abs(from[i]);
  return moved;
}

// The iterates are declared divergent when their largest component (in the solver's units) reaches this bound or is
// not a number.
inline bool IterateBounded(double max_abs) { return max_abs < 1e100; }

// The iterate with the smallest stopping measure seen (the measure need not fall with the merit function): the
// point a failed solve returns.
struct BestIterate {
  double residual = kInf;
  Vector z;

  void Reset() { residual = kInf; }
  void Track(double measure, const Vector& x) {
    if (measure < residual) {
      residual = measure;
      z = x;
    }
  }
};

}  // namespace newton
}  // namespace smcbench

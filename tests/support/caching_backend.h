// A backend with a cache, as Siconos' mlcp_direct_* solvers have one, for tests of "cold means cold": lemke behind a
// cache of its last answer, which a repeat of the same q gets with 0 iterations. Header-only (the suites that use
// it link the solvers already).
#pragma once

#include <memory>

#include "solvers/core/session.h"
#include "solvers/core/solver.h"
#include "solvers/registry/registry.h"

namespace smcbench::test_support {

// lemke behind a cache of its last answer: a repeat of the same q is answered from it with 0 iterations, as Siconos'
// mlcp_direct_* answer from their active-set cache. ForgetWarmState drops the cache, or, for a backend made with
// can_forget false, reports that it cannot.
class CachingBackend final : public Solver {
 public:
  explicit CachingBackend(bool can_forget) : can_forget_(can_forget) {}
  const SolverInfo& info() const override {
    static const SolverInfo kInfo{"caching", "lemke behind a cache of its last answer", "none"};
    return kInfo;
  }
  WarmStateReset ForgetWarmState() override {
    if (!cached_) return WarmStateReset::kNothingRemembered;
    if (!can_forget_) return WarmStateReset::kCannotForget;
    cached_ = false;
    return WarmStateReset::kForgotten;
  }
  int answered_from_cache() const { return answered_from_cache_; }
  int solved_by_lemke() const { return solved_by_lemke_; }

 protected:
  void DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) override {
    if (cached_ && cached_q_ == problem.q()) {
      result->z = cached_z_;
      result->iterations = 0;
      result->status = SolveStatus::kSolved;
      ++answered_from_cache_;
      return;
    }
    lemke_->Solve(problem, options, &lemke_result_);
    result->z = lemke_result_.z;
    result->iterations = lemke_result_.iterations;
    result->status = lemke_result_.status;
    ++solved_by_lemke_;
    cached_ = lemke_result_.solved();
    cached_q_ = problem.q();
    cached_z_ = lemke_result_.z;
  }

 private:
  bool can_forget_;
  bool cached_ = false;
  Vector cached_q_, cached_z_;
  SolveResult lemke_result_;
  int answered_from_cache_ = 0, solved_by_lemke_ = 0;
  std::unique_ptr<Solver> lemke_ = CreateSolver("lemke");
};

}  // namespace smcbench::test_support

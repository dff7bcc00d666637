// Prepare once, solve many (the shape of OSQP's setup/solve/update): a time-stepper or a benchmark solves one
// problem's M, l, u again and again with a new q. The session checks the options and the backend's capability
// once, keeps its own copies, and on each call tries the previous answer's active set before the backend.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "solvers/core/options.h"
#include "solvers/core/problem.h"
#include "solvers/core/result.h"

namespace smcbench {

class Solver;

namespace internal {
// A session's remembered active set and the LU factors of its free block (solvers/core/active_set.h, not
// installed): defined in session.cc.
struct SessionFactors;
}  // namespace internal

// How a session may answer.
struct SessionOptions {
  // Warm active-set reuse: try the last solved answer's active set first (bound rows at their bound, the free block
  // solved with its stored LU factors), accept it when the merit function passes both tests of the verdict, else
  // call the backend. Off: every call goes to the backend (to time or study the backend's own algorithm). Never
  // for an external backend (SolverInfo::external: siconos-*), whose own warm behaviour is what is measured.
  bool reuse_active_set = true;
};

// What Solver::ForgetWarmState (and SolveSession::ForgetWarmState) found. Explicit values, append only.
enum class WarmStateReset : int {
  kNothingRemembered = 0,  // nothing learned from earlier solves was kept: the next solve starts cold anyway
  kForgotten = 1,          // something was kept (a cache, an active set, a chosen candidate) and is dropped now
  kCannotForget = 2,       // something is kept that the backend cannot drop: its next solve may start warm
};
// "nothing_remembered", "forgotten", "cannot_forget".
std::string_view ToString(WarmStateReset reset);
// The outcome of forgetting in several places (a session, its backend, a meta-backend's candidates): the least
// cold of them.
inline WarmStateReset LeastCold(WarmStateReset a, WarmStateReset b) {
  return static_cast<int>(a) >= static_cast<int>(b) ? a : b;
}

// Which path produced a session's answer: SolveResult detail "path" (read it with SessionPathOf).
enum class SessionPath : int {
  kBackend = 0,          // the backend's own algorithm (then the base's polish and merit function)
  kReusedActiveSet = 1,  // the previous answer's active set, re-solved for the new q; iterations = 0
};
// "backend", "reused_active_set" (the detail's text in JSON and Python).
std::string_view ToString(SessionPath path);
std::optional<SessionPath> SessionPathFromString(std::string_view name);
inline constexpr CodeDetail<SessionPath, 2> kSessionPathDetail{"path"};
// The path that answered, or nullopt for a result that did not come from a session.
inline std::optional<SessionPath> SessionPathOf(const SolveResult& result) { return kSessionPathDetail.Get(result); }

// A prepared solve of one problem (M, l, u fixed; q per call) by one backend. Made by Solver::Prepare; holds a
// pointer to the backend, which must outlive it. Not thread-safe (the backend is not). Movable.
//
// Guarantees of Solve are those of Solver::Solve: result->w = M z + q, residual_* is the merit function at z,
// status kSolved ⇒ residual_rel ≤ tolerance and residual_scaled ≤ tolerance. Options that fail validation, or a
// backend that cannot take the problem, give the same status and message on every call as Solver::Solve would.
class SolveSession {
 public:
  SolveSession(Solver* backend, const BoxMLCP& problem, const SolverOptions& options,
               const SessionOptions& session = {});
  ~SolveSession();
  SolveSession(SolveSession&&) noexcept;
  SolveSession& operator=(SolveSession&&) noexcept;

  // Solves with this q (size n, finite; else InvalidInputError naming q) into *result (storage reused: no
  // allocation after the first call, for every backend but ipopt and siconos-*). warm_start: the start point for
  // the backend (nullptr or empty: the options' warm start, else cold). Detail "path" = SessionPath.
  void Solve(const Eigen::Ref<const Vector>& q, SolveResult* result, const Vector* warm_start = nullptr);

  // Replaces the options and checks them again, keeping the prepared problem and the remembered active set (the
  // shape of OSQP's update_settings): a caller that runs the same problem again with other options. No allocation
  // when warm_start keeps its size.
  void set_options(const SolverOptions& options);

  // The next call starts as the first did: the remembered active set is dropped, and so is what the backend keeps
  // (Solver::ForgetWarmState), and the meta-backend it was chosen by. Not timed by anyone: a benchmark calls it
  // between timed cold solves. Returns the least cold outcome of the three.
  WarmStateReset ForgetWarmState();

  // The problem as last solved (q of the last call).
  const BoxMLCP& problem() const { return problem_; }
  const SolverOptions& options() const { return options_; }
  const SessionOptions& session_options() const { return session_; }
  // The backend that solves: the one given to Prepare, or its delegate (Solver::DelegateFor, e.g. auto's choice;
  // a call the delegate does not solve goes to the backend given to Prepare, whose rule — auto's fallbacks —
  // decides, and the delegate is asked for again after that call and after ForgetWarmState).
  Solver& backend() const { return *backend_; }
  // Calls answered by the reused active set, and in all.
  std::int64_t reused() const { return reused_; }
  std::int64_t calls() const { return calls_; }

 private:
  template <int N>
  void SolveFixed(const double* q, SolveResult* result);
  void SolveGeneral(SolveResult* result);
  // options_.warm_start ← the call's warm start, when it gave one.
  void TakeWarmStart();
  // The warm path; true when it answered (result filled, solved).
  template <int N>
  bool TryReusedActiveSet(SolveResult* result);
  // After the backend's call: the meta-backend's rule when the delegate did not solve, detail "path", and the
  // answer's active set for the next call.
  void ConcludeBackendCall(SolveResult* result);
  // After a solved answer from the backend: store its active set (natural map in units of z) and factor M_FF.
  void RememberActiveSet(const SolveResult& result);
  // Re-runs the checks Prepare made when the backend's options changed since (Solver::option_generation).
  void CheckBackendOptions();
  // backend_ = the delegate of the backend given to Prepare for these options (DelegateFor), or that backend.
  void ResolveDelegate(Solver* prepared);
  // After the meta-backend solved or forgot (meta_ set): backend_ = its delegate now, which a fallback or a
  // ForgetWarmState may have changed. No allocation once every candidate exists.
  void ReviseDelegate();

  Solver* backend_;
  // The backend given to Prepare when backend_ is its delegate (auto's choice), else null: a call the delegate does
  // not solve is handed to it, so its own rule (auto's fallback chain) still decides.
  Solver* meta_ = nullptr;
  std::string_view backend_name_;  // backend_->info().name, read once (a virtual call per solve otherwise)
  BoxMLCP problem_;
  SolverOptions options_;
  SessionOptions session_;
  std::uint64_t checked_generation_ = 0;
  const Vector* warm_start_ = nullptr;  // this call's, until the backend is called
  // The per-call part only (options, backend options, dense, capability checked): the fixed-size fast path.
  bool fast_ = false;
  // Dense with at most BoxMLCP::kSmallSize rows: the fixed-size path (SolveFixed) applies when fast_.
  bool small_dense_ = false;
  // The warm path applies: dense, at most kMaxReusedSize rows, reuse on, not an external backend
  // (SolverInfo::external).
  bool reuse_ = false;
  std::unique_ptr<internal::SessionFactors> factors_;  // made when reuse_ holds
  std::vector<signed char> state_;
  // factors_ as an affine map of q, for n ≤ BoxMLCP::kSmallSize (ActiveSetFactors::AffineMap).
  struct SmallMap {
    double A[BoxMLCP::kSmallSize * BoxMLCP::kSmallSize];
    double c[BoxMLCP::kSmallSize];
    int free_row = -1;
  };
  SmallMap small_{};
  std::int64_t reused_ = 0, calls_ = 0;

  // Dense problems up to this size get the warm path (its factorization is O(n³) on an active-set change).
  static constexpr int kMaxReusedSize = 512;
};

}  // namespace smcbench

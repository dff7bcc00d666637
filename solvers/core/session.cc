#include "solvers/core/session.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "solvers/core/active_set.h"
#include "solvers/core/solver.h"

namespace smcbench {

std::string_view ToString(WarmStateReset reset) {
  switch (reset) {
    case WarmStateReset::kNothingRemembered: return "nothing_remembered";
    case WarmStateReset::kForgotten: return "forgotten";
    case WarmStateReset::kCannotForget: return "cannot_forget";
  }
  return "unknown";
}

namespace internal {
struct SessionFactors : ActiveSetFactors {};
}  // namespace internal

SolveSession::SolveSession(Solver* backend, const BoxMLCP& problem, const SolverOptions& options,
                           const SessionOptions& session)
    : backend_(backend), problem_(problem), options_(options), session_(session) {
  ResolveDelegate(backend);
  const int n = problem_.size();
  small_dense_ = !problem_.is_sparse() && n <= BoxMLCP::kSmallSize;
  reuse_ = session_.reuse_active_set && !backend_->info().external && !problem_.is_sparse() && n <= kMaxReusedSize;
  if (reuse_) {
    factors_ = std::make_unique<internal::SessionFactors>();
    factors_->Resize(n);
    state_.assign(n, 0);
  }
  CheckBackendOptions();
}

SolveSession::~SolveSession() = default;
SolveSession::SolveSession(SolveSession&&) noexcept = default;
SolveSession& SolveSession::operator=(SolveSession&&) noexcept = default;

void SolveSession::ResolveDelegate(Solver* prepared) {
  meta_ = nullptr;
  backend_ = prepared;
  if (Solver* delegate = prepared->DelegateFor(problem_, options_)) {
    meta_ = prepared;
    backend_ = delegate;
  }
  backend_name_ = backend_->info().name;
}

void SolveSession::ReviseDelegate() {
  Solver* delegate = meta_->DelegateFor(problem_, options_);
  if (delegate == nullptr || delegate == backend_) return;
  backend_ = delegate;
  backend_name_ = backend_->info().name;
  CheckBackendOptions();
}

void SolveSession::set_options(const SolverOptions& options) {
  options_ = options;
  ResolveDelegate(meta_ != nullptr ? meta_ : backend_);
  CheckBackendOptions();
}

WarmStateReset SolveSession::ForgetWarmState() {
  WarmStateReset reset = WarmStateReset::kNothingRemembered;
  if (factors_ && factors_->valid()) {
    factors_->Invalidate();
    reset = WarmStateReset::kForgotten;
  }
  reset = LeastCold(reset, backend_->ForgetWarmState());
  if (meta_ != nullptr) {
    reset = LeastCold(reset, meta_->ForgetWarmState());
    // The meta-backend forgot what a fallback taught it: its delegate is the rule's first choice again.
    ReviseDelegate();
  }
  return reset;
}

void SolveSession::CheckBackendOptions() {
  checked_generation_ = backend_->option_generation();
  fast_ = backend_->ChecksPass(problem_, options_);
}

void SolveSession::Solve(const Eigen::Ref<const Vector>& q, SolveResult* result, const Vector* warm_start) {
  if (checked_generation_ != backend_->option_generation()) CheckBackendOptions();
  ++calls_;
  // The warm start is copied into the options only when the backend is called (the reused active set needs none).
  warm_start_ = warm_start;
  if (fast_ && small_dense_ && q.size() == problem_.size()) {
    switch (problem_.size()) {
      case 1: return SolveFixed<1>(q.data(), result);
      case 2: return SolveFixed<2>(q.data(), result);
      case 3: return SolveFixed<3>(q.data(), result);
      case 4: return SolveFixed<4>(q.data(), result);
      default: break;
    }
  }
  problem_.set_q(q);  // throws for a wrong size or a non-finite entry
  SolveGeneral(result);
}

template <int N>
void SolveSession::SolveFixed(const double* q, SolveResult* result) {
  problem_.set_q<N>(q);
  if (reuse_ && factors_->valid() && TryReusedActiveSet<N>(result)) return;
  TakeWarmStart();
  backend_->SolveValidated<N>(problem_, options_, result);
  ConcludeBackendCall(result);
}

void SolveSession::SolveGeneral(SolveResult* result) {
  if (fast_ && reuse_ && factors_->valid() && TryReusedActiveSet<0>(result)) return;
  TakeWarmStart();
  backend_->Solve(problem_, options_, result);
  ConcludeBackendCall(result);
}

void SolveSession::TakeWarmStart() {
  if (warm_start_ == nullptr) return;
  const Vector& from = *warm_start_;
  Vector& to = options_.warm_start;
  if (to.size() != from.size()) to.resize(from.size());
  // Plain loop: Eigen's dynamic-size assignment is an out-of-line call costing more than n ≤ 4 copies.
  for (Eigen::Index i = 0; i < from.size(); ++i) to[i] = from[i];
}

template <int N>
bool SolveSession::TryReusedActiveSet(SolveResult* result) {
  using Clock = std::chrono::steady_clock;
  const auto start = options_.measure_time ? Clock::now() : Clock::time_point{};
  const int n = problem_.size();
  result->Reset();
  result->solver = backend_name_;
  if (result->z.size() != n) result->z.resize(n);
  if (result->w.size() != n) result->w.resize(n);
  const double *q = problem_.q().data(), *l = problem_.l().data(), *u = problem_.u().data();
  double* z = result->z.data();
  const DenseMatrix& M = problem_.dense_matrix();
  if constexpr (N > 0) {
    // z = A q + c; a single free row by one division, as the polish computes it (same bits).
    const SmallMap& map = small_;
    bool inside = true;
    for (int i = 0; i < N; ++i) {
      double zi = map.c[i];
      for (int j = 0; j < N; ++j) zi += map.A[i + j * N] * q[j];
      z[i] = zi;
    }
    if (map.free_row >= 0) {
      const int f = map.free_row;
      const double* m = M.data();
      double b = -q[f];
      for (int j = 0; j < N; ++j) b -= j == f ? 0.0 : m[f + j * N] * z[j];
      z[f] = b / m[f + f * N];
    }
    for (int i = 0; i < N; ++i) inside = inside && z[i] >= l[i] && z[i] <= u[i];
    if (!inside) return false;
  } else {
    if (!factors_->Solve<0>(M, q, l, u, z)) return false;
  }
  Residual r;
  if constexpr (N > 0) {
    r = problem_.template NaturalResidualFixed<N>(result->z, &result->w);
  } else {
    r = problem_.NaturalResidual(result->z, &result->w);
  }
  // The sign check of the active set, exact: a bound row's F = M z + q must push against its bound (≥ 0 at the
  // lower, ≤ 0 at the upper). The merit function alone would accept a wrong sign of rounding size, i.e. keep a row
  // at its bound whose exact solution has just left it (s = x/h = 1 − ε on the sliding surface, not 1).
  if (!active_set::BoundRowSignsHold<N>(n, factors_->state(), result->w.data(), l, u, 0.0)) return false;
  // The verdict's two tests, as Solver::Finish applies them to every backend's answer.
  if (!PassesBoxMlcpTolerance(r, options_.tolerance)) return false;
  result->status = SolveStatus::kSolved;
  result->residual_abs = r.abs;
  result->residual_rel = r.rel;
  result->residual_scaled = r.scaled;
  kSessionPathDetail.Set(result, SessionPath::kReusedActiveSet);
  if (options_.measure_time) result->solve_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  ++reused_;
  return true;
}

void SolveSession::ConcludeBackendCall(SolveResult* result) {
  // The delegate's answer is final (a proof, a spent budget) or the meta-backend's chain goes on after it.
  if (meta_ != nullptr && !result->solved() && !meta_->NoteDelegateFailure(problem_, *backend_, result)) {
    meta_->Solve(problem_, options_, result);
    // The meta-backend's chain may have learned a better first choice for this matrix (auto: the candidate that
    // answered): later calls go to it, so a delegate that fails on this matrix fails once, not on every call.
    ReviseDelegate();
  }
  kSessionPathDetail.Set(result, SessionPath::kBackend);
  if (reuse_ && result->solved()) RememberActiveSet(*result);
}

void SolveSession::RememberActiveSet(const SolveResult& result) {
  const int n = problem_.size();
  if (result.z.size() != n || result.w.size() != n) return;
  const double *z = result.z.data(), *w = result.w.data(), *inv_d = problem_.inv_row_scale().data();
  const double *l = problem_.l().data(), *u = problem_.u().data();
  bool same = factors_->valid();
  const signed char* known = factors_->state();
  for (int i = 0; i < n; ++i) {
    // In units of z (the equilibrated w), as the polish classifies rows.
    state_[i] = static_cast<signed char>(ClassifyRow(z[i], w[i] * inv_d[i], l[i], u[i]));
    same = same && state_[i] == known[i];
  }
  if (same) return;
  if (factors_->Factor(problem_.dense_matrix(), state_.data()) && n <= BoxMLCP::kSmallSize) {
    factors_->AffineMap(problem_.dense_matrix(), l, u, small_.A, small_.c, &small_.free_row);
  }
}

std::string_view ToString(SessionPath path) {
  switch (path) {
    case SessionPath::kBackend: return "backend";
    case SessionPath::kReusedActiveSet: return "reused_active_set";
  }
  return "unknown";
}

std::optional<SessionPath> SessionPathFromString(std::string_view name) {
  for (const SessionPath path : {SessionPath::kBackend, SessionPath::kReusedActiveSet}) {
    if (ToString(path) == name) return path;
  }
  return std::nullopt;
}

}  // namespace smcbench

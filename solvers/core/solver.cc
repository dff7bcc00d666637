#include "solvers/core/solver.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <memory>
#include <sstream>
#include <string>

#include "solvers/core/mcp_merit.h"
#include "solvers/core/polish.h"

namespace smcbench {

namespace internal {
struct SolverWorkspace {
  PolishWorkspace polish;
  McpMeritWorkspace mcp_merit;
};
}  // namespace internal

Solver::Solver() = default;
Solver::~Solver() = default;

bool Solver::RejectOptions(int n, const SolverOptions& options, SolveResult* result) {
  std::string why;
  if (options.IsValid(&why) && ValidateBackendOptions(&why)) {
    why = "warm_start has size " + std::to_string(options.warm_start.size()) + " but the problem has " +
          std::to_string(n) + " unknowns";
  }
  result->status = SolveStatus::kInvalidOptions;
  result->message = std::move(why);
  result->z.setZero();
  return false;
}

namespace {
// BeginSolve's rare branch, out of line: the start lay outside [l, u] and result->z holds its projection. Says how
// far it was moved (details start_projected and start_projection_distance, docs/problem.md).
[[gnu::noinline]] void NoteProjectedStart(const Vector& start, SolveResult* result) {
  int moved = 0;
  double distance = 0.0;
  for (Eigen::Index i = 0; i < start.size(); ++i) {
    const double d = std::abs(start[i] - result->z[i]);
    if (d > 0.0) ++moved;
    distance = std::max(distance, d);
  }
  result->SetDetail("start_projected", moved);
  result->SetDetail("start_projection_distance", distance);
}
}  // namespace

// Inlined into the Solve()s: a call boundary costs as much as the work for the paper's m = 1, 2 problems. Every
// check of SolverOptions::IsValid and ValidateBackendOptions runs on every call (kCheckOptions; a session made
// them in Prepare); only the messages are built out of line (RejectOptions), and the warm start's
// size and finiteness are tested while it is copied.
template <int N, bool kCheckOptions>
[[gnu::always_inline]] inline bool Solver::BeginSolve(int n_runtime, const Vector& l, const Vector& u,
                                                   const SolverOptions& options, std::string_view name,
                                                   SolveResult* result) {
  const int n = N > 0 ? N : n_runtime;
  polish_redundant_ = false;
  result->Reset();
  result->solver = name;
  if (result->z.size() != n) result->z.resize(n);
  if (result->w.size() != n) result->w.resize(n);
  const Eigen::Index warm_size = options.warm_start.size();
  double* z = result->z.data();
  bool ok = !kCheckOptions || options.ScalarsValid();
  if (warm_size == n) {
    // Plain loop: Eigen's dynamic-size assignment is an out-of-line call costing more than n ≤ 4 copies. The start
    // is projected onto [l, u] here, for every backend (docs/problem.md, "Starts outside the box").
    const double* ws = options.warm_start.data();
    const double* lo = l.data();
    const double* hi = u.data();
    double probe = 0.0;  // x − x is 0 exactly for finite x, NaN for NaN and ±∞
    bool moved = false;
    for (int i = 0; i < n; ++i) {
      const double v = ws[i];
      const double p = std::min(std::max(v, lo[i]), hi[i]);
      z[i] = p;
      moved |= p != v;
      probe += v - v;
    }
    ok = ok && probe == 0.0;
    if (moved && ok) NoteProjectedStart(options.warm_start, result);
  } else if (warm_size == 0) {
    for (int i = 0; i < n; ++i) z[i] = std::min(std::max(0.0, l[i]), u[i]);
  } else {
    ok = false;
  }
  std::string why;  // written only on failure
  if (!ok || (kCheckOptions && !ValidateBackendOptions(&why))) return RejectOptions(n, options, result);
  StartDeadline(options.time_limit_seconds);
  return true;
}

const BoxMLCP& Solver::EquilibratedFor(const BoxMLCP& problem) {
  // matrix_id names M, and copies keep it along with l and u (which have no setters): one id, one (M, l, u).
  if (equilibrated_source_ != problem.matrix_id()) {
    equilibrated_.reset();  // a throw below (out of memory) must not leave a stale copy under a new id
    equilibrated_source_ = 0;
    equilibrated_.emplace(problem.Equilibrated());
    equilibrated_source_ = problem.matrix_id();
  } else {
    equilibrated_->AssignEquilibratedQ(problem);
  }
  return *equilibrated_;
}

namespace {
// Statuses whose z is the backend's answer or its last iterate on the way to one: the polish may replace z, and a
// passing polished z makes a short stop (iteration or time limit, stall) solved. A refusal, a crash or a claim that
// there is no solution (numerical failure, ray, infeasible, ...) is left as the backend said it: the base does not
// solve problems on a backend's behalf.
bool Polishable(SolveStatus status) {
  return status == SolveStatus::kSolved || status == SolveStatus::kIterationLimit ||
         status == SolveStatus::kTimeLimit || status == SolveStatus::kStalled;
}

// A short stop whose point passes the tolerance is a success (the polish made it so, or it already was).
void UpgradeShortStop(double tolerance, const Residual& r, SolveResult* result) {
  if (result->status != SolveStatus::kSolved && PassesBoxMlcpTolerance(r, tolerance)) {
    result->status = SolveStatus::kSolved;
    result->message.clear();
  }
}
}  // namespace

template <int N>
[[gnu::always_inline]] inline void Solver::Polish(const BoxMLCP& problem, double tolerance, Residual* r,
                                                  SolveResult* result) {
  const int n = problem.size();
  const BoxMLCP& equilibrated = *equilibrated_;
  if (polish_z_.size() != n) polish_z_.resize(n);
  if (polish_w_.size() != n) polish_w_.resize(n);
  Residual candidate;
  if constexpr (N > 0) {
    double block[N * N], rhs[N];
    signed char state[N];
    int free_rows[N], pivots[N];
    if (!PolishDense<N>(equilibrated, result->z.data(), polish_z_.data(), {block, rhs, state, free_rows, pivots})) {
      return;
    }
    candidate = problem.template NaturalResidualFixed<N>(polish_z_, &polish_w_);
  } else {
    if (equilibrated.is_sparse()) {
      if (!PolishSparse(equilibrated, result->z, &polish_z_)) return;
    } else {
      if (n > kMaxPolishDenseSize) return;
      if (!workspace_) workspace_ = std::make_unique<internal::SolverWorkspace>();
      if (!PolishDense<0>(equilibrated, result->z.data(), polish_z_.data(), workspace_->polish.For(n))) return;
    }
    candidate = problem.NaturalResidual(polish_z_, &polish_w_);
  }
  // Not worse in units of z, and not pushing the unscaled test over the line.
  if (!(candidate.scaled <= r->scaled) || !(candidate.rel <= std::max(r->rel, tolerance))) return;
  result->z.swap(polish_z_);
  result->w.swap(polish_w_);
  *r = candidate;
  result->SetDetail("polished", 1.0);
  UpgradeShortStop(tolerance, *r, result);
}

// After DoSolve (or a refusal): the merit function at the returned z, the polish, then Finish. The fixed-size
// merit function needs z and w of size N; a backend that resized them gets the generic one.
template <int N>
[[gnu::always_inline]] inline void Solver::Conclude(const BoxMLCP& problem, const SolverOptions& options,
                                                    std::chrono::steady_clock::time_point start,
                                                    SolveResult* result) {
  const bool fixed = N > 0 && result->z.size() == N && result->w.size() == N;
  constexpr int kFixedN = N > 0 ? N : 1;
  Residual r = fixed ? problem.template NaturalResidualFixed<kFixedN>(result->z, &result->w)
                     : problem.NaturalResidual(result->z, &result->w);
  // A zero residual cannot be improved; an infinite one is a z with NaN/Inf (nothing to start from); a backend's
  // exact answer of the set the polish would solve (NotePolishRedundant) that passes is not solved again.
  const bool redundant = polish_redundant_;
  polish_redundant_ = false;
  if (options.polish && Polishable(result->status) && equilibrated_ &&
      equilibrated_source_ == problem.matrix_id() && result->z.size() == problem.size()) {
    if (r.abs == 0.0) {
      UpgradeShortStop(options.tolerance, r, result);
    } else if (redundant && PassesBoxMlcpTolerance(r, options.tolerance)) {
      // Nothing to do: the status is the backend's and stands (Finish applies the rule).
    } else if (r.abs < kInf) {
      if (fixed) {
        Polish<kFixedN>(problem, options.tolerance, &r, result);
      } else {
        Polish<0>(problem, options.tolerance, &r, result);
      }
    }
  }
  result->residual_abs = r.abs;
  result->residual_rel = r.rel;
  result->residual_scaled = r.scaled;
  Finish(options.tolerance, start, result);
}

namespace {
// Finish's rare branch, out of line so the common path does not set up a stream.
[[gnu::noinline]] void Downgrade(double tolerance, SolveResult* result) {
  std::ostringstream s;
  s << "backend reported success but the natural residual is ";
  if (!(result->residual_rel <= tolerance)) {
    s << result->residual_rel << " (relative) > " << tolerance;
  } else {
    s << result->residual_scaled << " in the row-equilibrated problem (units of z) > " << tolerance;
  }
  result->status = SolveStatus::kInaccurate;
  result->message = s.str();
}
}  // namespace

namespace {
// The end of every solve, box or MCP: a backend that set no status failed; the wall time.
[[gnu::always_inline]] inline void StampEnd(std::chrono::steady_clock::time_point start, SolveResult* result) {
  using Clock = std::chrono::steady_clock;
  if (result->status == SolveStatus::kNotRun) {
    result->status = SolveStatus::kNumericalFailure;
    result->message = "backend returned without setting a status";
  }
  result->solve_seconds = start == Clock::time_point{} ? 0.0 : std::chrono::duration<double>(Clock::now() - start).count();
}
}  // namespace

void Solver::Finish(double tolerance, std::chrono::steady_clock::time_point start, SolveResult* result) {
  // The rule: the merit function, not the backend, decides what "solved" means.
  if (result->status == SolveStatus::kSolved && !PassesBoxMlcpTolerance(result->residual(), tolerance)) {
    Downgrade(tolerance, result);
  }
  StampEnd(start, result);
}

namespace {
std::chrono::steady_clock::time_point StartClock(const SolverOptions& options) {
  return options.measure_time ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
}
}  // namespace

void Solver::Solve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) {
  const SolverInfo& solver_info = info();
  if (solver_info.delegates) return SolveDelegated(problem, options, result);
  // One size dispatch for the whole shared path: the paper's one-step problems have m = 1, 2.
  if (!problem.is_sparse()) {
    switch (problem.size()) {
      case 1: return SolveBox<1>(problem, options, solver_info, result);
      case 2: return SolveBox<2>(problem, options, solver_info, result);
      case 3: return SolveBox<3>(problem, options, solver_info, result);
      case 4: return SolveBox<4>(problem, options, solver_info, result);
      default: break;
    }
  }
  SolveBox<0>(problem, options, solver_info, result);
}

void Solver::SolveDelegated(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) {
  const auto start = StartClock(options);
  if (options.warm_start.size() == 0 && options.ScalarsValid()) {
    // Valid options and no warm start: the delegate's Solve does every shared step (the result's reset and start
    // point, the checks of the same options, the merit function and the rule for "solved" at the same tolerance),
    // so none is done twice here; only the meta-backend's own options are checked, and the call timed. Anything
    // else (a warm start, options to refuse) takes the full path below.
    std::string why;  // written only on failure
    if (ValidateBackendOptions(&why)) {
      DoSolve(problem, options, result);
      return StampEnd(start, result);
    }
  }
  if (BeginSolve<0, true>(problem.size(), problem.l(), problem.u(), options, info().name, result)) {
    DoSolve(problem, options, result);  // the delegate's Solve did the shared work: keep its residuals
    return Finish(options.tolerance, start, result);
  }
  Conclude<0>(problem, options, start, result);  // refused: the merit function at the start point, as any backend
}

template <int N>
void Solver::SolveBox(const BoxMLCP& problem, const SolverOptions& options, const SolverInfo& solver_info,
                      SolveResult* result) {
  static_assert(N <= BoxMLCP::kSmallSize);
  const auto start = StartClock(options);
  if (BeginSolve<N, true>(problem.size(), problem.l(), problem.u(), options, solver_info.name, result)) {
    const BoxMLCP& equilibrated = EquilibratedFixed<N>(problem);
    const BoxMLCP& given = solver_info.equilibrate ? equilibrated : problem;
    if (problem.is_sparse() && !solver_info.sparse) {
      // A dense-only backend gets a dense copy (allocates per solve; sparse inputs are not its hot path),
      // unless the copy would be unreasonably large.
      if (problem.size() > kMaxDensifiedSize) {
        result->status = SolveStatus::kNotApplicable;
        result->message = "backend accepts dense M only and n = " + std::to_string(problem.size()) + " > " +
                          std::to_string(kMaxDensifiedSize) + " is too large to densify";
      } else {
        const BoxMLCP dense(given.ToDense(), given.q(), given.l(), given.u(), given.name());
        DoSolve(dense, options, result);
        result->SetDetail("densified", 1.0);
      }
    } else if (solver_info.symmetric_only && !problem.IsSymmetric()) {
      result->status = SolveStatus::kNotApplicable;
      result->message = "backend requires symmetric M";
    } else {
      DoSolve(given, options, result);
    }
  }
  Conclude<N>(problem, options, start, result);
}

bool Solver::ChecksPass(const BoxMLCP& problem, const SolverOptions& options) const {
  std::string why;
  if (!options.IsValid(&why) || !ValidateBackendOptions(&why)) return false;
  const SolverInfo& solver_info = info();
  if (problem.is_sparse() ? !solver_info.sparse : !solver_info.dense) return false;
  return !solver_info.symmetric_only || problem.IsSymmetric();
}

template <int N>
void Solver::SolveValidated(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) {
  static_assert(N >= 1 && N <= BoxMLCP::kSmallSize);
  const auto start = StartClock(options);
  if (BeginSolve<N, false>(N, problem.l(), problem.u(), options, info().name, result)) {
    const BoxMLCP& equilibrated = EquilibratedFixed<N>(problem);
    DoSolve(info().equilibrate ? equilibrated : problem, options, result);
  }
  Conclude<N>(problem, options, start, result);
}

template void Solver::SolveValidated<1>(const BoxMLCP&, const SolverOptions&, SolveResult*);
template void Solver::SolveValidated<2>(const BoxMLCP&, const SolverOptions&, SolveResult*);
template void Solver::SolveValidated<3>(const BoxMLCP&, const SolverOptions&, SolveResult*);
template void Solver::SolveValidated<4>(const BoxMLCP&, const SolverOptions&, SolveResult*);

SolveSession Solver::Prepare(const BoxMLCP& problem, const SolverOptions& options, const SessionOptions& session) {
  return SolveSession(this, problem, options, session);
}

namespace {
// F and its Jacobian are the caller's code. The exceptions C++ code throws when an evaluation fails
// (std::runtime_error, std::logic_error) end the solve with a status and *why; InvalidInputError (bad input, an error
// naming the field, never a status) and exceptions of any other type (a host language's own, such as a Python
// exception raised in a callback, which its binding re-raises as itself) reach the caller unchanged.
template <typename Body>
bool EvaluationSucceeds(Body&& body, const char* context, std::string* why) {
  try {
    body();
    return true;
  } catch (const InvalidInputError&) {
    throw;
  } catch (const std::runtime_error& e) {
    *why = std::string(context) + e.what();
  } catch (const std::logic_error& e) {
    *why = std::string(context) + e.what();
  }
  return false;
}
}  // namespace

void Solver::Solve(const MCP& problem, const SolverOptions& options, SolveResult* result) {
  const auto start = StartClock(options);
  const SolverInfo& solver_info = info();
  if (BeginSolve<0, true>(problem.size(), problem.l(), problem.u(), options, solver_info.name, result)) {
    if (!solver_info.mcp) {
      result->status = SolveStatus::kNotApplicable;
      result->message = "backend does not solve nonlinear MCPs";
    } else {
      std::string why;  // written only on failure
      if (!EvaluationSucceeds([&] { DoSolveMCP(problem, options, result); },
                              "the solve stopped on an exception from F, its Jacobian or the backend: ", &why)) {
        result->status = SolveStatus::kNumericalFailure;
        result->message = std::move(why);
      }
    }
  }
  ConcludeMcp(problem, options, !solver_info.delegates || !solver_info.mcp, start, result);
}

namespace {
// Statuses that say the backend did not run on the problem: they keep their own reason even when the merit
// function cannot be evaluated at the returned z.
bool NothingRan(SolveStatus status) {
  return status == SolveStatus::kNotApplicable || status == SolveStatus::kInvalidOptions ||
         status == SolveStatus::kSizeLimit;
}
}  // namespace

void Solver::ConcludeMcp(const MCP& problem, const SolverOptions& options, bool recompute,
                         std::chrono::steady_clock::time_point start, SolveResult* result) {
  const double tolerance = options.tolerance;
  if (recompute) {
    std::string why;  // written only when the merit function cannot be evaluated
    Residual r;
    if (!workspace_) workspace_ = std::make_unique<internal::SolverWorkspace>();
    if (!internal::McpMerit(problem, result->z, &result->w, &workspace_->mcp_merit, &r, &why) &&
        !NothingRan(result->status)) {
      result->status = SolveStatus::kNumericalFailure;
      result->message = result->message.empty() ? why : why + " (backend: " + result->message + ")";
    }
    result->residual_abs = r.abs;
    result->residual_rel = r.rel;
    result->residual_scaled = r.scaled;
  }
  // The MCP rule: the scale-free residual decides; residual_rel does not (it is not invariant under row scaling).
  if (result->status == SolveStatus::kSolved && !PassesMcpTolerance(result->residual(), tolerance)) {
    std::ostringstream s;
    s << "backend reported success but the scale-free residual (rows divided by the Jacobian's row scales at z, in "
         "units of z) is "
      << result->residual_scaled << " > " << tolerance;
    result->status = SolveStatus::kInaccurate;
    result->message = s.str();
  }
  StampEnd(start, result);
}

SolveResult Solver::Solve(const BoxMLCP& problem, const SolverOptions& options) {
  SolveResult result;
  Solve(problem, options, &result);
  return result;
}

SolveResult Solver::Solve(const MCP& problem, const SolverOptions& options) {
  SolveResult result;
  Solve(problem, options, &result);
  return result;
}

void Solver::DoSolveMCP(const MCP&, const SolverOptions&, SolveResult* result) {
  result->status = SolveStatus::kNotApplicable;
  result->message = "backend does not solve nonlinear MCPs";
}

bool internal::McpMerit(const MCP& problem, const Vector& z, Vector* F, McpMeritWorkspace* workspace, Residual* r,
                        std::string* why) {
  const Eigen::Index n = problem.size();
  *r = Residual{};
  McpMeritWorkspace& ws = *workspace;
  if (F->size() != n) F->resize(n);
  if (ws.scale_point.size() != n) ws.scale_point.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) ws.scale_point[i] = std::min(std::max(0.0, problem.l()[i]), problem.u()[i]);
  if (z.size() != n) {
    *why = "z has size " + std::to_string(z.size()) + " but the problem has " + std::to_string(n) + " unknowns";
    return false;
  }
  bool jacobian_ok = true;
  const bool evaluated = EvaluationSucceeds(
      [&] {
        problem.Evaluate(ws.scale_point, F);
        const double scale = 1.0 + F->cwiseAbs().maxCoeff();
        problem.Evaluate(z, F);
        r->abs = NaturalResidualNorm(z, *F, problem.l(), problem.u());
        r->rel = r->abs / (std::isfinite(scale) ? scale : 1.0);
        if (!(r->abs < kInf)) return;
        const auto wrong_size = [&](Eigen::Index rows, Eigen::Index cols) {
          *why = "the Jacobian at z is " + std::to_string(rows) + "x" + std::to_string(cols) + ", expected " +
                 std::to_string(n) + "x" + std::to_string(n);
          jacobian_ok = false;
        };
        if (problem.jacobian_kind() == MCP::JacobianKind::kSparse) {
          problem.JacobianSparse(z, &ws.jacobian_sparse);
          if (ws.jacobian_sparse.rows() != n || ws.jacobian_sparse.cols() != n) {
            return wrong_size(ws.jacobian_sparse.rows(), ws.jacobian_sparse.cols());
          }
          McpRowScales(ws.jacobian_sparse, problem.variable_scale(), &ws.row_scale);
        } else {
          if (ws.jacobian_dense.rows() != n || ws.jacobian_dense.cols() != n) ws.jacobian_dense.resize(n, n);
          problem.JacobianDense(z, &ws.jacobian_dense);
          if (ws.jacobian_dense.rows() != n || ws.jacobian_dense.cols() != n) {
            return wrong_size(ws.jacobian_dense.rows(), ws.jacobian_dense.cols());
          }
          McpRowScales(ws.jacobian_dense, problem.variable_scale(), &ws.row_scale);
        }
        r->scaled = McpScaledResidual(z, *F, problem.l(), problem.u(), ws.row_scale, problem.variable_scale());
      },
      "F or its Jacobian threw at z: ", why);
  if (!evaluated) r->scaled = kInf;
  return evaluated && jacobian_ok;
}

void Solver::BindOptions(OptionBinder*) {}

bool Solver::ValidateBackendOptions(std::string*) const { return true; }

bool Solver::SetOption(std::string_view name, std::string_view value, std::string* error) {
  ++option_generation_;  // sessions checked the old values
  OptionBinder binder;
  BindOptions(&binder);
  const std::string previous = binder.ValueText(name);
  if (!binder.Set(name, value, error)) return false;
  std::string why;
  if (!ValidateBackendOptions(&why)) {
    // A rejected value is never kept: the backend stays exactly as it was.
    std::string ignored;
    binder.Set(name, previous, &ignored);
    *error = "invalid value for option '" + std::string(name) + "': " + why;
    return false;
  }
  return true;
}

std::string Solver::OptionsHelp() {
  OptionBinder binder;
  BindOptions(&binder);
  return binder.Help();
}

bool Solver::TimeLimitReached() const {
  return has_deadline_ && std::chrono::steady_clock::now() >= deadline_;
}

}  // namespace smcbench

// PSOR backend: projected SOR sweeps with an incrementally maintained w = M z + q (see psor_solver.h for the
// method, its convergence theory and the safeguards).
//
// The problem arrives row-equilibrated (Solver's base: rows divided by max_j |M_ij|). The sweep itself does not
// notice (z_i − ω w_i / M_ii is invariant under row scaling); the stopping test is the base's verdict applied to
// that problem: its natural residual r (in units of z) relative to 1 + ‖z‖∞ (Residual::scaled) and to 1 + ‖q‖∞
// (Residual::rel), i.e. r ≤ tol·(1 + min(‖z‖∞, ‖q‖∞)). So a sweep stops neither before the answer is right in z
// (1 + ‖q‖∞ alone lets wrong points pass when M is small, see docs/verdict.md) nor at a runaway z (1 + ‖z‖∞ alone
// would), and not long after the verdict would accept it.
#include "solvers/psor/psor_solver.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <type_traits>
#include <vector>

#include "solvers/core/active_set.h"
#include "solvers/core/polish.h"

namespace smcbench {
namespace {

// Column access to a dense column-major M with compile-time size N (Eigen::Dynamic for general n). Fixed N
// lets Eigen unroll the column update completely for the tiny problems where call overhead dominates.
template <int N>
class DenseColumns {
 public:
  using Mat = Eigen::Matrix<double, N, N>;
  using Vec = Eigen::Matrix<double, N, 1>;

  explicit DenseColumns(const DenseMatrix& M)
      : M_(M.data(), M.rows(), M.cols()), n_(static_cast<int>(M.rows())) {}

  int size() const { return N > 0 ? N : n_; }
  double Diagonal(int j) const { return M_(j, j); }
  double MaxAbs() const { return M_.cwiseAbs().maxCoeff(); }
  // w += a · M(:,j): contiguous in column-major storage.
  void Axpy(int j, double a, double* w) const { Eigen::Map<Vec>(w, size()) += a * M_.col(j); }
  // w = M z + q, exactly (no incremental history).
  void Affine(const double* z, const double* q, double* w) const {
    Eigen::Map<Vec> wv(w, size());
    wv.noalias() = M_ * Eigen::Map<const Vec>(z, size());
    wv += Eigen::Map<const Vec>(q, size());
  }

 private:
  Eigen::Map<const Mat> M_;
  int n_;
};

// Column access to a CSC sparse M: a column update touches only the column's nonzeros, so neither a row-major
// copy nor any per-problem cache is needed. Works on compressed and uncompressed storage.
class SparseColumns {
 public:
  explicit SparseColumns(const SparseMatrix& M)
      : outer_(M.outerIndexPtr()),
        inner_nnz_(M.innerNonZeroPtr()),
        inner_(M.innerIndexPtr()),
        values_(M.valuePtr()),
        n_(static_cast<int>(M.cols())) {}

  int size() const { return n_; }
  double Diagonal(int j) const {
    double d = 0.0;  // a structurally missing diagonal is a zero diagonal
    for (int p = Begin(j), e = End(j); p < e; ++p) {
      if (inner_[p] == j) d += values_[p];  // sums duplicates, should uncompressed storage hold any
    }
    return d;
  }
  double MaxAbs() const {
    double m = 0.0;
    for (int j = 0; j < n_; ++j) {
      for (int p = Begin(j), e = End(j); p < e; ++p) m = std::max(m, std::abs(values_[p]));
    }
    return m;
  }
  void Axpy(int j, double a, double* w) const {
    for (int p = Begin(j), e = End(j); p < e; ++p) w[inner_[p]] += a * values_[p];
  }
  void Affine(const double* z, const double* q, double* w) const {
    std::copy(q, q + n_, w);
    for (int j = 0; j < n_; ++j) {
      if (z[j] != 0.0) Axpy(j, z[j], w);
    }
  }

 private:
  int Begin(int j) const { return outer_[j]; }
  int End(int j) const { return inner_nnz_ ? outer_[j] + inner_nnz_[j] : outer_[j + 1]; }

  const int* outer_;
  const int* inner_nnz_;
  const int* inner_;
  const double* values_;
  int n_;
};

inline double Clamp(double x, double lo, double hi) { return std::min(std::max(x, lo), hi); }

// One pass over the iterate: the natural residual ‖z − Π(z − w)‖∞ (as NaturalResidualNorm computes it),
// ‖z‖∞ for the divergence test and the relative residual, and whether every z_i, w_i is finite.
struct Merit {
  double residual = 0.0;
  double z_norm = 0.0;
  bool finite = true;
  // The stopping measure (file comment): residual / (1 + min(‖z‖∞, ‖q‖∞)), both residuals of the base's verdict.
  double relative(double q_norm) const { return residual / (1.0 + std::min(z_norm, q_norm)); }
};

// Always inlined: with the backward and symmetric sweeps' instantiations GCC would otherwise call it out of line,
// which cost the m ≤ 4 forward path some 8 % of its instructions (the perf gate).
[[gnu::always_inline]] inline Merit EvaluateMerit(int n, const double* z, const double* w, const double* l, const double* u) {
  Merit m;
  double nan_probe = 0.0;  // x − x is 0 for finite x and NaN for ±∞ or NaN: one branch-free test for all
  for (int i = 0; i < n; ++i) {
    m.residual = std::max(m.residual, std::abs(z[i] - Clamp(z[i] - w[i], l[i], u[i])));
    m.z_norm = std::max(m.z_norm, std::abs(z[i]));
    nan_probe += (z[i] - z[i]) + (w[i] - w[i]);
  }
  m.finite = nan_probe == 0.0;
  return m;
}

// The active set the natural map reads off (z, w) in the same pass (the subspace step's trigger): each row as the
// polish classifies it (ClassifyRow: z_i − w_i at or below l_i, at or above u_i, or inside) stored in pattern as −1,
// +1 or 0; *changed counts the entries that differ from what pattern held, *inside the rows inside.
inline Merit EvaluateMeritAndPattern(int n, const double* z, const double* w, const double* l, const double* u,
                                     signed char* pattern, int* changed, int* inside) {
  Merit m;
  double nan_probe = 0.0;
  int changes = 0, free_rows = 0;
  for (int i = 0; i < n; ++i) {
    const double t = z[i] - w[i];
    m.residual = std::max(m.residual, std::abs(z[i] - Clamp(t, l[i], u[i])));
    m.z_norm = std::max(m.z_norm, std::abs(z[i]));
    nan_probe += (z[i] - z[i]) + (w[i] - w[i]);
    const int now = static_cast<int>(t >= u[i]) - static_cast<int>(t <= l[i]);  // branch-free: 1, −1 or 0
    changes += static_cast<int>(now != pattern[i]);
    free_rows += static_cast<int>(now == 0);
    pattern[i] = static_cast<signed char>(now);
  }
  m.finite = nan_probe == 0.0;
  *changed = changes;
  *inside = free_rows;
  return m;
}

// One projected SOR pass over the rows, in row order (forward) or reversed (CPS §5.2, eq. for z^{k+1}_i with the
// newest z_j); w follows every change of z so that the next row sees it. Returns how many z_i moved.
template <bool kBackward, typename Columns>
inline int SweepRows(const Columns& M, const double* step, const double* l, const double* u, double* z, double* w) {
  const int n = M.size();
  int updates = 0;
  for (int k = 0; k < n; ++k) {
    const int i = kBackward ? n - 1 - k : k;
    const double zi = z[i];
    const double next = Clamp(zi - step[i] * w[i], l[i], u[i]);
    // Rows that do not move are skipped: measured faster than branch-free zero updates for n = 4..64, and it
    // makes rows resting on a bound O(1). The test is true for NaN, which then reaches w and the merit pass.
    if (next != zi) {
      z[i] = next;
      M.Axpy(i, next - zi, w);
      ++updates;
    }
  }
  return updates;
}

// One sweep in PsorOptions::sweep's order (symmetric: the forward pass, then the backward one). Returns how many
// z_i moved (both passes' moves for symmetric).
template <PsorOptions::SweepOrder Order, typename Columns>
inline int Sweep(const Columns& M, const double* step, const double* l, const double* u, double* z, double* w) {
  if constexpr (Order == PsorOptions::kForwardSweep) {
    return SweepRows<false>(M, step, l, u, z, w);
  } else if constexpr (Order == PsorOptions::kBackwardSweep) {
    return SweepRows<true>(M, step, l, u, z, w);
  } else {
    const int forward = SweepRows<false>(M, step, l, u, z, w);
    return forward + SweepRows<true>(M, step, l, u, z, w);
  }
}

// The message of an unsolved result, printf-style (counts as %d, values as %g/%e).
template <typename... Args>
void SetMessage(SolveResult* result, const char* format, Args... args) {
  char buffer[400];
  std::snprintf(buffer, sizeof buffer, format, args...);
  result->message.assign(buffer);
}

// One solve's state, shared by the phases of PsorSolver::Iterate.
template <typename Columns>
struct PsorRun {
  PsorRun(const Columns& m, const PsorOptions& o, const SolverOptions& so, const BoxMLCP& problem, double* z_data,
          double* w_data, double* step_data)
      : M(m), opt(o), options(so), l(problem.l().data()), u(problem.u().data()), q(problem.q().data()), z(z_data),
        w(w_data), step(step_data) {}
  const Columns& M;
  const PsorOptions& opt;
  const SolverOptions& options;
  const double* l;
  const double* u;
  const double* q;
  double* z;
  double* w;
  double* step;
  int n = 0;
  double q_norm = 0.0;        // ‖q‖∞
  double z0_norm = 0.0;       // ‖z⁰‖∞ of the projected start
  double min_diagonal = kInf;  // smallest M_ii over the rows that move
  int sweeps = 0, refreshes = 0, budget = 0;
  long long column_updates = 0;
  double rel = kInf;   // Merit::relative at the last merit evaluation
  double best = kInf;  // smallest rel seen
  bool w_exact = true;  // no incremental update since the last refresh
  int since_refresh = 0;
  double window_best = kInf;  // best residual when the current stall window opened
  int window_start = 0;
  double divergence_limit = kInf;
  // The subspace step's trigger (dense run-time n with the step on, else null): the natural map's active set at the
  // last merit check, how many rows it changed there, and how many rows it has inside.
  // It is tracked only while the residual falls slowly (track_pattern, set by the step): fast runs pay nothing.
  signed char* pattern = nullptr;
  bool track_pattern = false, pattern_tracked = false;
  int pattern_changes = 0, inside = 0;

  // w = M z + q exactly (a cold start at 0: w = q without a product).
  [[gnu::always_inline]] void Refresh() {
    if (z0_norm == 0.0 && refreshes == 0) {
      std::copy(q, q + n, w);
    } else {
      M.Affine(z, q, w);
    }
    ++refreshes;
    w_exact = true;
    since_refresh = 0;
  }
};

// Safeguard before any sweep: the update divides by M_ii and is a descent step only for M_ii > 0. Rows with
// l_i = u_i are fixed by the projection whatever M_ii is, so they are exempt. Sets the steps ω / M_ii; false with
// the message when some row's diagonal is below min_diagonal · max|M|.
template <typename Columns>
[[gnu::always_inline]] inline bool SetSteps(PsorRun<Columns>* run, SolveResult* result) {
  const double diagonal_floor = run->opt.min_diagonal > 0.0 ? run->opt.min_diagonal * run->M.MaxAbs() : 0.0;
  int first_bad = -1, num_bad = 0;
  for (int i = 0; i < run->n; ++i) {
    if (run->l[i] == run->u[i]) {
      run->step[i] = 0.0;
      continue;
    }
    const double d = run->M.Diagonal(i);
    if (!(d > diagonal_floor)) {
      if (first_bad < 0) first_bad = i;
      ++num_bad;
      continue;
    }
    run->step[i] = run->opt.omega / d;
    run->min_diagonal = std::min(run->min_diagonal, d);
  }
  if (first_bad < 0) return true;
  SetMessage(result,
             "PSOR needs M_ii > %g (min_diagonal * max|M|) on every row with l_i < u_i, but M(%d,%d) = %g "
             "(%d such row(s)); zero, tiny or negative diagonals are outside the method's scope",
             diagonal_floor, first_bad, first_bad, run->M.Diagonal(first_bad), num_bad);
  result->status = SolveStatus::kNotApplicable;
  result->iterations = 0;
  return false;
}

// The stall message: a residual already at rounding level (tolerance too tight) and a genuinely nonconvergent M
// (cycling) look alike here; it says which one it is. Takes values, not the run: a run whose address escapes
// stays in memory, which costs the m ≤ 4 sweep loop a large share of its instructions (callgrind shows it).
[[gnu::noinline]] void StallMessage(double best, double rel, int sweeps, int n, const PsorOptions& opt,
                                    SolveResult* result) {
  const bool at_rounding_level = best <= 100.0 * n * std::numeric_limits<double>::epsilon();
  SetMessage(result,
             "PSOR stalled: best scaled residual %.3e did not fall by a factor %g within %d sweeps (now %.3e after "
             "%d sweeps); %s",
             best, opt.stall_factor, opt.stall_sweeps, rel, sweeps,
             at_rounding_level ? "the residual is at rounding level, the tolerance is below the attainable accuracy"
                               : "M may be outside PSOR's convergence classes (symmetric PD, H-matrix)");
}

// The merit test after a sweep: kNotRun to sweep on, else the status the solve ends with (message set).
// fixed_point: the sweep moved nothing; swept_with_exact_w: it started from an exact w.
// Inlined into the sweep loop: on the m ≤ 4 problems of the time-steppers a call here is a large share of a
// solve.
template <typename Columns, typename TimeUp>
[[gnu::always_inline]] inline SolveStatus Checkpoint(PsorRun<Columns>* run, int updates, bool swept_with_exact_w, const TimeUp& time_up,
                       SolveResult* result) {
  const double tolerance = run->options.tolerance;
  const bool fixed_point = updates == 0;
  Merit merit;
  if constexpr (std::is_same_v<Columns, DenseColumns<Eigen::Dynamic>>) {
    run->pattern_tracked = run->track_pattern;
    merit = !run->track_pattern ? EvaluateMerit(run->n, run->z, run->w, run->l, run->u)
                                : EvaluateMeritAndPattern(run->n, run->z, run->w, run->l, run->u, run->pattern,
                                                          &run->pattern_changes, &run->inside);
  } else {
    merit = EvaluateMerit(run->n, run->z, run->w, run->l, run->u);
  }
  run->rel = merit.relative(run->q_norm);
  if (!merit.finite) {
    SetMessage(result,
               "PSOR diverged: non-finite iterate after %d sweeps (best scaled residual %.3e); M is likely outside "
               "PSOR's convergence classes or omega = %g is too large",
               run->sweeps, run->best, run->opt.omega);
    return SolveStatus::kDiverged;
  }
  if (run->rel <= tolerance && !run->w_exact) {
    // Confirm against an exact w before claiming success: the incremental one carries rounding drift.
    run->Refresh();
    merit = EvaluateMerit(run->n, run->z, run->w, run->l, run->u);
    run->rel = merit.relative(run->q_norm);
  }
  run->best = std::min(run->best, run->rel);
  if (run->rel <= tolerance) return SolveStatus::kSolved;
  if (merit.z_norm > run->divergence_limit) {
    SetMessage(result, "PSOR diverged: |z|inf = %.3e exceeds the divergence limit %.3e (scaled residual %.3e)",
               merit.z_norm, run->divergence_limit, run->rel);
    return SolveStatus::kDiverged;
  }
  if (fixed_point && swept_with_exact_w) {
    SetMessage(result,
               "PSOR stalled at a floating-point fixed point (no coordinate moves) with scaled residual %.3e > "
               "tolerance %.1e: the tolerance is below the accuracy attainable for this scaling",
               run->rel, tolerance);
    return SolveStatus::kStalled;
  }
  if (run->best <= run->opt.stall_factor * run->window_best) {
    run->window_best = run->best;
    run->window_start = run->sweeps;
  } else if (run->opt.stall_sweeps > 0 && run->sweeps - run->window_start >= run->opt.stall_sweeps) {
    StallMessage(run->best, run->rel, run->sweeps, run->n, run->opt, result);
    return SolveStatus::kStalled;
  }
  if (run->options.verbosity > 1) {
    std::fprintf(stderr, "psor: sweep %6d  residual %.3e  moved %d/%d\n", run->sweeps, run->rel, updates, run->n);
  }
  if (run->options.time_limit_seconds < kInf && time_up()) {
    SetMessage(result, "PSOR hit the time limit after %d sweeps with scaled residual %.3e (best %.3e)", run->sweeps,
               run->rel, run->best);
    return SolveStatus::kTimeLimit;
  }
  return SolveStatus::kNotRun;
}

// Status, iterations and details of the result.
template <typename Columns>
[[gnu::always_inline]] inline void FinishRun(const PsorRun<Columns>& run, SolveStatus status, SolveResult* result) {
  result->status = status;
  result->iterations = run.sweeps;
  result->SetDetail("column_updates", static_cast<double>(run.column_updates));
  result->SetDetail("w_refreshes", run.refreshes);
  if (run.options.verbosity > 0) {
    std::fprintf(stderr,
                 "psor: %s after %d sweeps, scaled residual %.3e (best %.3e, tolerance %.1e), %lld column updates, "
                 "%d exact refreshes of w\n",
                 std::string(ToString(status)).c_str(), run.sweeps, run.rel, run.best, run.options.tolerance,
                 run.column_updates, run.refreshes);
  }
}

// When the subspace step tries (psor_solver.h): merit checks since the bound pattern last changed, the stable
// checks a try waits for (doubled after a failed one), the residual of the previous check (for the rate).
struct SubspaceSchedule {
  int stable = 0;
  int wait = 0;
  double last_rel = kInf;
};

enum class SubspaceOutcome { kNone, kSolved, kSolvedAsPolishWould };

// The rate per merit check at or below which the subspace step neither tracks the pattern nor tries (the run is
// fast enough on its own).
constexpr double kFastRate = 0.5;

// Block exchanges the subspace step may add to the set read off the sweeps before it gives up.
constexpr int kSubspaceCorrections = 4;

// One block exchange on the set in s.state whose exact solution is (z, w): bound rows with w of the wrong sign
// (rows with l_i = u_i excepted) become free, then the set is solved again as the polish solves it
// (SolveSetMovingCrossedRows). False when no row changed or the new set cannot be solved.
bool ExchangeRows(const BoxMLCP& problem, const PsorRun<DenseColumns<Eigen::Dynamic>>& run, double* z,
                  const double* w, const PolishScratch& s) {
  bool changed = false;
  for (int i = 0; i < run.n; ++i) {
    const auto state = static_cast<RowState>(s.state[i]);
    if (run.l[i] == run.u[i]) continue;  // a fixed row takes any w
    if ((state == RowState::kLower && w[i] < 0.0) || (state == RowState::kUpper && w[i] > 0.0)) {
      s.state[i] = static_cast<signed char>(RowState::kFree);
      changed = true;
    }
  }
  return changed && SolveSetMovingCrossedRows<0>(problem, s, z);
}

// After a merit check of a dense run-time-n run (which updated run->pattern): updates the schedule and, when the
// pattern is stable and the sweeps still needed at the observed rate (log(tol/rel) / log(rate)) would cost more
// than the exact solve (the polish's classification and the candidate's w, 2n², the right-hand side n·n_f, the LU
// n_f³/3), solves the free rows exactly (PolishDense) and keeps the candidate when it passes the sweeps' own
// stopping test. kSolvedAsPolishWould: the base's polish would read the same set off the answer and factor the
// same block again.
template <typename Workspace>
SubspaceOutcome SubspaceStep(const BoxMLCP& problem, PsorRun<DenseColumns<Eigen::Dynamic>>* run, int updates,
                             SubspaceSchedule* schedule, Workspace* ws) {
  const double rate = run->rel / schedule->last_rel;
  schedule->last_rel = run->rel;
  // A residual that at least halves per check converges within a few dozen sweeps, and one that does not fall is
  // not converging to anything a step could read: neither tracks the pattern nor tries.
  run->track_pattern = rate > kFastRate && rate < 1.0;
  schedule->stable = run->pattern_tracked && run->pattern_changes == 0 ? schedule->stable + 1 : 0;
  if (schedule->stable < schedule->wait) return SubspaceOutcome::kNone;
  const double n = run->n, nf = run->inside;
  const double remaining = rate < 1.0 ? std::log(run->options.tolerance / run->rel) / std::log(rate)
                                      : static_cast<double>(run->budget - run->sweeps);
  const double sweep_cost = n * (1.0 + updates);
  const double solve_cost = 2.0 * n * n + n * nf + nf * nf * nf / 3.0;
  if (!(solve_cost < remaining * sweep_cost)) return SubspaceOutcome::kNone;

  ++ws->tries;
  schedule->stable = 0;
  const PolishScratch scratch = ws->active_set.For(run->n);
  double* candidate = ws->candidate.data();
  double* candidate_w = ws->candidate_w.data();
  if (PolishDense<0>(problem, run->z, candidate, scratch)) {
    // The set read off the sweeps, then up to kSubspaceCorrections block exchanges (Júdice & Pires, 1994): every
    // bound row whose w pushes away from its bound is freed, every free row that leaves the box goes to the bound
    // it crossed, and the set is solved again. A row near its switching point is where the sweeps' set is wrong.
    for (int pass = 0;; ++pass) {
      run->M.Affine(candidate, run->q, candidate_w);
      const Merit merit = EvaluateMerit(run->n, candidate, candidate_w, run->l, run->u);
      const double rel = merit.relative(run->q_norm);
      if (merit.finite && rel <= run->options.tolerance) {
        std::copy(candidate, candidate + run->n, run->z);
        std::copy(candidate_w, candidate_w + run->n, run->w);
        run->rel = rel;
        run->best = std::min(run->best, rel);
        run->w_exact = true;
        run->since_refresh = 0;
        ++ws->steps;
        ClassifyRowsForPolish<0>(problem, candidate, ws->candidate_state.data(), scratch.rhs);
        return std::equal(ws->candidate_state.begin(), ws->candidate_state.end(), scratch.state)
                   ? SubspaceOutcome::kSolvedAsPolishWould
                   : SubspaceOutcome::kSolved;
      }
      if (pass == kSubspaceCorrections || !merit.finite || !ExchangeRows(problem, *run, candidate, candidate_w, scratch)) {
        break;
      }
    }
  }
  schedule->wait *= 2;
  return SubspaceOutcome::kNone;
}

}  // namespace

bool PsorOptions::IsValid(std::string* why) const {
  const auto fail = [why](const char* text) {
    if (why) *why = text;
    return false;
  };
  if (!(omega > 0.0 && omega < 2.0)) {
    return fail("psor: omega must lie in the open interval (0, 2) (PSOR diverges or stands still outside it)");
  }
  if (sweep != kForwardSweep && sweep != kBackwardSweep && sweep != kSymmetricSweep) {
    return fail("psor: sweep must be forward, backward or symmetric");
  }
  if (check_interval < 1) return fail("psor: check_interval must be >= 1");
  if (refresh_interval < 1) return fail("psor: refresh_interval must be >= 1");
  if (!(divergence_threshold > 1.0) || std::isnan(divergence_threshold)) {
    return fail("psor: divergence_threshold must be > 1");
  }
  if (stall_sweeps < 0) return fail("psor: stall_sweeps must be >= 0 (0 disables the stall test)");
  if (!(stall_factor > 0.0 && stall_factor < 1.0)) return fail("psor: stall_factor must lie in (0, 1)");
  if (!(min_diagonal >= 0.0 && min_diagonal < 1.0)) return fail("psor: min_diagonal must lie in [0, 1)");
  if (subspace_sweeps < 0) return fail("psor: subspace_sweeps must be >= 0 (0 disables the subspace step)");
  return true;
}

// The subspace step's storage (psor_solver.h), sized once per n: the bound pattern of the last check, the exact
// candidate and its exact w, the polish's classification of the candidate, the active-set solve's scratch.
struct PsorSolver::SubspaceWorkspace {
  std::vector<signed char> pattern, candidate_state;
  Vector candidate, candidate_w;
  ActiveSetWorkspace active_set;
  int tries = 0, steps = 0;  // this solve's exact solves, and those accepted

  void Resize(int n) {
    if (static_cast<int>(pattern.size()) == n) return;
    pattern.assign(n, 0);
    candidate_state.assign(n, 0);
    candidate.resize(n);
    candidate_w.resize(n);
  }
};

PsorSolver::PsorSolver() = default;
PsorSolver::PsorSolver(const PsorOptions& options) : BackendWithOptions(options) {}
PsorSolver::~PsorSolver() = default;

const SolverInfo& PsorSolver::info() const {
  static const SolverInfo kInfo{
      "psor",
      "projected SOR (Gauss-Seidel) sweeps on the box, incremental w = Mz+q; needs M_ii > 0",
      "Cottle, Pang, Stone: The Linear Complementarity Problem (1992), sec. 5.2",
      /*dense=*/true,
      /*sparse=*/true,
      /*symmetric_only=*/false,
      /*exact=*/false,
      /*mcp=*/false,
      /*default_size_limit=*/0,
      /*equilibrate=*/true,
      /*delegates=*/false,
      /*external=*/false,
      /*allocation_free=*/true,
      /*solves_every_p_matrix=*/false};
  return kInfo;
}

void PsorSolver::BindOptions(OptionBinder* binder) {
  binder->Add("omega", &options_.omega, "relaxation factor in (0,2); 1 = projected Gauss-Seidel");
  binder->Add("check_interval", &options_.check_interval, "sweeps between merit-function evaluations (>= 1)");
  binder->Add("refresh_interval", &options_.refresh_interval,
              "sweeps between exact recomputations of w = Mz+q (>= 1)");
  binder->Add("divergence_threshold", &options_.divergence_threshold,
              "diverged once |z|inf > this * (1 + |z0|inf + |q|inf / min M_ii)");
  binder->Add("stall_sweeps", &options_.stall_sweeps,
              "stalled if the best residual does not fall by stall_factor within this many sweeps (0: off)");
  binder->Add("stall_factor", &options_.stall_factor, "required decrease of the best residual, in (0,1)");
  binder->Add("min_diagonal", &options_.min_diagonal, "rows need M_ii > min_diagonal * max|M_jk|, in [0,1)");
  binder->Add("subspace_sweeps", &options_.subspace_sweeps,
              "merit checks with an unchanged bound pattern before an exact solve on it (dense 5..512 rows; 0: off)");
  binder->Add("sweep", &options_.sweep,
              {{"forward", PsorOptions::kForwardSweep},
               {"backward", PsorOptions::kBackwardSweep},
               {"symmetric", PsorOptions::kSymmetricSweep}},
              "row order of a sweep: forward (0..n-1), backward (n-1..0: one sweep solves upper triangular M) or "
              "symmetric (forward then backward, projected SSOR)");
}

bool PsorSolver::ValidateBackendOptions(std::string* why) const {
  return options_.IsValid(why);
}

void PsorSolver::DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) {
  const int n = problem.size();
  if (step_.size() != n) step_.resize(n);
  if (w_.size() != n) w_.resize(n);
  if (options_.sweep != PsorOptions::kForwardSweep) return IterateBackwardOrSymmetric(problem, options, result);
  constexpr PsorOptions::SweepOrder kForward = PsorOptions::kForwardSweep;
  if (problem.is_sparse()) {
    Iterate<kForward>(SparseColumns(problem.sparse_matrix()), problem, options, result);
    return;
  }
  const DenseMatrix& M = problem.dense_matrix();
  switch (n) {
    case 1: Iterate<kForward>(DenseColumns<1>(M), problem, options, result); break;
    case 2: Iterate<kForward>(DenseColumns<2>(M), problem, options, result); break;
    case 3: Iterate<kForward>(DenseColumns<3>(M), problem, options, result); break;
    case 4: Iterate<kForward>(DenseColumns<4>(M), problem, options, result); break;
    default: IterateDense<kForward>(problem, options, result); break;
  }
}

void PsorSolver::IterateBackwardOrSymmetric(const BoxMLCP& problem, const SolverOptions& options,
                                            SolveResult* result) {
  const bool backward = options_.sweep == PsorOptions::kBackwardSweep;
  if (problem.is_sparse()) {
    const SparseColumns M(problem.sparse_matrix());
    return backward ? Iterate<PsorOptions::kBackwardSweep>(M, problem, options, result)
                    : Iterate<PsorOptions::kSymmetricSweep>(M, problem, options, result);
  }
  return backward ? IterateDense<PsorOptions::kBackwardSweep>(problem, options, result)
                  : IterateDense<PsorOptions::kSymmetricSweep>(problem, options, result);
}

// A dense problem of run-time size, with the subspace step's counts as details.
template <PsorOptions::SweepOrder Order>
void PsorSolver::IterateDense(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) {
  if (subspace_) subspace_->tries = subspace_->steps = 0;
  Iterate<Order>(DenseColumns<Eigen::Dynamic>(problem.dense_matrix()), problem, options, result);
  result->SetDetail("subspace_tries", subspace_ ? subspace_->tries : 0);
  result->SetDetail("subspace_steps", subspace_ ? subspace_->steps : 0);
}

// The phases in order: the diagonal safeguard, the projected start, then sweeps with a merit checkpoint every
// check_interval sweeps (and at a fixed point or the last sweep), refreshing the incremental w to bound its drift.
template <PsorOptions::SweepOrder Order, typename Columns>
void PsorSolver::Iterate(const Columns& M, const BoxMLCP& problem, const SolverOptions& options,
                         SolveResult* result) {
  PsorRun<Columns> run(M, options_, options, problem, result->z.data(), w_.data(), step_.data());
  run.n = M.size();
  run.q_norm = problem.residual_scale() - 1.0;
  if (!SetSteps(&run, result)) return;
  // Start from the projection of the warm start (or of Π(0), which it already is).
  for (int i = 0; i < run.n; ++i) {
    run.z[i] = Clamp(run.z[i], run.l[i], run.u[i]);
    run.z0_norm = std::max(run.z0_norm, std::abs(run.z[i]));
  }
  run.budget = IterationBudget(options, kDefaultMaxSweeps);
  run.Refresh();
  const Merit merit = EvaluateMerit(run.n, run.z, run.w, run.l, run.u);
  run.rel = run.best = merit.relative(run.q_norm);
  if (!merit.finite) {
    SetMessage(result, "PSOR: M z0 + q is not finite at the starting point (|z0|inf = %.3e): overflow", run.z0_norm);
    return FinishRun(run, SolveStatus::kNumericalFailure, result);
  }
  if (run.rel <= options.tolerance) return FinishRun(run, SolveStatus::kSolved, result);  // the (warm) start solves it

  // Only needed once sweeping (time-steppers' warm starts usually return above): no division before that.
  run.divergence_limit = options_.divergence_threshold *
                         (1.0 + run.z0_norm + (run.min_diagonal < kInf ? run.q_norm / run.min_diagonal : 0.0));
  run.window_best = run.rel;
  // The subspace step (psor_solver.h) runs on dense problems of run-time size only: the fixed-size kernels of
  // n ≤ 4 stay as they are, and the sparse path has no dense kernel to call.
  constexpr bool kSubspace = std::is_same_v<Columns, DenseColumns<Eigen::Dynamic>>;
  SubspaceSchedule schedule;
  if constexpr (kSubspace) {
    if (options_.subspace_sweeps > 0 && run.n <= kMaxPolishDenseSize) {
      if (!subspace_) subspace_ = std::make_unique<SubspaceWorkspace>();
      subspace_->Resize(run.n);
      run.pattern = subspace_->pattern.data();
      // No row matches 2 (a pattern entry is −1, 0 or 1): a cold solve starts from nothing an earlier one left.
      std::fill(subspace_->pattern.begin(), subspace_->pattern.end(), static_cast<signed char>(2));
      schedule.wait = options_.subspace_sweeps;
      schedule.last_rel = run.rel;
    }
  }
  int until_check = options_.check_interval;  // a countdown: no integer division per sweep
  const auto time_up = [this] { return TimeLimitReached(); };
  while (true) {
    if (run.sweeps >= run.budget) {
      SetMessage(result,
                 "PSOR reached the sweep limit (%d) with scaled residual %.3e (best %.3e); raise max_iterations, or M "
                 "is ill-conditioned or outside PSOR's convergence classes (symmetric PD, H-matrix)",
                 run.budget, run.rel, run.best);
      return FinishRun(run, SolveStatus::kIterationLimit, result);
    }
    const int updates = Sweep<Order>(M, run.step, run.l, run.u, run.z, run.w);
    ++run.sweeps;
    ++run.since_refresh;
    run.column_updates += updates;
    const bool swept_with_exact_w = run.w_exact;
    if (updates > 0) run.w_exact = false;
    // A sweep that moves nothing is a fixed point of the PSOR map. With an exact w this means every row
    // satisfies its 1-D complementarity condition up to rounding, so the residual cannot improve further.
    const bool fixed_point = updates == 0;
    if (fixed_point || --until_check == 0 || run.sweeps == run.budget) {
      until_check = options_.check_interval;
      const SolveStatus status = Checkpoint(&run, updates, swept_with_exact_w, time_up, result);
      if (status != SolveStatus::kNotRun) return FinishRun(run, status, result);
      if constexpr (kSubspace) {
        if (schedule.wait > 0) {
          const SubspaceOutcome outcome = SubspaceStep(problem, &run, updates, &schedule, subspace_.get());
          if (outcome == SubspaceOutcome::kSolvedAsPolishWould) NotePolishRedundant();
          if (outcome != SubspaceOutcome::kNone) return FinishRun(run, SolveStatus::kSolved, result);
        }
      }
    }
    // Bound the rounding drift of the incremental w; also makes a fixed point found on a drifted w be re-tested.
    if (!run.w_exact && (run.since_refresh >= options_.refresh_interval || fixed_point)) run.Refresh();
  }
}

}  // namespace smcbench

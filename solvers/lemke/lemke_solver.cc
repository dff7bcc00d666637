// Lemke's method with lexicographic degeneracy resolution on the LCP reduction of a box-MLCP. The reduction
// (bound shifts, sign flips, the [[M, I], [−I, 0]] multiplier split of box rows; free rows by Schur complement,
// kept basic, or split x⁺ − x⁻) and the numerical safeguards are documented at the top of lemke_solver.h.
#include "solvers/lemke/lemke_solver.h"

#include "solvers/core/active_set.h"
#include "solvers/core/dense_lu.h"
#include "solvers/core/matrix_class.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <string>

namespace smcbench {
namespace {

using lemke_internal::Workspace;
constexpr double kEps = std::numeric_limits<double>::epsilon();

enum RowKind : signed char { kLower, kUpper, kBox, kFree, kFixed };
enum class FreeMode { kNone = 0, kSchur = 1, kBasic = 2, kSplit = 3 };

// Grows a buffer to at least n entries; never shrinks, so a repeated solve of the same size never allocates.
template <typename T>
void Ensure(std::vector<T>* v, size_t n) {
  if (v->size() < n) v->resize(n);
}

// ---------------------------------------------------------------------------------------------------------------
// The pivoting engine on LCP(N, r) with covering vector d. Variables: w_j = j, x_j = p + j, z₀ = 2p. The basis
// matrix B has columns e_j (w_j), −N_·j (x_j), −d (z₀), so that I w − N x − d z₀ = r and x_B = B⁻¹r − θ B⁻¹a when
// the variable with column a enters at level θ.

class Engine {
 public:
  // nx: number of x slots; y_owner[j] (j ≥ nx): the x slot whose box row the multiplier y_j belongs to.
  Engine(Workspace* ws, int p, int nx, const int* y_owner)
      : ws_(*ws), p_(p), nx_(nx), z0_(2 * p), y_owner_(y_owner), noise_factor_(std::max(1e-14, 8.0 * p * kEps)) {}

  int z0() const { return z0_; }
  int Complement(int var) const { return var < p_ ? var + p_ : var - p_; }
  bool FreeRow(int i) const { return ws_.var_free[ws_.basis[i]] != 0; }

  // col = B⁻¹ a_var. The columns of N have their nonzeros in the x rows [0, nx) plus at most one ±1 in a y row
  // (box rows): the product only touches those columns of B⁻¹ (column-major, so each is a contiguous axpy).
  void Column(int var) {
    double* c = ws_.col.data();
    const double* binv = ws_.binv.data();
    const int p = p_;
    if (var < p) {  // slack: a column of B⁻¹
      std::copy(binv + size_t(var) * p, binv + size_t(var + 1) * p, c);
      return;
    }
    const int j = var - p;
    if (var != z0_ && j >= nx_) {  // box multiplier y: N_·y = e_a for its x row a
      const double* ba = binv + size_t(y_owner_[j]) * p;
      for (int i = 0; i < p; ++i) c[i] = -ba[i];
      return;
    }
    const double* a = var == z0_ ? ws_.d.data() : ws_.N.data() + size_t(j) * p;
    const int width = var == z0_ ? p : nx_;
    if (p <= 64) {  // small: axpy loops (no reduction chain) beat the dispatch of a dynamic-size product
      std::fill(c, c + p, 0.0);
      for (int k = 0; k < width; ++k) {
        const double ak = a[k];
        if (ak == 0.0) continue;
        const double* bk = binv + size_t(k) * p;
        for (int i = 0; i < p; ++i) c[i] -= ak * bk[i];
      }
    } else {
      Eigen::Map<Vector> cv(c, p);
      cv.setZero();
      cv.noalias() -= Eigen::Map<const DenseMatrix>(binv, p, width) * Eigen::Map<const Vector>(a, width);
    }
    if (var != z0_ && ws_.slot_y[j] >= 0) {  // the −1 of the y row: −B⁻¹·(−e_y)
      const double* by = binv + size_t(ws_.slot_y[j]) * p;
      for (int i = 0; i < p; ++i) c[i] += by[i];
    }
  }

  // Gauss-Jordan step on row r with the column in ws_.col; var enters the basis.
  void Pivot(int r, int var) {
    const int p = p_;
    double* c = ws_.col.data();
    double* binv = ws_.binv.data();
    double* beta = ws_.beta.data();
    const double pivot = c[r];
    const double inv = 1.0 / pivot;
    beta[r] *= inv;
    c[r] = 0.0;  // row r is scaled, not eliminated
    for (int i = 0; i < p; ++i) beta[i] -= c[i] * beta[r];
    for (int k = 0; k < p; ++k) {
      double* bk = binv + size_t(k) * p;
      const double brk = (bk[r] *= inv);
      if (brk == 0.0) continue;  // common early on: the slack part of B⁻¹ is sparse
      for (int i = 0; i < p; ++i) bk[i] -= c[i] * brk;
    }
    c[r] = pivot;
    ws_.where[ws_.basis[r]] = -1;
    ws_.basis[r] = var;
    ws_.where[var] = r;
  }

  // The slack basis: B = I, β = r.
  void SlackBasis() {
    std::fill(ws_.binv.begin(), ws_.binv.begin() + size_t(p_) * p_, 0.0);
    std::fill(ws_.where.begin(), ws_.where.begin() + 2 * p_ + 1, -1);
    for (int i = 0; i < p_; ++i) {
      ws_.binv[size_t(i) * p_ + i] = 1.0;
      ws_.basis[i] = i;
      ws_.where[i] = i;
    }
    std::copy(ws_.r.begin(), ws_.r.begin() + p_, ws_.beta.begin());
  }

  // Leaving row by the lexicographic minimum ratio test (Cottle-Pang-Stone ch. 4): among sign-constrained rows with
  // c_i > tol, the lexicographically smallest [β_i, B⁻¹_i·] / c_i. z₀ leaves whenever it ties in the first
  // component, which ends the method at a complementary basis. Returns −1 if no row blocks (secondary ray).
  // clamp = false only for the first step, where the basic values are negative by design.
  int RatioTest(double tol, bool clamp = true) {
    const double floor = clamp ? 0.0 : -kInf;
    const double* c = ws_.col.data();
    const double* beta = ws_.beta.data();
    double theta = kInf, bmax = 0.0;
    int arg = -1;
    for (int i = 0; i < p_; ++i) {
      if (FreeRow(i)) continue;
      bmax = std::max(bmax, std::abs(beta[i]));
      // A degenerate value rounded below zero counts as zero: a negative ratio would step backwards.
      if (c[i] > tol) {
        const double ratio = std::max(beta[i], floor) / c[i];
        if (ratio < theta) theta = ratio, arg = i;
      }
    }
    if (arg < 0) return -1;
    // Ties in the first component, up to rounding. A loose filter relative to the largest basic value first; the
    // survivors are then held to the rounding scale of their own row, max(1e-14, 8pε)·Σ_k |B⁻¹_ik r_k|, so that
    // rows of very different magnitude (box widths next to a tiny z) are not mistaken for ties.
    const double delta = 1e-10 * bmax;
    int* ties = ws_.ties.data();
    int nt = 0;
    for (int i = 0; i < p_; ++i) {
      if (c[i] > tol && !FreeRow(i) && std::max(beta[i], floor) - theta * c[i] <= delta) ties[nt++] = i;
    }
    const int z0_row = ws_.where[z0_];
    if (nt == 1) return ties[0];
    const double* binv = ws_.binv.data();  // column-major: row i of B⁻¹ is binv[i + k·p]
    const double* r = ws_.r.data();
    const auto noise = [&](int i) {
      double s = 0.0;
      for (int k = 0; k < p_; ++k) s += std::abs(binv[size_t(k) * p_ + i] * r[k]);
      return noise_factor_ * s / c[i];
    };
    const double arg_noise = noise(arg);
    int kept = 0;
    for (int t = 0; t < nt; ++t) {
      const int i = ties[t];
      if (i == arg || std::max(beta[i], floor) / c[i] - theta <= noise(i) + arg_noise) {
        if (i == z0_row) return i;
        ties[kept++] = i;
      }
    }
    nt = kept;
    if (nt == 1) return ties[0];
    // Rows of B⁻¹ scaled by 1/c_i, compared column by column; τ absorbs rounding in B⁻¹.
    double scale = 0.0;
    for (int t = 0; t < nt; ++t) {
      double m = 0.0;
      for (int k = 0; k < p_; ++k) m = std::max(m, std::abs(binv[size_t(k) * p_ + ties[t]]));
      scale = std::max(scale, m / c[ties[t]]);
    }
    const double tau = 1e-11 * scale;
    for (int k = 0; k < p_ && nt > 1; ++k) {
      double vmin = kInf;
      for (int t = 0; t < nt; ++t) vmin = std::min(vmin, binv[size_t(k) * p_ + ties[t]] / c[ties[t]]);
      int left = 0;
      for (int t = 0; t < nt; ++t) {
        if (binv[size_t(k) * p_ + ties[t]] / c[ties[t]] <= vmin + tau) ties[left++] = ties[t];
      }
      nt = left;
    }
    int best = ties[0];  // numerically indistinguishable rows: take the largest pivot
    for (int t = 1; t < nt; ++t) {
      if (c[ties[t]] > c[best]) best = ties[t];
    }
    return best;
  }

  // Pivots every sign-free x into the basis in place of a free slack (the MLCP start, see the header). Returns
  // false if the free columns are dependent, so that no complementary basis holds them all.
  bool BringFreeVariablesIn(int* pivots) {
    constexpr double kRankTol = 1e-10;  // relative size below which a pivot candidate counts as zero
    const auto free_slack_row = [&](int i) { return ws_.basis[i] < p_ && ws_.var_free[p_ + ws_.basis[i]]; };
    int* pending = ws_.mark.data();
    int np = 0;
    for (int j = 0; j < p_; ++j) {  // pass 1: Gauss-Jordan with partial pivoting over the free slack rows
      if (!ws_.var_free[p_ + j]) continue;
      Column(p_ + j);
      const double* c = ws_.col.data();
      double cmax = 0.0, best = 0.0;
      int row = -1;
      for (int i = 0; i < p_; ++i) {
        cmax = std::max(cmax, std::abs(c[i]));
        if (free_slack_row(i) && std::abs(c[i]) > best) best = std::abs(c[i]), row = i;
      }
      if (row >= 0 && best > kRankTol * cmax) {
        Pivot(row, p_ + j);
        ++*pivots;
      } else {
        pending[np++] = j;
      }
    }
    for (int t = 0; t < np; ++t) {  // pass 2: 2×2 principal block pivots with a bounded row
      const int j = pending[t];
      Column(p_ + j);
      std::copy(ws_.col.begin(), ws_.col.begin() + p_, ws_.col2.begin());
      const double* cj = ws_.col2.data();
      double cj_max = 0.0;
      for (int i = 0; i < p_; ++i) cj_max = std::max(cj_max, std::abs(cj[i]));
      if (!(cj_max > 0.0)) return false;
      double best = 0.0;
      int best_i = -1, best_k = -1;
      for (int i = 0; i < p_; ++i) {
        const int ri = ws_.where[i];  // row of w_i
        if (ws_.var_free[p_ + i] || ri < 0 || ws_.where[p_ + i] >= 0 || std::abs(cj[ri]) == 0.0) continue;
        Column(p_ + i);
        const double* ci = ws_.col.data();
        double ci_max = 0.0;
        for (int k = 0; k < p_; ++k) ci_max = std::max(ci_max, std::abs(ci[k]));
        for (int k = 0; k < p_; ++k) {
          if (!free_slack_row(k) || !(std::abs(ci[k]) > kRankTol * ci_max)) continue;
          const double e2 = cj[ri] - ci[ri] * cj[k] / ci[k];
          const double score = std::abs(ci[k]) / ci_max * std::abs(e2) / cj_max;
          if (score > best) best = score, best_i = i, best_k = k;
        }
      }
      if (best_i < 0 || !(best > kRankTol)) return false;
      Column(p_ + best_i);
      Pivot(best_k, p_ + best_i);
      Column(p_ + j);
      Pivot(ws_.where[best_i], p_ + j);
      *pivots += 2;
    }
    return true;
  }

  // d = Bê: the covering direction that raises every sign-constrained basic variable at unit rate (B⁻¹d = ê).
  void CoverFromBasis() {
    double* d = ws_.d.data();
    std::fill(d, d + p_, 0.0);
    for (int i = 0; i < p_; ++i) {
      if (FreeRow(i)) continue;
      const int v = ws_.basis[i];
      if (v < p_) {
        d[v] += 1.0;
      } else {
        const double* a = ws_.N.data() + size_t(v - p_) * p_;
        for (int k = 0; k < p_; ++k) d[k] -= a[k];
      }
    }
  }

  // Recomputes B⁻¹ of the current basis from its columns (Gauss-Jordan from the slack basis with partial pivoting
  // over the rows still held by slacks that are not in the basis), then β = B⁻¹r with one refinement step.
  // Returns false if the basis is numerically singular.
  bool Reinvert() {
    int* mark = ws_.mark.data();  // mark[j] = 1: w_j stays basic
    int* targets = ws_.ties.data();
    int nt = 0;
    std::fill(mark, mark + p_, 0);
    for (int i = 0; i < p_; ++i) {
      const int v = ws_.basis[i];
      if (v < p_) {
        mark[v] = 1;
      } else {
        targets[nt++] = v;
      }
    }
    SlackBasis();
    for (int t = 0; t < nt; ++t) {
      const int v = targets[t];
      Column(v);
      const double* c = ws_.col.data();
      int r = -1;
      double best = 0.0, cmax = 0.0;
      for (int i = 0; i < p_; ++i) {
        cmax = std::max(cmax, std::abs(c[i]));
        const int b = ws_.basis[i];
        if (b < p_ && !mark[b] && std::abs(c[i]) > best) best = std::abs(c[i]), r = i;
      }
      if (r < 0 || !(best > p_ * kEps * cmax)) return false;
      Pivot(r, v);
    }
    Eigen::Map<const DenseMatrix> Binv(ws_.binv.data(), p_, p_);
    Eigen::Map<Vector> beta(ws_.beta.data(), p_);
    Eigen::Map<const Vector> r(ws_.r.data(), p_);
    beta.noalias() = Binv * r;
    // One step of iterative refinement: res = r − Bβ, β += B⁻¹ res.
    Eigen::Map<Vector> res(ws_.tmp.data(), p_);
    res = r;
    for (int i = 0; i < p_; ++i) {
      const int v = ws_.basis[i];
      if (v < p_) {
        res[v] -= beta[i];
      } else {
        const double* a = v == z0_ ? ws_.d.data() : ws_.N.data() + size_t(v - p_) * p_;
        res += beta[i] * Eigen::Map<const Vector>(a, p_);
      }
    }
    beta.noalias() += Binv * res;
    return beta.allFinite();
  }

 private:
  Workspace& ws_;
  const int p_, nx_, z0_;
  const int* y_owner_;
  const double noise_factor_;  // relative rounding level of a basic value, for the tie test
};

void Append(std::string* s, const char* fmt, double a, double b = 0.0) {
  char buf[320];
  std::snprintf(buf, sizeof buf, fmt, a, b);
  *s += buf;
}

const char* FreeModeName(FreeMode mode) {
  switch (mode) {
    case FreeMode::kNone: return "none";
    case FreeMode::kSchur: return "schur";
    case FreeMode::kBasic: return "basic";
    case FreeMode::kSplit: return "split";
  }
  return "?";
}

// The run's mode as the option value that names it (detail "free_row_mode"); only asked when there are free rows.
LemkeOptions::FreeRows FreeRowsUsed(FreeMode mode) {
  switch (mode) {
    case FreeMode::kSchur: return LemkeOptions::FreeRows::kSchur;
    case FreeMode::kBasic: return LemkeOptions::FreeRows::kBasic;
    case FreeMode::kSplit: return LemkeOptions::FreeRows::kSplit;
    case FreeMode::kNone: break;
  }
  return LemkeOptions::FreeRows::kAutomatic;
}

// The larger of the two, for "is this point better" comparisons (NaN-safe: NaN compares as not better).
double Worst(const Residual& r) { return std::max(r.rel, r.scaled); }

// Why the box-MLCP is known to have a solution, or nullptr: every bound finite (a continuous map on a compact box
// always has one), M with a positive definite symmetric part, or M a P-matrix (the box-MLCP then has exactly one
// solution whatever the bounds). Positive row scaling keeps all three, so the equilibrated M serves. Only called
// when Lemke ends on a ray: a ray on such a problem is a failure of the method, not a verdict on the problem.
const char* SolutionExistsReason(const BoxMLCP& problem) {
  const Vector& l = problem.l();
  const Vector& u = problem.u();
  bool all_finite = true;
  for (int i = 0; i < problem.size(); ++i) all_finite = all_finite && l[i] > -kInf && u[i] < kInf;
  if (all_finite) return "every bound is finite";
  const DenseMatrix& M = problem.dense_matrix();
  if (ClassifySymmetricPartPositiveDefinite(M).answer == MatrixClassAnswer::kYes) {
    return "the symmetric part of M is positive definite";
  }
  // Every principal minor up to n = 12 (2^n − 1 small factorizations, allocating: only on this failure path).
  if (ClassifyPMatrix(M).answer == MatrixClassAnswer::kYes) return "M is a P-matrix";
  return nullptr;
}

// Builds LCP(N, r) from the classified rows for the given free-row mode (Schur data already in ws). Returns p and
// sets *nx, the number of x slots (the y slots of the box rows follow them).
int BuildLcp(const BoxMLCP& problem, FreeMode mode, LemkeOptions::Covering covering, Workspace* ws_ptr, int* c_out, int* nx_out) {
  Workspace& ws = *ws_ptr;
  const DenseMatrix& M = problem.dense_matrix();
  const Vector& l = problem.l();
  const Vector& u = problem.u();
  const int n = problem.size();
  const int f = static_cast<int>(std::count(ws.kind.begin(), ws.kind.begin() + n, kFree));
  int c = 0, num_box = 0;
  for (int i = 0; i < n; ++i) {
    const signed char k = ws.kind[i];
    if (k == kFixed || (k == kFree && mode == FreeMode::kSchur)) continue;
    ws.core[c++] = i;
    num_box += k == kBox;
  }
  Ensure(&ws.Mc, size_t(c) * c);
  Ensure(&ws.qc, c);
  for (int a = 0; a < c; ++a) {
    const int i = ws.core[a];
    ws.qc[a] = ws.qhat[i];
    for (int b = 0; b < c; ++b) ws.Mc[size_t(a) * c + b] = M(i, ws.core[b]);
  }
  if (mode == FreeMode::kSchur) {  // M_C −= M_CF G, q_C −= M_CF g with G = A⁻¹M_FC, g = A⁻¹q̂_F
    Ensure(&ws.G, size_t(f) * c);
    for (int k = 0; k < f; ++k) {
      const int i = ws.free_rows[k];
      ws.g[k] = ws.qhat[i];
      for (int b = 0; b < c; ++b) ws.G[size_t(k) * c + b] = M(i, ws.core[b]);
    }
    if (c > 0) dense_lu::SolveRows(ws.lu.data(), f, f, ws.lu_perm.data(), ws.G.data(), c);
    dense_lu::SolveRows(ws.lu.data(), f, f, ws.lu_perm.data(), ws.g.data(), 1);
    for (int a = 0; a < c; ++a) {
      const int i = ws.core[a];
      double* row = ws.Mc.data() + size_t(a) * c;
      for (int k = 0; k < f; ++k) {
        const double m = M(i, ws.free_rows[k]);
        if (m == 0.0) continue;
        const double* gk = ws.G.data() + size_t(k) * c;
        for (int b = 0; b < c; ++b) row[b] -= m * gk[b];
        ws.qc[a] -= m * ws.g[k];
      }
    }
  }

  Ensure(&ws.slot_core, 2 * size_t(c));
  Ensure(&ws.slot_sign, 2 * size_t(c));
  Ensure(&ws.slot_y, 2 * size_t(c));
  Ensure(&ws.var_free, 4 * size_t(c) + 2 * size_t(num_box) + 1);
  int nx = 0;
  for (int a = 0; a < c; ++a) {
    const signed char k = ws.kind[ws.core[a]];
    if (k != kUpper) ws.slot_core[nx] = a, ws.slot_sign[nx] = 1.0, ws.slot_y[nx++] = -1;
    if (k == kUpper || (k == kFree && mode == FreeMode::kSplit)) {
      ws.slot_core[nx] = a, ws.slot_sign[nx] = -1.0, ws.slot_y[nx++] = -1;
    }
  }
  const int p = nx + num_box;
  const size_t pp = size_t(p) * p;
  Ensure(&ws.N, pp);
  Ensure(&ws.binv, pp);
  for (std::vector<double>* v : {&ws.r, &ws.d, &ws.beta, &ws.col, &ws.col2, &ws.tmp}) Ensure(v, p);
  for (std::vector<int>* v : {&ws.basis, &ws.ties, &ws.mark, &ws.y_owner}) Ensure(v, p);
  Ensure(&ws.where, 2 * size_t(p) + 1);
  Ensure(&ws.xcore, c);
  std::fill(ws.N.begin(), ws.N.begin() + pp, 0.0);
  std::fill(ws.var_free.begin(), ws.var_free.begin() + 2 * p + 1, 0);
  int ny = nx;
  for (int a = 0; a < nx; ++a) {
    const int ca = ws.slot_core[a];
    const double sa = ws.slot_sign[a];
    ws.r[a] = sa * ws.qc[ca];
    for (int b = 0; b < nx; ++b) {
      ws.N[size_t(b) * p + a] = sa * ws.slot_sign[b] * ws.Mc[size_t(ca) * c + ws.slot_core[b]];
    }
    const int orig = ws.core[ca];
    if (ws.kind[orig] == kFree && mode == FreeMode::kBasic) ws.var_free[p + a] = 1;
    if (ws.kind[orig] == kBox) {
      const int y = ny++;
      ws.slot_y[a] = y;
      ws.y_owner[y] = a;
      ws.N[size_t(y) * p + a] = 1.0;   // x-row: M z + q + y
      ws.N[size_t(a) * p + y] = -1.0;  // y-row: (u − l) − x
      ws.r[y] = u[orig] - l[orig];
    }
  }
  for (int i = 0; i < p; ++i) {
    double di = 1.0;
    if (covering == LemkeOptions::Covering::kRowScaled) {
      double m = 0.0;
      for (int j = 0; j < p; ++j) m = std::max(m, std::abs(ws.N[size_t(j) * p + i]));
      if (m > 0.0) di = m;
    }
    ws.d[i] = di;
  }
  *c_out = c;
  *nx_out = nx;
  return p;
}

// ---------------------------------------------------------------------------------------------------------------
// The phases of LemkeSolver::DoSolve, in the order it runs them: classify rows, reduce free rows, the pivot path
// (with the free-variable start and its split fallback), recover z, polish, report.

// One solve's state, handed from phase to phase.
struct LemkeRun {
  LemkeRun(const BoxMLCP& p, const SolverOptions& o, const LemkeOptions& lo, Workspace& w, Vector& zr)
      : problem(p), options(o), lemke(lo), ws(w), z(zr) {}
  const BoxMLCP& problem;
  const SolverOptions& options;
  const LemkeOptions& lemke;
  Workspace& ws;
  Vector& z;
  int n = 0;  // rows of the problem
  int f = 0;  // free rows (both bounds infinite)
  FreeMode mode = FreeMode::kNone;
  double rcond = std::numeric_limits<double>::quiet_NaN();  // of the free block, when a Schur complement was tried
  int c = 0, nx = 0, p = 0;                                 // core rows, x slots, LCP size
  int pivot_budget = 0;  // SolverOptions::max_iterations if positive, else 0 (the default, which needs p)
  int pivots = 0, reinversions = 0, max_pivots = 0;
  const char* failure = nullptr;  // why the path stopped, for kNumericalFailure / kSingular
  double z0_value = 0.0;          // the artificial variable where the path stopped
  bool z0_exit = false;           // accepted at a negligible z₀ (exit_residual is then the answer's residual)
  bool polished = false;          // the polish replaced z
  bool split_fallback = false;    // the free-variable start failed and the split took over
  Residual exit_residual;
};

// 1. Classifies every row by its bounds, sets the base point z̄ and q̂ = q + M z̄; lists the free rows in run->f.
void ClassifyRows(LemkeRun* run) {
  Workspace& ws = run->ws;
  const Vector& q = run->problem.q();
  const Vector& l = run->problem.l();
  const Vector& u = run->problem.u();
  const DenseMatrix& M = run->problem.dense_matrix();  // info().sparse is false: the base class refuses sparse M
  const int n = run->n;
  Ensure(&ws.kind, n);
  Ensure(&ws.zbar, n);
  Ensure(&ws.qhat, n);
  Ensure(&ws.core, n);
  Ensure(&ws.free_rows, n);
  int f = 0;
  for (int i = 0; i < n; ++i) {
    const bool lo = l[i] > -kInf, up = u[i] < kInf;
    signed char k;
    double zb = 0.0;
    if (lo && up) {
      k = l[i] == u[i] ? kFixed : kBox, zb = l[i];
    } else if (lo) {
      k = kLower, zb = l[i];
    } else if (up) {
      k = kUpper, zb = u[i];
    } else {
      k = kFree;
      ws.free_rows[f++] = i;
    }
    ws.kind[i] = k;
    ws.zbar[i] = zb;
    ws.qhat[i] = q[i];
  }
  for (int j = 0; j < n; ++j) {
    const double zb = ws.zbar[j];
    if (zb == 0.0) continue;
    const double* mj = M.data() + size_t(j) * n;
    for (int i = 0; i < n; ++i) ws.qhat[i] += zb * mj[i];
  }
  run->f = f;
}

// 2. Chooses how the free rows enter the LCP: a Schur complement when the free block is well conditioned (its LU
// stays in ws for BuildLcp and Recover), else kept basic, else split. False, with result set to kSingular, when
// the method is Schur only and the block is singular or ill-conditioned.
bool ReduceFreeRows(LemkeRun* run, SolveResult* result) {
  using FreeRows = LemkeOptions::FreeRows;
  const int f = run->f;
  if (f == 0) return true;
  const FreeRows method = run->lemke.free_row_method;
  run->mode = method == FreeRows::kSplit ? FreeMode::kSplit : FreeMode::kBasic;
  if (method != FreeRows::kAutomatic && method != FreeRows::kSchur) return true;
  Workspace& ws = run->ws;
  const DenseMatrix& M = run->problem.dense_matrix();
  Ensure(&ws.lu, size_t(f) * f);
  Ensure(&ws.lu_perm, f);
  Ensure(&ws.g, f);
  Ensure(&ws.hager_x, f);
  Ensure(&ws.hager_y, f);
  double anorm1 = 0.0;
  for (int b = 0; b < f; ++b) {
    double colsum = 0.0;
    for (int a = 0; a < f; ++a) {
      const double v = M(ws.free_rows[a], ws.free_rows[b]);
      ws.lu[a + size_t(b) * f] = v;
      colsum += std::abs(v);
    }
    anorm1 = std::max(anorm1, colsum);
  }
  run->rcond = 0.0;
  if (dense_lu::FactorRelative(ws.lu.data(), f, f, ws.lu_perm.data())) {
    run->rcond = 1.0 / (anorm1 * dense_lu::InverseNorm1Estimate(ws.lu.data(), f, f, ws.lu_perm.data(),
                                                                ws.hager_x.data(), ws.hager_y.data()));
  }
  if (run->rcond >= run->lemke.free_block_min_rcond) {
    run->mode = FreeMode::kSchur;
  } else if (method == FreeRows::kSchur) {
    result->status = SolveStatus::kSingular;
    Append(&result->message, "the free block M_FF is singular or ill-conditioned (rcond estimate %.3e < %.3e); "
           "free_row_method = auto or basic keeps the free variables basic instead", run->rcond,
           run->lemke.free_block_min_rcond);
    result->SetDetail("free_block_rcond", run->rcond);
    return false;
  }
  return true;
}

// Back to z: x from the basis (z₀ ignored), z_C = z̄_C + S x clipped to the box, z_F from the Schur relation.
void Recover(LemkeRun* run, bool have_basis) {
  Workspace& ws = run->ws;
  const Vector& l = run->problem.l();
  const Vector& u = run->problem.u();
  Vector& z = run->z;
  const int c = run->c, p = run->p;
  std::fill(ws.xcore.begin(), ws.xcore.begin() + c, 0.0);
  if (have_basis) {
    for (int a = 0; a < run->nx; ++a) {
      const int row = ws.where[p + a];
      if (row >= 0) ws.xcore[ws.slot_core[a]] += ws.slot_sign[a] * ws.beta[row];
    }
  }
  for (int i = 0; i < run->n; ++i) {
    if (ws.kind[i] == kFixed) z[i] = l[i];
  }
  for (int a = 0; a < c; ++a) {
    const int i = ws.core[a];
    z[i] = std::min(std::max(ws.zbar[i] + ws.xcore[a], l[i]), u[i]);
    ws.xcore[a] = z[i] - ws.zbar[i];
  }
  if (run->mode == FreeMode::kSchur) {
    for (int k = 0; k < run->f; ++k) {
      double s = ws.g[k];
      const double* gk = ws.G.data() + size_t(k) * c;
      for (int b = 0; b < c; ++b) s += gk[b] * ws.xcore[b];
      z[ws.free_rows[k]] = -s;
    }
  }
}

// Where a row sits in the polish's active set (the kernel's states, active_set.h): free rows are the set E solved
// for, fixed rows are pinned and never switch.
constexpr signed char kInE = static_cast<signed char>(RowState::kFree);
constexpr signed char kAtLower = static_cast<signed char>(RowState::kLower);
constexpr signed char kAtUpper = static_cast<signed char>(RowState::kUpper);
constexpr signed char kPinned = static_cast<signed char>(RowState::kFixed);

// The polish's first active set: from the final basis (x basic: in E; y basic: at u; else at its base bound).
void ActiveSetOfBasis(const LemkeRun& run, signed char* state) {
  const Workspace& ws = run.ws;
  for (int i = 0; i < run.n; ++i) state[i] = ws.kind[i] == kFixed ? kPinned : ws.kind[i] == kFree ? kInE : kAtLower;
  for (int a = 0; a < run.nx && run.p > 0; ++a) {
    const int i = ws.core[ws.slot_core[a]];
    const signed char k = ws.kind[i];
    if (k == kFree) continue;
    const bool x_basic = ws.where[run.p + a] >= 0;
    const bool y_basic = ws.slot_y[a] >= 0 && ws.where[run.p + ws.slot_y[a]] >= 0;
    state[i] = y_basic ? kAtUpper : x_basic ? kInE : k == kUpper ? kAtUpper : kAtLower;
  }
}

// Solves M_EE z_E = −(q_E + M_EN z_N) in ws.z_polish for the rows E in state kInE (LU of M_EE, one refinement step
// in the original data). False if M_EE is numerically singular.
bool SolveActiveRows(LemkeRun* run, const signed char* state) {
  Workspace& ws = run->ws;
  const BoxMLCP& problem = run->problem;
  const DenseMatrix& M = problem.dense_matrix();
  const Vector& l = problem.l();
  const Vector& u = problem.u();
  const int e =
      active_set::PlaceBoundRows(run->n, state, l.data(), u.data(), ws.z_polish.data(), ws.active_list.data());
  Ensure(&ws.active_lu, size_t(e) * e);
  Ensure(&ws.active_perm, e);
  Ensure(&ws.active_res, e);
  if (e == 0) return true;
  const int* E = ws.active_list.data();
  // The right-hand side from Eigen's product in the original data, and a row-oriented solve with one refinement
  // step: lemke's own answers (the kernel's column sums and substitutions round differently).
  problem.Affine(ws.z_polish, &ws.w);  // with z_E = 0: w_E = q_E + M_EN z_N
  for (int a = 0; a < e; ++a) ws.active_res[a] = -ws.w[E[a]];
  active_set::GatherFreeBlock(M.data(), run->n, E, e, ws.active_lu.data(), e);
  if (!dense_lu::FactorRelative(ws.active_lu.data(), e, e, ws.active_perm.data())) return false;
  dense_lu::SolveRows(ws.active_lu.data(), e, e, ws.active_perm.data(), ws.active_res.data(), 1);
  for (int a = 0; a < e; ++a) ws.z_polish[E[a]] = ws.active_res[a];
  // One refinement step in the original data: −w_E = rhs − M_EE z_E, solved again.
  problem.Affine(ws.z_polish, &ws.w);
  for (int a = 0; a < e; ++a) ws.active_res[a] = -ws.w[E[a]];
  dense_lu::SolveRows(ws.active_lu.data(), e, e, ws.active_perm.data(), ws.active_res.data(), 1);
  for (int a = 0; a < e; ++a) ws.z_polish[E[a]] += ws.active_res[a];
  return true;
}

// Polish, for when rounding leaves the merit function above the tolerance (an ill-conditioned reduction, or a
// base-point shift M·l much larger than q). The active set of the final basis is solved in the original variables;
// rows whose result leaves the box, or whose pinned w has the wrong sign, then switch sides, for at most
// kPolishRounds rounds (primal-dual active-set steps started from Lemke's answer, Hintermüller, Ito & Kunisch
// 2002). The best point replaces z if it beats the current one; returns its residual.
Residual PolishActiveSet(LemkeRun* run, Residual current) {
  constexpr int kPolishRounds = 5;
  Workspace& ws = run->ws;
  const BoxMLCP& problem = run->problem;
  const Vector& l = problem.l();
  const Vector& u = problem.u();
  const int n = run->n;
  Ensure(&ws.active, n);
  Ensure(&ws.active_list, n);
  signed char* state = ws.active.data();
  ActiveSetOfBasis(*run, state);
  if (ws.z_polish.size() != n) ws.z_polish.resize(n);
  Residual best = current;
  for (int round = 0; round < kPolishRounds; ++round) {
    if (!SolveActiveRows(run, state)) break;
    // Next active set, judged on the unclipped point: E rows outside the box go to the bound they cross,
    // pinned rows whose w pushes into the box join E.
    problem.Affine(ws.z_polish, &ws.w);
    bool changed = false;
    for (int i = 0; i < n; ++i) {
      const double zi = ws.z_polish[i], wi = ws.w[i];
      if (state[i] == kInE && zi < l[i]) {
        state[i] = kAtLower, changed = true;
      } else if (state[i] == kInE && zi > u[i]) {
        state[i] = kAtUpper, changed = true;
      } else if ((state[i] == kAtLower && wi < 0.0) || (state[i] == kAtUpper && wi > 0.0)) {
        state[i] = kInE, changed = true;
      }
      ws.z_polish[i] = std::min(std::max(zi, l[i]), u[i]);
    }
    const Residual r = problem.NaturalResidual(ws.z_polish, &ws.w);
    if (Worst(r) < Worst(best)) {
      run->z = ws.z_polish;
      best = r;
      run->polished = true;
    }
    if (PassesBoxMlcpTolerance(best, run->options.tolerance) || !changed) break;
  }
  return best;
}

// The first pivot: z₀ enters at the level that makes every sign-constrained basic variable nonnegative. With
// c = B⁻¹d this is the lexicographic minimum of [β_i, B⁻¹_i·]/c_i, the same test as later (for B = I, d = e: the
// largest index among the most negative r_i). Returns the variable that left, or −1 (run->failure set).
int EnterArtificial(LemkeRun* run, Engine& engine) {
  Workspace& ws = run->ws;
  const int p = run->p;
  engine.Column(engine.z0());
  double cmax = 0.0;
  for (int i = 0; i < p; ++i) ws.col[i] = -ws.col[i], cmax = std::max(cmax, std::abs(ws.col[i]));
  const int r0 = engine.RatioTest(run->lemke.pivot_tolerance * cmax, /*clamp=*/false);
  for (int i = 0; i < p; ++i) ws.col[i] = -ws.col[i];
  if (r0 < 0) {
    run->failure = "the covering direction does not reach the infeasible rows";
    return -1;
  }
  const int leaving = ws.basis[r0];
  engine.Pivot(r0, engine.z0());
  ++run->pivots;
  return leaving;
}

// Recomputes B⁻¹ every refactor interval. False (run->failure set) when the basis became singular or lost
// feasibility; rounding that left degenerate basic values at −1e-17 is cleared.
bool ReinvertChecked(LemkeRun* run, Engine& engine) {
  Workspace& ws = run->ws;
  const int p = run->p;
  ++run->reinversions;
  if (!engine.Reinvert()) {
    run->failure = "the basis became numerically singular at a reinversion";
    return false;
  }
  double bmax = 0.0, bmin = 0.0;
  for (int i = 0; i < p; ++i) {
    if (engine.FreeRow(i)) continue;
    bmax = std::max(bmax, std::abs(ws.beta[i]));
    bmin = std::min(bmin, ws.beta[i]);
  }
  if (bmin < -1e-6 * (1.0 + bmax)) {
    run->failure = "the basis lost feasibility at a reinversion (ill-conditioned basis)";
    return false;
  }
  for (int i = 0; i < p; ++i) {
    if (!engine.FreeRow(i)) ws.beta[i] = std::max(ws.beta[i], 0.0);
  }
  return true;
}

// Once z₀ is negligible, the almost-complementary point without it: accepted (run->z0_exit) only if the merit
// function says it solves the problem, which includes every sign condition (w ≥ 0 on rows at l, ≤ 0 at u) to
// tol·(1 + ‖z‖∞) in units of z. A point that misses only by rounding is polished, at most three times per solve
// (a degenerate stretch may keep z₀ tiny for long).
bool AcceptWithoutArtificial(LemkeRun* run, double dmax, int* exit_polishes) {
  const double tolerance = run->options.tolerance;
  Recover(run, true);
  run->exit_residual = run->problem.NaturalResidual(run->z, &run->ws.w);
  const bool negligible_in_z = run->z0_value * dmax <= tolerance * (1.0 + run->z.cwiseAbs().maxCoeff());
  if (!PassesBoxMlcpTolerance(run->exit_residual, tolerance) && negligible_in_z && *exit_polishes < 3) {
    ++*exit_polishes;
    run->exit_residual = PolishActiveSet(run, run->exit_residual);
  }
  run->z0_exit = PassesBoxMlcpTolerance(run->exit_residual, tolerance);
  return run->z0_exit;
}

// One verbosity-2 line per pivot.
void TracePivot(const LemkeRun& run, const Engine& engine, int entering, int leaving, int row, double cmax) {
  const int p = run.p;
  const Workspace& ws = run.ws;
  double bmin = 0.0;
  for (int i = 0; i < p; ++i) {
    if (!engine.FreeRow(i)) bmin = std::min(bmin, ws.beta[i]);
  }
  const char* out = leaving == engine.z0() ? "z" : leaving < p ? "w" : "x";
  std::fprintf(stderr, "lemke: pivot %d: in %c%d, out %s%d, z0 = %.6e, pivot %.2e (relative %.2e), min basic %.2e\n",
               run.pivots + 1, entering < p ? 'w' : 'x', entering % p, out, leaving == engine.z0() ? 0 : leaving % p,
               run.z0_value, ws.col[row], ws.col[row] / cmax, bmin);
}

// 3. Lemke's complementary path from the start basis in engine, until z₀ leaves (or is negligible), a secondary
// ray, the pivot or time budget, or a numerical failure.
template <typename TimeUp>
SolveStatus PivotPath(LemkeRun* run, Engine& engine, const TimeUp& time_up) {
  Workspace& ws = run->ws;
  const int p = run->p;
  bool feasible = true;
  for (int i = 0; i < p; ++i) feasible = feasible && (engine.FreeRow(i) || ws.beta[i] >= 0.0);
  if (feasible) return SolveStatus::kSolved;  // the start basis already solves the LCP
  int leaving = EnterArtificial(run, engine);
  if (leaving < 0) return SolveStatus::kNumericalFailure;
  const int refactor = run->lemke.refactor_interval > 0 ? run->lemke.refactor_interval : std::max(64, p);
  double dmax = 0.0;
  for (int i = 0; i < p; ++i) dmax = std::max(dmax, std::abs(ws.d[i]));
  // Dropping z₀ moves w (of the equilibrated problem: units of z) by up to z₀·‖d‖∞, so the point without z₀ can
  // only pass the merit function once z₀·‖d‖∞ is within its tolerance: tol·(1 + ‖q‖∞) for the relative residual
  // (a cheap first filter) and tol·(1 + ‖z‖∞) for the residual in units of z (checked on the recovered z).
  const double z0_negligible = run->options.tolerance * run->problem.residual_scale() / dmax;
  int exit_polishes = 0;
  while (true) {
    const int entering = engine.Complement(leaving);
    run->z0_value = ws.beta[ws.where[engine.z0()]];
    if (run->z0_value <= z0_negligible && AcceptWithoutArtificial(run, dmax, &exit_polishes)) {
      return SolveStatus::kSolved;
    }
    if (run->pivots >= run->max_pivots) return SolveStatus::kIterationLimit;
    if ((run->pivots & 31) == 0 && time_up()) return SolveStatus::kTimeLimit;
    engine.Column(entering);
    double cmax = 0.0;
    bool finite = true;
    for (int i = 0; i < p; ++i) {
      cmax = std::max(cmax, std::abs(ws.col[i]));
      finite = finite && std::isfinite(ws.col[i]) && std::isfinite(ws.beta[i]);
    }
    if (!finite) {
      run->failure = "NaN or Inf in the basis inverse";
      return SolveStatus::kNumericalFailure;
    }
    const int row = cmax > 0.0 ? engine.RatioTest(run->lemke.pivot_tolerance * cmax) : -1;
    if (row < 0) return SolveStatus::kRayTermination;
    leaving = ws.basis[row];
    if (run->options.verbosity > 1) TracePivot(*run, engine, entering, leaving, row, cmax);
    engine.Pivot(row, entering);
    ++run->pivots;
    if (leaving == engine.z0()) return SolveStatus::kSolved;  // complementary basis
    if (run->pivots % refactor == 0 && !ReinvertChecked(run, engine)) return SolveStatus::kNumericalFailure;
  }
}

// Builds the LCP and runs the path; with free variables kept basic, pivots them into the start basis first. In
// automatic mode a failed free-variable start (dependent free columns) falls back to the split.
template <typename TimeUp>
SolveStatus BuildAndPivot(LemkeRun* run, const TimeUp& time_up) {
  Workspace& ws = run->ws;
  for (int attempt = 0; attempt < 2; ++attempt) {
    run->p = BuildLcp(run->problem, run->mode, run->lemke.covering_vector, &ws, &run->c, &run->nx);
    run->max_pivots = run->pivot_budget > 0 ? run->pivot_budget : std::max(kLemkeDefaultMinPivots, 50 * run->p);
    if (run->p == 0) return SolveStatus::kSolved;
    Engine engine(&ws, run->p, run->nx, ws.y_owner.data());
    engine.SlackBasis();
    if (run->mode == FreeMode::kBasic) {
      if (!engine.BringFreeVariablesIn(&run->pivots)) {
        if (run->lemke.free_row_method == LemkeOptions::FreeRows::kAutomatic) {
          run->mode = FreeMode::kSplit;
          run->split_fallback = true;
          continue;
        }
        run->failure = "the free columns are linearly dependent: no complementary basis holds every free variable";
        return SolveStatus::kSingular;
      }
      engine.CoverFromBasis();
    }
    return PivotPath(run, engine, time_up);
  }
  return SolveStatus::kSolved;  // not reached: the split always builds
}

// The message of an unsolved result: why the method stopped, with z₀ and the residual where it did.
std::string FailureMessage(const LemkeRun& run, SolveStatus status, const char* exists, const Residual& res) {
  const std::string pivots = std::to_string(run.pivots);
  std::string msg;
  switch (status) {
    case SolveStatus::kRayTermination:
      msg = "Lemke's method ended on a secondary ray after " + pivots +
            " pivots (the entering column has no blocking row): no solution found by this method";
      Append(&msg, " (z0 = %.3e, residual %.3e)", run.z0_value, Worst(res));
      msg += "; this proves infeasibility only for a copositive-plus M in exact arithmetic, which was not checked";
      if (run.mode == FreeMode::kSplit || run.mode == FreeMode::kBasic) {
        msg += std::string("; free rows handled by the ") + FreeModeName(run.mode) + " method";
        if (run.split_fallback) msg += " (the free columns are dependent)";
      }
      break;
    case SolveStatus::kIterationLimit:
      msg = "pivot limit " + std::to_string(run.max_pivots) + " reached";
      Append(&msg, " (z0 = %.3e, residual %.3e)", run.z0_value, Worst(res));
      break;
    case SolveStatus::kTimeLimit:
      msg = "time limit reached after " + pivots + " pivots";
      Append(&msg, " (residual %.3e)", Worst(res));
      break;
    default:
      if (exists) {
        msg = std::string("a solution exists (") + exists + ") but Lemke's method failed: it ended on a secondary "
              "ray after " + pivots + " pivots";
        Append(&msg, " (z0 = %.3e, residual %.3e)", run.z0_value, Worst(res));
        break;
      }
      msg = std::string(run.failure ? run.failure : "numerical failure") + " after " + pivots + " pivots";
      Append(&msg, " (residual %.3e)", Worst(res));
      break;
  }
  return msg;
}

// Status, iterations, details and message of the result.
void Report(const LemkeRun& run, SolveStatus status, const char* exists, const Residual& res, SolveResult* result) {
  result->status = status;
  result->iterations = run.pivots;
  // Details (few, since each costs a name search): the optional ones only when they carry information.
  result->SetDetail("lcp_size", run.p);
  result->SetDetail("reinversions", run.reinversions);
  if (run.f > 0) {
    kFreeRowModeDetail.Set(result, FreeRowsUsed(run.mode));
    const LemkeOptions::FreeRows method = run.lemke.free_row_method;
    if (method == LemkeOptions::FreeRows::kAutomatic || method == LemkeOptions::FreeRows::kSchur) {
      result->SetDetail("free_block_rcond", run.rcond);
    }
  }
  if (run.polished) result->SetDetail("polished", 1.0);
  if (run.z0_exit) result->SetDetail("z0_negligible_exit", 1.0);
  if (status != SolveStatus::kSolved) result->message = FailureMessage(run, status, exists, res);
  if (run.options.verbosity > 0) {
    std::fprintf(stderr, "lemke: n = %d, LCP size %d, %d free rows (%s), %d pivots, %d reinversions%s: %s %s\n", run.n,
                 run.p, run.f, FreeModeName(run.mode), run.pivots, run.reinversions, run.polished ? ", polished" : "",
                 std::string(ToString(status)).c_str(), result->message.c_str());
  }
}

}  // namespace

std::string_view ToString(LemkeOptions::Covering covering) {
  switch (covering) {
    case LemkeOptions::Covering::kOnes: return "ones";
    case LemkeOptions::Covering::kRowScaled: return "row-scaled";
  }
  return "?";
}

std::string_view ToString(LemkeOptions::FreeRows method) {
  switch (method) {
    case LemkeOptions::FreeRows::kAutomatic: return "auto";
    case LemkeOptions::FreeRows::kSchur: return "schur";
    case LemkeOptions::FreeRows::kBasic: return "basic";
    case LemkeOptions::FreeRows::kSplit: return "split";
  }
  return "?";
}

std::optional<LemkeOptions::FreeRows> FreeRowsFromString(std::string_view name) {
  using FreeRows = LemkeOptions::FreeRows;
  for (const FreeRows method : {FreeRows::kAutomatic, FreeRows::kSchur, FreeRows::kBasic, FreeRows::kSplit}) {
    if (ToString(method) == name) return method;
  }
  return std::nullopt;
}

bool LemkeOptions::IsValid(std::string* why) const {
  // Cheap checks first: this runs on every solve, the message is only built on failure.
  const int covering = static_cast<int>(covering_vector), method = static_cast<int>(free_row_method);
  const bool ok = pivot_tolerance > 0.0 && pivot_tolerance <= 1e-3 && (covering == 0 || covering == 1) &&
                  refactor_interval >= 0 && free_block_min_rcond >= 0.0 && free_block_min_rcond < 1.0 &&
                  method >= 0 && method <= 3;
  if (ok) return true;
  std::ostringstream s;
  if (!(pivot_tolerance > 0.0 && pivot_tolerance <= 1e-3)) {
    s << "pivot_tolerance must be in (0, 1e-3], got " << pivot_tolerance;
  } else if (covering != 0 && covering != 1) {
    s << "covering_vector must be ones or row-scaled, got the code " << covering;
  } else if (refactor_interval < 0) {
    s << "refactor_interval must be >= 0 (0 = automatic), got " << refactor_interval;
  } else if (!(free_block_min_rcond >= 0.0 && free_block_min_rcond < 1.0)) {
    s << "free_block_min_rcond must be in [0, 1), got " << free_block_min_rcond;
  } else {
    s << "free_row_method must be auto, schur, basic or split, got the code " << method;
  }
  if (why) *why = s.str();
  return false;
}

const SolverInfo& LemkeSolver::info() const {
  static const SolverInfo kInfo{
      "lemke",
      "Lemke complementary pivoting (covering vector e, lexicographic ratio test, explicit basis inverse with "
      "periodic reinversion) on the exact LCP reduction of the box-MLCP (bound shifts, [[M,I],[-I,0]] split of "
      "box rows, free rows by Schur complement or kept basic); warm start ignored",
      "C.E. Lemke, Bimatrix equilibrium points and mathematical programming, Management Science 11 (1965); "
      "R.W. Cottle, J.-S. Pang, R.E. Stone, The Linear Complementarity Problem (1992), ch. 4 (lexicographic rule); "
      "box-to-LCP split as in V. Acary, B. Brogliato, Numerical Methods for Nonsmooth Dynamical Systems (2008)",
      /*dense=*/true,
      /*sparse=*/false,
      /*symmetric_only=*/false,
      /*exact=*/true,
      /*mcp=*/false,
      /*default_size_limit=*/0};
  return kInfo;
}

void LemkeSolver::BindOptions(OptionBinder* binder) {
  using Covering = LemkeOptions::Covering;
  using FreeRows = LemkeOptions::FreeRows;
  binder->Add("pivot_tolerance", &options_.pivot_tolerance,
              "pivot candidates need c_i > pivot_tolerance * max|c| (relative)");
  // Both choice options were integer-coded: their old numbers are still read (the name lists after the choices).
  binder->Add("covering_vector", &options_.covering_vector,
              {{"ones", static_cast<int>(Covering::kOnes)}, {"row-scaled", static_cast<int>(Covering::kRowScaled)}},
              {"ones", "row-scaled"}, "ones: d = e; row-scaled: d_i = max_j |N_ij|");
  binder->Add("refactor_interval", &options_.refactor_interval,
              "recompute the basis inverse every this many pivots (0 = max(64, LCP size))");
  binder->Add("free_block_min_rcond", &options_.free_block_min_rcond,
              "Schur-eliminate free rows only if the rcond estimate of M_FF is at least this");
  binder->Add("free_row_method", &options_.free_row_method,
              {{"auto", static_cast<int>(FreeRows::kAutomatic)},
               {"schur", static_cast<int>(FreeRows::kSchur)},
               {"basic", static_cast<int>(FreeRows::kBasic)},
               {"split", static_cast<int>(FreeRows::kSplit)}},
              {"auto", "schur", "basic", "split"},
              "free rows: auto (Schur, else basic, else split), schur, basic (free variables kept basic), split "
              "(x+ - x-)");
}

bool LemkeSolver::ValidateBackendOptions(std::string* why) const { return options_.IsValid(why); }

// The phases in order; each is a function above.
void LemkeSolver::DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) {
  LemkeRun run(problem, options, options_, ws_, result->z);
  run.n = problem.size();
  run.pivot_budget = IterationBudget(options, 0);
  ClassifyRows(&run);
  if (!ReduceFreeRows(&run, result)) return;
  SolveStatus status = BuildAndPivot(&run, [this] { return TimeLimitReached(); });

  Residual res;
  if (run.z0_exit) {
    res = run.exit_residual;
  } else {
    Recover(&run, run.p > 0 && status != SolveStatus::kSingular);
    res = problem.NaturalResidual(run.z, &ws_.w);
  }
  // The pivots accumulate rounding of order ε·max|β|, and β holds q̂ (a huge multiplier on one row, a base-point
  // shift M·l): an answer that is not at the rounding level in units of z has its active set solved again.
  const double rounding_level = 1e3 * run.n * kEps;
  if (status == SolveStatus::kSolved &&
      !(PassesBoxMlcpTolerance(res, options.tolerance) && res.scaled <= rounding_level)) {
    res = PolishActiveSet(&run, res);
  }
  if (status == SolveStatus::kSolved && !std::isfinite(res.abs)) {
    status = SolveStatus::kNumericalFailure;
    run.failure = "the solution contains NaN or Inf";
  }
  // The merit function decides: wherever the method stopped, a point it accepts is a solution.
  if (status != SolveStatus::kSolved && PassesBoxMlcpTolerance(res, options.tolerance)) {
    status = SolveStatus::kSolved;
  }
  // A secondary ray is no verdict on the problem (in floating point not even for copositive-plus M): on a problem
  // known to have a solution it is a failure of the method.
  const char* exists = status == SolveStatus::kRayTermination ? SolutionExistsReason(problem) : nullptr;
  if (exists) status = SolveStatus::kNumericalFailure;
  Report(run, status, exists, res, result);
}

}  // namespace smcbench

// Lemke's method with lexicographic degeneracy resolution on the LCP reduction of a box-MLCP. The reduction
// (bound shifts, sign flips, the [[M, I], [−I, 0]] multiplier split of box rows; free rows by Schur complement,
// kept basic, or split x⁺ − x⁻) and the numerical safeguards are documented at the top of lemke_solver.h.
#include "solvers/lemke/lemke_solver.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

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
// Dense LU with partial pivoting on a row-major f×f array (PA = LU), used for the free block. Own code rather than
// Eigen::PartialPivLU so that the factorization, the solves and the condition estimate run in preallocated storage.

// Returns false if a pivot is below f·ε·max|A| (numerically singular).
bool LuFactor(double* a, int f, int* perm) {
  double amax = 0.0;
  for (int i = 0; i < f * f; ++i) amax = std::max(amax, std::abs(a[i]));
  const double tiny = std::max(f, 1) * kEps * amax;
  if (!(amax > 0.0)) return false;
  for (int k = 0; k < f; ++k) {
    int piv = k;
    double best = std::abs(a[k * f + k]);
    for (int i = k + 1; i < f; ++i) {
      const double v = std::abs(a[i * f + k]);
      if (v > best) best = v, piv = i;
    }
    perm[k] = piv;
    if (!(best > tiny)) return false;
    if (piv != k) std::swap_ranges(a + k * f, a + (k + 1) * f, a + piv * f);
    const double inv = 1.0 / a[k * f + k];
    const double* rk = a + k * f;
    for (int i = k + 1; i < f; ++i) {
      double* ri = a + i * f;
      const double l = (ri[k] *= inv);
      if (l == 0.0) continue;
      for (int j = k + 1; j < f; ++j) ri[j] -= l * rk[j];
    }
  }
  return true;
}

// Solves A X = B in place for a row-major f×m right-hand side B (m = 1: a vector).
void LuSolveRows(const double* lu, int f, const int* perm, double* b, int m) {
  for (int k = 0; k < f; ++k) {
    if (perm[k] != k) std::swap_ranges(b + k * m, b + (k + 1) * m, b + perm[k] * m);
  }
  for (int i = 1; i < f; ++i) {  // L (unit diagonal)
    double* bi = b + i * m;
    for (int k = 0; k < i; ++k) {
      const double l = lu[i * f + k];
      if (l == 0.0) continue;
      const double* bk = b + k * m;
      for (int j = 0; j < m; ++j) bi[j] -= l * bk[j];
    }
  }
  for (int i = f - 1; i >= 0; --i) {  // U
    double* bi = b + i * m;
    for (int k = i + 1; k < f; ++k) {
      const double u = lu[i * f + k];
      if (u == 0.0) continue;
      const double* bk = b + k * m;
      for (int j = 0; j < m; ++j) bi[j] -= u * bk[j];
    }
    const double inv = 1.0 / lu[i * f + i];
    for (int j = 0; j < m; ++j) bi[j] *= inv;
  }
}

// Solves Aᵀ x = b in place: Aᵀ = Uᵀ Lᵀ P.
void LuSolveTransposed(const double* lu, int f, const int* perm, double* b) {
  for (int i = 0; i < f; ++i) {  // Uᵀ t = b
    double s = b[i];
    for (int k = 0; k < i; ++k) s -= lu[k * f + i] * b[k];
    b[i] = s / lu[i * f + i];
  }
  for (int i = f - 1; i >= 0; --i) {  // Lᵀ s = t
    double s = b[i];
    for (int k = i + 1; k < f; ++k) s -= lu[k * f + i] * b[k];
    b[i] = s;
  }
  for (int k = f - 1; k >= 0; --k) {
    if (perm[k] != k) std::swap(b[k], b[perm[k]]);
  }
}

// Hager's estimate of ‖A⁻¹‖₁ (Hager 1984; Higham, Accuracy and Stability of Numerical Algorithms, §15.3), at most
// five solve pairs. A lower bound that is almost always within a small factor of the truth.
double HagerInverseNorm1(const double* lu, int f, const int* perm, double* x, double* y) {
  for (int i = 0; i < f; ++i) x[i] = 1.0 / f;
  double estimate = 0.0;
  int last_j = -1;
  for (int iter = 0; iter < 5; ++iter) {
    std::copy(x, x + f, y);
    LuSolveRows(lu, f, perm, y, 1);
    double norm = 0.0;
    for (int i = 0; i < f; ++i) norm += std::abs(y[i]);
    if (!std::isfinite(norm)) return kInf;
    if (iter > 0 && norm <= estimate) break;
    estimate = norm;
    for (int i = 0; i < f; ++i) y[i] = y[i] >= 0.0 ? 1.0 : -1.0;
    LuSolveTransposed(lu, f, perm, y);
    int j = 0;
    for (int i = 1; i < f; ++i) {
      if (std::abs(y[i]) > std::abs(y[j])) j = i;
    }
    double ztx = 0.0;
    for (int i = 0; i < f; ++i) ztx += y[i] * x[i];
    if (iter > 0 && (std::abs(y[j]) <= ztx || j == last_j)) break;
    last_j = j;
    std::fill(x, x + f, 0.0);
    x[j] = 1.0;
  }
  return estimate;
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

// What "solved" means inside DoSolve: the merit function of the (row-equilibrated) problem it was given, relative
// residual and residual in units of z both within the tolerance, as Solver::Finish requires. The relative one
// alone is blind when ‖q‖ dwarfs the rows (a bound row with a huge multiplier): it let sign violations of order
// tol·‖q‖ through.
bool Passes(const Residual& r, double tolerance) { return r.rel <= tolerance && r.scaled <= tolerance; }
// The larger of the two, for "is this point better" comparisons (NaN-safe: NaN compares as not better).
double Worst(const Residual& r) { return std::max(r.rel, r.scaled); }

// Largest LCP size for which the ray-termination path tests every principal minor (2^n − 1 LU factorizations).
constexpr int kMaxPMatrixTestSize = 12;

// True when every principal minor of the dense n×n M is positive with a margin (each LU pivot of each principal
// submatrix above 1e3·k·ε times its largest entry, so that the sign is not rounding): M is a P-matrix. Only on the
// failure path (a ray): 2^n small factorizations, allocating.
bool IsPMatrix(const DenseMatrix& M) {
  const int n = static_cast<int>(M.rows());
  if (n > kMaxPMatrixTestSize) return false;
  std::vector<double> a(size_t(n) * n);
  std::vector<int> idx(n), perm(n);
  for (unsigned mask = 1; mask < (1u << n); ++mask) {
    int k = 0;
    for (int i = 0; i < n; ++i) {
      if (mask >> i & 1u) idx[k++] = i;
    }
    double amax = 0.0;
    for (int r = 0; r < k; ++r) {
      for (int c = 0; c < k; ++c) {
        a[size_t(r) * k + c] = M(idx[r], idx[c]);
        amax = std::max(amax, std::abs(a[size_t(r) * k + c]));
      }
    }
    if (!LuFactor(a.data(), k, perm.data())) return false;
    double sign = 1.0, pmin = kInf;
    for (int r = 0; r < k; ++r) {
      const double d = a[size_t(r) * k + r];
      sign *= d > 0.0 ? 1.0 : -1.0;
      if (perm[r] != r) sign = -sign;
      pmin = std::min(pmin, std::abs(d));
    }
    if (!(sign > 0.0) || !(pmin > 1e3 * k * kEps * amax)) return false;
  }
  return true;
}

// True when the symmetric part S = (M + Mᵀ)/2 is positive definite with a margin: the Cholesky factorization of
// S − δI, δ = 1e3·n·ε·‖S‖∞, succeeds (rounding in forming and factoring S cannot make it so).
bool SymmetricPartPositiveDefinite(const DenseMatrix& M) {
  const int n = static_cast<int>(M.rows());
  DenseMatrix S = 0.5 * (M + M.transpose());
  const double delta = 1e3 * n * kEps * S.cwiseAbs().rowwise().sum().maxCoeff();
  S.diagonal().array() -= delta;
  Eigen::LLT<DenseMatrix> llt(S);
  return llt.info() == Eigen::Success;
}

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
  if (SymmetricPartPositiveDefinite(M)) return "the symmetric part of M is positive definite";
  if (IsPMatrix(M)) return "M is a P-matrix";
  return nullptr;
}

// Builds LCP(N, r) from the classified rows for the given free-row mode (Schur data already in ws). Returns p and
// sets *nx, the number of x slots (the y slots of the box rows follow them).
int BuildLcp(const BoxMLCP& problem, FreeMode mode, int covering, Workspace* ws_ptr, int* c_out, int* nx_out) {
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
    if (c > 0) LuSolveRows(ws.lu.data(), f, ws.lu_perm.data(), ws.G.data(), c);
    LuSolveRows(ws.lu.data(), f, ws.lu_perm.data(), ws.g.data(), 1);
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
    if (covering == 1) {
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

}  // namespace

bool LemkeOptions::IsValid(std::string* why) const {
  // Cheap checks first: this runs on every solve, the message is only built on failure.
  const bool ok = pivot_tolerance > 0.0 && pivot_tolerance <= 1e-3 && (covering_vector == 0 || covering_vector == 1) &&
                  refactor_interval >= 0 && free_block_min_rcond >= 0.0 && free_block_min_rcond < 1.0 &&
                  free_row_method >= 0 && free_row_method <= 3;
  if (ok) return true;
  std::ostringstream s;
  if (!(pivot_tolerance > 0.0 && pivot_tolerance <= 1e-3)) {
    s << "pivot_tolerance must be in (0, 1e-3], got " << pivot_tolerance;
  } else if (covering_vector != 0 && covering_vector != 1) {
    s << "covering_vector must be 0 (ones) or 1 (row-scaled), got " << covering_vector;
  } else if (refactor_interval < 0) {
    s << "refactor_interval must be >= 0 (0 = automatic), got " << refactor_interval;
  } else if (!(free_block_min_rcond >= 0.0 && free_block_min_rcond < 1.0)) {
    s << "free_block_min_rcond must be in [0, 1), got " << free_block_min_rcond;
  } else {
    s << "free_row_method must be 0 (auto), 1 (Schur), 2 (basic) or 3 (split), got " << free_row_method;
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
  binder->Add("pivot_tolerance", &options_.pivot_tolerance,
              "pivot candidates need c_i > pivot_tolerance * max|c| (relative)");
  binder->Add("covering_vector", &options_.covering_vector, "0 = e (ones), 1 = row infinity norms of N");
  binder->Add("refactor_interval", &options_.refactor_interval,
              "recompute the basis inverse every this many pivots (0 = max(64, LCP size))");
  binder->Add("free_block_min_rcond", &options_.free_block_min_rcond,
              "Schur-eliminate free rows only if the rcond estimate of M_FF is at least this");
  binder->Add("free_row_method", &options_.free_row_method,
              "free rows: 0 auto (Schur, else basic, else split), 1 Schur, 2 basic free variables, 3 x+ - x- split");
}

bool LemkeSolver::ValidateBackendOptions(std::string* why) const { return options_.IsValid(why); }

void LemkeSolver::DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) {
  Workspace& ws = ws_;
  const DenseMatrix& M = problem.dense_matrix();  // info().sparse is false: the base class refuses sparse M
  const Vector& q = problem.q();
  const Vector& l = problem.l();
  const Vector& u = problem.u();
  const int n = problem.size();
  Vector& z = result->z;

  // --- 1. Classify rows, base point z̄, q̂ = q + M z̄. ---
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

  // --- 2. Free rows: Schur complement if the free block is well conditioned, else kept basic, else split. ---
  FreeMode mode = FreeMode::kNone;
  double rcond = std::numeric_limits<double>::quiet_NaN();
  const int method = options_.free_row_method;
  if (f > 0) {
    mode = method == 2 ? FreeMode::kBasic : method == 3 ? FreeMode::kSplit : FreeMode::kBasic;
    if (method <= 1) {
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
          ws.lu[size_t(a) * f + b] = v;
          colsum += std::abs(v);
        }
        anorm1 = std::max(anorm1, colsum);
      }
      rcond = 0.0;
      if (LuFactor(ws.lu.data(), f, ws.lu_perm.data())) {
        rcond = 1.0 / (anorm1 * HagerInverseNorm1(ws.lu.data(), f, ws.lu_perm.data(), ws.hager_x.data(),
                                                  ws.hager_y.data()));
      }
      if (rcond >= options_.free_block_min_rcond) {
        mode = FreeMode::kSchur;
      } else if (method == 1) {
        result->status = SolveStatus::kSingular;
        Append(&result->message, "the free block M_FF is singular or ill-conditioned (rcond estimate %.3e < %.3e); "
               "free_row_method = 0 or 2 keeps the free variables basic instead", rcond,
               options_.free_block_min_rcond);
        result->SetDetail("free_block_rcond", rcond);
        return;
      }
    }
  }

  // --- 3. Lemke's method on LCP(N, r); in automatic mode, a failed free-variable start falls back to the split. ---
  int c = 0, nx = 0, p = 0, pivots = 0, reinversions = 0, max_pivots = 0;
  const char* failure = nullptr;
  double z0_value = 0.0;
  bool z0_exit = false, polished = false;
  Residual exit_residual;
  SolveStatus status = SolveStatus::kSolved;
  // Back to z: x from the basis (z₀ ignored), z_C = z̄_C + S x clipped to the box, z_F from the Schur relation.
  const auto recover = [&](bool have_basis) {
    std::fill(ws.xcore.begin(), ws.xcore.begin() + c, 0.0);
    if (have_basis) {
      for (int a = 0; a < nx; ++a) {
        const int row = ws.where[p + a];
        if (row >= 0) ws.xcore[ws.slot_core[a]] += ws.slot_sign[a] * ws.beta[row];
      }
    }
    for (int i = 0; i < n; ++i) {
      if (ws.kind[i] == kFixed) z[i] = l[i];
    }
    for (int a = 0; a < c; ++a) {
      const int i = ws.core[a];
      z[i] = std::min(std::max(ws.zbar[i] + ws.xcore[a], l[i]), u[i]);
      ws.xcore[a] = z[i] - ws.zbar[i];
    }
    if (mode == FreeMode::kSchur) {
      for (int k = 0; k < f; ++k) {
        double s = ws.g[k];
        const double* gk = ws.G.data() + size_t(k) * c;
        for (int b = 0; b < c; ++b) s += gk[b] * ws.xcore[b];
        z[ws.free_rows[k]] = -s;
      }
    }
  };
  // Polish, for when rounding leaves the merit function above the tolerance (an ill-conditioned reduction, or a
  // base-point shift M·l much larger than q). The active set of the final basis is solved in the original variables
  // (LU of M_EE, one refinement step); rows whose result leaves the box, or whose pinned w has the wrong sign, then
  // switch sides, for at most kPolishRounds rounds (primal-dual active-set steps started from Lemke's answer,
  // Hintermüller, Ito & Kunisch 2002). The best point is kept if it beats the current one; returns its residual.
  enum : signed char { kInE = 0, kAtLower = 1, kAtUpper = 2, kPinned = 3 };
  const auto polish = [&](Residual current) -> Residual {
    constexpr int kPolishRounds = 5;
    Ensure(&ws.active, n);
    Ensure(&ws.active_list, n);
    signed char* state = ws.active.data();
    for (int i = 0; i < n; ++i) state[i] = ws.kind[i] == kFixed ? kPinned : ws.kind[i] == kFree ? kInE : kAtLower;
    for (int a = 0; a < nx && p > 0; ++a) {
      const int i = ws.core[ws.slot_core[a]];
      const signed char k = ws.kind[i];
      if (k == kFree) continue;
      const bool x_basic = ws.where[p + a] >= 0;
      const bool y_basic = ws.slot_y[a] >= 0 && ws.where[p + ws.slot_y[a]] >= 0;
      state[i] = y_basic ? kAtUpper : x_basic ? kInE : k == kUpper ? kAtUpper : kAtLower;
    }
    if (ws.z_polish.size() != n) ws.z_polish.resize(n);
    Residual best = current;
    for (int round = 0; round < kPolishRounds; ++round) {
      int e = 0;
      for (int i = 0; i < n; ++i) {
        if (state[i] == kInE) {
          ws.active_list[e++] = i;
          ws.z_polish[i] = 0.0;
        } else {
          ws.z_polish[i] = state[i] == kAtUpper ? u[i] : l[i];
        }
      }
      Ensure(&ws.active_lu, size_t(e) * e);
      Ensure(&ws.active_perm, e);
      Ensure(&ws.active_res, e);
      const int* E = ws.active_list.data();
      if (e > 0) {
        problem.Affine(ws.z_polish, &ws.w);  // with z_E = 0: w_E = q_E + M_EN z_N
        for (int a = 0; a < e; ++a) {
          ws.active_res[a] = -ws.w[E[a]];
          for (int b = 0; b < e; ++b) ws.active_lu[size_t(a) * e + b] = M(E[a], E[b]);
        }
        if (!LuFactor(ws.active_lu.data(), e, ws.active_perm.data())) break;
        LuSolveRows(ws.active_lu.data(), e, ws.active_perm.data(), ws.active_res.data(), 1);
        for (int a = 0; a < e; ++a) ws.z_polish[E[a]] = ws.active_res[a];
        // One refinement step in the original data: −w_E = rhs − M_EE z_E, solved again.
        problem.Affine(ws.z_polish, &ws.w);
        for (int a = 0; a < e; ++a) ws.active_res[a] = -ws.w[E[a]];
        LuSolveRows(ws.active_lu.data(), e, ws.active_perm.data(), ws.active_res.data(), 1);
        for (int a = 0; a < e; ++a) ws.z_polish[E[a]] += ws.active_res[a];
      }
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
        z = ws.z_polish;
        best = r;
        polished = true;
      }
      if (Passes(best, options.tolerance) || !changed) break;
    }
    return best;
  };
  const auto run_path = [&](Engine& engine) -> SolveStatus {
    bool feasible = true;
    for (int i = 0; i < p; ++i) feasible = feasible && (engine.FreeRow(i) || ws.beta[i] >= 0.0);
    if (feasible) return SolveStatus::kSolved;  // the start basis already solves the LCP
    // First step: z₀ enters at the level that makes every sign-constrained basic variable nonnegative. With
    // c = B⁻¹d this is the lexicographic minimum of [β_i, B⁻¹_i·]/c_i, the same test as below (for B = I, d = e:
    // the largest index among the most negative r_i).
    engine.Column(engine.z0());
    double cmax = 0.0;
    for (int i = 0; i < p; ++i) ws.col[i] = -ws.col[i], cmax = std::max(cmax, std::abs(ws.col[i]));
    const int r0 = engine.RatioTest(options_.pivot_tolerance * cmax, /*clamp=*/false);
    for (int i = 0; i < p; ++i) ws.col[i] = -ws.col[i];
    if (r0 < 0) {
      failure = "the covering direction does not reach the infeasible rows";
      return SolveStatus::kNumericalFailure;
    }
    int leaving = ws.basis[r0];
    engine.Pivot(r0, engine.z0());
    ++pivots;
    const int refactor = options_.refactor_interval > 0 ? options_.refactor_interval : std::max(64, p);
    double dmax = 0.0;
    for (int i = 0; i < p; ++i) dmax = std::max(dmax, std::abs(ws.d[i]));
    // Dropping z₀ moves w (of the equilibrated problem: units of z) by up to z₀·‖d‖∞, so the point without z₀ can
    // only pass the merit function once z₀·‖d‖∞ is within its tolerance: tol·(1 + ‖q‖∞) for the relative residual
    // (a cheap first filter) and tol·(1 + ‖z‖∞) for the residual in units of z (checked on the recovered z).
    const double z0_negligible = options.tolerance * problem.residual_scale() / dmax;
    int exit_polishes = 0;
    while (true) {
      const int entering = engine.Complement(leaving);
      z0_value = ws.beta[ws.where[engine.z0()]];
      if (z0_value <= z0_negligible) {
        // z₀ may be zero up to rounding (degenerate end of the path, where tiny pivots would follow): accept the
        // almost-complementary point without z₀ only if the merit function says it solves the problem, which
        // includes every sign condition (w ≥ 0 on rows at l, ≤ 0 at u) to tol·(1 + ‖z‖∞) in units of z.
        recover(true);
        exit_residual = problem.NaturalResidual(z, &ws.w);
        const bool negligible_in_z = z0_value * dmax <= options.tolerance * (1.0 + z.cwiseAbs().maxCoeff());
        if (!Passes(exit_residual, options.tolerance) && negligible_in_z && exit_polishes < 3) {
          ++exit_polishes;  // bounded: a degenerate stretch may keep z₀ tiny for long
          exit_residual = polish(exit_residual);
        }
        if (Passes(exit_residual, options.tolerance)) {
          z0_exit = true;
          return SolveStatus::kSolved;
        }
      }
      if (pivots >= max_pivots) return SolveStatus::kIterationLimit;
      if ((pivots & 31) == 0 && TimeLimitReached()) return SolveStatus::kTimeLimit;
      engine.Column(entering);
      cmax = 0.0;
      bool finite = true;
      for (int i = 0; i < p; ++i) {
        cmax = std::max(cmax, std::abs(ws.col[i]));
        finite = finite && std::isfinite(ws.col[i]) && std::isfinite(ws.beta[i]);
      }
      if (!finite) {
        failure = "NaN or Inf in the basis inverse";
        return SolveStatus::kNumericalFailure;
      }
      const int row = cmax > 0.0 ? engine.RatioTest(options_.pivot_tolerance * cmax) : -1;
      if (row < 0) return SolveStatus::kRayTermination;
      leaving = ws.basis[row];
      if (options.verbosity > 1) {
        double bmin = 0.0;
        for (int i = 0; i < p; ++i) {
          if (!engine.FreeRow(i)) bmin = std::min(bmin, ws.beta[i]);
        }
        const char* out = leaving == engine.z0() ? "z" : leaving < p ? "w" : "x";
        std::fprintf(stderr, "lemke: pivot %d: in %c%d, out %s%d, z0 = %.6e, pivot %.2e (relative %.2e), "
                     "min basic %.2e\n", pivots + 1, entering < p ? 'w' : 'x', entering % p, out,
                     leaving == engine.z0() ? 0 : leaving % p, z0_value, ws.col[row], ws.col[row] / cmax, bmin);
      }
      engine.Pivot(row, entering);
      ++pivots;
      if (leaving == engine.z0()) return SolveStatus::kSolved;  // complementary basis
      if (pivots % refactor == 0) {
        ++reinversions;
        if (!engine.Reinvert()) {
          failure = "the basis became numerically singular at a reinversion";
          return SolveStatus::kNumericalFailure;
        }
        // Rounding can leave degenerate basic values at −1e-17; a real loss of feasibility is a failure.
        double bmax = 0.0, bmin = 0.0;
        for (int i = 0; i < p; ++i) {
          if (engine.FreeRow(i)) continue;
          bmax = std::max(bmax, std::abs(ws.beta[i]));
          bmin = std::min(bmin, ws.beta[i]);
        }
        if (bmin < -1e-6 * (1.0 + bmax)) {
          failure = "the basis lost feasibility at a reinversion (ill-conditioned basis)";
          return SolveStatus::kNumericalFailure;
        }
        for (int i = 0; i < p; ++i) {
          if (!engine.FreeRow(i)) ws.beta[i] = std::max(ws.beta[i], 0.0);
        }
      }
    }
  };
  bool split_fallback = false;
  for (int attempt = 0; attempt < 2; ++attempt) {
    p = BuildLcp(problem, mode, options_.covering_vector, &ws, &c, &nx);
    max_pivots = IterationBudget(options, std::max(kLemkeDefaultMinPivots, 50 * p));
    if (p == 0) break;
    Engine engine(&ws, p, nx, ws.y_owner.data());
    engine.SlackBasis();
    if (mode == FreeMode::kBasic) {
      if (!engine.BringFreeVariablesIn(&pivots)) {
        if (method == 0) {
          mode = FreeMode::kSplit;
          split_fallback = true;
          continue;
        }
        status = SolveStatus::kSingular;
        failure = "the free columns are linearly dependent: no complementary basis holds every free variable";
        break;
      }
      engine.CoverFromBasis();
    }
    status = run_path(engine);
    break;
  }

  Residual res;
  if (z0_exit) {
    res = exit_residual;
  } else {
    recover(p > 0 && status != SolveStatus::kSingular);
    res = problem.NaturalResidual(z, &ws.w);
  }
  // The pivots accumulate rounding of order ε·max|β|, and β holds q̂ (a huge multiplier on one row, a base-point
  // shift M·l): an answer that is not at the rounding level in units of z has its active set solved again.
  const double rounding_level = 1e3 * n * kEps;
  if (status == SolveStatus::kSolved && !(Passes(res, options.tolerance) && res.scaled <= rounding_level)) {
    res = polish(res);
  }
  if (status == SolveStatus::kSolved && !std::isfinite(res.abs)) {
    status = SolveStatus::kNumericalFailure;
    failure = "the solution contains NaN or Inf";
  }
  // The merit function decides: wherever the method stopped, a point it accepts is a solution.
  if (status != SolveStatus::kSolved && Passes(res, options.tolerance)) status = SolveStatus::kSolved;
  // A secondary ray is no verdict on the problem (in floating point not even for copositive-plus M): on a problem
  // known to have a solution it is a failure of the method.
  const char* exists = status == SolveStatus::kRayTermination ? SolutionExistsReason(problem) : nullptr;
  if (exists) status = SolveStatus::kNumericalFailure;

  result->status = status;
  result->iterations = pivots;
  // Details (few, since each costs a name search): the optional ones only when they carry information.
  result->SetDetail("lcp_size", p);
  result->SetDetail("reinversions", reinversions);
  if (f > 0) {
    result->SetDetail("free_row_mode", static_cast<double>(mode));  // 1 Schur, 2 basic, 3 split
    if (method <= 1) result->SetDetail("free_block_rcond", rcond);
  }
  if (polished) result->SetDetail("polished", 1.0);
  if (z0_exit) result->SetDetail("z0_negligible_exit", 1.0);

  if (status != SolveStatus::kSolved) {
    std::string& msg = result->message;
    switch (status) {
      case SolveStatus::kRayTermination:
        msg = "Lemke's method ended on a secondary ray after " + std::to_string(pivots) +
              " pivots (the entering column has no blocking row): no solution found by this method";
        Append(&msg, " (z0 = %.3e, residual %.3e)", z0_value, Worst(res));
        msg += "; this proves infeasibility only for a copositive-plus M in exact arithmetic, which was not checked";
        if (mode == FreeMode::kSplit || mode == FreeMode::kBasic) {
          msg += std::string("; free rows handled by the ") + FreeModeName(mode) + " method";
          if (split_fallback) msg += " (the free columns are dependent)";
        }
        break;
      case SolveStatus::kIterationLimit:
        msg = "pivot limit " + std::to_string(max_pivots) + " reached";
        Append(&msg, " (z0 = %.3e, residual %.3e)", z0_value, Worst(res));
        break;
      case SolveStatus::kTimeLimit:
        msg = "time limit reached after " + std::to_string(pivots) + " pivots";
        Append(&msg, " (residual %.3e)", Worst(res));
        break;
      default:
        if (exists) {
          msg = std::string("a solution exists (") + exists + ") but Lemke's method failed: it ended on a secondary "
                "ray after " + std::to_string(pivots) + " pivots";
          Append(&msg, " (z0 = %.3e, residual %.3e)", z0_value, Worst(res));
          break;
        }
        msg = failure ? failure : "numerical failure";
        Append(&msg, " after %.0f pivots (residual %.3e)", pivots, Worst(res));
        break;
    }
  }
  if (options.verbosity > 0) {
    std::fprintf(stderr, "lemke: n = %d, LCP size %d, %d free rows (%s), %d pivots, %d reinversions%s: %s %s\n", n,
                 p, f, FreeModeName(mode), pivots, reinversions, polished ? ", polished" : "",
                 std::string(ToString(status)).c_str(), result->message.c_str());
  }
}

}  // namespace smcbench

// Exhaustive active-set enumeration for the box-MLCP (see enumerative_solver.h for the method and references).
#include "solvers/enumerative/enumerative_solver.h"

#include "solvers/core/active_set.h"
#include "solvers/core/matrix_class.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace smcbench {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr int kMaxGuidedSteps = 100000;  // history costs guided_steps · n ints
// kInfeasible needs every candidate to miss its sign-test threshold τ by more than this factor.
constexpr double kCertifyMargin = 100.0;

// The state of one row in a candidate active set.
enum RowState : int {
  kLower = 0,  // z_i = l_i, needs w_i ≥ 0
  kUpper = 1,  // z_i = u_i, needs w_i ≤ 0
  kFree = 2,   // z_i from the free-block solve, needs l_i ≤ z_i ≤ u_i (and w_i = 0 by construction)
  kFixed = 3,  // l_i = u_i: z_i = l_i, any w_i
};

constexpr char kStateChar[] = {'L', 'U', 'F', 'X'};

// Raw views of the search workspace; the same code runs on stack arrays (m ≤ 4) and on the heap workspace.
struct Buffers {
  int ld = 0;              // leading dimension of the k×k column-major blocks (= n)
  double* A = nullptr;     // n×n: the free block M_FF, factored in place
  double* T = nullptr;     // n×n: transposed R factor for the least-norm solve
  double* z = nullptr;     // candidate z
  double* w = nullptr;     // candidate w = M z + q
  double* y = nullptr;     // natural-map point z − D⁻¹ w that defines the current guess
  double* rhs = nullptr;   // right-hand side, overwritten by z_F
  double* xref = nullptr;  // Π_[l,u](0) on the free rows: the centre of the least-norm solve
  double* tau = nullptr;   // Householder scalars (QR with column pivoting)
  double* tau2 = nullptr;  // Householder scalars (QR of Rᵀ)
  double* v = nullptr;     // least-norm work vector
  double* margin = nullptr;  // confidence of the guessed state, per row
  double* start = nullptr;   // the starting point, restored when nothing is found
  double* best = nullptr;    // the candidate with the smallest merit value so far
  int* piv = nullptr;        // LU row swaps
  int* jpvt = nullptr;       // QR column permutation
  int* free_idx = nullptr;   // rows of the free block
  int* state = nullptr;      // RowState per row
  int* choice = nullptr;     // 3 per row: the row's states, most likely first
  int* radix = nullptr;      // number of states per branching position
  int* order = nullptr;      // branching rows, least confident first
  int* comb = nullptr;       // enumeration: positions changed from the guess
  int* offset = nullptr;     // enumeration: choice index per position
  int* history = nullptr;    // guided phase: the sets already tried, n ints each
};

// Stack storage for the fixed-size path.
template <int N>
struct FixedStorage {
  static constexpr int kHistory = 32;  // guided steps held on the stack
  std::array<double, N * N> A, T;
  std::array<double, N> z, w, y, rhs, xref, tau, tau2, v, margin, start, best;
  std::array<int, N> piv, jpvt, free_idx, state, radix, order, comb, offset;
  std::array<int, 3 * N> choice;
  std::array<int, kHistory * N> history;
  Buffers View() {
    Buffers b;
    b.ld = N;
    b.history = history.data(), b.y = y.data();
    b.A = A.data(), b.T = T.data(), b.z = z.data(), b.w = w.data(), b.rhs = rhs.data(), b.xref = xref.data();
    b.tau = tau.data(), b.tau2 = tau2.data(), b.v = v.data(), b.margin = margin.data(), b.start = start.data();
    b.best = best.data(), b.piv = piv.data(), b.jpvt = jpvt.data(), b.free_idx = free_idx.data();
    b.state = state.data(), b.choice = choice.data(), b.radix = radix.data(), b.order = order.data();
    b.comb = comb.data(), b.offset = offset.data();
    return b;
  }
};
template <>
struct FixedStorage<0> {};

constexpr int kRealBlocks = 2;    // A, T (n×n each)
constexpr int kRealVectors = 11;  // z … best
constexpr int kIntVectors = 8;    // piv … offset; then choice (3n) and history (guided_steps · n)

// ---------------------------------------------------------------------------------------------------------
// Dense kernels on a k×k column-major block with leading dimension ld (no allocation, any k ≤ ld).

// ‖x‖₂ without overflow or harmful underflow.
double StableNorm(const double* x, int len) {
  double scale = 0.0;
  for (int i = 0; i < len; ++i) scale = std::max(scale, std::abs(x[i]));
  if (scale == 0.0 || !std::isfinite(scale)) return scale;
  double s = 0.0;
  for (int i = 0; i < len; ++i) {
    const double t = x[i] / scale;
    s += t * t;
  }
  return scale * std::sqrt(s);
}

// Householder reflector H = I − τ v vᵀ zeroing column s below row s of the m×ncols matrix a (v stored below
// the diagonal with v_s = 1 implicit), applied to columns s+1 … ncols−1. norm = ‖a(s:m, s)‖₂.
void Householder(double* a, int ld, int m, int ncols, int s, double norm, double* tau) {
  double* cs = a + static_cast<std::ptrdiff_t>(s) * ld;
  const double alpha = cs[s];
  if (norm == 0.0) {
    *tau = 0.0;
    return;
  }
  const double beta = -std::copysign(norm, alpha);
  const double denom = alpha - beta;
  for (int i = s + 1; i < m; ++i) cs[i] /= denom;
  *tau = (beta - alpha) / beta;
  cs[s] = beta;
  for (int c = s + 1; c < ncols; ++c) {
    double* cc = a + static_cast<std::ptrdiff_t>(c) * ld;
    double dot = cc[s];
    for (int i = s + 1; i < m; ++i) dot += cs[i] * cc[i];
    dot *= *tau;
    cc[s] -= dot;
    for (int i = s + 1; i < m; ++i) cc[i] -= dot * cs[i];
  }
}

// Householder QR with column pivoting (Businger–Golub) of the k×k block: A P = Q R. Stops when the largest
// remaining column norm is ≤ rank_tol · |R_00|; returns that numerical rank r.
int QrColumnPivoting(double* a, int ld, int k, int* jpvt, double* tau, double rank_tol) {
  for (int j = 0; j < k; ++j) jpvt[j] = j;
  double rmax = 0.0;
  for (int s = 0; s < k; ++s) {
    int p = s;
    double best = -1.0;
    // Norms recomputed from scratch each step: this path is rare, and it avoids norm-downdating cancellation.
    for (int c = s; c < k; ++c) {
      const double nc = StableNorm(a + s + static_cast<std::ptrdiff_t>(c) * ld, k - s);
      if (nc > best) best = nc, p = c;
    }
    if (s == 0) rmax = best;
    if (!(best > rank_tol * rmax) || rmax == 0.0) return s;
    if (p != s) {
      double* cs = a + static_cast<std::ptrdiff_t>(s) * ld;
      double* cp = a + static_cast<std::ptrdiff_t>(p) * ld;
      for (int i = 0; i < k; ++i) std::swap(cs[i], cp[i]);
      std::swap(jpvt[s], jpvt[p]);
    }
    Householder(a, ld, k, k, s, best, &tau[s]);
  }
  return k;
}

// Least-norm solution, about the centre xref, of the k×k system A x = b with A possibly rank deficient:
// x = xref + argmin{‖d‖ : d minimizes ‖A d − (b − A xref)‖ after cutting A to its numerical rank}. Uses
// A P = Q [R1; 0] (column-pivoted QR) and then R1ᵀ = Q2 [S; 0] so that the cut system is [Sᵀ 0] Q2ᵀ Pᵀ d = c1
// (a complete orthogonal decomposition, Golub & Van Loan §5.5). b is overwritten by x. Returns the rank.
int LeastNormSolve(double* a, double* t, int ld, int k, const double* xref, double* b, double* tau, double* tau2,
                   double* v, int* jpvt, double rank_tol) {
  for (int c = 0; c < k; ++c) {
    const double xc = xref[c];
    if (xc == 0.0) continue;
    const double* ac = a + static_cast<std::ptrdiff_t>(c) * ld;
    for (int i = 0; i < k; ++i) b[i] -= ac[i] * xc;
  }
  const int r = QrColumnPivoting(a, ld, k, jpvt, tau, rank_tol);
  for (int s = 0; s < r; ++s) {  // b := Qᵀ b
    const double* cs = a + static_cast<std::ptrdiff_t>(s) * ld;
    double dot = b[s];
    for (int i = s + 1; i < k; ++i) dot += cs[i] * b[i];
    dot *= tau[s];
    b[s] -= dot;
    for (int i = s + 1; i < k; ++i) b[i] -= dot * cs[i];
  }
  for (int j = 0; j < r; ++j) {  // t := R1ᵀ (k×r)
    double* tj = t + static_cast<std::ptrdiff_t>(j) * ld;
    for (int i = 0; i < k; ++i) tj[i] = i >= j ? a[j + static_cast<std::ptrdiff_t>(i) * ld] : 0.0;
  }
  for (int s = 0; s < r; ++s) {
    Householder(t, ld, k, r, s, StableNorm(t + s + static_cast<std::ptrdiff_t>(s) * ld, k - s), &tau2[s]);
  }
  for (int j = 0; j < r; ++j) {  // Sᵀ y = c1
    const double* tj = t + static_cast<std::ptrdiff_t>(j) * ld;
    double s = b[j];
    for (int i = 0; i < j; ++i) s -= tj[i] * v[i];
    v[j] = s / tj[j];
  }
  for (int i = r; i < k; ++i) v[i] = 0.0;
  for (int s = r - 1; s >= 0; --s) {  // v := Q2 [y; 0]
    const double* ts = t + static_cast<std::ptrdiff_t>(s) * ld;
    double dot = v[s];
    for (int i = s + 1; i < k; ++i) dot += ts[i] * v[i];
    dot *= tau2[s];
    v[s] -= dot;
    for (int i = s + 1; i < k; ++i) v[i] -= dot * ts[i];
  }
  for (int i = 0; i < k; ++i) b[jpvt[i]] = xref[jpvt[i]] + v[i];
  return r;
}

// The enumeration's row states and placement are its own: they are its digits (four states, compared as whole
// sets). Its free blocks are factored and solved by the active-set kernel's blocked entry point.
using active_set::BlockPivots;
using active_set::FactorBlock;
using active_set::FactoredPivots;
using active_set::SolveBlock;
using active_set::SolveFactored;

// Why the box-MLCP is known to have a solution, or nullptr; for the failure path of the search only (allocates):
// every bound finite (a continuous map on a compact box), M + Mᵀ positive definite with a margin (matrix_class.h's
// Cholesky test: (M + Mᵀ)/2 − δI factors, δ = 1e3·n·ε·‖(M + Mᵀ)/2‖∞), or, from the search itself, every free block's
// determinant of one sign with clear pivots (the Schur complement of the always-free rows is then a P-matrix).
const char* SolutionExistsReason(const BoxMLCP& problem, bool determinants_of_one_sign) {
  const Vector& l = problem.l();
  const Vector& u = problem.u();
  const int n = problem.size();
  bool all_finite = true;
  for (int i = 0; i < n; ++i) all_finite = all_finite && l[i] > -kInf && u[i] < kInf;
  if (all_finite) return "every bound is finite";
  if (ClassifySymmetricPartPositiveDefinite(problem.dense_matrix()).answer == MatrixClassAnswer::kYes) {
    return "M + Mᵀ is positive definite";
  }
  if (determinants_of_one_sign) return "every free block's determinant has the same sign (a P-matrix problem)";
  return nullptr;
}

// A determinant's sign counts (for the P-matrix argument) only when every LU pivot exceeds this · k · ε · max|M_FF|.
constexpr double kDeterminantSignMargin = 1e3;

// The line on which every solution of a rank-(k − 1) free block lies, from the column-pivoted QR left in a by
// LeastNormSolve: A P = Q [R11 r12; 0 ρ] with R11 (k−1)×(k−1) upper triangular, so A P n = 0 up to ρ for
// n = [−R11⁻¹ r12; 1]; v = P n scaled to ‖v‖∞ = 1 (scratch: k doubles for n). growth = max |R_ss| / min |R_ss|
// over the kept part: how much it amplifies rounding. ok is false if something is not finite.
struct LineOfSolutions {
  bool ok = false;
  double growth = kInf;
};
inline LineOfSolutions FitLine(const double* a, int ld, int k, const int* jpvt, double* scratch, double* v) {
  const int r = k - 1;
  const auto R = [&](int s, int c) { return a[s + static_cast<std::ptrdiff_t>(c) * ld]; };
  double* n_perm = scratch;
  n_perm[r] = 1.0;
  double dmax = 0.0, dmin = kInf;
  for (int s = r - 1; s >= 0; --s) {
    double sum = -R(s, r);
    for (int c = s + 1; c < r; ++c) sum -= R(s, c) * n_perm[c];
    n_perm[s] = sum / R(s, s);
    dmax = std::max(dmax, std::abs(R(s, s)));
    dmin = std::min(dmin, std::abs(R(s, s)));
  }
  LineOfSolutions line;
  double norm = 0.0;
  for (int i = 0; i < k; ++i) norm = std::max(norm, std::abs(n_perm[i]));
  if (!(norm > 0.0) || !std::isfinite(norm)) return line;
  for (int i = 0; i < k; ++i) v[jpvt[i]] = n_perm[i] / norm;
  line.growth = r == 0 ? 1.0 : dmax / dmin;
  line.ok = std::isfinite(line.growth);
  return line;
}

// True when Σ_a row(a)·v[a] is exactly zero in real arithmetic: every product and every partial sum is computed
// without rounding (error-free transformations: the FMA residual of each product, Knuth's TwoSum of each sum).
template <typename Row>
bool ExactlyZeroDot(int k, const Row& row, const double* v) {
  double sum = 0.0;
  for (int a = 0; a < k; ++a) {
    const double m = row(a);
    const double p = m * v[a];
    if (std::fma(m, v[a], -p) != 0.0) return false;
    const double t = sum + p;
    const double bp = t - sum;
    if ((sum - (t - bp)) + (p - bp) != 0.0) return false;
    sum = t;
  }
  return sum == 0.0;
}

// min over t of the largest violation max_j max(0, −(α_j + β_j t)) of linear constraints α_j + β_j t ≥ 0, with the
// t that attains it (the one nearest 0, i.e. nearest the least-norm point). constraints(f) calls f(α, β) for each
// constraint; it is called a few times (pairs are compared, nothing is stored: no allocation). Exact: the upper
// envelope of the decreasing violations meets that of the increasing ones at a crossing of one pair of them.
struct LeastViolation {
  double violation = 0.0;
  double t = 0.0;
};
template <typename Constraints>
LeastViolation MinimizeWorstViolation(const Constraints& constraints) {
  double v = 0.0;
  constraints([&](double alpha, double beta) {
    if (beta == 0.0) {
      v = std::max(v, -alpha);
    } else if (beta > 0.0) {
      constraints([&](double alpha2, double beta2) {
        if (beta2 < 0.0) v = std::max(v, (-alpha * -beta2 - alpha2 * beta) / (beta - beta2));
      });
    }
  });
  double lo = -kInf, hi = kInf;
  constraints([&](double alpha, double beta) {
    if (beta > 0.0) lo = std::max(lo, (-alpha - v) / beta);
    if (beta < 0.0) hi = std::min(hi, (alpha + v) / -beta);
  });
  LeastViolation best;
  best.violation = v;
  best.t = lo > 0.0 ? lo : (hi < 0.0 ? hi : 0.0);
  if (lo > hi) best.t = 0.5 * (lo + hi);  // rounding at the crossing
  return best;
}

// The first active set tried for row i: the state of the Jacobi-scaled natural map y = z0 − (M z0 + q)_i / d_i
// (d_i = M_ii where positive, else 1) projected on [l_i, u_i]. At a solution z0 = z* it is z*'s active set,
// and from the cold start Π(0) of a 1×1 problem with M > 0 it gives the exact answer Π(−q/M).
inline int GuessState(double y, double l, double u) {
  if (l == u) return kFixed;
  if (l > -kInf && y <= l) return kLower;
  if (u < kInf && y >= u) return kUpper;
  return kFree;
}

inline double JacobiScale(double m_ii) { return m_ii > 0.0 ? m_ii : 1.0; }

// The inverse of the 2×2 block [[a00, a01], [a10, a11]] if its ∞-norm condition number is at most
// BlockCache::kInverseConditionLimit: then x = A⁻¹ b is within about κ ε of the LU solution, far below the solve
// tolerance, and the merit function checks the result anyway. False (inv unset) otherwise.
inline bool WellConditionedInverse(double a00, double a10, double a01, double a11, double inv[4]) {
  const double det = a00 * a11 - a01 * a10;
  if (!std::isfinite(det) || det == 0.0) return false;
  const double i00 = a11 / det, i10 = -a10 / det, i01 = -a01 / det, i11 = a00 / det;
  const double norm = std::max(std::abs(a00) + std::abs(a01), std::abs(a10) + std::abs(a11));
  const double inv_norm = std::max(std::abs(i00) + std::abs(i01), std::abs(i10) + std::abs(i11));
  if (!(norm * inv_norm <= EnumerativeSolver::BlockCache::kInverseConditionLimit)) return false;
  inv[0] = i00, inv[1] = i10, inv[2] = i01, inv[3] = i11;
  return true;
}

// Fills a fast-path cache entry for the free set free_mask of the n×n (column-major) M: gathers and factors M_FF
// (FactorBlock; kSingular below rank_tol · max|M_FF|) and, for a well-conditioned 2×2 block, its scattered
// inverse. Out of line: runs once per free set and matrix.
[[gnu::noinline]] void FillBlockEntry(const double* M, int n, unsigned free_mask, double rank_tol,
                                      EnumerativeSolver::BlockCache::Entry* e) {
  int idx[EnumerativeSolver::BlockCache::kMaxRows];
  int k = 0;
  for (int i = 0; i < n; ++i) {
    if (free_mask >> i & 1u) idx[k++] = i;
  }
  e->k = k;
  double amax = 0.0;
  for (int c = 0; c < k; ++c) {
    for (int r = 0; r < k; ++r) {
      e->a[r + c * n] = M[idx[r] + idx[c] * n];
      amax = std::max(amax, std::abs(e->a[r + c * n]));
    }
  }
  double inv[4];
  e->has_inverse = k == 2 && WellConditionedInverse(e->a[0], e->a[1], e->a[n], e->a[n + 1], inv);
  if (e->has_inverse) {
    std::fill(e->inverse, e->inverse + n * n, 0.0);
    for (int c = 0; c < 2; ++c) {
      for (int r = 0; r < 2; ++r) e->inverse[idx[r] + idx[c] * n] = inv[r + 2 * c];
    }
  }
  e->state = k == 0 || FactorBlock(e->a, n, k, e->piv, rank_tol * amax) ? EnumerativeSolver::BlockCache::kFactored
                                                                        : EnumerativeSolver::BlockCache::kSingular;
}

// The fixed-size fast path for m ≤ 4 (the paper's one-step relay problems have m = 1, 2): forms the candidate of
// the guessed active set at z0 (GuessState's natural-map set) into z. True if the set's free block is nonsingular
// and the candidate finite; the caller then tests it with the merit function. cache holds the free blocks' factors
// for this M (SolveFast checked its key): a time-stepper's M is constant while the guessed set repeats, so each
// block is gathered and factored once. Written for the time-stepper's critical path: every index is a compile-time
// constant, so z0, w, the right side and z stay in registers (a local array written element by element and read
// back as a vector stalls store forwarding), the guess compares without dividing, and a free block of one row is
// divided, of two rows multiplied by its cached inverse, larger ones solved from their LU factors.
template <int N>
bool SolveGuessedSet(const BoxMLCP& problem, double rank_tol, const double* z0, double* z,
                     EnumerativeSolver::BlockCache* cache) {
  const double* M = problem.dense_matrix().data();
  const double* q = problem.q().data();
  const double* l = problem.l().data();
  const double* u = problem.u().data();
  double w[N], r[N];
  for (int i = 0; i < N; ++i) w[i] = q[i];
  for (int j = 0; j < N; ++j) {
    for (int i = 0; i < N; ++i) w[i] += M[i + j * N] * z0[j];
  }
  unsigned free_mask = 0;
  for (int i = 0; i < N; ++i) {
    // GuessState(y = z0 − w / d): with d > 0, y ≤ l ⇔ (z0 − l) d ≤ w and y ≥ u ⇔ (z0 − u) d ≥ w (up to rounding
    // at a tie, where either set is a fair guess).
    const double d = JacobiScale(M[i + i * N]);
    if (l[i] == u[i]) {
      z[i] = l[i];
    } else if (l[i] > -kInf && (z0[i] - l[i]) * d <= w[i]) {
      z[i] = l[i];
    } else if (u[i] < kInf && (z0[i] - u[i]) * d >= w[i]) {
      z[i] = u[i];
    } else {
      z[i] = 0.0;
      free_mask |= 1u << i;
    }
  }
  // r = q + M z_B; the free rows then solve M_FF z_F = −r_F.
  for (int i = 0; i < N; ++i) r[i] = q[i];
  for (int j = 0; j < N; ++j) {
    if (free_mask >> j & 1u) continue;  // z_j = 0
    for (int i = 0; i < N; ++i) r[i] += M[i + j * N] * z[j];
  }
  EnumerativeSolver::BlockCache::Entry& e = cache->entries[free_mask];
  if (e.state == EnumerativeSolver::BlockCache::kUnknown) FillBlockEntry(M, N, free_mask, rank_tol, &e);
  if (e.state == EnumerativeSolver::BlockCache::kSingular) return false;
  if (e.k == 1) {
    for (int i = 0; i < N; ++i) {
      if (free_mask == 1u << i) z[i] = -r[i] / e.a[0];
    }
  } else if (e.has_inverse) {
    for (int i = 0; i < N; ++i) {
      double sum = 0.0;
      for (int j = 0; j < N; ++j) sum += e.inverse[i + j * N] * r[j];
      z[i] -= sum;  // the inverse is zero outside the free rows and columns
    }
  } else if (e.k > 1) {
    double rhs[N];
    int idx[N];
    int k = 0;
    for (int i = 0; i < N; ++i) {
      if (free_mask >> i & 1u) idx[k] = i, rhs[k++] = -r[i];
    }
    SolveFactored(e.a, N, k, e.piv, rhs);
    for (int c = 0; c < k; ++c) z[idx[c]] = rhs[c];
  }
  double probe = 0.0;  // x − x is 0 exactly for finite x, NaN for NaN and ±∞
  for (int i = 0; i < N; ++i) probe += z[i] - z[i];
  if (!(probe == 0.0)) return false;
  for (int i = 0; i < N; ++i) z[i] = std::min(std::max(z[i], l[i]), u[i]);  // bound rows stay where they are
  return true;
}

// ---------------------------------------------------------------------------------------------------------
// Nearest-first order: all state vectors by increasing number of rows changed from the guess (Hamming
// distance), positions taken least-confident first. Position p has radix[p] ≥ 2 states, 0 being the guess.
class NearestFirst {
 public:
  NearestFirst(int nb, const int* radix, int* comb, int* offset) : nb_(nb), radix_(radix), comb_(comb), off_(offset) {
    for (int p = 0; p < nb_; ++p) off_[p] = 0;
  }
  // Rows changed from the guess in the current state vector (nondecreasing over the order).
  int distance() const { return d_; }
  // Advances offset[] to the next state vector; false once all have been produced.
  bool Next() {
    for (int j = d_ - 1; j >= 0; --j) {  // odometer over the changed positions, last one fastest
      const int p = comb_[j];
      if (off_[p] + 1 < radix_[p]) {
        ++off_[p];
        for (int jj = j + 1; jj < d_; ++jj) off_[comb_[jj]] = 1;
        return true;
      }
    }
    for (int j = 0; j < d_; ++j) off_[comb_[j]] = 0;
    int j = d_ - 1;  // next d-subset in lexicographic order, else the first (d+1)-subset
    while (j >= 0 && comb_[j] == nb_ - d_ + j) --j;
    if (j >= 0) {
      ++comb_[j];
      for (int jj = j + 1; jj < d_; ++jj) comb_[jj] = comb_[jj - 1] + 1;
    } else {
      if (++d_ > nb_) return false;
      for (int jj = 0; jj < d_; ++jj) comb_[jj] = jj;
    }
    for (int jj = 0; jj < d_; ++jj) off_[comb_[jj]] = 1;
    return true;
  }

 private:
  int nb_;
  const int* radix_;
  int* comb_;
  int* off_;
  int d_ = 0;
};

// An active-set count for messages: exact below 2^53, else in scientific notation.
std::string CountText(double count) {
  if (count < 9007199254740992.0) return std::to_string(static_cast<long long>(count));
  std::ostringstream s;
  s.precision(3);
  s << count;
  return s.str();
}

// The search's details, out of line: one call site of SetDetail for every instantiation of the search keeps the
// translation unit small enough for the fast path's own SetDetail calls to stay inlined (out of line they add to
// every m = 1 solve about the perf gate's threshold; results/baseline/perf.json holds the counts).
[[gnu::noinline]] void SetSearchDetails(double total, double guided, double singular, SolveResult* result) {
  result->SetDetail("active_sets_total", total);
  result->SetDetail("guided_sets", guided);
  result->SetDetail("singular_blocks", singular);
}

// One verbosity-2 line: the active set as a string of L/U/F/X and what became of it.
void Trace(long long index, const int* state, int n, const char* what, double value) {
  char pattern[65];
  const int shown = std::min(n, 64);
  for (int i = 0; i < shown; ++i) pattern[i] = kStateChar[state[i]];
  pattern[shown] = '\0';
  std::fprintf(stderr, "enum: set %lld %s%s: %s %.3g\n", index, pattern, n > shown ? "..." : "", what, value);
}

// What a search that found no solution saw, for its message.
struct SearchTally {
  long long examined = 0, guided = 0, exhaustive = 0, singular = 0, singular_skipped = 0, nonfinite = 0,
            near_misses = 0, unresolved = 0;
  double total = 0.0;          // active sets in the full search
  double best_merit = kInf;    // smallest merit value among the candidates that reached the merit test
  double closest = kInf;       // the closest refutation, relative to its threshold closest_tau
  double closest_tau = 1.0;
  bool one_sign = false;       // det M_FF of one sign with clear pivots over the exhaustive phase
};

// The end of a search that found no solution (result->z already holds the best candidate or the start): the
// merit function's last word, then the status and the message that says why — a proof of infeasibility only with
// every active set refuted with a margin.
void ReportUnsolved(const BoxMLCP& problem, const SolverOptions& options, SolveStatus stop, const SearchTally& t,
                    SolveResult* result) {
  const bool have_best = std::isfinite(t.best_merit);
  // The merit function has the last word: a point it accepts is an answer, whatever the search's own tests said.
  if (have_best && PassesBoxMlcpTolerance(problem.NaturalResidual(result->z, &result->w), options.tolerance)) {
    result->status = SolveStatus::kSolved;
    return;
  }
  std::ostringstream s;
  s.precision(3);
  if (stop == SolveStatus::kIterationLimit || stop == SolveStatus::kTimeLimit) {
    result->status = stop;
    s << "enum: " << (stop == SolveStatus::kTimeLimit ? "time limit" : "iteration limit (max_iterations)")
      << " reached after " << t.examined << " active sets (" << t.guided << " guided, " << t.exhaustive << " of the "
      << CountText(t.total) << " of the full search) without a solution";
  } else {
    // Every active set was examined. "No solution exists" needs a certificate: each set refuted with a margin, no
    // singular block left unresolved, and a problem of a class that can lack a solution. Anything else is a
    // failure of the method, and says why.
    std::ostringstream why;
    const char* sep = "";
    const auto reason = [&]() -> std::ostringstream& {
      why << sep;
      sep = "; ";
      return why;
    };
    why.precision(3);
    if (t.near_misses > 0) {
      reason() << t.near_misses << " active sets pass the sign tests at roundoff level (ill-conditioned blocks)";
    }
    if (t.nonfinite > 0) reason() << t.nonfinite << " block solves overflowed";
    if (t.singular_skipped > 0) {
      reason() << t.singular_skipped << " singular free blocks were skipped (solve_singular_blocks is off)";
    }
    if (t.unresolved > 0) {
      reason() << t.unresolved << " active sets have a singular free block whose solution set was not searched (only "
               << "its least-norm point was tried)";
    }
    if (std::isfinite(t.closest) && t.closest <= kCertifyMargin * t.closest_tau) {
      reason() << "the closest refutation misses by " << t.closest << " against a threshold of " << t.closest_tau
               << " (a certificate needs " << kCertifyMargin << "x)";
    }
    if (const char* exists = SolutionExistsReason(problem, t.one_sign)) {
      reason() << exists << ", so a solution exists";
    }
    if (why.str().empty()) {
      result->status = SolveStatus::kInfeasible;
      s << "enum: no solution exists: all " << t.exhaustive << " active sets examined (after " << t.guided
        << " guided), each refuted with a margin of at least " << kCertifyMargin << "x the rounding threshold";
      if (t.singular > 0) s << " (" << t.singular << " singular free blocks, each refuted on its whole solution set)";
    } else {
      result->status = SolveStatus::kNumericalFailure;
      s << "enum: enumeration found no verified active set (all " << t.exhaustive << " examined); not a proof of "
        << "infeasibility: " << why.str();
    }
  }
  if (have_best) s << "; best candidate's natural residual " << t.best_merit << " (absolute)";
  result->message = s.str();
  if (options.verbosity >= 1) std::fprintf(stderr, "%s\n", result->message.c_str());
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------

namespace {
// EnumerativeOptions::IsValid's failure path, out of line: a stream set up in the function that runs on every Solve
// made GCC reserve its frame and load its vtables before the checks (50 instructions a call, for a valid struct).
[[gnu::noinline, gnu::cold]] bool ExplainInvalid(const EnumerativeOptions& o, std::string* why) {
  std::ostringstream s;
  if (o.size_limit < 1) {
    s << "size_limit must be >= 1, got " << o.size_limit;
  } else if (o.max_candidates < 1) {
    s << "max_candidates must be >= 1, got " << o.max_candidates;
  } else if (!(o.feasibility_scale >= 0.0) || !std::isfinite(o.feasibility_scale)) {
    s << "feasibility_scale must be a finite number >= 0, got " << o.feasibility_scale;
  } else if (!(o.rank_tolerance > 0.0 && o.rank_tolerance < 1.0)) {
    s << "rank_tolerance must be in (0, 1), got " << o.rank_tolerance;
  } else {
    s << "guided_steps must be in [0, " << kMaxGuidedSteps << "], got " << o.guided_steps;
  }
  if (why) *why = s.str();
  return false;
}
}  // namespace

bool EnumerativeOptions::IsValid(std::string* why) const {
  // Checked on every Solve(): the happy path must not construct a stream (that alone costs more than a small solve).
  const bool ok = size_limit >= 1 && max_candidates >= 1 && feasibility_scale >= 0.0 &&
                  std::isfinite(feasibility_scale) && rank_tolerance > 0.0 && rank_tolerance < 1.0 &&
                  guided_steps >= 0 && guided_steps <= kMaxGuidedSteps;
  return ok || ExplainInvalid(*this, why);
}

const SolverInfo& EnumerativeSolver::info() const {
  static const SolverInfo kInfo{
      "enum",
      "exhaustive active-set enumeration (lower/upper/free per row) after guided block-principal-pivoting "
      "steps from the natural-map guess, nearest-first; LU block solves with a rank-revealing least-norm "
      "fallback for singular blocks; proves infeasibility",
      "Murty 1988, Linear Complementarity, Linear and Nonlinear Programming, ch. 1 (total enumeration); "
      "Judice 1994, Algorithms for linear complementarity problems (enumerative methods); "
      "Judice & Pires 1994 (block principal pivoting)",
      /*dense=*/true,
      /*sparse=*/false,
      /*symmetric_only=*/false,
      /*exact=*/true,
      /*mcp=*/false,
      /*default_size_limit=*/EnumerativeOptions{}.size_limit};
  return kInfo;
}

void EnumerativeSolver::BindOptions(OptionBinder* binder) {
  binder->Add("size_limit", &options_.size_limit,
              "largest number of rows with a choice of state (LCP: n); larger problems get size_limit");
  binder->Add("max_candidates", &options_.max_candidates,
              "largest number of active sets (2^n LCP, 3^n box) the full search may need");
  binder->Add("feasibility_scale", &options_.feasibility_scale,
              "roundoff allowance kappa in tau = max(kappa n eps (|M||z| + |q|), tol (1 + |q|))");
  binder->Add("rank_tolerance", &options_.rank_tolerance,
              "relative pivot / R-diagonal below which a free block is treated as singular");
  binder->Add("solve_singular_blocks", &options_.solve_singular_blocks,
              "try least-norm solutions of consistent singular free blocks");
  binder->Add("guided_steps", &options_.guided_steps,
              "block principal pivoting steps before the exhaustive search (0: none)");
}

bool EnumerativeSolver::ValidateBackendOptions(std::string* why) const {
  return options_.IsValid(why);
}

void EnumerativeSolver::Reserve(int n, int guided_steps) {
  if (n == workspace_n_ && guided_steps <= workspace_history_) return;
  const std::size_t un = static_cast<std::size_t>(n);
  real_work_.assign(kRealBlocks * un * un + kRealVectors * un, 0.0);
  int_work_.assign((kIntVectors + 3 + static_cast<std::size_t>(std::max(guided_steps, 1))) * un, 0);
  workspace_n_ = n;
  workspace_history_ = std::max(guided_steps, 1);
}

template <int N>
[[gnu::always_inline]] inline bool EnumerativeSolver::SolveFast(const BoxMLCP& problem, const SolverOptions& options,
                                                                SolveResult* result) {
  // The block factors depend on M, the rank tolerance and n only, the size of the search on l and u, which never
  // change after construction (so matrix_id identifies them too): keep both while those stay the same.
  if (block_cache_.matrix_id != problem.matrix_id() || block_cache_.n != N ||
      block_cache_.rank_tolerance != options_.rank_tolerance) {
    for (auto& e : block_cache_.entries) e.state = BlockCache::kUnknown;
    block_cache_.matrix_id = problem.matrix_id();
    block_cache_.n = N;
    block_cache_.rank_tolerance = options_.rank_tolerance;
    double total = 1.0;
    const double* l = problem.l().data();
    const double* u = problem.u().data();
    for (int i = 0; i < N; ++i) {  // states per row: 1 fixed or free, 2 one finite bound, 3 two
      const bool lower = l[i] > -kInf, upper = u[i] < kInf;
      total *= l[i] == u[i] ? 1.0 : lower ? (upper ? 3.0 : 2.0) : (upper ? 2.0 : 1.0);
    }
    block_cache_.active_sets_total = total;
  }
  double* zr = result->z.data();
  double z0[N], z[N];
  for (int i = 0; i < N; ++i) z0[i] = zr[i];
  if (!SolveGuessedSet<N>(problem, options_.rank_tolerance, z0, z, &block_cache_)) return false;
  for (int i = 0; i < N; ++i) zr[i] = z[i];
  // Accepted by the merit function, both of its tests, division-free and 4 ulps on the safe side: the problem is
  // the row-equilibrated one (row scales 1), so the residual in units of z is abs / (1 + ‖z‖∞) and both tests bound
  // abs. Only when that fails, the exact test (a point the merit function accepts must not be passed over: the
  // search would judge another candidate, not this one); it recomputes the merit, a cold path.
  double z_norm = 0.0;
  for (int i = 0; i < N; ++i) z_norm = std::max(z_norm, std::abs(z[i]));
  const double abs = problem.template NaturalResidualAbsFixed<N>(z);  // the merit's abs, without w (the base's)
  if (!(abs <= options.tolerance * std::min(problem.residual_scale(), 1.0 + z_norm) * (1.0 - 4.0 * kEps)) &&
      !PassesBoxMlcpTolerance(FixedSizeMerit<N>(problem, result), options.tolerance)) {
    for (int i = 0; i < N; ++i) zr[i] = z0[i];  // the search starts from the caller's point
    return false;
  }
  result->status = SolveStatus::kSolved;
  result->iterations = 1;
  result->SetDetails({"active_sets_total", "guided_sets", "singular_blocks"},
                     {block_cache_.active_sets_total, 1.0, 0.0});
  return true;
}

void EnumerativeSolver::DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) {
  switch (problem.size()) {
    case 1: if (!SolveFast<1>(problem, options, result)) Search<1>(problem, options, result); return;
    case 2: if (!SolveFast<2>(problem, options, result)) Search<2>(problem, options, result); return;
    case 3: if (!SolveFast<3>(problem, options, result)) Search<3>(problem, options, result); return;
    case 4: if (!SolveFast<4>(problem, options, result)) Search<4>(problem, options, result); return;
    default: Search<0>(problem, options, result); return;
  }
}


// ---------------------------------------------------------------------------------------------------------
// The search, in named phases that share one state (N = 1..4 fixed at compile time, 0 read at run time). Run()
// reads top to bottom: refuse an oversized problem, measure the scales, guess from the start point, the guided
// phase, the exhaustive phase, record the answer. One object on the stack holds what the phases share, so the
// compiler keeps inlining them into Run as it did the single function (a split passing many parameters was
// measurably slower on the small solves).

// How a candidate ended, and how a rejection counts. judge: kRefutes (it refutes the active set, at the threshold τ
// widened by the block solve's error, growth = max|M_FF| over the smallest LU pivot), kUnresolved (it does not: a
// point of a singular block's solution set), kAttempt (no bookkeeping: the caller tries more points of the same set).
namespace {
enum class Outcome { kSolution, kRejected, kBroken };
enum class Refutation { kRefutes, kUnresolved, kAttempt };
}  // namespace

template <int N>
class EnumerativeSolver::ActiveSetSearch {
 public:
  ActiveSetSearch(EnumerativeSolver& solver, const BoxMLCP& problem, const SolverOptions& options,
                  SolveResult* result)
      : solver(solver),
        problem(problem),
        options(options),
        result(result),
        n_runtime(N > 0 ? N : problem.size()),
        M(problem.dense_matrix().data()),
        q(problem.q().data()),
        l(problem.l().data()),
        u(problem.u().data()) {}

  void Run() {
    if (!WithinSizeLimit()) return;
    AttachWorkspace();
    MeasureScales();
    GuessFromStart();
    GuidedPhase();
    if (stop == SolveStatus::kNotRun) ExhaustivePhase();
    RecordOutcome();
  }

 private:
  // ---- Phase: classify the bounds. The size of the full search depends only on them: refuse before any work.
  bool WithinSizeLimit() {
    const int n = N > 0 ? N : n_runtime;
    int nb = 0;  // rows with a choice of state
    for (int i = 0; i < n; ++i) {
      const int count = l[i] == u[i] ? 1 : 1 + (l[i] > -kInf) + (u[i] < kInf);
      nb += count > 1;
      total *= count;
    }
    const EnumerativeOptions& limits = solver.options_;
    if (nb <= limits.size_limit && total <= static_cast<double>(limits.max_candidates)) return true;
    std::ostringstream s;
    s << "enum: " << nb << " of the " << n << " rows have a choice of state, so the full search may need "
      << CountText(total) << " active sets; limits are size_limit = " << limits.size_limit
      << " rows and max_candidates = " << limits.max_candidates
      << " sets (raise them with the options size_limit=N / max_candidates=N; the work grows as 2^n to 3^n)";
    result->status = SolveStatus::kSizeLimit;
    result->message = s.str();
    result->iterations = 0;
    return false;
  }

  // ---- Phase: the problem's scales, for the merit tolerance and the roundoff allowance of the sign tests
  // (header, feasibility_scale). Needs the workspace (AttachWorkspace).
  void MeasureScales() {
    const int n = N > 0 ? N : n_runtime;
    tol_abs = options.tolerance * problem.residual_scale();
    q_norm = problem.residual_scale() - 1.0;
    for (int i = 0; i < n; ++i) b.w[i] = 0.0;  // the row sums of |M|, column by column (w is scratch here)
    for (int j = 0; j < n; ++j) {
      const double* mj = col(j);
      for (int i = 0; i < n; ++i) b.w[i] += std::abs(mj[i]);
    }
    for (int i = 0; i < n; ++i) m_norm = std::max(m_norm, b.w[i]);
    roundoff = solver.options_.feasibility_scale * n * kEps;
  }

  // The views of the workspace: the stack arrays for N > 0 (the heap for a history longer than they hold), the
  // solver's vectors for N = 0.
  void AttachWorkspace() {
    const int n = N > 0 ? N : n_runtime;
    const int guided_max = solver.options_.guided_steps;
    if constexpr (N > 0) {
      b = storage.View();
      if (guided_max > FixedStorage<N>::kHistory) {  // a larger history than the stack holds: use the heap
        solver.Reserve(n, guided_max);
        b.history = solver.int_work_.data() + (kIntVectors + 3) * static_cast<std::size_t>(n);
      }
    } else {
      solver.Reserve(n, guided_max);
      const std::size_t un = static_cast<std::size_t>(n);
      double* r = solver.real_work_.data();
      double** reals[] = {&b.z, &b.w, &b.y, &b.rhs, &b.xref, &b.tau, &b.tau2, &b.v, &b.margin, &b.start, &b.best};
      b.ld = n;
      b.A = r, r += un * un;
      b.T = r, r += un * un;
      for (double** p : reals) *p = r, r += un;
      int* k = solver.int_work_.data();
      int** ints[] = {&b.piv, &b.jpvt, &b.free_idx, &b.state, &b.radix, &b.order, &b.comb, &b.offset};
      for (int** p : ints) *p = k, k += un;
      b.choice = k, k += 3 * un;
      b.history = k;
    }
  }

  // ---- Phase: the first guess, the natural-map active set at the starting point (GuessState).
  void GuessFromStart() {
    const int n = N > 0 ? N : n_runtime;
    const double* z0 = result->z.data();
    for (int i = 0; i < n; ++i) b.start[i] = z0[i], b.xref[i] = std::min(std::max(0.0, l[i]), u[i]);
    Affine(z0, b.w);
    for (int i = 0; i < n; ++i) {
      b.y[i] = z0[i] - b.w[i] / JacobiScale(col(i)[i]);
      b.state[i] = GuessState(b.y[i], l[i], u[i]);
    }
  }

  // ---- Phase 1, guided: block principal pivoting (Júdice & Pires 1994), i.e. the primal-dual active-set step
  // (Hintermüller, Ito & Kunisch 2002): the next set is the natural-map active set at the last candidate,
  // y = z − D⁻¹(M z + q) with z_F unclipped. It usually ends in a few sets; it stops at a repeated set.
  void GuidedPhase() {
    const int n = N > 0 ? N : n_runtime;
    const int guided_max = solver.options_.guided_steps;
    for (int step = 0; step < guided_max; ++step) {
      int* seen = b.history + static_cast<std::ptrdiff_t>(step) * n;
      for (int i = 0; i < n; ++i) seen[i] = b.state[i];
      ++examined, ++guided;
      const Outcome outcome = Examine();
      if (outcome == Outcome::kSolution) {
        stop = SolveStatus::kSolved;
        return;
      }
      if (outcome == Outcome::kBroken || OutOfBudget()) return;
      for (int a = 0, i = 0; i < n; ++i) {  // z with z_F unclipped, then y and the next set
        if (b.state[i] == kFree) b.z[i] = b.rhs[a++];
      }
      Affine(b.z, b.w);
      for (int i = 0; i < n; ++i) {
        b.y[i] = b.z[i] - b.w[i] / JacobiScale(col(i)[i]);
        b.state[i] = GuessState(b.y[i], l[i], u[i]);
      }
      bool repeated = false;
      for (int s = 0; s <= step && !repeated; ++s) {
        const int* old = b.history + static_cast<std::ptrdiff_t>(s) * n;
        repeated = std::equal(old, old + n, b.state);
      }
      if (repeated) return;
    }
  }

  // ---- Phase 2, exhaustive: every active set, nearest-first around the last guess (Hamming distance from it),
  // least confident rows (y nearest to a switch of state) first.
  void ExhaustivePhase() {
    const int nb = OrderChoices();
    NearestFirst order(nb, b.radix, b.comb, b.offset);
    KeyGuidedSets(nb);
    in_exhaustive = true;
    while (true) {
      for (int p = 0; p < nb; ++p) {
        const int i = b.order[p];
        b.state[i] = b.choice[3 * i + b.offset[p]];
      }
      ++examined, ++exhaustive;
      if (order.distance() <= guided_max_distance && GuidedRepeat(OffsetKey(nb))) {
        CountRepeatedSet();
      } else if (Examine() == Outcome::kSolution) {
        stop = SolveStatus::kSolved;
        return;
      }
      if (!order.Next() || OutOfBudget()) return;
    }
  }

  // The exhaustive phase starts at the set the guided phase stopped on, a repeat, and its nearest neighbours are
  // often guided sets too; examining them again costs most on singular blocks (a QR and the line of solutions:
  // lcp_CPS_4, lcp_inf_sol_perturbed, relay2_mlcp). The guided sets (the first kKeyedGuidedSets) within
  // kRepeatDistance rows of that start are keyed by their index in the exhaustive order's mixed radix
  // (< max_candidates), with a 64-bit filter on key mod 64. Only the first 1 + 2·nb sets (nearest-first) are
  // checked: keying farther sets cost the 3^8 sets of a strongly nonsymmetric relay 5 % more instructions.
  void KeyGuidedSets(int nb) {
    const int n = N > 0 ? N : n_runtime;
    const long long count = std::min<long long>(guided, kKeyedGuidedSets);
    for (long long s = 0; s < count; ++s) {
      const int* seen = b.history + static_cast<std::ptrdiff_t>(s) * n;
      int changed = 0;  // rows away from the first exhaustive set (offset 0 everywhere), counted up to one too many
      for (int p = 0; p < nb && changed <= kRepeatDistance; ++p) changed += seen[b.order[p]] != b.choice[3 * b.order[p]];
      if (changed > kRepeatDistance) continue;
      std::uint64_t key = 0;
      int distance = 0;    // rows away from the exhaustive phase's first set
      bool listed = true;  // every row's guided state is one of its choices (always: both phases use GuessState's)
      for (int p = nb - 1; p >= 0 && listed; --p) {
        const int i = b.order[p];
        int offset = 0;
        while (offset < b.radix[p] && b.choice[3 * i + offset] != seen[i]) ++offset;
        listed = offset < b.radix[p];
        key = key * static_cast<std::uint64_t>(b.radix[p]) + static_cast<std::uint64_t>(offset);
        distance += offset != 0;
      }
      if (!listed || distance > kRepeatDistance) continue;
      guided_keys[guided_key_count++] = key;
      guided_key_filter |= std::uint64_t{1} << (key & 63);
      guided_max_distance = std::max(guided_max_distance, distance);
    }
  }

  // The current set's key (KeyGuidedSets) from the order's offsets.
  std::uint64_t OffsetKey(int nb) const {
    std::uint64_t key = 0;
    for (int p = nb - 1; p >= 0; --p) {
      key = key * static_cast<std::uint64_t>(b.radix[p]) + static_cast<std::uint64_t>(b.offset[p]);
    }
    return key;
  }

  bool GuidedRepeat(std::uint64_t key) const {
    if ((guided_key_filter >> (key & 63) & 1) == 0) return false;
    for (int c = 0; c < guided_key_count; ++c) {
      if (guided_keys[c] == key) return true;
    }
    return false;
  }

  // A set the guided phase examined and refuted (it did not solve, or the search would have stopped): judged again
  // it is refuted again, the search being deterministic, and every tally but the exhaustive phase's own already
  // holds it. Only those are kept, as Examine keeps them: its determinant's sign and the singular-block counts.
  void CountRepeatedSet() {
    const int k = PlaceBoundRows();
    if (verbose) Trace(examined, b.state, N > 0 ? N : n_runtime, "examined in the guided phase; not again", 0.0);
    if (k == 0) {
      ++det_positive;
      return;
    }
    BuildRhs(k);
    const double amax = Gather(k);
    if (SolveBlock(b.A, b.ld, k, b.rhs, b.piv, solver.options_.rank_tolerance * amax)) {
      CountDeterminantSign(FactoredPivots(b.A, b.ld, k, b.piv), k, amax);
      return;
    }
    ++singular, ++det_unclear;
    if (!solver.options_.solve_singular_blocks) ++singular_skipped;
  }

  // The set b.state's bound rows at their bounds in b.z (its free rows at 0, listed in b.free_idx): the free count.
  [[gnu::always_inline]] inline int PlaceBoundRows() {
    const int n = N > 0 ? N : n_runtime;
    int k = 0;
    for (int i = 0; i < n; ++i) {
      const int s = b.state[i];
      if (s == kFree) {
        b.free_idx[k++] = i;
        b.z[i] = 0.0;
      } else {
        b.z[i] = s == kUpper ? u[i] : l[i];
      }
    }
    return k;
  }

  // The exhaustive phase's tally of det M_FF's sign (clear pivots) for the one-sign test of ReportUnsolved.
  void CountDeterminantSign(const BlockPivots& pivots, int k, double amax) {
    const bool clear = pivots.smallest > kDeterminantSignMargin * k * kEps * amax;
    ++(!clear ? det_unclear : pivots.sign > 0 ? det_positive : det_negative);
  }

  // The exhaustive phase's order: per row its states, the guess at b.y first, then the nearer bound; the rows
  // with a choice (returned: how many) least confident first, with their number of states per position.
  int OrderChoices() {
    const int n = N > 0 ? N : n_runtime;
    int nb = 0;
    for (int i = 0; i < n; ++i) {
      const double y = b.y[i];
      const int guess = GuessState(y, l[i], u[i]);
      const bool has_l = l[i] > -kInf, has_u = u[i] < kInf;
      int* ch = b.choice + 3 * i;
      int count = 0;
      double margin = 0.0;
      ch[count++] = guess;
      if (guess == kLower) {
        ch[count++] = kFree;
        if (has_u) ch[count++] = kUpper;
        margin = l[i] - y;
      } else if (guess == kUpper) {
        ch[count++] = kFree;
        if (has_l) ch[count++] = kLower;
        margin = y - u[i];
      } else if (guess == kFree) {
        const double dl = y - l[i], du = u[i] - y;  // +∞ for an absent bound
        if (has_l && (!has_u || dl <= du)) {
          ch[count++] = kLower;
          if (has_u) ch[count++] = kUpper;
        } else if (has_u) {
          ch[count++] = kUpper;
          if (has_l) ch[count++] = kLower;
        }
        margin = std::min(dl, du);
      }
      b.state[i] = guess;
      if (count > 1) {
        b.order[nb++] = i;
        b.margin[i] = margin;
        b.radix[i] = count;
      }
    }
    std::sort(b.order, b.order + nb, [&](int a, int c) {
      return b.margin[a] < b.margin[c] || (b.margin[a] == b.margin[c] && a < c);
    });
    for (int p = 0; p < nb; ++p) b.comb[p] = b.radix[b.order[p]];
    for (int p = 0; p < nb; ++p) b.radix[p] = b.comb[p];  // now per position
    return nb;
  }

  // ---- Phase: record the answer, or say why there is none.
  void RecordOutcome() {
    const int n = N > 0 ? N : n_runtime;
    result->iterations = examined > std::numeric_limits<int>::max() ? std::numeric_limits<int>::max()
                                                                    : static_cast<int>(examined);
    SetSearchDetails(total, static_cast<double>(guided), static_cast<double>(singular), result);
    if (stop == SolveStatus::kSolved) {
      result->status = SolveStatus::kSolved;
      if (options.verbosity >= 1) {
        std::fprintf(stderr, "enum: solved after %lld active sets (%lld guided) of %s\n", examined, guided,
                     CountText(total).c_str());
      }
      return;
    }
    // No solution found. Return the best candidate by merit value if there was one, else the starting point.
    const bool have_best = std::isfinite(best_merit);
    for (int i = 0; i < n; ++i) result->z[i] = have_best ? b.best[i] : b.start[i];
    SearchTally tally;
    tally.examined = examined, tally.guided = guided, tally.exhaustive = exhaustive, tally.singular = singular;
    tally.singular_skipped = singular_skipped, tally.nonfinite = nonfinite, tally.near_misses = near_misses;
    tally.unresolved = unresolved, tally.total = total, tally.best_merit = best_merit, tally.closest = closest;
    tally.closest_tau = closest_tau;
    tally.one_sign = det_unclear == 0 && (det_positive == 0 || det_negative == 0);
    ReportUnsolved(problem, options, stop, tally, result);
  }

  // ---- One active set (b.state): factor and solve its free block M_FF z_F = −(q_F + M_FB z_B), then judge.
  [[gnu::always_inline]] inline Outcome Examine() {
    const int k = PlaceBoundRows();
    if (k == 0) {
      if (in_exhaustive) ++det_positive;  // the empty block: det = 1
      return Judge(0, 1.0, Refutation::kRefutes);
    }
    BuildRhs(k);
    const double amax = Gather(k);
    if (SolveBlock(b.A, b.ld, k, b.rhs, b.piv, solver.options_.rank_tolerance * amax)) {
      const BlockPivots pivots = FactoredPivots(b.A, b.ld, k, b.piv);
      if (in_exhaustive) CountDeterminantSign(pivots, k, amax);
      return Judge(k, amax / pivots.smallest, Refutation::kRefutes);
    }
    // Numerically singular M_FF (a pivot below rank_tolerance · max|M_FF|).
    ++singular;
    if (in_exhaustive) ++det_unclear;
    if (!solver.options_.solve_singular_blocks) {
      ++singular_skipped;
      if (verbose) Trace(examined, b.state, N > 0 ? N : n_runtime, "singular block skipped", 0.0);
      return Outcome::kBroken;
    }
    return ExamineSingular(k);
  }

  // Judges the candidate with z_B in b.z and the free rows' values (unclipped) in b.rhs (Refutation: above).
  inline Outcome Judge(int k, double growth, Refutation refutation) {
    const int n = N > 0 ? N : n_runtime;
    double zmax = 0.0;
    for (int i = 0; i < n; ++i) zmax = std::max(zmax, b.state[i] == kFree ? 0.0 : std::abs(b.z[i]));
    for (int a = 0; a < k; ++a) {
      if (!std::isfinite(b.rhs[a])) {
        if (refutation == Refutation::kAttempt) return Outcome::kRejected;
        ++nonfinite;
        if (verbose) Trace(examined, b.state, n, "block solution overflowed", 0.0);
        return Outcome::kBroken;
      }
      zmax = std::max(zmax, std::abs(b.rhs[a]));
    }
    const double roundoff_scale = roundoff * (m_norm * zmax + q_norm);
    const double tau = std::max(roundoff_scale, tol_abs);
    const double tau_certify = std::max(tau, roundoff_scale * growth);
    const auto miss = [&](double value) {
      if (refutation == Refutation::kRefutes) RecordMiss(value, tau_certify);
      if (refutation == Refutation::kUnresolved) ++unresolved;
    };
    // z_F within its bounds up to τ, then clipped onto them.
    double violation = 0.0;
    for (int a = 0; a < k; ++a) {
      const int i = b.free_idx[a];
      violation = std::max(violation, std::max(l[i] - b.rhs[a], b.rhs[a] - u[i]));
    }
    if (violation > tau) {
      miss(violation);
      if (verbose) Trace(examined, b.state, n, "z_F outside its bounds by", violation);
      return Outcome::kRejected;
    }
    double z_norm = 0.0;
    for (int a = 0; a < k; ++a) {
      const int i = b.free_idx[a];
      b.z[i] = std::min(std::max(b.rhs[a], l[i]), u[i]);
    }
    for (int i = 0; i < n; ++i) z_norm = std::max(z_norm, std::abs(b.z[i]));
    // The merit function decides: r = ‖z − Π(z − (M z + q))‖∞. On bound rows it is the sign violation of w, on
    // free rows the equation residual, so it is also the sign test (at threshold τ). "Solved" (Solver::Finish)
    // needs r ≤ tol·(1 + ‖q‖∞) and r ≤ tol·(1 + ‖z‖∞) (the problem is equilibrated): clearly below both, the
    // candidate is accepted; near them, BoxMLCP::NaturalResidual, the function the base class applies, decides.
    Affine(b.z, b.w);
    double merit = 0.0;
    for (int i = 0; i < n; ++i) {
      merit = std::max(merit, std::abs(b.z[i] - std::min(std::max(b.z[i] - b.w[i], l[i]), u[i])));
    }
    const double accept = options.tolerance * std::min(problem.residual_scale(), 1.0 + z_norm);
    const double reject = options.tolerance * std::max(problem.residual_scale(), 1.0 + z_norm);
    if (merit <= 2.0 * reject) {
      for (int i = 0; i < n; ++i) result->z[i] = b.z[i];
      if (merit <= 0.5 * accept ||
          PassesBoxMlcpTolerance(problem.NaturalResidual(result->z, &result->w), options.tolerance)) {
        if (verbose) Trace(examined, b.state, n, "solves; merit", merit);
        return Outcome::kSolution;
      }
    }
    if (merit < best_merit) {
      best_merit = merit;
      for (int i = 0; i < n; ++i) b.best[i] = b.z[i];
    }
    if (refutation == Refutation::kAttempt) return Outcome::kRejected;
    if (merit <= tau) ++near_misses;  // passes the sign tests at roundoff level only: ill-conditioned
    if (verbose) Trace(examined, b.state, n, merit <= tau ? "near-solution; merit" : "sign test fails; merit", merit);
    miss(merit);
    return Outcome::kRejected;
  }

  // ---- A numerically singular free block (rare): out of line, so that it does not weigh on the inlining budget
  // of the fixed-size paths. First the LU solution itself, when its pivots are nonzero (the merit function, not the
  // size of a pivot, decides whether it solves the problem); then the least-norm solution about Π(0) of the
  // rank-cut system (a consistent singular block has a whole affine set of solutions), and the set's refutation.
  [[gnu::noinline]] Outcome ExamineSingular(int k) {
    BuildRhs(k);
    Gather(k);
    if (SolveBlock(b.A, b.ld, k, b.rhs, b.piv, 0.0) && Judge(k, kInf, Refutation::kAttempt) == Outcome::kSolution) {
      return Outcome::kSolution;
    }
    BuildRhs(k);
    Gather(k);
    for (int a = 0; a < k; ++a) b.w[a] = b.xref[b.free_idx[a]];  // w is scratch until the merit test
    const int rank =
        LeastNormSolve(b.A, b.T, b.ld, k, b.w, b.rhs, b.tau, b.tau2, b.v, b.jpvt, solver.options_.rank_tolerance);
    // Rank k − 1: every solution of this active set (the whole line if the block is exactly singular and the
    // system consistent, the one point if the cut direction was merely tiny, none if inconsistent) lies on the line
    // x₀ + t·v, v spanning the cut direction of the QR. The set is refuted when no point of that line meets the
    // equations, box and sign conditions; otherwise the best point of the line is the candidate.
    LineOfSolutions line;
    if (rank == k - 1) line = FitLine(b.A, b.ld, k, b.jpvt, b.T, b.v);  // T is free after LeastNormSolve
    MarkRowsBlindToTheBlock(k);
    return line.ok ? JudgeLineOfSolutions(k, line) : JudgeDeeplyDeficient(k);
  }

  // Rows whose entries on the free columns are all exactly zero: their w does not depend on x at all, so their
  // conditions hold or fail for every point of the block's solution set alike (b.margin[i] = 1; scratch here).
  void MarkRowsBlindToTheBlock(int k) {
    const int n = N > 0 ? N : n_runtime;
    for (int i = 0; i < n; ++i) {
      bool zero = true;
      for (int a = 0; a < k && zero; ++a) zero = col(b.free_idx[a])[i] == 0.0;
      b.margin[i] = zero ? 1.0 : 0.0;
    }
  }

  // A rank deficiency above one: the least-norm point (in b.rhs) is one of many and refutes nothing; only a row
  // that does not see x (MarkRowsBlindToTheBlock) can refute the set, for every x at once.
  Outcome JudgeDeeplyDeficient(int k) {
    const int n = N > 0 ? N : n_runtime;
    double zmax = 0.0;
    for (int a = 0, i = 0; i < n; ++i) {
      if (b.state[i] == kFree) b.z[i] = b.rhs[a++];
      zmax = std::max(zmax, std::abs(b.z[i]));
    }
    Affine(b.z, b.w);
    double blind_violation = 0.0;  // the largest violated condition among the rows that do not see x
    for (int i = 0; i < n; ++i) {
      if (b.margin[i] == 0.0) continue;
      const double wi = b.w[i];
      const int st = b.state[i];
      const double violated = st == kFree ? std::abs(wi) : st == kLower ? -wi : st == kUpper ? wi : 0.0;
      blind_violation = std::max(blind_violation, violated);
    }
    for (int i = 0; i < n; ++i) {
      if (b.state[i] == kFree) b.z[i] = 0.0;
    }
    if (Judge(k, kInf, Refutation::kAttempt) == Outcome::kSolution) return Outcome::kSolution;
    const double tau = std::max(roundoff * (m_norm * zmax + q_norm), tol_abs);
    if (blind_violation > kCertifyMargin * tau) {
      RecordMiss(blind_violation, tau);
    } else {
      ++unresolved;
    }
    if (verbose) Trace(examined, b.state, n, "singular block; violation independent of x", blind_violation);
    return Outcome::kRejected;
  }

  // A rank k − 1 block: its solutions lie on the line x₀ + t·v (x₀ in b.rhs, v in b.v). The set is refuted with a
  // margin when no point of the line comes within the rounding threshold of every condition; the point of least
  // violation is judged as the candidate.
  Outcome JudgeLineOfSolutions(int k, const LineOfSolutions& line) {
    const int n = N > 0 ? N : n_runtime;
    const bool null_exact = ExactNullDirection(k);
    // Constraints α_j + β_j t ≥ 0 on the line: the free rows' equations w_i = 0 (both signs: an inconsistent block
    // violates them everywhere on the line) and bounds, the signs of w on the bound rows (w at x₀ in b.w, its change
    // Δw = M_·F v per unit of t in b.y).
    for (int i = 0; i < n; ++i) b.y[i] = 0.0;
    for (int a = 0; a < k; ++a) {
      const double* mj = col(b.free_idx[a]);
      for (int i = 0; i < n; ++i) b.y[i] += mj[i] * b.v[a];
    }
    double bound_max = 0.0;  // largest |z_i| over the bound rows
    for (int a = 0, i = 0; i < n; ++i) {
      if (b.state[i] == kFree) {
        b.z[i] = b.rhs[a++];
      } else {
        bound_max = std::max(bound_max, std::abs(b.z[i]));
      }
    }
    Affine(b.z, b.w);
    // take(α, β, sees_x): sees_x is false for a row that does not see x, whose condition is exact along the line.
    const auto constraints_flagged = [&](const auto& take) {
      for (int a = 0; a < k; ++a) {
        const int i = b.free_idx[a];
        if (l[i] > -kInf) take(b.rhs[a] - l[i], b.v[a], true);
        if (u[i] < kInf) take(u[i] - b.rhs[a], -b.v[a], true);
      }
      for (int i = 0; i < n; ++i) {
        const bool sees_x = b.margin[i] == 0.0;
        if (b.state[i] == kLower || b.state[i] == kFree) take(b.w[i], b.y[i], sees_x);
        if (b.state[i] == kUpper || b.state[i] == kFree) take(-b.w[i], -b.y[i], sees_x);
      }
    };
    const auto constraints = [&](const auto& take) {
      constraints_flagged([&](double alpha, double beta, bool) { take(alpha, beta); });
    };
    // Refuted with a margin when no t meets every constraint to within kCertifyMargin·τ(t), where the rounding
    // threshold τ(t) grows with ‖x(t)‖∞ (far along the line the computed Δw is mostly rounding: a nearly singular
    // block's one solution can sit at |t| ~ 1/σ_min). τ(t) = tol·(1 + ‖q‖) + G·feasibility_scale·n·ε·(‖M‖‖x(t)‖∞
    // + ‖q‖), G the growth of the kept part of the QR. ‖x(t)‖∞ is the largest of the pieces ±(x₀ + t v)_a and the
    // bound rows' |z|: the constraints hold at some t for the largest piece iff they do for one piece, an interval
    // test each. A row that does not see x keeps a constant threshold: its w is the same at every point.
    const double growth = std::max(1.0, line.growth);
    const double slack0 = kCertifyMargin * (tol_abs + growth * roundoff * q_norm);
    const double slack1 = null_exact ? 0.0 : kCertifyMargin * growth * roundoff * m_norm;
    const auto some_t_within_slack = [&](double piece0, double piece1) {
      double lo = -kInf, hi = kInf;
      bool ok = true;
      constraints_flagged([&](double alpha, double beta, bool sees_x) {
        const double grow = sees_x ? slack1 : 0.0;
        const double a0 = alpha + slack0 + grow * piece0, a1 = beta + grow * piece1;
        if (a1 > 0.0) {
          lo = std::max(lo, -a0 / a1);
        } else if (a1 < 0.0) {
          hi = std::min(hi, -a0 / a1);
        } else {
          ok = ok && a0 >= 0.0;
        }
      });
      return ok && lo <= hi;
    };
    bool refuted = !some_t_within_slack(bound_max, 0.0);
    for (int a = 0; a < k && refuted; ++a) {
      refuted = !some_t_within_slack(b.rhs[a], b.v[a]) && !some_t_within_slack(-b.rhs[a], -b.v[a]);
    }
    // The candidate: the point of the line with the least violation, nearest x₀.
    const LeastViolation least = MinimizeWorstViolation(constraints);
    for (int a = 0, i = 0; i < n; ++i) {
      if (b.state[i] == kFree) b.z[i] = 0.0, b.rhs[a] += least.t * b.v[a], ++a;
    }
    if (Judge(k, line.growth, Refutation::kAttempt) == Outcome::kSolution) return Outcome::kSolution;
    if (!refuted) ++near_misses;  // some point of the line is within rounding of every condition
    if (verbose) {
      Trace(examined, b.state, n, refuted ? "singular block, no point of its line qualifies; least violation"
                                          : "singular block, a point of its line is within rounding; violation",
            least.violation);
    }
    return Outcome::kRejected;
  }

  // Whether M_FF v = 0 holds exactly for the line's direction b.v (checked without rounding): then v spans the
  // exact null space, the solution set is exactly parallel to the line and a constant threshold suffices. The QR's
  // v carries rounding, so v rounded to 20 bits (an exact null vector of a matrix of small integers and simple
  // ratios, e.g. (1, 1)) is tried too, and kept in b.v when it is exact.
  bool ExactNullDirection(int k) {
    const auto exact_null = [&](const double* vec) {
      bool exact = true;
      for (int c = 0; c < k && exact; ++c) {
        const int i = b.free_idx[c];
        exact = ExactlyZeroDot(k, [&](int a) { return col(b.free_idx[a])[i]; }, vec);
      }
      return exact;
    };
    if (exact_null(b.v)) return true;
    for (int a = 0; a < k; ++a) b.T[a] = std::ldexp(std::round(std::ldexp(b.v[a], 20)), -20);
    if (!exact_null(b.T)) return false;
    std::copy(b.T, b.T + k, b.v);
    return true;
  }

  // ---- Small shared steps.
  const double* col(int j) const { return M + static_cast<std::ptrdiff_t>(j) * (N > 0 ? N : n_runtime); }

  // w = M z + q, column by column.
  [[gnu::always_inline]] inline void Affine(const double* z, double* w) const {
    const int n = N > 0 ? N : n_runtime;
    for (int i = 0; i < n; ++i) w[i] = q[i];
    for (int j = 0; j < n; ++j) {
      const double zj = z[j];
      if (zj == 0.0) continue;
      const double* mj = col(j);
      for (int i = 0; i < n; ++i) w[i] += mj[i] * zj;
    }
  }

  // The free block of the active set in b.state (rows b.free_idx[0 .. k)): right-hand side −(q_F + M_FB z_B)
  // into b.rhs.
  [[gnu::always_inline]] inline void BuildRhs(int k) {
    const int n = N > 0 ? N : n_runtime;
    for (int a = 0; a < k; ++a) b.rhs[a] = -q[b.free_idx[a]];
    for (int j = 0; j < n; ++j) {
      const double zj = b.z[j];
      if (zj == 0.0 || b.state[j] == kFree) continue;
      const double* mj = col(j);
      for (int a = 0; a < k; ++a) b.rhs[a] -= mj[b.free_idx[a]] * zj;
    }
  }

  // M_FF into b.A; returns max |M_FF|.
  [[gnu::always_inline]] inline double Gather(int k) {
    double amax = 0.0;
    for (int c = 0; c < k; ++c) {
      const double* mj = col(b.free_idx[c]);
      double* ac = b.A + static_cast<std::ptrdiff_t>(c) * b.ld;
      for (int a = 0; a < k; ++a) {
        ac[a] = mj[b.free_idx[a]];
        amax = std::max(amax, std::abs(ac[a]));
      }
    }
    return amax;
  }

  // The closest refutation of any candidate (bound violation of z_F, or merit value) relative to its certificate
  // threshold (τ, widened by the block's pivot growth).
  void RecordMiss(double miss, double tau) {
    if (miss * closest_tau < closest * tau) closest = miss, closest_tau = tau;
  }

  // Budget and clock, checked after each examined set that did not solve.
  bool OutOfBudget() {
    if (budget > 0 && examined >= budget) {
      stop = SolveStatus::kIterationLimit;
    } else if ((examined & 15) == 0 && solver.TimeLimitReached()) {
      stop = SolveStatus::kTimeLimit;
    }
    return stop != SolveStatus::kNotRun;
  }

  // ---- The shared state.
  EnumerativeSolver& solver;  // its options_, workspace and clock
  const BoxMLCP& problem;     // the row-equilibrated problem
  const SolverOptions& options;
  SolveResult* result;
  const int n_runtime;  // rows; the phases read N instead when it is fixed
  const double* M;
  const double* q;
  const double* l;
  const double* u;
  FixedStorage<N> storage;  // the workspace of the fixed-size path (empty for N = 0)
  Buffers b;
  double total = 1.0;  // active sets in the full search
  // Problem scales: the merit tolerance and the roundoff allowance of the sign tests.
  double tol_abs = 0.0, q_norm = 0.0, m_norm = 0.0, roundoff = 0.0;
  const bool verbose = options.verbosity >= 2;
  const long long budget = options.max_iterations > 0 ? options.max_iterations : -1;
  long long examined = 0, guided = 0, exhaustive = 0, singular = 0, singular_skipped = 0, nonfinite = 0,
            near_misses = 0, unresolved = 0;
  double best_merit = kInf;  // smallest merit value among the candidates that reached the merit test
  double closest = kInf, closest_tau = 1.0;  // RecordMiss
  // Signs of det M_FF over the exhaustive phase (every free set appears there): one sign throughout, with clear
  // pivots, means the Schur complement of the always-free rows is a P-matrix, so a solution exists.
  bool in_exhaustive = false;
  long long det_positive = 0, det_negative = 0, det_unclear = 0;
  // KeyGuidedSets: the guided sets the exhaustive phase does not examine again.
  static constexpr int kKeyedGuidedSets = 16;  // guided_steps' default
  static constexpr int kRepeatDistance = 1;
  std::uint64_t guided_keys[kKeyedGuidedSets] = {};
  int guided_key_count = 0;
  std::uint64_t guided_key_filter = 0;  // bit key mod 64 of every keyed set
  int guided_max_distance = -1;         // the largest Hamming distance of a keyed set from the first exhaustive one
  SolveStatus stop = SolveStatus::kNotRun;  // kSolved, or why the search stopped early
};

// Out of line: the search is the fast path's fallback, and inlined into DoSolve it would crowd out the inlining
// of the fast path's own calls.
template <int N>
[[gnu::noinline]] void EnumerativeSolver::Search(const BoxMLCP& problem, const SolverOptions& options,
                                                 SolveResult* result) {
  ActiveSetSearch<N> search(*this, problem, options, result);
  search.Run();
}

}  // namespace smcbench

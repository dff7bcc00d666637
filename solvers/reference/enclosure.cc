// Interval proof of a box-MLCP solution near a point (see enclosure.h for the method and the rounding argument).
#include "solvers/reference/enclosure.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "solvers/core/number_text.h"

namespace smcbench {
namespace {

using Quad = __float128;  // as in certify.cc: libgcc arithmetic, no libquadmath call

constexpr double kUnit = std::numeric_limits<double>::epsilon() / 2;  // u = 2⁻⁵³, round to nearest
constexpr Quad kQuadUnit = 0x1p-113;
// Every bound below is a sum or product of nonnegative numbers computed in at most a few hundred roundings, each
// of relative error ≤ u, so its exact value is at most (1 − u)^-1000 < 1 + 1e-12 times the computed one; gradual
// underflow adds at most 2⁻¹⁰⁷⁵ per operation. Up() covers both, generously.
constexpr double kSlack = 1.0 + 1e-12;
constexpr double kUnderflow = 1e-300;

// An upper bound of the exact value of a nonnegative quantity x was computed as (see kSlack).
double Up(double x) { return x * kSlack + kUnderflow; }
// A lower bound of a positive exact value computed as x (one rounding, or exact).
double Down(double x) { return x / kSlack - kUnderflow; }
// γ_k = k u / (1 − k u) ≤ 2 k u (k u ≤ 1/2): the bound of an k-term dot product's rounding error, relative to the
// sum of its terms' magnitudes (Higham, §3.1).
double Gamma(int k) { return 2.0 * k * kUnit; }

Quad Abs(Quad x) { return x < 0 ? -x : x; }
// The least double ≥ x (x finite and within double's range).
double RoundUp(Quad x) {
  double d = static_cast<double>(x);
  if (static_cast<Quad>(d) < x) d = std::nextafter(d, std::numeric_limits<double>::infinity());
  return d;
}

SolutionEnclosure NotProved(std::string why) {
  SolutionEnclosure e;
  e.why_not = std::move(why);
  return e;
}

std::string Row(int i) { return "row " + std::to_string(i); }

}  // namespace

SolutionEnclosure EncloseSolution(const BoxMLCP& problem, const Vector& z) {
  const int n = problem.size();
  if (n > kMaxEnclosureSize) {
    return NotProved("n = " + std::to_string(n) + " > " + std::to_string(kMaxEnclosureSize) + " is not attempted");
  }
  if (z.size() != n || !z.allFinite()) return NotProved("the point is not a finite vector of the problem's size");
  const DenseMatrix M = problem.is_sparse() ? DenseMatrix(problem.sparse_matrix()) : problem.dense_matrix();
  const Vector &q = problem.q(), &l = problem.l(), &u = problem.u();

  // The active set of z: free rows strictly inside their box, the others at a bound (fixed when l_i = u_i).
  enum class State { kLower, kUpper, kFixed, kFree };
  std::vector<State> state(static_cast<std::size_t>(n));
  std::vector<int> free_rows;
  for (int i = 0; i < n; ++i) {
    if (z[i] < l[i] || z[i] > u[i]) return NotProved(Row(i) + ": z = " + NumberText(z[i]) + " is outside [l, u]");
    State& s = state[static_cast<std::size_t>(i)];
    s = l[i] == u[i] ? State::kFixed : z[i] == l[i] ? State::kLower : z[i] == u[i] ? State::kUpper : State::kFree;
    if (s == State::kFree) free_rows.push_back(i);
  }

  // s = M z + q enclosed by [s_mid ± s_rad]: accumulated in quad, where each product of two doubles is exact, so
  // the only error is the sum's, at most γ_{n+1} (in quad's unit) times the sum of the terms' magnitudes.
  Vector s_mid(n), s_rad(n);
  for (int i = 0; i < n; ++i) {
    Quad sum = q[i], magnitude = Abs(static_cast<Quad>(q[i]));
    for (int j = 0; j < n; ++j) {
      const Quad term = static_cast<Quad>(M(i, j)) * static_cast<Quad>(z[j]);
      sum += term;
      magnitude += Abs(term);
    }
    s_mid[i] = static_cast<double>(sum);
    const Quad bound = Abs(sum - static_cast<Quad>(s_mid[i])) + 4 * (n + 2) * kQuadUnit * magnitude;
    if (!std::isfinite(s_mid[i]) || !std::isfinite(static_cast<double>(magnitude))) {
      return NotProved(Row(i) + ": M z + q overflows");
    }
    s_rad[i] = RoundUp(bound);
  }

  // The free block: e = z*_F − z_F solves M_FF e = r with r = −s_F; enclosed by Krawczyk's bound (enclosure.h).
  const int nf = static_cast<int>(free_rows.size());
  Vector e = Vector::Zero(nf);
  if (nf > 0) {
    DenseMatrix A(nf, nf);
    for (int a = 0; a < nf; ++a) {
      for (int b = 0; b < nf; ++b) A(a, b) = M(free_rows[a], free_rows[b]);
    }
    const DenseMatrix R = Eigen::PartialPivLU<DenseMatrix>(A).inverse();
    if (!R.allFinite()) return NotProved("the free block M_FF is singular in double");
    const DenseMatrix RA = R * A;
    const DenseMatrix RA_magnitude = R.cwiseAbs() * A.cwiseAbs();
    // |C_ij| ≤ |δ_ij − fl(RA)_ij| + γ_nf (|R||A|)_ij, the latter's computed value inflated by another γ_nf.
    const double gamma = Gamma(2 * nf + 4);
    Vector c(nf), beta(nf);
    double alpha = 0.0, beta_max = 0.0;
    for (int a = 0; a < nf; ++a) {
      double row = 0.0, rr = 0.0;
      for (int b = 0; b < nf; ++b) {
        row += std::abs((a == b ? 1.0 : 0.0) - RA(a, b)) + gamma * RA_magnitude(a, b);
        const int j = free_rows[b];
        rr += std::abs(R(a, b)) * (std::abs(s_mid[j]) + s_rad[j]);
      }
      c[a] = Up(row);
      beta[a] = Up(rr);
      alpha = std::max(alpha, c[a]);
      beta_max = std::max(beta_max, beta[a]);
    }
    if (!(alpha < 1.0) || !std::isfinite(beta_max)) {
      return NotProved("the free block is not proved nonsingular: ||I - R M_FF||inf <= " + NumberText(alpha) +
                       " is not below 1 (M_FF too ill-conditioned)");
    }
    const double rho = Up(beta_max / Down(1.0 - alpha));
    for (int a = 0; a < nf; ++a) e[a] = Up(beta[a] + c[a] * rho);
  }

  // Free rows: the enclosure of z*_i strictly inside (l_i, u_i).
  for (int a = 0; a < nf; ++a) {
    const int i = free_rows[a];
    const bool above_l = std::isinf(l[i]) || Down(z[i] - l[i]) > e[a];
    const bool below_u = std::isinf(u[i]) || Down(u[i] - z[i]) > e[a];
    if (!above_l || !below_u) {
      return NotProved(Row(i) + ": free, but its enclosure z = " + NumberText(z[i]) + " +- " + NumberText(e[a]) +
                       " reaches its bound");
    }
  }
  // Bound rows: w_i = (M z* + q)_i = s_i + Σ_F M_ij e_j has the sign the bound needs over its whole enclosure.
  for (int i = 0; i < n; ++i) {
    const State s = state[static_cast<std::size_t>(i)];
    if (s == State::kFree || s == State::kFixed) continue;
    double spread = s_rad[i];
    for (int a = 0; a < nf; ++a) spread += std::abs(M(i, free_rows[a])) * e[a];
    spread = spread == 0.0 ? 0.0 : Up(spread);  // exactly 0: s_i is exact and no free row moves it
    const double w = s == State::kLower ? s_mid[i] : -s_mid[i];  // must be ≥ 0
    const bool proved = spread == 0.0 ? w >= 0.0 : w > 0.0 && Down(w) >= spread;
    if (!proved) {
      return NotProved(Row(i) + ": at its " + (s == State::kLower ? "lower" : "upper") + " bound, but w = " +
                       NumberText(s_mid[i]) + " +- " + NumberText(spread) + " does not have the sign it needs" +
                       (std::abs(s_mid[i]) <= spread ? " (degenerate: w = 0 is inside)" : ""));
    }
  }
  SolutionEnclosure out;
  out.proved = true;
  out.radius = nf > 0 ? e.maxCoeff() : 0.0;
  return out;
}

bool ProveSymmetricPartPositiveDefinite(const DenseMatrix& M) {
  const int n = static_cast<int>(M.rows());
  if (n == 0 || n > kMaxEnclosureSize || M.cols() != n || !M.allFinite()) return false;
  // S = fl((M + Mᵀ)/2): the sum rounds (|E_S| ≤ u|S| entrywise, so ‖E_S‖₂ ≤ u‖S‖_F), the halving is exact.
  DenseMatrix S(n, n);
  double frobenius2 = 0.0, trace = 0.0, diagonal_max = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      S(i, j) = (M(i, j) + M(j, i)) / 2;
      frobenius2 += S(i, j) * S(i, j);
    }
    trace += S(i, i);
    diagonal_max = std::max(diagonal_max, std::abs(S(i, i)));
  }
  if (!(trace > 0.0) || !std::isfinite(frobenius2)) return false;
  const double symmetrization = Up(kUnit * std::sqrt(Up(frobenius2)));
  // The shift: twice what the factorization's error can be (‖L̃‖_F² = tr(S − cI) + rounding ≤ tr S).
  const double c = 2.0 * (Up(Gamma(n + 1) * trace) + symmetrization + Up(kUnit * diagonal_max));
  // Cholesky of S − cI, unblocked and in the textbook order (the bound above is for it).
  DenseMatrix L = DenseMatrix::Zero(n, n);
  for (int j = 0; j < n; ++j) {
    double d = S(j, j) - c;
    for (int k = 0; k < j; ++k) d -= L(j, k) * L(j, k);
    if (!(d > 0.0)) return false;
    L(j, j) = std::sqrt(d);
    for (int i = j + 1; i < n; ++i) {
      double v = S(i, j);
      for (int k = 0; k < j; ++k) v -= L(i, k) * L(j, k);
      L(i, j) = v / L(j, j);
    }
  }
  if (!L.allFinite()) return false;
  // λ_min(exact symmetric part) ≥ c − ‖ΔA‖₂ − ‖E_shift‖₂ − ‖E_S‖₂, ‖ΔA‖₂ ≤ γ_{n+1}‖ |L̃||L̃ᵀ| ‖₂ ≤ γ_{n+1}‖L̃‖_F².
  const double factorization = Up(Gamma(n + 1) * Up(L.squaredNorm()));
  const double shift_rounding = Up(kUnit * (diagonal_max + c));
  return Down(c) > Up(factorization + shift_rounding + symmetrization);
}

}  // namespace smcbench

// The generated families of the "families" and "scale" suites. Each construction below states why its z* solves
// the problem and why the matrix-class tags and the expected outcome are true.
//
// Reproducibility: random numbers come from suites_detail::Random (mt19937_64 bits, no std distributions) and
// the reductions that define q are explicit loops in a fixed order, so a seed gives the same bits on every run and
// every machine (this file is compiled with -ffp-contract=off, like the generator it wraps). The scene family calls
// the stepper's discretization (Eigen), which is deterministic on one machine.
#include "problems/suites/families.h"

#include <cmath>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "problems/library/matrix_tags.h"
#include "problems/scenes/scene.h"
#include "problems/scenes/registry.h"
#include "problems/suites/generation_detail.h"

namespace smcbench {
namespace {

using suites_detail::MakeProblem;
using suites_detail::PlantedRow;
using suites_detail::PlantRow;
using suites_detail::Random;
using suites_detail::PlantedState;
using suites_detail::StepText;

constexpr int kMaxDenseFamilySize = 4096;  // dense constructions cost O(m³) (PSD) or O(m²)
constexpr int kMaxSparseFamilySize = 4'000'000;
constexpr int kMaxMurtySize = 40;  // 2^(n+1) stays exact and Lemke's 2^n pivots stay countable in int

[[noreturn]] void Fail(const std::string& owner, const std::string& what) {
  throw InvalidInputError(owner + ": " + what);
}

void CheckSize(const char* owner, int m, int min_size, int max_size) {
  if (m < min_size || m > max_size) {
    Fail(owner, "m = " + std::to_string(m) + " must lie in [" + std::to_string(min_size) + ", " +
                    std::to_string(max_size) + "]");
  }
}

std::string Id(std::string_view suite, const std::string& family, const std::string& parameters) {
  return std::string(suite) + "/" + family + "/" + parameters;
}

std::string SizeSeed(int m, std::uint64_t seed) { return "m" + std::to_string(m) + "/s" + std::to_string(seed); }

// out = M z with every entry summed over j in increasing order (explicit loop: fixed rounding).
Vector Multiply(const DenseMatrix& M, const Vector& z) {
  Vector out(M.rows());
  for (Eigen::Index i = 0; i < M.rows(); ++i) {
    double s = 0.0;
    for (Eigen::Index j = 0; j < M.cols(); ++j) s += M(i, j) * z[j];
    out[i] = s;
  }
  return out;
}

// q = w − M z.
Vector DeriveQ(const DenseMatrix& M, const Vector& z, const Vector& w) {
  const Vector Mz = Multiply(M, z);
  Vector q(w.size());
  for (Eigen::Index i = 0; i < w.size(); ++i) q[i] = w[i] - Mz[i];
  return q;
}

// Relay-type (l = −1, u = 1) or LCP (l = 0, u = ∞) bounds; only these two for the constructions that need them.
void CheckLcpOrRelay(const char* owner, BoundKind bounds) {
  if (bounds != BoundKind::kLCP && bounds != BoundKind::kRelay) {
    Fail(owner, "bounds " + ToString(bounds) + " not supported (use lcp or relay)");
  }
}

double LowerOf(BoundKind bounds) { return bounds == BoundKind::kRelay ? -1.0 : 0.0; }
double UpperOf(BoundKind bounds) { return bounds == BoundKind::kRelay ? 1.0 : kInf; }

// A row state allowed by [l, u], with equal odds among the allowed ones.
PlantedState DrawState(double l, double u, Random& rng) {
  const bool has_l = l > -kInf;
  const bool has_u = u < kInf;
  const int states = 1 + (has_l ? 1 : 0) + (has_u ? 1 : 0);
  int s = rng.Index(states);  // 0 inside, then lower (if any), then upper (if any)
  if (s == 1 && !has_l) s = 2;
  return s == 0 ? PlantedState::kInside : (s == 1 ? PlantedState::kAtLower : PlantedState::kAtUpper);
}

}  // namespace

bool FamiliesOptions::IsValid(std::string* why) const {
  if (seeds < 1) {
    *why = "FamiliesOptions: seeds = " + std::to_string(seeds) + " must be at least 1";
    return false;
  }
  if (max_size < 1) {
    *why = "FamiliesOptions: max_size = " + std::to_string(max_size) + " must be at least 1";
    return false;
  }
  return true;
}

bool ScaleOptions::IsValid(std::string* why) const {
  if (max_size < 1) {
    *why = "ScaleOptions: max_size = " + std::to_string(max_size) + " must be at least 1";
    return false;
  }
  if (!(h > 0.0 && h <= 1.0)) {
    *why = "ScaleOptions: h = " + NumberText(h) + " must lie in (0, 1]";
    return false;
  }
  return true;
}

// --- Wrappers of GenerateProblem. ------------------------------------------------------------------------------
LibraryProblem RandomFamilyProblem(MatrixFamily family, BoundKind bounds, int m, std::uint64_t seed,
                                   double degenerate_fraction) {
  GeneratorOptions g;
  g.size = m;
  g.family = family;
  g.bounds = bounds;
  g.seed = seed;
  g.degenerate_fraction = degenerate_fraction;
  GeneratedProblem generated = GenerateProblem(g);  // validates the options

  std::string family_name = ToString(family) + "-" + ToString(bounds);
  if (degenerate_fraction > 0.0) family_name += "-deg" + NumberText(degenerate_fraction);
  const std::string generator_name = generated.problem.name();
  MatrixTags tags;
  switch (family) {
    case MatrixFamily::kSymmetricPositiveDefinite:  // S = AᵀA/λ̂ + δI, exactly symmetric, spectrum in [δ, 1 + δ]
      tags = {Tristate::kYes, Tristate::kYes, Tristate::kYes};
      break;
    case MatrixFamily::kNonsymmetricPMatrix:  // S + K, K skew: symmetric part S is PD, hence a P-matrix
      tags = {Tristate::kNo, Tristate::kYes, Tristate::kYes};
      break;
    case MatrixFamily::kDiagonallyDominant:  // strictly row dominant, positive diagonal: a P-matrix
      tags = {Tristate::kNo, ClassifyMatrix(generated.problem).positive_definite, Tristate::kYes};
      break;
    case MatrixFamily::kSkewPMatrix:  // S + K, K skew with unit entries: symmetric part S is PD, hence a P-matrix
      tags = {Tristate::kNo, Tristate::kYes, Tristate::kYes};
      break;
    case MatrixFamily::kScaledPMatrix:  // W D⁻¹ with W row dominant: an H-matrix with positive diagonal, a P-matrix
      tags = {Tristate::kNo, ClassifyMatrix(generated.problem).positive_definite, Tristate::kYes};
      break;
  }
  if (m == 1) tags.symmetric = Tristate::kYes;
  LibraryProblem p = MakeProblem(Id(kFamiliesSuite, family_name, SizeSeed(m, seed)), "generated:" + ToString(family),
                                 std::move(generated.problem), tags, ExpectedOutcome::kSolvable);
  p.tags = {ToString(family), ToString(bounds)};
  if (degenerate_fraction > 0.0) p.tags.push_back("degenerate");
  p.seed = seed;
  p.solution = std::move(generated.z_star);
  p.metadata["family"] = ToString(family);
  p.metadata["bounds"] = ToString(bounds);
  p.metadata["degenerate_fraction"] = NumberText(degenerate_fraction);
  p.metadata["generator"] = generator_name;
  return p;
}

// --- PSD singular. ---------------------------------------------------------------------------------------------
// Construction: rows of z* are drawn inside (w* = 0) or at a bound (w* ≠ 0), with at least two inside; d is a
// random unit vector supported on the inside rows; A (r × m, r = ⌈m/2⌉, entries U(−1, 1)) is replaced by
// A − (A d) dᵀ so that A d = 0; M = AᵀA / r. Then M is symmetric positive semidefinite, M d = 0, so M is singular
// (not PD, and det M = 0 is a principal minor: not a P-matrix). q = w* − M z* makes z* a solution, and so is
// z* + t d for every |t| small enough to keep the inside rows inside: w is unchanged (M d = 0) and the rows that
// move are exactly those with w = 0. Hence infinitely many solutions.
LibraryProblem PsdSingularProblem(BoundKind bounds, int m, std::uint64_t seed) {
  const char* owner = "PsdSingularProblem";
  CheckLcpOrRelay(owner, bounds);
  CheckSize(owner, m, 2, kMaxDenseFamilySize);
  Random rng(seed);
  const double l = LowerOf(bounds);
  const double u = UpperOf(bounds);

  std::vector<PlantedState> state(static_cast<std::size_t>(m));
  int inside = 0;
  for (PlantedState& s : state) {
    s = DrawState(l, u, rng);
    if (s == PlantedState::kInside) ++inside;
  }
  for (int i = 0; i < m && inside < 2; ++i) {
    if (state[static_cast<std::size_t>(i)] != PlantedState::kInside) {
      state[static_cast<std::size_t>(i)] = PlantedState::kInside;
      ++inside;
    }
  }
  Vector z(m), w(m), d = Vector::Zero(m);
  for (int i = 0; i < m; ++i) {
    const PlantedRow row = PlantRow(l, u, state[static_cast<std::size_t>(i)], rng);
    z[i] = row.z;
    w[i] = row.w;
  }
  double norm2 = 0.0;
  while (!(norm2 > 0.1)) {  // a direction with real weight (redrawn in the unlikely case it is tiny)
    norm2 = 0.0;
    for (int i = 0; i < m; ++i) {
      if (state[static_cast<std::size_t>(i)] != PlantedState::kInside) continue;
      d[i] = rng.Uniform(-1.0, 1.0);
      norm2 += d[i] * d[i];
    }
  }
  const double inv_norm = 1.0 / std::sqrt(norm2);
  for (int i = 0; i < m; ++i) d[i] *= inv_norm;

  const int r = (m + 1) / 2;
  DenseMatrix A(r, m);
  for (int k = 0; k < r; ++k) {
    for (int j = 0; j < m; ++j) A(k, j) = rng.Uniform(-1.0, 1.0);
  }
  for (int k = 0; k < r; ++k) {  // A ← A − (A d) dᵀ
    double ad = 0.0;
    for (int j = 0; j < m; ++j) ad += A(k, j) * d[j];
    for (int j = 0; j < m; ++j) A(k, j) -= ad * d[j];
  }
  DenseMatrix M(m, m);
  for (int i = 0; i < m; ++i) {
    for (int j = i; j < m; ++j) {
      double s = 0.0;
      for (int k = 0; k < r; ++k) s += A(k, i) * A(k, j);
      M(i, j) = s / r;
      M(j, i) = s / r;
    }
  }
  Vector q = DeriveQ(M, z, w);
  const std::string family = "psd-singular-" + ToString(bounds);
  LibraryProblem p = MakeProblem(Id(kFamiliesSuite, family, SizeSeed(m, seed)), "generated:psd-singular",
                                 BoxMLCP(std::move(M), std::move(q), Vector::Constant(m, l), Vector::Constant(m, u)),
                                 {Tristate::kYes, Tristate::kNo, Tristate::kNo}, ExpectedOutcome::kSolvable);
  p.tags = {"psd-singular", "non-unique", ToString(bounds)};
  p.seed = seed;
  p.solution = std::move(z);
  p.metadata["family"] = "psd-singular";
  p.metadata["bounds"] = ToString(bounds);
  p.metadata["rank_bound"] = std::to_string(std::min(r, m - 1));
  p.metadata["non_unique"] = "z* + t d for small t, d in null(M) supported on the rows where z* is inside";
  return p;
}

// --- Non-P, several solutions. ---------------------------------------------------------------------------------
// Construction (before a random symmetric permutation, which maps solutions to solutions): with k = max(1, m/4)
//   M = [[−(I + E), 0], [G, K]],  E ≥ 0 entrywise (k × k), G arbitrary, K a P-matrix (GenerateProblem's
//   nonsymmetric P-matrix family, (m − k) × (m − k)).
// Because the upper-right block is zero, the first k rows form a problem of their own in z₁; for each of its
// solutions z₁ the last rows are a box-MLCP in z₂ with matrix K and vector q₂ + G z₁, which has exactly one
// solution (K is a P-matrix). So the problem has as many solutions as its first block, and the first block has two:
//   LCP:   q₁ > 0 makes z₁ = 0 a solution (w₁ = q₁ > 0); the planted z₁* ≥ 0, nonzero on J ≠ ∅, with
//          q₁_J = ((I + E) z₁*)_J > 0 (so w₁_J = 0) and q₁_i = ((I + E) z₁*)_i + U(0.1, 1.1) > 0 off J (w₁_i > 0),
//          is another one.
//   relay: with |q₁_i| < 1, z₁ = e gives w₁ = q₁ − (I + E)e < 0 (valid at the upper bound) and z₁ = −e gives
//          w₁ = q₁ + (I + E)e > 0 (valid at the lower bound): two solutions; z₁* is one of them at random.
// M_ii = −(1 + E_ii) < 0 for i in the first block: a negative 1×1 principal minor (not P) and e_iᵀ M e_i < 0 (not
// PD); M is not symmetric (G ≠ 0 below a zero block).
LibraryProblem NonPMultipleProblem(BoundKind bounds, int m, std::uint64_t seed) {
  const char* owner = "NonPMultipleProblem";
  CheckLcpOrRelay(owner, bounds);
  CheckSize(owner, m, 2, kMaxDenseFamilySize);
  Random rng(seed);
  const double l = LowerOf(bounds);
  const double u = UpperOf(bounds);
  const int k = std::max(1, m / 4);
  const int m2 = m - k;

  GeneratorOptions g;  // K: the P-matrix block (its own seed stream, derived from ours)
  g.size = m2;
  g.family = MatrixFamily::kNonsymmetricPMatrix;
  g.bounds = BoundKind::kLCP;
  g.seed = seed * 0x9E3779B97F4A7C15ull + 1;
  const DenseMatrix K = GenerateProblem(g).problem.dense_matrix();

  DenseMatrix Mb = DenseMatrix::Zero(m, m);
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j) Mb(i, j) = -((i == j ? 1.0 : 0.0) + rng.Uniform(0.0, 0.5 / k));
  }
  for (int i = k; i < m; ++i) {
    for (int j = 0; j < k; ++j) Mb(i, j) = rng.Uniform(-0.5, 0.5);
    for (int j = k; j < m; ++j) Mb(i, j) = K(i - k, j - k);
  }

  Vector zb(m), wb(m);
  // First block.
  if (bounds == BoundKind::kLCP) {
    std::vector<bool> in_j(static_cast<std::size_t>(k));
    bool any = false;
    for (int i = 0; i < k; ++i) {
      in_j[static_cast<std::size_t>(i)] = rng.Coin();
      any = any || in_j[static_cast<std::size_t>(i)];
    }
    if (!any) in_j[static_cast<std::size_t>(rng.Index(k))] = true;
    for (int i = 0; i < k; ++i) zb[i] = in_j[static_cast<std::size_t>(i)] ? rng.Uniform(0.5, 1.5) : 0.0;
    for (int i = 0; i < k; ++i) wb[i] = in_j[static_cast<std::size_t>(i)] ? 0.0 : rng.Uniform(0.1, 1.1);
  } else {
    const double s = rng.Coin() ? 1.0 : -1.0;
    for (int i = 0; i < k; ++i) zb[i] = s;
    // w₁ = M₁₁ z₁ + q₁ with q₁ ∈ U(−0.9, 0.9): the sign of w₁ is −s (see above), so we draw q₁ and set w₁ from it.
    for (int i = 0; i < k; ++i) {
      const double q1 = rng.Uniform(-0.9, 0.9);
      double mz = 0.0;
      for (int j = 0; j < k; ++j) mz += Mb(i, j) * zb[j];
      wb[i] = mz + q1;  // q₁ is recovered below as w₁ − M₁₁z₁ (up to one rounding)
    }
  }
  // Second block: planted rows of the P-matrix part.
  for (int i = k; i < m; ++i) {
    const PlantedRow row = PlantRow(l, u, DrawState(l, u, rng), rng);
    zb[i] = row.z;
    wb[i] = row.w;
  }

  // Random symmetric permutation: new row/column a is old perm[a].
  std::vector<int> perm(static_cast<std::size_t>(m));
  for (int i = 0; i < m; ++i) perm[static_cast<std::size_t>(i)] = i;
  for (int i = m - 1; i > 0; --i)
    std::swap(perm[static_cast<std::size_t>(i)], perm[static_cast<std::size_t>(rng.Index(i + 1))]);
  DenseMatrix M(m, m);
  Vector z(m), w(m);
  for (int a = 0; a < m; ++a) {
    const int pa = perm[static_cast<std::size_t>(a)];
    for (int b = 0; b < m; ++b) M(a, b) = Mb(pa, perm[static_cast<std::size_t>(b)]);
    z[a] = zb[pa];
    w[a] = wb[pa];
  }
  Vector q = DeriveQ(M, z, w);

  const std::string family = "nonp-multi-" + ToString(bounds);
  LibraryProblem p = MakeProblem(Id(kFamiliesSuite, family, SizeSeed(m, seed)), "generated:nonp-multi",
                                 BoxMLCP(std::move(M), std::move(q), Vector::Constant(m, l), Vector::Constant(m, u)),
                                 {Tristate::kNo, Tristate::kNo, Tristate::kNo}, ExpectedOutcome::kSolvable);
  p.tags = {"non-p", "non-unique", ToString(bounds)};
  p.seed = seed;
  p.solution = std::move(z);
  p.metadata["family"] = "nonp-multi";
  p.metadata["bounds"] = ToString(bounds);
  p.metadata["first_block_size"] = std::to_string(k);
  p.metadata["non_unique"] = bounds == BoundKind::kLCP
                                 ? "z1 = 0 on the first block, extended uniquely through the P-matrix block"
                                 : "z1 = -z1* on the first block, extended uniquely through the P-matrix block";
  return p;
}

// --- Non-P, infeasible. ----------------------------------------------------------------------------------------
// With finite bounds on every row a box-MLCP always has a solution (a VI on a compact convex set, Brouwer), so
// infeasibility needs a row with an infinite bound. Certificate row i, orientation s:
//   s = +1: l_i finite, u_i = +∞.  At a solution z_i < u_i, so the multiplier of the upper bound vanishes and
//           (Mz + q)_i = w_i ≥ 0.
//   s = −1: l_i = −∞, u_i finite.  Likewise (Mz + q)_i = −v_i ≤ 0.
// Both say s (Mz + q)_i ≥ 0 at every solution. We choose row i's coefficients so that s M_ij z_j is bounded above
// on [l_j, u_j] (s M_ij > 0 only where u_j is finite, s M_ij < 0 only where l_j is finite, 0 on free columns) and
// set s q_i = −Σ_j sup(s M_ij z_j) − U(0.1, 1.1). Then s (Mz + q)_i ≤ −0.1 for every z in the box: no solution.
// The natural residual also stays away from 0 (a z within ε of the box has s (Mz + q)_i ≤ −0.1 + O(ε)), so no
// backend can reach the tolerance. M_ii < 0 in both orientations; infeasibility alone rules out P (a P-matrix
// box-MLCP is solvable for every q and every box) and PD.
LibraryProblem NonPInfeasibleProblem(BoundKind bounds, int m, std::uint64_t seed) {
  const char* owner = "NonPInfeasibleProblem";
  if (bounds != BoundKind::kLCP && bounds != BoundKind::kMixed) {
    Fail(owner,
         "bounds " + ToString(bounds) + " not supported (use lcp or mixed: infeasibility needs an infinite bound)");
  }
  CheckSize(owner, m, 1, kMaxDenseFamilySize);
  Random rng(seed);
  Vector l(m), u(m);
  for (int i = 0; i < m; ++i) {
    if (bounds == BoundKind::kLCP) {
      l[i] = 0.0;
      u[i] = kInf;
      continue;
    }
    switch (rng.Index(4)) {
      case 0:
        l[i] = -kInf;
        u[i] = kInf;
        break;
      case 1:
        l[i] = 0.0;
        u[i] = kInf;
        break;
      case 2:
        l[i] = -kInf;
        u[i] = rng.Uniform(-1.0, 2.0);
        break;
      default:
        l[i] = rng.Uniform(-2.0, 1.0);
        u[i] = l[i] + rng.Uniform(0.5, 3.0);
        break;
    }
  }
  // The rest of M: U(−1, 1) off the diagonal, a diagonal of either sign (no class on purpose).
  DenseMatrix M(m, m);
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j) M(i, j) = rng.Uniform(-1.0, 1.0);
  }
  Vector q(m);
  for (int i = 0; i < m; ++i) q[i] = rng.Uniform(-1.0, 1.0);

  // Certificate rows: max(1, m/8) distinct rows chosen by a partial Fisher–Yates shuffle.
  const int count = std::max(1, m / 8);
  std::vector<int> rows(static_cast<std::size_t>(m));
  for (int i = 0; i < m; ++i) rows[static_cast<std::size_t>(i)] = i;
  for (int c = 0; c < count; ++c) {
    std::swap(rows[static_cast<std::size_t>(c)], rows[static_cast<std::size_t>(c + rng.Index(m - c))]);
  }
  std::vector<std::string> certificate;
  for (int c = 0; c < count; ++c) {
    const int i = rows[static_cast<std::size_t>(c)];
    // Exactly one infinite bound on row i: keep an LCP or upper-only row, turn a free or box row into one.
    if (!(std::isinf(l[i]) != std::isinf(u[i]))) {
      if (rng.Coin()) {
        l[i] = 0.0;
        u[i] = kInf;
      } else {
        l[i] = -kInf;
        u[i] = rng.Uniform(-1.0, 2.0);
      }
    }
  }
  for (int c = 0; c < count; ++c) {
    const int i = rows[static_cast<std::size_t>(c)];
    const double s = std::isinf(u[i]) ? 1.0 : -1.0;
    double sup = 0.0;  // Σ_j sup over [l_j, u_j] of s M_ij z_j
    for (int j = 0; j < m; ++j) {
      const bool up_ok = std::isfinite(u[j]);    // s M_ij > 0 allowed
      const bool down_ok = std::isfinite(l[j]);  // s M_ij < 0 allowed
      double a = 0.0;                            // the value of s M_ij
      if (up_ok && down_ok) {
        a = (rng.Coin() ? 1.0 : -1.0) * rng.Uniform(0.1, 1.0);
      } else if (up_ok) {
        a = rng.Uniform(0.1, 1.0);
      } else if (down_ok) {
        a = -rng.Uniform(0.1, 1.0);
      }
      M(i, j) = s * a;
      if (a > 0.0) sup += a * u[j];
      if (a < 0.0) sup += a * l[j];
    }
    q[i] = s * (-sup - rng.Uniform(0.1, 1.1));
    certificate.push_back(std::to_string(i));
  }
  std::string certificate_rows;
  for (const std::string& r : certificate) certificate_rows += (certificate_rows.empty() ? "" : " ") + r;

  const std::string family = "nonp-infeasible-" + ToString(bounds);
  LibraryProblem p = MakeProblem(Id(kFamiliesSuite, family, SizeSeed(m, seed)), "generated:nonp-infeasible",
                                 BoxMLCP(std::move(M), std::move(q), std::move(l), std::move(u)),
                                 {m == 1 ? Tristate::kYes : Tristate::kNo, Tristate::kNo, Tristate::kNo},
                                 ExpectedOutcome::kInfeasible);
  p.tags = {"non-p", "infeasible", ToString(bounds)};
  p.seed = seed;
  p.metadata["family"] = "nonp-infeasible";
  p.metadata["bounds"] = ToString(bounds);
  p.metadata["certificate_rows"] = certificate_rows;
  return p;
}

// --- Scene one-step problems (h-sweep). --------------------------------------------------------------------------
std::vector<double> HSweepSteps() { return {1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8}; }

LibraryProblem SceneStepProblem(std::string_view scene_name, double h, std::uint64_t seed) {
  const std::string owner = "SceneStepProblem('" + std::string(scene_name) + "')";
  if (!(h > 0.0 && std::isfinite(h))) Fail(owner, "h = " + NumberText(h) + " must be positive and finite");
  const std::unique_ptr<Scene> scene = LoadScene(scene_name);
  const LinearPlant* linear = scene->linear_plant();
  if (linear == nullptr) Fail(owner, "not a linear scene (its one-step problem is not a fixed box-MLCP)");
  SimulationSettings settings = scene->defaults();
  settings.method = Method::kImplicit;
  settings.h = h;
  const OneStepData step = linear->Discretization(settings);
  DenseMatrix W = step.OneStepMatrix();
  const int m = static_cast<int>(W.rows());

  // At least one row at a bound (q = O(1)); with m ≥ 2 at least one row strictly inside (q_i = O(h)).
  Random rng(seed);
  std::vector<PlantedState> state(static_cast<std::size_t>(m));
  for (PlantedState& s : state) s = DrawState(-1.0, 1.0, rng);
  const auto count = [&](bool inside) {
    int c = 0;
    for (PlantedState s : state) c += ((s == PlantedState::kInside) == inside) ? 1 : 0;
    return c;
  };
  if (count(false) == 0) {
    state[static_cast<std::size_t>(rng.Index(m))] = rng.Coin() ? PlantedState::kAtUpper : PlantedState::kAtLower;
  }
  if (m >= 2 && count(true) == 0) {
    state[static_cast<std::size_t>(rng.Index(m))] = PlantedState::kInside;  // m ≥ 2 rows at bounds: one stays
  }
  Vector z(m), w(m);
  for (int i = 0; i < m; ++i) {
    const PlantedRow row = PlantRow(-1.0, 1.0, state[static_cast<std::size_t>(i)], rng);
    z[i] = row.z;
    w[i] = row.w;
  }
  Vector q = DeriveQ(W, z, w);
  BoxMLCP problem = BoxMLCP::Relay(std::move(W), std::move(q));
  const MatrixTags tags = ClassifyMatrix(problem);
  const std::string name(scene_name);
  LibraryProblem p = MakeProblem(Id(kFamiliesSuite, "h-sweep", name + "/h" + StepText(h) + "/s" + std::to_string(seed)),
                                 "generated:scene-step", std::move(problem), tags, ExpectedOutcome::kSolvable);
  p.tags = {"h-sweep", name, "relay"};
  p.seed = seed;
  p.solution = std::move(z);
  p.metadata["scene"] = name;
  p.metadata["h"] = NumberText(h);
  p.metadata["theta"] = NumberText(settings.theta);
  p.metadata["method"] = "implicit";
  p.metadata["one_step_matrix"] = "W = hC(I - h theta E)^-1 B";
  return p;
}

// --- The small-h family. ----------------------------------------------------------------------------------------
std::vector<double> SmallHSteps() { return {1e-2, 1e-4, 1e-6, 1e-8, 1e-10}; }

namespace {

// The planted relay solution of the small-h family: row states drawn with equal odds, then at least one row at a
// bound and (m ≥ 2) at least one strictly inside; a bound row's slack is h·U(0.1, 1.1), signed by its bound.
void PlantSmallH(int m, double h, Random& rng, Vector* z, Vector* w) {
  std::vector<PlantedState> state(static_cast<std::size_t>(m));
  for (PlantedState& s : state) s = DrawState(-1.0, 1.0, rng);
  int inside = 0;
  for (PlantedState s : state) inside += s == PlantedState::kInside ? 1 : 0;
  if (inside == m) {
    state[static_cast<std::size_t>(rng.Index(m))] = rng.Coin() ? PlantedState::kAtUpper : PlantedState::kAtLower;
  }
  if (m >= 2 && inside == 0) state[static_cast<std::size_t>(rng.Index(m))] = PlantedState::kInside;
  z->resize(m);
  w->resize(m);
  for (int i = 0; i < m; ++i) {
    const PlantedRow row = PlantRow(-1.0, 1.0, state[static_cast<std::size_t>(i)], rng);
    (*z)[i] = row.z;
    (*w)[i] = h * row.w;  // 0 inside; ±U(0.1, 1.1) at a bound, scaled to O(h)
  }
}

LibraryProblem SmallHProblem(std::string id, const std::string& kind, DenseMatrix W, double h, Random& rng,
                             const MatrixTags* proved_tags) {
  const int m = static_cast<int>(W.rows());
  Vector z, w;
  PlantSmallH(m, h, rng, &z, &w);
  Vector q = DeriveQ(W, z, w);
  BoxMLCP problem = BoxMLCP::Relay(std::move(W), std::move(q));
  const MatrixTags tags = proved_tags ? *proved_tags : ClassifyMatrix(problem);
  LibraryProblem p =
      MakeProblem(std::move(id), "generated:small-h", std::move(problem), tags, ExpectedOutcome::kSolvable);
  p.tags = {"small-h", kind, "relay"};
  p.solution = std::move(z);
  p.metadata["family"] = "small-h";
  p.metadata["h"] = NumberText(h);
  p.metadata["slack"] = "w*_i = +-h c_i, c_i in [0.1, 1.1], on the rows at a bound; 0 inside";
  return p;
}

}  // namespace

LibraryProblem SmallHSceneProblem(std::string_view scene_name, double h, std::uint64_t seed) {
  const std::string owner = "SmallHSceneProblem('" + std::string(scene_name) + "')";
  if (!(h > 0.0 && std::isfinite(h))) Fail(owner, "h = " + NumberText(h) + " must be positive and finite");
  const std::unique_ptr<Scene> scene = LoadScene(scene_name);
  const LinearPlant* linear = scene->linear_plant();
  if (linear == nullptr) Fail(owner, "not a linear scene (its one-step problem is not a fixed box-MLCP)");
  if (scene->info().m < 2) Fail(owner, "m = " + std::to_string(scene->info().m) + ": the family takes m >= 2");
  SimulationSettings settings = scene->defaults();
  settings.method = Method::kImplicit;
  settings.h = h;
  DenseMatrix W = linear->Discretization(settings).OneStepMatrix();
  Random rng(seed);
  const std::string name(scene_name);
  const std::string id = Id(kFamiliesSuite, "small-h", name + "/h" + StepText(h) + "/s" + std::to_string(seed));
  LibraryProblem p = SmallHProblem(id, name, std::move(W), h, rng, nullptr);
  p.seed = seed;
  p.metadata["scene"] = name;
  p.metadata["theta"] = NumberText(settings.theta);
  p.metadata["one_step_matrix"] = "W = hC(I - h theta E)^-1 B";
  return p;
}

// G = P(I + K)Pᵀ, P = QΛ^½, K skew, ‖K‖₂ ≤ ‖K‖_F = 1. Why each claim holds:
//   P-matrix: xᵀGx = (Pᵀx)ᵀ(I + K)(Pᵀx) = ‖Pᵀx‖² > 0 for x ≠ 0 (xᵀKx = 0), so the symmetric part QΛQᵀ is PD;
//     every principal submatrix inherits it, so every principal minor is positive. h > 0 keeps all of this.
//   ‖G‖₂ ≤ ‖P‖₂²‖I + K‖₂ ≤ 1·√2 (I + K is normal with singular values √(1 + μ²), μ ≤ ‖K‖₂ ≤ 1), and ‖G‖₂ ≥ 1
//     (uᵀGu = λ_max for the top eigenvector u of QΛQᵀ).
//   ‖G⁻¹‖₂ ≤ ‖P⁻¹‖₂²‖(I + K)⁻¹‖₂ ≤ c·1, and ‖G⁻¹‖₂ ≥ vᵀG⁻¹v = (1/λ_min) e_kᵀ(I + K)⁻¹e_k ≥ c/2 for v = Qe_k the
//     bottom eigenvector (the symmetric part of (I + K)⁻¹ is (I + KᵀK)⁻¹ ≥ I/2). Hence κ₂(G) ∈ [c/2, √2·c].
// Explicit loops in a fixed order: the same bits on every machine.
LibraryProblem SmallHPMatrixProblem(int m, int log10_condition, double h, std::uint64_t seed) {
  const char* owner = "SmallHPMatrixProblem";
  CheckSize(owner, m, 2, 64);
  if (log10_condition < 0 || log10_condition > 12) {
    Fail(owner, "log10_condition = " + std::to_string(log10_condition) + " must lie in [0, 12]");
  }
  if (!(h > 0.0 && std::isfinite(h))) Fail(owner, "h = " + NumberText(h) + " must be positive and finite");
  Random rng(seed);
  // Q = H1 H2 H3 (Householder reflections I − 2vvᵀ/vᵀv), applied to I from the right.
  DenseMatrix Q = DenseMatrix::Identity(m, m);
  for (int r = 0; r < 3; ++r) {
    Vector v(m);
    double vv = 0.0;
    for (int i = 0; i < m; ++i) {
      v[i] = rng.Uniform(-1.0, 1.0);
      vv += v[i] * v[i];
    }
    for (int i = 0; i < m; ++i) {
      double t = 0.0;
      for (int j = 0; j < m; ++j) t += Q(i, j) * v[j];
      for (int j = 0; j < m; ++j) Q(i, j) -= (2.0 / vv) * t * v[j];
    }
  }
  DenseMatrix P(m, m);
  for (int k = 0; k < m; ++k) {
    const double lambda = std::pow(10.0, -static_cast<double>(log10_condition) * k / (m - 1));
    for (int i = 0; i < m; ++i) P(i, k) = Q(i, k) * std::sqrt(lambda);
  }
  DenseMatrix A = DenseMatrix::Identity(m, m);  // I + K
  double frobenius = 0.0;
  for (int i = 0; i < m; ++i) {
    for (int j = i + 1; j < m; ++j) {
      A(i, j) = rng.Uniform(-1.0, 1.0);
      frobenius += 2.0 * A(i, j) * A(i, j);
    }
  }
  frobenius = std::sqrt(frobenius);
  for (int i = 0; i < m; ++i) {
    for (int j = i + 1; j < m; ++j) {
      A(i, j) /= frobenius;
      A(j, i) = -A(i, j);
    }
  }
  DenseMatrix PA(m, m), W(m, m);
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j) {
      double t = 0.0;
      for (int k = 0; k < m; ++k) t += P(i, k) * A(k, j);
      PA(i, j) = t;
    }
  }
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j) {
      double g = 0.0;  // G_ij = Σ_k (PA)_ik P_jk
      for (int k = 0; k < m; ++k) g += PA(i, k) * P(j, k);
      W(i, j) = h * g;
    }
  }
  const MatrixTags proved{Tristate::kNo, Tristate::kYes, Tristate::kYes};
  const std::string family = "pmatrix-m" + std::to_string(m) + "-cond1e" + std::to_string(log10_condition);
  const std::string id = Id(kFamiliesSuite, "small-h", family + "/h" + StepText(h) + "/s" + std::to_string(seed));
  LibraryProblem p = SmallHProblem(id, "pmatrix", std::move(W), h, rng, &proved);
  p.seed = seed;
  p.metadata["one_step_matrix"] = "W = h G, G = P (I + K) P^T, P = Q Lambda^(1/2), K skew, |K|_F = 1";
  p.metadata["condition"] = "kappa_2(G) in [c/2, sqrt(2) c], c = 1e" + std::to_string(log10_condition);
  return p;
}

// --- Murty's exponential family. ---------------------------------------------------------------------------------
// Murty, "Computational complexity of complementary pivot methods", Math. Programming Study 7 (1978) 61–73, and
// Murty, "Linear Complementarity, Linear and Nonlinear Programming" (1988), ch. 6: M̃(n) is lower triangular with
// m̃_ii = 1 and m̃_ij = 2 for j < i; on q̂(n) = −(2ⁿ, 2ⁿ + 2ⁿ⁻¹, ..., 2ⁿ + ... + 2) the complementary pivot method
// (Lemke with covering vector e) goes through all 2ⁿ complementary cones. Siconos keeps the same problem with the
// index order reversed as lcp/lcp_exp_murty2.dat (n = 6, M upper triangular, q = −(126, 124, ..., 64)).
// Solution: z* = 2ⁿ e₁, w*_1 = 0 and w*_i = 2·2ⁿ + q̂_i = 2ⁿ⁻ⁱ⁺¹ > 0 for i ≥ 2 (1-based), all exact in double.
// Tags: triangular with unit diagonal, so every principal minor is 1 (a P-matrix); M + Mᵀ = 2eeᵀ is singular for
// n ≥ 2, so the symmetric part is only semidefinite (not PD).
LibraryProblem MurtyProblem(int n) {
  CheckSize("MurtyProblem", n, 2, kMaxMurtySize);
  DenseMatrix M = DenseMatrix::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    M(i, i) = 1.0;
    for (int j = 0; j < i; ++j) M(i, j) = 2.0;
  }
  const double two_n = std::ldexp(1.0, n);
  Vector q(n), z = Vector::Zero(n);
  for (int i = 0; i < n; ++i) q[i] = -(2.0 * two_n - std::ldexp(1.0, n - i));  // −(2ⁿ⁺¹ − 2ⁿ⁻ⁱ), 0-based i
  z[0] = two_n;
  LibraryProblem p = MakeProblem(Id(kFamiliesSuite, "murty", "n" + std::to_string(n)), "generated:murty",
                                 BoxMLCP::LCP(std::move(M), std::move(q)),
                                 {Tristate::kNo, Tristate::kNo, Tristate::kYes}, ExpectedOutcome::kSolvable);
  p.tags = {"murty", "lcp"};
  p.solution = std::move(z);
  p.metadata["family"] = "murty";
  p.metadata["reference"] = "Murty 1978; Murty 1988 ch. 6: (q^(n), M~(n)), 2^n complementary pivots";
  // Raw Lemke with covering vector e on these rows (not our lemke, which works on the row-equilibrated problem).
  p.metadata["lemke_pivots_expected"] = NumberText(two_n);
  return p;
}

// --- Coupled sliding-mode subsystems (sparse). -----------------------------------------------------------------
// Subsystem k: x_k ∈ R², A_k = [[0, 1], [−a_k, −b_k]], C_k = [c_k, 1], input column B_kj = β_kj e₂ with
// β_kk = α_k and β_kj = ε_kj α_j for j = k ± 1 (actuator crosstalk). A is block diagonal, so
//   W_kj = h C_k (I − hA_k)⁻¹ e₂ β_kj = h g_k β_kj,   (I − hA_k)⁻¹ = [[1 + h b_k, h], [−h a_k, 1]] / det_k,
//   g_k = (1 + h c_k) / det_k,  det_k = 1 + h b_k + h² a_k > 0,
// a tridiagonal W computed in O(1) per entry. With a, b, c > 0, g_k > 0; |ε| ≤ 0.2 and α ∈ [0.8, 1.2] give
// Σ_{j≠k} |W_kj| ≤ 0.48 h g_k < W_kk: strictly row diagonally dominant with a positive diagonal (a P-matrix,
// checked below rather than assumed). Column dominance too ⇒ the symmetric part is diagonally dominant ⇒ PD.
LibraryProblem CoupledSlidingModeProblem(int m, std::uint64_t seed, double h, std::string_view suite) {
  const char* owner = "CoupledSlidingModeProblem";
  CheckSize(owner, m, 1, kMaxSparseFamilySize);
  if (!(h > 0.0 && h <= 1.0)) Fail(owner, "h = " + NumberText(h) + " must lie in (0, 1]");
  Random rng(seed);
  std::vector<double> g(static_cast<std::size_t>(m)), alpha(static_cast<std::size_t>(m));
  std::vector<double> lower(static_cast<std::size_t>(m), 0.0),
      upper(static_cast<std::size_t>(m), 0.0);  // ε_k,k−1, ε_k,k+1
  for (int k = 0; k < m; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    const double a = rng.Uniform(0.5, 2.0);
    const double b = rng.Uniform(0.5, 2.0);
    const double c = rng.Uniform(0.5, 2.0);
    alpha[kk] = rng.Uniform(0.8, 1.2);
    if (k > 0) lower[kk] = rng.Uniform(-0.2, 0.2);
    if (k + 1 < m) upper[kk] = rng.Uniform(-0.2, 0.2);
    g[kk] = (1.0 + h * c) / (1.0 + h * b + h * h * a);
  }
  // W entries: diag d_k = h g_k α_k, sub s_k = W_k,k−1 = h g_k ε_k,k−1 α_{k−1}, super t_k = W_k,k+1.
  std::vector<double> diag(static_cast<std::size_t>(m)), sub(static_cast<std::size_t>(m), 0.0),
      super(static_cast<std::size_t>(m), 0.0);
  for (int k = 0; k < m; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    diag[kk] = h * g[kk] * alpha[kk];
    if (k > 0) sub[kk] = h * g[kk] * lower[kk] * alpha[kk - 1];
    if (k + 1 < m) super[kk] = h * g[kk] * upper[kk] * alpha[kk + 1];
  }
  bool row_dominant = true, column_dominant = true, symmetric = true;
  for (int k = 0; k < m; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    if (!(diag[kk] > std::abs(sub[kk]) + std::abs(super[kk]))) row_dominant = false;
    const double column = (k > 0 ? std::abs(super[kk - 1]) : 0.0) + (k + 1 < m ? std::abs(sub[kk + 1]) : 0.0);
    if (!(diag[kk] > column)) column_dominant = false;
    if (k + 1 < m && super[kk] != sub[kk + 1]) symmetric = false;
  }

  // Planted relay solution: inside with probability ½, else at either bound.
  Vector z(m), w(m);
  for (int k = 0; k < m; ++k) {
    const int pick = rng.Index(4);
    const PlantedState s =
        pick < 2 ? PlantedState::kInside : (pick == 2 ? PlantedState::kAtLower : PlantedState::kAtUpper);
    const PlantedRow row = PlantRow(-1.0, 1.0, s, rng);
    z[k] = row.z;
    w[k] = row.w;
  }
  Vector q(m);
  for (int k = 0; k < m; ++k) {  // q = w − W z, summed left to right
    const auto kk = static_cast<std::size_t>(k);
    double s = 0.0;
    if (k > 0) s += sub[kk] * z[k - 1];
    s += diag[kk] * z[k];
    if (k + 1 < m) s += super[kk] * z[k + 1];
    q[k] = w[k] - s;
  }
  // Column-major assembly straight into the compressed arrays (no triplet sort): column j holds W_{j−1,j},
  // W_jj, W_{j+1,j}.
  SparseMatrix W(m, m);
  W.reserve(Eigen::VectorXi::Constant(m, 3));
  for (int j = 0; j < m; ++j) {
    const auto jj = static_cast<std::size_t>(j);
    if (j > 0) W.insert(j - 1, j) = super[jj - 1];
    W.insert(j, j) = diag[jj];
    if (j + 1 < m) W.insert(j + 1, j) = sub[jj + 1];
  }
  W.makeCompressed();

  const MatrixTags tags{symmetric ? Tristate::kYes : Tristate::kNo,
                        row_dominant && column_dominant ? Tristate::kYes : Tristate::kUnknown,
                        row_dominant ? Tristate::kYes : Tristate::kUnknown};
  LibraryProblem p =
      MakeProblem(Id(suite, "coupled-smc", SizeSeed(m, seed)), "generated:coupled-smc",
                  BoxMLCP(std::move(W), std::move(q), Vector::Constant(m, -1.0), Vector::Constant(m, 1.0)), tags,
                  ExpectedOutcome::kSolvable);
  p.tags = {"coupled-smc", "sparse", "relay"};
  p.seed = seed;
  p.solution = std::move(z);
  p.metadata["family"] = "coupled-smc";
  p.metadata["h"] = NumberText(h);
  p.metadata["subsystems"] = std::to_string(m);
  p.metadata["one_step_matrix"] = "W = hC(I - hA)^-1 B, A block diagonal (2x2), B with nearest-neighbour crosstalk";
  return p;
}

// --- The suites. -------------------------------------------------------------------------------------------------
ProblemSet FamiliesSuite(const FamiliesOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw InvalidInputError(why);
  ProblemSet set;
  set.name = std::string(kFamiliesSuite);
  set.description =
      "generated families with planted solutions: SPD, P-matrix, diagonally dominant, PSD singular, "
      "non-P (several / no solutions), scene one-step matrices over h, small h (W = h G, h down to 1e-10), Murty, "
      "coupled sliding modes";
  auto& out = set.problems;
  const auto fits = [&](int m) { return m <= options.max_size; };
  const auto seeds = [&](auto&& add) {
    for (int s = 1; s <= options.seeds; ++s) add(static_cast<std::uint64_t>(s));
  };
  for (MatrixFamily family : {MatrixFamily::kSymmetricPositiveDefinite, MatrixFamily::kNonsymmetricPMatrix,
                              MatrixFamily::kDiagonallyDominant}) {
    for (int m : {8, 64}) {
      if (!fits(m)) continue;
      for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay, BoundKind::kMixed}) {
        seeds([&](std::uint64_t seed) { out.push_back(RandomFamilyProblem(family, bounds, m, seed)); });
      }
    }
  }
  // The classes auto's rule is measured on beyond these (docs/auto.md): strongly nonsymmetric, and P without a
  // positive definite symmetric part.
  for (MatrixFamily family : {MatrixFamily::kSkewPMatrix, MatrixFamily::kScaledPMatrix}) {
    for (int m : {8, 64}) {
      if (!fits(m)) continue;
      for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay}) {
        seeds([&](std::uint64_t seed) { out.push_back(RandomFamilyProblem(family, bounds, m, seed)); });
      }
    }
  }
  for (int m : {8, 32}) {
    if (!fits(m)) continue;
    for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay}) {
      seeds([&](std::uint64_t seed) { out.push_back(PsdSingularProblem(bounds, m, seed)); });
      seeds([&](std::uint64_t seed) { out.push_back(NonPMultipleProblem(bounds, m, seed)); });
    }
    for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kMixed}) {
      seeds([&](std::uint64_t seed) { out.push_back(NonPInfeasibleProblem(bounds, m, seed)); });
    }
  }
  if (options.scenes) {
    for (const char* scene : {"galias-yu-2007", "multi-surface", "filippov", "observer", "parasitic"}) {
      for (double h : HSweepSteps()) out.push_back(SceneStepProblem(scene, h, 1));
    }
  }
  // Small h: the paper's linear scenes with m ≥ 2, then P-matrices of growing condition (and size), each at every
  // h of SmallHSteps, one seed (the family varies h and the condition, not the draw).
  if (options.scenes) {
    for (std::string_view scene : PaperSceneNames()) {
      const std::unique_ptr<Scene> loaded = LoadScene(scene);
      if (loaded->step_kind() != SceneStepKind::kLinearBox || loaded->info().m < 2 ||
          !fits(loaded->info().m)) {
        continue;
      }
      for (double h : SmallHSteps()) out.push_back(SmallHSceneProblem(scene, h, 1));
    }
  }
  for (const auto& [m, log10_condition] : {std::pair{2, 1}, std::pair{3, 2}, std::pair{4, 3}, std::pair{6, 4},
                                           std::pair{8, 6}}) {
    if (!fits(m)) continue;
    for (double h : SmallHSteps()) out.push_back(SmallHPMatrixProblem(m, log10_condition, h, 1));
  }
  for (int n = 4; n <= 16 && fits(n); ++n) out.push_back(MurtyProblem(n));
  for (int m : {16, 64}) {
    if (!fits(m)) continue;
    seeds([&](std::uint64_t seed) { out.push_back(CoupledSlidingModeProblem(m, seed)); });
  }
  set.Validate();
  return set;
}

ProblemSet ScaleSuite(const ScaleOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw InvalidInputError(why);
  ProblemSet set;
  set.name = "scale";
  set.description = "coupled sliding-mode subsystems, sparse tridiagonal one-step matrix, m = 1e2 ... 1e5";
  for (int m : {100, 1000, 10000, 100000}) {
    if (m <= options.max_size) set.problems.push_back(CoupledSlidingModeProblem(m, options.seed, options.h, "scale"));
  }
  set.Validate();
  return set;
}

}  // namespace smcbench

// Extended-precision active-set certification of box-MLCP solutions (see certify.h for the method and why quad).
#include "solvers/reference/certify.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstddef>
#include <string>
#include <unordered_map>
#include <utility>

#include "solvers/core/number_text.h"
#include "solvers/reference/enclosure.h"
#include "solvers/reference/quad_lu.h"

namespace smcbench {
namespace {

// GCC's and clang's binary128: +, −, ×, ÷, conversions and comparisons come from libgcc; no libquadmath call is
// made (and no quad literal suffix is used: the build is strict ISO C++17).
using Quad = __float128;

constexpr Quad kQuadEps = 0x1p-112;  // spacing of quad numbers at 1
// A free block whose complete-pivoting elimination meets a pivot below this times its largest entry is singular.
constexpr double kPivotTolerance = 1e-28;
// δ = kMarginFactor · n · ε · (1 + μ) · (1 + ‖z‖∞ + ‖D⁻¹q‖∞), at least kMarginFloor: a bound on the quad solve's
// error in z (backward error n ε of the elimination and of w, amplified by μ), in units of z.
constexpr double kMarginFactor = 64.0;
constexpr double kMarginFloor = 1e-30;
// A set whose δ exceeds this times (1 + ‖z‖∞ + ‖D⁻¹q‖∞) is too ill-conditioned to decide (μ beyond ~1e20).
constexpr double kMaxRelativeMargin = 1e-10;
// Rows of a candidate within this of a bound with |w_i/d_i| within it too are near-degenerate: their state is a
// coin toss in double, so the other choice is tried when the natural-map set fails (at most kMaxFlips rows).
constexpr double kNearDegenerate = 1e-6;
constexpr int kMaxFlips = 8;
// Block-principal-pivoting steps (natural-map set at the last set's point) from a point whose set failed.
constexpr int kGuidedSteps = 32;
// P-matrix tests: every principal minor (2^n of them) only up to this size; a minor counts as positive when its
// elimination keeps every pivot above kMinorPivot times its largest entry (far above the quad rounding) and the
// determinant is positive. A symmetric part counts as positive definite when its LDLᵀ survives a shift of
// kDefiniteShift times its norm (which covers the factorization's backward error).
constexpr int kMaxMinorsSize = 12;
constexpr double kMinorPivot = 1e-24;
constexpr double kDefiniteShift = 1e-26;

Quad Abs(Quad x) { return x < 0 ? -x : x; }
bool IsFinite(Quad x) { return x - x == 0; }  // NaN for ±∞ and NaN
Quad NormInf(const std::vector<Quad>& v) {
  Quad m = 0;
  for (Quad x : v) m = std::max(m, Abs(x));
  return m;
}
std::size_t Index(int i, int j, int n) { return static_cast<std::size_t>(i) * static_cast<std::size_t>(n) + j; }

// One row's state in an active set; a set is a string of them (hashable, comparable).
enum State : char { kLower = 'L', kUpper = 'U', kFree = 'F', kFixed = 'X' };
using ActiveSet = std::string;

// The problem with every row divided by its scale d_i: A z + b = D⁻¹(M z + q), in quad.
struct Equilibrated {
  int n = 0;
  std::vector<Quad> a;  // row-major n×n
  std::vector<Quad> b;
  std::vector<double> l, u, d;
  Quad b_norm = 0;
  Quad A(int i, int j) const { return a[Index(i, j, n)]; }
  bool has_lower(int i) const { return l[i] > -kInf; }
  bool has_upper(int i) const { return u[i] < kInf; }
  bool fixed(int i) const { return l[i] == u[i]; }
  bool unbounded(int i) const { return !has_lower(i) && !has_upper(i); }
};

Equilibrated Equilibrate(const BoxMLCP& problem) {
  const DenseMatrix M = problem.is_sparse() ? problem.ToDense() : problem.dense_matrix();
  Equilibrated p;
  p.n = problem.size();
  p.a.resize(Index(p.n, 0, p.n));
  p.b.resize(p.n);
  p.l.assign(problem.l().data(), problem.l().data() + p.n);
  p.u.assign(problem.u().data(), problem.u().data() + p.n);
  p.d.assign(problem.row_scale().data(), problem.row_scale().data() + p.n);
  for (int i = 0; i < p.n; ++i) {
    const Quad d = p.d[i];
    for (int j = 0; j < p.n; ++j) p.a[Index(i, j, p.n)] = static_cast<Quad>(M(i, j)) / d;
    p.b[i] = static_cast<Quad>(problem.q()[i]) / d;
    p.b_norm = std::max(p.b_norm, Abs(p.b[i]));
  }
  return p;
}

// H = S + Sᵀ positive definite, tested by LDLᵀ of H − τI with τ = kDefiniteShift·‖H‖∞ (every pivot positive).
// Not solvers/core/matrix_class.h's double-precision test on purpose: a certificate must hold beyond double rounding.
bool SymmetricPartPositiveDefinite(const std::vector<Quad>& s, int n) {
  std::vector<Quad> h(Index(n, 0, n));
  Quad norm = 0;
  for (int i = 0; i < n; ++i) {
    Quad row_sum = 0;
    for (int j = 0; j < n; ++j) {
      h[Index(i, j, n)] = s[Index(i, j, n)] + s[Index(j, i, n)];
      row_sum += Abs(h[Index(i, j, n)]);
    }
    norm = std::max(norm, row_sum);
  }
  if (!(norm > 0)) return false;
  const Quad shift = kDefiniteShift * norm;
  std::vector<Quad> L(Index(n, 0, n), Quad(0)), D(n);
  for (int j = 0; j < n; ++j) {
    Quad dj = h[Index(j, j, n)] - shift;
    for (int t = 0; t < j; ++t) dj -= L[Index(j, t, n)] * L[Index(j, t, n)] * D[t];
    if (!(dj > 0)) return false;
    D[j] = dj;
    for (int i = j + 1; i < n; ++i) {
      Quad v = h[Index(i, j, n)];
      for (int t = 0; t < j; ++t) v -= L[Index(i, t, n)] * L[Index(j, t, n)] * D[t];
      L[Index(i, j, n)] = v / dj;
    }
  }
  return true;
}

// Every principal minor of the n×n matrix a positive (a P-matrix), each by complete-pivoting elimination.
bool PrincipalMinorsPositive(const std::vector<Quad>& a, int n) {
  std::vector<int> idx;
  QuadLu lu;
  for (std::uint32_t mask = 1; mask < (1u << n); ++mask) {
    idx.clear();
    for (int i = 0; i < n; ++i) {
      if (mask >> i & 1u) idx.push_back(i);
    }
    const int k = static_cast<int>(idx.size());
    std::vector<Quad> block(Index(k, 0, k));
    Quad largest = 0;
    for (int r = 0; r < k; ++r) {
      for (int c = 0; c < k; ++c) {
        block[Index(r, c, k)] = a[Index(idx[r], idx[c], n)];
        largest = std::max(largest, Abs(block[Index(r, c, k)]));
      }
    }
    lu.Factor(k, std::move(block), kMinorPivot * largest);
    if (!lu.PositiveDeterminant()) return false;
  }
  return true;
}

// What one active set gave.
struct Outcome {
  bool singular = false;    // the free block is (numerically) singular: z is a basic solution
  bool conclusive = false;  // δ is narrow enough to decide
  bool verified = false;    // z meets every sign and bound condition within δ
  bool degenerate = false;  // some row is within δ of the other choice
  double mu = 0.0;          // ‖B⁻¹‖∞ of the free block B (of its nonsingular pivot block when singular)
  Quad delta = 0;
  std::vector<Quad> z;           // the set's point (also when rejected: guided steps start from it)
  std::vector<bool> degenerate_rows;
  std::vector<Quad> null;        // singular only: a null direction of the free block, ‖·‖∞ = 1, 0 off it
};

// A verified point; points closer than their margins are one.
struct Found {
  std::vector<Quad> z;
  ActiveSet set;
  Quad delta = 0;
  double mu = 0.0;
  bool singular = false;
  bool degenerate = false;
  std::vector<bool> degenerate_rows;
};

class Certifier {
 public:
  Certifier(const BoxMLCP& problem, const CertifyOptions& options) : p_(Equilibrate(problem)), options_(options) {}

  ReferenceSolution Run(const std::vector<Vector>& candidates, CertifyStats* stats) {
    const int n = p_.n;
    // 1. The candidates' sets, in the caller's order (a planted or captured solution first wins z*); all of them,
    //    so two candidates at different solutions show non-uniqueness. Guided steps only while nothing is verified.
    for (const Vector& c : candidates) {
      if (c.size() != n || !c.allFinite()) continue;
      TryFromPoint(ToQuad(c), found_.empty() ? Reach::kGuided : Reach::kFlips);
    }
    // 2. The cold point Π(0): its set, and more only while nothing is verified.
    Vector cold;
    ProjectZeroOntoBox(Vector::Map(p_.l.data(), n), Vector::Map(p_.u.data(), n), &cold);
    const std::vector<Quad> cold_point = ToQuad(cold);
    TryFromPoint(cold_point, found_.empty() ? Reach::kGuided : Reach::kSet);
    // 3. Every set, when there are few enough.
    const double total = ActiveSetCount();
    const bool enumerate = total <= static_cast<double>(options_.max_enumerated);
    if (enumerate) Enumerate(cold_point);

    ReferenceSolution out;
    if (found_.empty()) {
      out.certificate = Certificate::kNoneFound;
    } else {
      Classify(enumerate, &out);
    }
    if (stats) {
      stats->active_sets = static_cast<std::int64_t>(tried_.size());
      stats->active_sets_total = total;
      stats->enumerated = enumerate;
      stats->singular_blocks = singular_;
      stats->inconclusive = inconclusive_;
    }
    return out;
  }

 private:
  std::vector<Quad> ToQuad(const Vector& v) const {
    std::vector<Quad> out(p_.n);
    for (int i = 0; i < p_.n; ++i) out[i] = v[i];
    return out;
  }

  // w = A z + b (scaled units).
  std::vector<Quad> Affine(const std::vector<Quad>& z) const {
    std::vector<Quad> w(p_.b);
    for (int i = 0; i < p_.n; ++i) {
      for (int j = 0; j < p_.n; ++j) w[i] += p_.A(i, j) * z[j];
    }
    return w;
  }

  // The natural-map set at z: at lower if z_i − w_i ≤ l_i, at upper if ≥ u_i, else free.
  ActiveSet NaturalSet(const std::vector<Quad>& z, const std::vector<Quad>& w) const {
    ActiveSet set(p_.n, kFree);
    for (int i = 0; i < p_.n; ++i) {
      const Quad y = z[i] - w[i];
      if (p_.fixed(i)) {
        set[i] = kFixed;
      } else if (p_.has_lower(i) && y <= p_.l[i]) {
        set[i] = kLower;
      } else if (p_.has_upper(i) && y >= p_.u[i]) {
        set[i] = kUpper;
      }
    }
    return set;
  }

  // The nearer finite bound's state for row i at value zi (rows with at least one finite bound).
  State NearestBound(int i, Quad zi) const {
    if (!p_.has_upper(i)) return kLower;
    if (!p_.has_lower(i)) return kUpper;
    return Abs(zi - p_.l[i]) <= Abs(zi - p_.u[i]) ? kLower : kUpper;
  }

  // How far TryFromPoint goes when the point's natural-map set fails.
  enum class Reach { kSet, kFlips, kGuided };

  // The natural-map set at point; if it fails (and reach allows), its near-degenerate rows flipped one at a time
  // and all together; then guided steps. Stops at the first verified set.
  void TryFromPoint(const std::vector<Quad>& point, Reach reach) {
    const std::vector<Quad> w = Affine(point);
    const ActiveSet set = NaturalSet(point, w);
    if (Try(set, point).verified || reach == Reach::kSet) return;

    std::vector<std::pair<Quad, int>> near;  // (ambiguity, row)
    for (int i = 0; i < p_.n; ++i) {
      if (p_.fixed(i) || p_.unbounded(i)) continue;
      const State bound = NearestBound(i, point[i]);
      const double b = bound == kLower ? p_.l[i] : p_.u[i];
      const Quad ambiguity = std::max(Abs(point[i] - b), Abs(w[i])) / (1 + std::abs(b));
      if (ambiguity <= kNearDegenerate) near.emplace_back(ambiguity, i);
    }
    std::sort(near.begin(), near.end());
    if (near.size() > static_cast<std::size_t>(kMaxFlips)) near.resize(kMaxFlips);
    ActiveSet all = set;
    for (const auto& [ambiguity, i] : near) {
      ActiveSet one = set;
      one[i] = set[i] == kFree ? NearestBound(i, point[i]) : kFree;
      all[i] = one[i];
      if (Try(one, point).verified) return;
    }
    if ((near.size() > 1 && Try(all, point).verified) || reach == Reach::kFlips) return;

    std::vector<Quad> z = tried_.at(set).z;
    for (int step = 0; step < kGuidedSteps; ++step) {
      const ActiveSet next = NaturalSet(z, Affine(z));
      if (tried_.count(next)) return;  // a cycle, or a set already decided
      const Outcome& o = Try(next, point);
      if (o.verified) return;
      z = o.z;
    }
  }

  // All active sets, odometer order (anchor: the values of rank-deficient variables in singular blocks).
  void Enumerate(const std::vector<Quad>& anchor) {
    std::vector<std::vector<State>> choices(p_.n);
    for (int i = 0; i < p_.n; ++i) {
      if (p_.fixed(i)) {
        choices[i] = {kFixed};
      } else {
        if (p_.has_lower(i)) choices[i].push_back(kLower);
        if (p_.has_upper(i)) choices[i].push_back(kUpper);
        choices[i].push_back(kFree);
      }
    }
    std::vector<std::size_t> digit(p_.n, 0);
    ActiveSet set(p_.n, kFree);
    for (;;) {
      for (int i = 0; i < p_.n; ++i) set[i] = choices[i][digit[i]];
      Try(set, anchor);
      int i = 0;
      while (i < p_.n && ++digit[i] == choices[i].size()) digit[i++] = 0;
      if (i == p_.n) return;
    }
  }

  double ActiveSetCount() const {
    double count = 1.0;
    for (int i = 0; i < p_.n; ++i) {
      if (!p_.fixed(i)) count *= 1.0 + (p_.has_lower(i) ? 1.0 : 0.0) + (p_.has_upper(i) ? 1.0 : 0.0);
    }
    return count;
  }

  // Solves set once (memoized), records a verified point, and on a verified singular block probes its null
  // direction for a second solution.
  const Outcome& Try(const ActiveSet& set, const std::vector<Quad>& anchor) {
    const auto it = tried_.find(set);
    if (it != tried_.end()) return it->second;
    Outcome& o = tried_.emplace(set, Evaluate(set, anchor)).first->second;  // references survive rehashing
    if (o.singular) ++singular_;
    if (!o.conclusive) ++inconclusive_;
    if (o.verified) {
      Record(o, set);
      if (o.singular) ProbeNullDirection(set, o);
    }
    return o;
  }

  Outcome Evaluate(const ActiveSet& set, const std::vector<Quad>& anchor) const {
    const int n = p_.n;
    Outcome o;
    o.z.assign(n, Quad(0));
    std::vector<int> free;
    for (int i = 0; i < n; ++i) {
      if (set[i] == kFree) {
        free.push_back(i);
      } else {
        o.z[i] = set[i] == kUpper ? p_.u[i] : p_.l[i];
      }
    }
    // (A_FF) z_F = −(b_F + A_FB z_B).
    const int k = static_cast<int>(free.size());
    std::vector<Quad> block(Index(k, 0, k)), rhs(k), fixed(k), x;
    Quad largest = 0;
    for (int r = 0; r < k; ++r) {
      const int i = free[r];
      Quad s = p_.b[i];
      for (int j = 0; j < n; ++j) {
        if (set[j] != kFree) s += p_.A(i, j) * o.z[j];
      }
      rhs[r] = -s;
      fixed[r] = anchor[i];
      for (int c = 0; c < k; ++c) {
        block[Index(r, c, k)] = p_.A(i, free[c]);
        largest = std::max(largest, Abs(block[Index(r, c, k)]));
      }
    }
    QuadLu lu;
    const Quad tolerance = kPivotTolerance * largest;
    lu.Factor(k, std::move(block), tolerance);
    o.singular = lu.rank < k;
    lu.Solve(rhs, fixed.data(), &x);
    for (int r = 0; r < k; ++r) o.z[free[r]] = x[r];
    const Quad mu = lu.InverseNorm();
    o.mu = static_cast<double>(mu);
    if (o.singular) {  // the first rank-deficient variable set to 1, the others to 0, the right-hand side to 0
      std::vector<Quad> zero(k, Quad(0)), unit(k, Quad(0));
      unit[lu.col[lu.rank]] = 1;
      lu.Solve(zero, unit.data(), &x);
      o.null.assign(n, Quad(0));
      Quad size = 0;
      for (int r = 0; r < k; ++r) size = std::max(size, Abs(x[r]));
      for (int r = 0; r < k; ++r) o.null[free[r]] = x[r] / size;
    }

    const Quad scale = 1 + NormInf(o.z) + p_.b_norm;
    o.delta = std::max(Quad(kMarginFloor), kMarginFactor * n * kQuadEps * (1 + mu) * scale);
    // A singular block drops entries below the tolerance: their effect on w_F, and through μ on z_F.
    if (o.singular) o.delta += k * tolerance * (1 + mu) * scale;
    bool finite = IsFinite(scale);
    for (Quad zi : o.z) finite = finite && IsFinite(zi);  // NormInf would skip a NaN
    o.conclusive = finite && o.delta <= kMaxRelativeMargin * scale;
    if (o.conclusive) o.verified = Check(o.z, set, o.delta, &o.degenerate, &o.degenerate_rows);
    return o;
  }

  // The sign and bound conditions of set at z within δ; *degenerate if some row is within δ of the other choice.
  bool Check(const std::vector<Quad>& z, const ActiveSet& set, Quad delta, bool* degenerate,
             std::vector<bool>* degenerate_rows) const {
    const std::vector<Quad> w = Affine(z);
    degenerate_rows->assign(p_.n, false);
    for (int i = 0; i < p_.n; ++i) {
      bool near = false;
      switch (set[i]) {
        case kFixed:
          break;
        case kLower:
          if (w[i] < -delta) return false;
          near = w[i] <= delta;
          break;
        case kUpper:
          if (w[i] > delta) return false;
          near = w[i] >= -delta;
          break;
        case kFree:
          if (Abs(w[i]) > delta) return false;
          if (p_.has_lower(i)) {
            const Quad margin = delta * (1 + std::abs(p_.l[i]));
            if (z[i] < p_.l[i] - margin) return false;
            near = near || z[i] <= p_.l[i] + margin;
          }
          if (p_.has_upper(i)) {
            const Quad margin = delta * (1 + std::abs(p_.u[i]));
            if (z[i] > p_.u[i] + margin) return false;
            near = near || z[i] >= p_.u[i] - margin;
          }
          break;
      }
      (*degenerate_rows)[i] = near;
    }
    *degenerate = std::find(degenerate_rows->begin(), degenerate_rows->end(), true) != degenerate_rows->end();
    return true;
  }

  // A verified point with a singular free block: moves along the block's null direction v (w_F stays 0) as far as
  // the bounds of the free rows and the signs of the bound rows allow, and records the point halfway if it is
  // verified too. Strictly complementary points always have room (a segment of solutions); degenerate rows may
  // block both ways.
  void ProbeNullDirection(const ActiveSet& set, const Outcome& o) {
    const std::vector<Quad>& z = o.z;
    const std::vector<Quad> w = Affine(z);
    std::vector<Quad> av(p_.n, Quad(0));
    for (int i = 0; i < p_.n; ++i) {
      for (int j = 0; j < p_.n; ++j) av[i] += p_.A(i, j) * o.null[j];
    }
    const Quad reach = 1 + NormInf(z);
    Quad lo = -reach, hi = reach;
    const auto keep = [&](Quad slack, Quad rate) {  // slack + t·rate ≥ 0
      if (Abs(rate) <= o.delta) return;
      const Quad t = -slack / rate;
      if (rate > 0) {
        lo = std::max(lo, t);
      } else {
        hi = std::min(hi, t);
      }
    };
    for (int i = 0; i < p_.n; ++i) {
      if (set[i] == kFree) {
        if (p_.has_lower(i)) keep(z[i] - p_.l[i], o.null[i]);
        if (p_.has_upper(i)) keep(p_.u[i] - z[i], -o.null[i]);
      } else if (set[i] == kLower) {
        keep(w[i], av[i]);
      } else if (set[i] == kUpper) {
        keep(-w[i], -av[i]);
      }
    }
    const Quad t = hi >= -lo ? hi / 2 : lo / 2;
    if (!(Abs(t) > 8 * o.delta)) return;
    Outcome other = o;
    for (int i = 0; i < p_.n; ++i) other.z[i] = z[i] + t * o.null[i];
    other.verified = Check(other.z, set, o.delta, &other.degenerate, &other.degenerate_rows);
    if (other.verified) Record(other, set);
  }

  // Adds a verified point, or merges it into a known one within both margins (keeping a nonsingular set's copy).
  void Record(const Outcome& o, const ActiveSet& set) {
    for (Found& f : found_) {
      Quad distance = 0;
      for (int i = 0; i < p_.n; ++i) distance = std::max(distance, Abs(f.z[i] - o.z[i]));
      if (distance > 4 * (f.delta + o.delta)) continue;
      const bool degenerate = f.degenerate || o.degenerate;  // a row degenerate under either set is degenerate
      std::vector<bool> rows = f.degenerate_rows;
      for (int i = 0; i < p_.n; ++i) rows[i] = rows[i] || o.degenerate_rows[i];
      if (f.singular && !o.singular) f = {o.z, set, o.delta, o.mu, false, false, {}};
      f.degenerate = degenerate;
      f.degenerate_rows = std::move(rows);
      return;
    }
    found_.push_back({o.z, set, o.delta, o.mu, o.singular, o.degenerate, o.degenerate_rows});
  }

  // z* is the first point verified through a nonsingular block (else the first); certificate and μ as in the header.
  void Classify(bool enumerated, ReferenceSolution* out) {
    std::size_t pick = 0;
    while (pick < found_.size() && found_[pick].singular) ++pick;
    if (pick == found_.size()) pick = 0;
    const Found primary = found_[pick];  // a copy: the alternatives below may add points

    double mu = primary.singular ? kInf : primary.mu;
    if (primary.degenerate && !primary.singular) {
      // μ with the degenerate rows at their bounds and with them free: an error may move z* either way.
      ActiveSet at_bounds = primary.set, all_free = primary.set;
      for (int i = 0; i < p_.n; ++i) {
        if (!primary.degenerate_rows[i]) continue;
        if (primary.set[i] == kFree) {
          at_bounds[i] = NearestBound(i, primary.z[i]);
        } else {
          all_free[i] = kFree;
        }
      }
      for (const ActiveSet& other : {at_bounds, all_free}) {
        const Outcome& o = Try(other, primary.z);
        if (!o.singular && o.conclusive) mu = std::max(mu, o.mu);
      }
    }

    if (found_.size() >= 2 || primary.singular) {
      out->certificate = Certificate::kNonUnique;
    } else {
      const bool by_enumeration = enumerated && singular_ == 0 && inconclusive_ == 0;
      const bool unique = by_enumeration || PMatrix();
      if (unique) {
        out->certificate = primary.degenerate ? Certificate::kDegenerate : Certificate::kUnique;
      } else {
        // Degenerate points land here too: verdict.h's kIsolated says "strictly complementary"; with every nearby
        // set nonsingular the point is still locally unique, which is what the verdict uses it for.
        out->certificate = Certificate::kIsolated;
      }
    }
    out->z.resize(p_.n);
    for (int i = 0; i < p_.n; ++i) out->z[i] = static_cast<double>(primary.z[i]);
    out->condition = mu;
  }

  // M is a P-matrix: the caller says so, or a sufficient test passes (P-ness survives positive row and column
  // scalings, so D⁻¹M and D^-½ M D^-½ are tested).
  bool PMatrix() const {
    if (options_.p_matrix) return *options_.p_matrix;
    const int n = p_.n;
    if (SymmetricPartPositiveDefinite(p_.a, n)) return true;
    std::vector<Quad> s(p_.a.size());
    std::vector<Quad> root(n);
    for (int i = 0; i < n; ++i) root[i] = std::sqrt(p_.d[i]);  // any positive values keep P-ness
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) s[Index(i, j, n)] = p_.A(i, j) * root[i] / root[j];
    }
    if (SymmetricPartPositiveDefinite(s, n)) return true;
    return n <= kMaxMinorsSize && PrincipalMinorsPositive(p_.a, n);
  }

  const Equilibrated p_;
  const CertifyOptions options_;
  std::unordered_map<ActiveSet, Outcome> tried_;
  std::vector<Found> found_;
  std::int64_t singular_ = 0;
  std::int64_t inconclusive_ = 0;
};

}  // namespace

ReferenceSolution Certify(const BoxMLCP& problem, const std::vector<Vector>& candidates, const CertifyOptions& options,
                          CertifyStats* stats) {
  if (stats) *stats = {};
  if (problem.size() == 0 || problem.size() > options.max_size) return {};
  ReferenceSolution reference = Certifier(problem, options).Run(candidates, stats);
  AddProof(problem, &reference);
  return reference;
}

void AddProof(const BoxMLCP& problem, ReferenceSolution* reference) {
  if (!reference->verified()) return;
  const SolutionEnclosure enclosure = EncloseSolution(problem, reference->z);
  if (!enclosure.proved) return;
  reference->proved_radius = enclosure.radius;
  reference->proved_unique = !problem.is_sparse() && ProveSymmetricPartPositiveDefinite(problem.dense_matrix());
}

const SolverInfo& ReferenceSolver::info() const {
  static const SolverInfo kInfo{
      "reference",
      "exhaustive-enumeration + quad certification, dense n <= 64: active sets from the start point, the warm "
      "start and Pi(0) (with near-degenerate flips and guided steps), all of them when at most 6561, each solved "
      "and verified with error margins in __float128",
      "extended-precision active-set certification (this project)",
      /*dense=*/true,
      /*sparse=*/false,
      /*symmetric_only=*/false,
      /*exact=*/true,
      /*mcp=*/false,
      /*default_size_limit=*/CertifyOptions{}.max_size,
      // Certify equilibrates in quad; a double-rounded D⁻¹M would be a slightly different problem.
      /*equilibrate=*/false};
  return kInfo;
}

void ReferenceSolver::DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) {
  const CertifyOptions certify_options;
  if (problem.size() > certify_options.max_size) {
    result->status = SolveStatus::kSizeLimit;
    result->message = "n = " + std::to_string(problem.size()) + " > " + std::to_string(certify_options.max_size) +
                      ": the reference backend certifies dense problems up to that size";
    return;
  }
  std::vector<Vector> candidates{result->z};
  if (options.warm_start.size() == problem.size()) candidates.push_back(options.warm_start);
  CertifyStats stats;
  const ReferenceSolution reference = Certify(problem, candidates, certify_options, &stats);
  result->iterations = static_cast<int>(std::min<std::int64_t>(stats.active_sets, INT_MAX));
  kCertificateDetail.Set(result, reference.certificate);
  result->SetDetail("condition", reference.condition);
  if (reference.verified()) {
    result->status = SolveStatus::kSolved;
    result->z = reference.z;
    return;
  }
  result->status = SolveStatus::kNumericalFailure;
  std::string& m = result->message;
  m = "no active set verified in extended precision: " + std::to_string(stats.active_sets) +
      " sets solved (natural-map sets at the start point and at Pi(0), near-degenerate flips, guided steps";
  if (stats.enumerated) {
    m += ", and all " + NumberText(stats.active_sets_total) + " sets";
  } else {
    m += "; the full enumeration, " + NumberText(stats.active_sets_total) + " sets, is above " +
         std::to_string(certify_options.max_enumerated) + " and was skipped";
  }
  m += ")";
  if (stats.singular_blocks > 0) m += ", " + std::to_string(stats.singular_blocks) + " with singular free blocks";
  if (stats.inconclusive > 0) m += ", " + std::to_string(stats.inconclusive) + " too ill-conditioned to decide";
  m += "; this is not a proof that no solution exists";
}

}  // namespace smcbench

// Extended-precision refinement and verification of MCP solutions (see mcp_certify.h for the method).
#include "solvers/reference/mcp_certify.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <set>
#include <string>
#include <utility>

#include "solvers/reference/quad_lu.h"

namespace smcbench {
namespace {

constexpr Quad kQuadEps = 0x1p-112;
constexpr double kPivotTolerance = 1e-28;  // relative to the block's largest entry: singular below it
constexpr double kMarginFactor = 64.0;
constexpr double kMarginFloor = 1e-30;
constexpr double kMaxRelativeMargin = 1e-10;  // a wider margin decides nothing
constexpr double kStepTolerance = 1e-32;      // Newton stops when ‖C⁻¹Δz‖∞ ≤ this (1 + ‖C⁻¹z‖∞)
constexpr int kMaxHalvings = 60;
constexpr int kMaxMinorsSize = 10;  // principal-minor P-matrix check up to this n (2^n minors)

Quad Abs(Quad x) { return x < 0 ? -x : x; }
bool Finite(Quad x) { return x - x == 0; }

enum State : char { kLower = 'L', kUpper = 'U', kFree = 'F', kFixed = 'X' };
using ActiveSet = std::string;

// A factored reduced Jacobian A = D_F⁻¹ J_FF C_F: solves, and μ = ‖A⁻¹‖∞ (+∞ when it cannot be bounded).
struct ReducedFactor {
  virtual ~ReducedFactor() = default;
  virtual bool singular() const = 0;
  virtual void Solve(const std::vector<Quad>& b, std::vector<Quad>* x) const = 0;
  virtual Quad InverseNorm() const = 0;
};

// Complete-pivoting LU of a k×k row-major block (quad_lu.h): rank-revealing; solves and ‖B⁻¹‖∞. Singular below
// kPivotTolerance times the block's largest entry.
struct SmallLu final : ReducedFactor {
  QuadLu lu;
  void Factor(int size, std::vector<Quad> block) {
    Quad largest = 0;
    for (Quad v : block) largest = std::max(largest, Abs(v));
    lu.Factor(size, std::move(block), kPivotTolerance * largest);
  }
  bool singular() const override { return lu.singular(); }
  // x = B⁻¹ b (nonsingular only).
  void Solve(const std::vector<Quad>& b, std::vector<Quad>* x) const override { lu.Solve(b, nullptr, x); }
  Quad InverseNorm() const override { return lu.InverseNorm(); }
  bool PositiveDeterminant() const { return lu.PositiveDeterminant(); }
};

// LU without pivoting of a k×k band matrix (lower bandwidth p, upper q; row-major band storage), for the large
// sparse problems whose reduced Jacobian is a nonsingular M-matrix (discretized −Δ + monotone terms): elimination
// without pivoting is then stable and keeps the band. μ: for a Z-matrix A (off-diagonal ≤ 0), a solution x > 0 of
// A x = e proves A a nonsingular M-matrix, so A⁻¹ ≥ 0 and ‖A⁻¹‖∞ = ‖A⁻¹e‖∞ = max x; otherwise μ is not bounded
// here (+∞: the point is not certified).
struct BandLu final : ReducedFactor {
  int k = 0, p = 0, q = 0;
  bool z_matrix = true, failed = false;
  std::vector<Quad> a;
  int width() const { return p + q + 1; }
  Quad& At(int r, int c) { return a[static_cast<std::size_t>(r) * width() + (c - r + p)]; }
  Quad At(int r, int c) const { return a[static_cast<std::size_t>(r) * width() + (c - r + p)]; }

  void Factor() {
    Quad largest = 0;
    for (Quad v : a) largest = std::max(largest, Abs(v));
    const Quad tolerance = kPivotTolerance * largest;
    for (int s = 0; s < k && !failed; ++s) {
      const Quad pivot = At(s, s);
      if (!(Abs(pivot) > tolerance) || !Finite(pivot)) {
        failed = true;
        break;
      }
      for (int i = s + 1; i <= std::min(k - 1, s + p); ++i) {
        const Quad m = At(i, s) / pivot;
        At(i, s) = m;
        if (m == 0) continue;
        for (int j = s + 1; j <= std::min(k - 1, s + q); ++j) At(i, j) -= m * At(s, j);
      }
    }
  }
  bool singular() const override { return failed; }
  void Solve(const std::vector<Quad>& b, std::vector<Quad>* x) const override {
    x->assign(b.begin(), b.end());
    std::vector<Quad>& y = *x;
    for (int r = 0; r < k; ++r) {
      for (int c = std::max(0, r - p); c < r; ++c) y[r] -= At(r, c) * y[c];
    }
    for (int r = k - 1; r >= 0; --r) {
      for (int c = r + 1; c <= std::min(k - 1, r + q); ++c) y[r] -= At(r, c) * y[c];
      y[r] /= At(r, r);
    }
  }
  Quad InverseNorm() const override {
    const Quad unbounded = static_cast<Quad>(kInf);
    if (!z_matrix) return unbounded;
    std::vector<Quad> x;
    Solve(std::vector<Quad>(k, Quad(1)), &x);
    Quad norm = 0;
    for (Quad v : x) {
      if (!(v > 0)) return unbounded;
      norm = std::max(norm, v);
    }
    return norm;
  }
};

// The outcome of one active set.
struct Attempt {
  bool converged = false;
  bool verified = false;
  bool degenerate = false;
  std::vector<bool> near;  // rows within δ of the other state
  std::vector<Quad> z;
  Quad delta = 0;
  double mu = 0.0;
  int iterations = 0;
  ActiveSet next;  // the corrected set when a condition failed (empty: nothing to change)
};

class McpCertifier {
 public:
  McpCertifier(const ExtendedPrecisionMCP& problem, const McpCertifyOptions& options, bool banded)
      : p_(problem), options_(options), n_(problem.size()), banded_(banded) {
    l_.assign(problem.l().data(), problem.l().data() + n_);
    u_.assign(problem.u().data(), problem.u().data() + n_);
    c_.assign(n_, 1.0);
    if (problem.variable_scale().size() == n_) {
      for (int i = 0; i < n_; ++i) c_[i] = problem.variable_scale()[i];
    }
    F_.resize(n_);
    if (!banded_) J_.resize(static_cast<std::size_t>(n_) * n_);
  }

  void Run(const std::vector<Vector>& candidates) {
    for (const Vector& candidate : candidates) {
      if (candidate.size() != n_ || !candidate.allFinite() || NearFound(candidate)) continue;
      std::vector<Quad> z(n_);
      for (int i = 0; i < n_; ++i) z[i] = std::min(std::max(candidate[i], l_[i]), u_[i]);
      ActiveSet set;
      if (!NaturalSet(z, &set)) continue;
      std::set<ActiveSet> tried;
      for (int change = 0; change <= options_.max_set_changes && tried.insert(set).second; ++change) {
        Attempt a = Solve(set, z);
        if (a.verified) {
          Record(a, set);
          break;
        }
        if (!a.converged || a.next.empty()) break;
        z = a.z;
        set = a.next;
      }
    }
    Classify();
  }

  std::vector<McpCertifiedSolution> Results() {
    std::vector<McpCertifiedSolution> out;
    for (std::size_t s = 0; s < found_.size(); ++s) {
      McpCertifiedSolution c;
      c.reference = found_[s].reference;
      c.z = found_[s].attempt.z;
      c.margin = static_cast<double>(found_[s].attempt.delta);
      c.degenerate = found_[s].attempt.degenerate;
      c.newton_iterations = found_[s].attempt.iterations;
      if (c.reference.verified()) {
        c.reference.z.resize(n_);
        // Clamped: a free row within δ of its bound may sit a rounding outside it.
        for (int i = 0; i < n_; ++i) c.reference.z[i] = std::min(std::max(static_cast<double>(c.z[i]), l_[i]), u_[i]);
      }
      out.push_back(std::move(c));
    }
    return out;
  }

 private:
  struct Found {
    ActiveSet set;
    Attempt attempt;
    ReferenceSolution reference;
  };

  // A candidate within 1e-8 (relative, in units of z) of a verified point would only verify it again (backends'
  // answers from several starts usually agree): skipped, which keeps the cost per problem to a few Newton runs.
  bool NearFound(const Vector& candidate) const {
    for (const Found& f : found_) {
      double distance = 0.0, size = 0.0;
      for (int i = 0; i < n_; ++i) {
        distance = std::max(distance, std::abs(candidate[i] - static_cast<double>(f.attempt.z[i])) / c_[i]);
        size = std::max(size, std::abs(candidate[i]) / c_[i]);
      }
      if (distance <= 1e-8 * (1 + size)) return true;
    }
    return false;
  }

  bool Evaluate(const std::vector<Quad>& z) {
    p_.EvaluateQuad(z.data(), F_.data());
    for (Quad f : F_) {
      if (!Finite(f)) return false;
    }
    return true;
  }
  void Jacobian(const std::vector<Quad>& z) {
    if (!banded_) {
      p_.JacobianQuad(z.data(), J_.data());
      return;
    }
    // Sorted by (row, col) with repeated entries summed, so that each row's scale sees the true J_ij.
    p_.JacobianQuadEntries(z.data(), &entries_);
    std::sort(entries_.begin(), entries_.end(), [](const QuadEntry& x, const QuadEntry& y) {
      return x.row != y.row ? x.row < y.row : x.col < y.col;
    });
    std::size_t out = 0;
    for (std::size_t e = 0; e < entries_.size(); ++e) {
      if (out > 0 && entries_[out - 1].row == entries_[e].row && entries_[out - 1].col == entries_[e].col) {
        entries_[out - 1].value += entries_[e].value;
      } else {
        entries_[out++] = entries_[e];
      }
    }
    entries_.resize(out);
  }
  Quad J(int i, int j) const { return J_[static_cast<std::size_t>(j) * n_ + i]; }

  // d_i = max_j |J_ij| c_j (zero rows: the largest other); false if J is not finite.
  bool RowScales(std::vector<Quad>* d) const {
    d->assign(n_, Quad(0));
    Quad largest = 0;
    if (banded_) {
      for (const QuadEntry& e : entries_) {
        const Quad a = Abs(e.value) * c_[e.col];
        if (!Finite(a)) return false;
        (*d)[e.row] = std::max((*d)[e.row], a);
      }
      for (Quad di : *d) largest = std::max(largest, di);
    }
    for (int i = 0; i < n_ && !banded_; ++i) {
      for (int j = 0; j < n_; ++j) {
        const Quad a = Abs(J(i, j)) * c_[j];
        if (!Finite(a)) return false;
        (*d)[i] = std::max((*d)[i], a);
      }
      largest = std::max(largest, (*d)[i]);
    }
    if (largest == 0) largest = 1;
    for (Quad& di : *d) {
      if (di == 0) di = largest;
    }
    return true;
  }

  bool NaturalSet(const std::vector<Quad>& z, ActiveSet* set) {
    if (!Evaluate(z)) return false;
    Jacobian(z);
    std::vector<Quad> d;
    if (!RowScales(&d)) return false;
    set->assign(n_, kFree);
    for (int i = 0; i < n_; ++i) {
      if (l_[i] == u_[i]) {
        (*set)[i] = kFixed;
        continue;
      }
      const Quad t = z[i] - c_[i] * F_[i] / d[i];
      if (l_[i] > -kInf && t <= l_[i])
        (*set)[i] = kLower;
      else if (u_[i] < kInf && t >= u_[i])
        (*set)[i] = kUpper;
    }
    return true;
  }

  // max over free rows of |F_i| / d_i.
  static Quad ReducedResidual(const std::vector<Quad>& F, const std::vector<Quad>& d, const std::vector<int>& free) {
    Quad r = 0;
    for (int i : free) r = std::max(r, Abs(F[i] / d[i]));
    return r;
  }

  // The reduced Jacobian A = D_F⁻¹ J_FF C_F, factored: dense with complete pivoting, or banded (a band wider than
  // max_bandwidth counts as singular: the point is then not certified).
  std::unique_ptr<ReducedFactor> ReducedLu(const std::vector<int>& free, const std::vector<Quad>& d) const {
    const int k = static_cast<int>(free.size());
    if (!banded_) {
      std::vector<Quad> block(static_cast<std::size_t>(k) * k);
      for (int r = 0; r < k; ++r) {
        for (int s = 0; s < k; ++s)
          block[static_cast<std::size_t>(r) * k + s] = J(free[r], free[s]) * c_[free[s]] / d[free[r]];
      }
      auto lu = std::make_unique<SmallLu>();
      lu->Factor(k, std::move(block));
      return lu;
    }
    auto lu = std::make_unique<BandLu>();
    lu->k = k;
    std::vector<int> position(n_, -1);
    for (int r = 0; r < k; ++r) position[free[r]] = r;
    for (const QuadEntry& e : entries_) {
      const int r = position[e.row], s = position[e.col];
      if (r < 0 || s < 0) continue;
      lu->p = std::max(lu->p, r - s);
      lu->q = std::max(lu->q, s - r);
    }
    if (lu->p > options_.max_bandwidth || lu->q > options_.max_bandwidth) {
      lu->failed = true;
      return lu;
    }
    lu->a.assign(static_cast<std::size_t>(k) * lu->width(), Quad(0));
    for (const QuadEntry& e : entries_) {
      const int r = position[e.row], s = position[e.col];
      if (r < 0 || s < 0) continue;
      const Quad v = e.value * c_[e.col] / d[e.row];
      lu->At(r, s) += v;
    }
    for (int r = 0; r < k; ++r) {
      for (int s = std::max(0, r - lu->p); s <= std::min(k - 1, r + lu->q); ++s) {
        if (s == r ? !(lu->At(r, s) > 0) : lu->At(r, s) > 0) lu->z_matrix = false;
      }
    }
    lu->Factor();
    return lu;
  }

  Attempt Solve(const ActiveSet& set, std::vector<Quad> z) {
    Attempt a;
    std::vector<int> free;
    for (int i = 0; i < n_; ++i) {
      if (set[i] == kFree)
        free.push_back(i);
      else if (set[i] == kUpper)
        z[i] = u_[i];
      else
        z[i] = l_[i];
    }
    const int k = static_cast<int>(free.size());
    std::vector<Quad> d, rhs(k), step, trial;
    // Newton on F_F(z) = 0 in the scaled unknowns y = C⁻¹z.
    if (!Evaluate(z)) return a;
    bool converged = k == 0;
    for (int it = 0; it < options_.max_newton_iterations && !converged; ++it) {
      Jacobian(z);
      if (!RowScales(&d)) return a;
      const std::unique_ptr<ReducedFactor> lu = ReducedLu(free, d);
      if (lu->singular()) return a;
      for (int r = 0; r < k; ++r) rhs[r] = -F_[free[r]] / d[free[r]];
      lu->Solve(rhs, &step);
      const Quad before = ReducedResidual(F_, d, free);
      Quad size = 0, z_norm = 0;
      for (int r = 0; r < k; ++r) size = std::max(size, Abs(step[r]));
      for (int i = 0; i < n_; ++i) z_norm = std::max(z_norm, Abs(z[i]) / c_[i]);
      Quad t = 1;
      bool accepted = false;
      for (int h = 0; h <= kMaxHalvings; ++h, t /= 2) {
        trial = z;
        for (int r = 0; r < k; ++r) trial[free[r]] += t * step[r] * c_[free[r]];
        if (!Evaluate(trial)) continue;
        // Accept any decrease, or the full step near convergence where the residual is rounding.
        if (ReducedResidual(F_, d, free) < before || (h == 0 && size <= 1e-20 * (1 + z_norm))) {
          accepted = true;
          break;
        }
      }
      if (!accepted) {
        Evaluate(z);
        break;
      }
      z = trial;
      a.iterations = it + 1;
      converged = t == 1 && size <= kStepTolerance * (1 + z_norm);
    }
    if (!converged) {
      // The last accepted point may still be a root to full accuracy (the step stalls on rounding).
      if (!Evaluate(z)) return a;
    }
    Jacobian(z);
    if (!RowScales(&d)) return a;
    const std::unique_ptr<ReducedFactor> lu = ReducedLu(free, d);
    if (lu->singular()) return a;
    const Quad mu = k > 0 ? lu->InverseNorm() : Quad(0);
    Quad z_norm = 0;
    for (int i = 0; i < n_; ++i) z_norm = std::max(z_norm, Abs(z[i]) / c_[i]);
    const Quad residual = ReducedResidual(F_, d, free);
    a.delta = std::max(Quad(kMarginFloor), kMarginFactor * n_ * kQuadEps * (1 + mu) * (1 + z_norm)) + 4 * mu * residual;
    a.mu = static_cast<double>(mu);
    a.z = z;
    a.converged = Finite(a.delta) && a.delta <= kMaxRelativeMargin * (1 + z_norm);
    if (!a.converged) return a;

    // The sign and bound conditions within δ (units of z: c_i F_i/d_i and (z_i − bound)/c_i).
    a.near.assign(n_, false);
    ActiveSet next = set;
    bool ok = true;
    for (int i = 0; i < n_; ++i) {
      const Quad s = c_[i] * F_[i] / d[i] / c_[i];
      switch (set[i]) {
        case kFixed:
          break;
        case kLower:
          if (s < -a.delta) ok = false, next[i] = kFree;
          a.near[i] = s <= a.delta;
          break;
        case kUpper:
          if (s > a.delta) ok = false, next[i] = kFree;
          a.near[i] = s >= -a.delta;
          break;
        case kFree: {
          if (l_[i] > -kInf) {
            const Quad gap = (z[i] - l_[i]) / c_[i];
            if (gap < -a.delta) ok = false, next[i] = kLower;
            a.near[i] = a.near[i] || gap <= a.delta;
          }
          if (u_[i] < kInf) {
            const Quad gap = (u_[i] - z[i]) / c_[i];
            if (gap < -a.delta) ok = false, next[i] = kUpper;
            a.near[i] = a.near[i] || gap <= a.delta;
          }
          break;
        }
      }
    }
    if (!ok) {
      a.next = next;
      return a;
    }
    a.verified = true;
    a.degenerate = std::find(a.near.begin(), a.near.end(), true) != a.near.end();
    return a;
  }

  void Record(const Attempt& a, const ActiveSet& set) {
    for (Found& f : found_) {
      Quad distance = 0;
      for (int i = 0; i < n_; ++i) distance = std::max(distance, Abs(f.attempt.z[i] - a.z[i]) / c_[i]);
      if (distance <= 4 * (f.attempt.delta + a.delta)) return;
    }
    found_.push_back({set, a, {}});
  }

  // The problem's declared property, checked at z where cheap.
  bool DeclaredUnique(const std::vector<Quad>& z) {
    const SolutionSetProperty property = p_.solution_set_property();
    if (property == SolutionSetProperty::kNone) return false;
    // Too large to check cheaply: the declaration is trusted.
    if (property == SolutionSetProperty::kUniqueByProof || banded_) return true;
    Jacobian(z);
    if (property == SolutionSetProperty::kStronglyMonotone) {
      // xᵀJx > 0 for all x: the symmetric part positive definite (Cholesky-like LDLᵀ, every pivot positive).
      std::vector<Quad> h(static_cast<std::size_t>(n_) * n_);
      for (int i = 0; i < n_; ++i) {
        for (int j = 0; j < n_; ++j) h[static_cast<std::size_t>(i) * n_ + j] = (J(i, j) + J(j, i)) / 2;
      }
      for (int s = 0; s < n_; ++s) {
        const Quad pivot = h[static_cast<std::size_t>(s) * n_ + s];
        if (!(pivot > 0)) return false;
        for (int i = s + 1; i < n_; ++i) {
          const Quad m = h[static_cast<std::size_t>(i) * n_ + s] / pivot;
          for (int j = s + 1; j < n_; ++j)
            h[static_cast<std::size_t>(i) * n_ + j] -= m * h[static_cast<std::size_t>(s) * n_ + j];
        }
      }
      return true;
    }
    if (n_ > kMaxMinorsSize) return true;  // P-function declared; too large to check cheaply
    for (unsigned mask = 1; mask < (1u << n_); ++mask) {
      std::vector<int> idx;
      for (int i = 0; i < n_; ++i) {
        if (mask >> i & 1u) idx.push_back(i);
      }
      const int k = static_cast<int>(idx.size());
      std::vector<Quad> block(static_cast<std::size_t>(k) * k);
      for (int r = 0; r < k; ++r) {
        for (int s = 0; s < k; ++s) block[static_cast<std::size_t>(r) * k + s] = J(idx[r], idx[s]);
      }
      SmallLu lu;
      lu.Factor(k, std::move(block));
      if (!lu.PositiveDeterminant()) return false;
    }
    return true;
  }

  void Classify() {
    for (Found& f : found_) {
      const Attempt& a = f.attempt;
      double mu = a.mu;
      bool alternatives_nonsingular = true;
      if (a.degenerate) {
        ActiveSet at_bounds = f.set, all_free = f.set;
        for (int i = 0; i < n_; ++i) {
          if (!a.near[i]) continue;
          if (f.set[i] == kFree) {
            const bool lower = l_[i] > -kInf && (u_[i] == kInf || Abs(a.z[i] - l_[i]) <= Abs(u_[i] - a.z[i]));
            at_bounds[i] = lower ? kLower : kUpper;
          } else {
            all_free[i] = kFree;
          }
        }
        for (const ActiveSet& other : {at_bounds, all_free}) {
          if (other == f.set) continue;
          const Attempt o = Solve(other, a.z);
          if (o.converged) {
            mu = std::max(mu, o.mu);
          } else {
            alternatives_nonsingular = false;
          }
        }
      }
      ReferenceSolution& ref = f.reference;
      ref.condition = mu;
      if (found_.size() >= 2) {
        ref.certificate = Certificate::kNonUnique;
      } else if (DeclaredUnique(a.z)) {
        ref.certificate = a.degenerate ? Certificate::kDegenerate : Certificate::kUnique;
      } else if (!a.degenerate || alternatives_nonsingular) {
        ref.certificate = Certificate::kIsolated;
      } else {
        ref.certificate = Certificate::kNoneFound;
      }
    }
  }

  const ExtendedPrecisionMCP& p_;
  const McpCertifyOptions options_;
  const int n_;
  std::vector<double> l_, u_, c_;
  const bool banded_;
  std::vector<Quad> F_, J_;
  std::vector<QuadEntry> entries_;  // banded: the Jacobian's entries, sorted, repeats summed
  std::vector<Found> found_;
};

}  // namespace

namespace {
// Dense up to max_size; sparse problems up to max_banded_size banded; others not attempted.
bool Attempted(const ExtendedPrecisionMCP& problem, const McpCertifyOptions& options, bool* banded) {
  const int n = problem.size();
  *banded = n > options.max_size;
  return n > 0 && (n <= options.max_size ||
                   (problem.jacobian_kind() == MCP::JacobianKind::kSparse && n <= options.max_banded_size));
}
}  // namespace

std::vector<McpCertifiedSolution> CertifyMCPSolutions(const ExtendedPrecisionMCP& problem,
                                                      const std::vector<Vector>& candidates,
                                                      const McpCertifyOptions& options) {
  bool banded = false;
  if (!Attempted(problem, options, &banded)) return {};
  McpCertifier certifier(problem, options, banded);
  certifier.Run(candidates);
  return certifier.Results();
}

ReferenceSolution CertifyMCP(const ExtendedPrecisionMCP& problem, const std::vector<Vector>& candidates,
                             const McpCertifyOptions& options) {
  bool banded = false;
  if (!Attempted(problem, options, &banded)) return {};
  const std::vector<McpCertifiedSolution> found = CertifyMCPSolutions(problem, candidates, options);
  for (const McpCertifiedSolution& s : found) {
    if (s.reference.verified()) return s.reference;
  }
  ReferenceSolution none;
  none.certificate = Certificate::kNoneFound;
  return none;
}

}  // namespace smcbench

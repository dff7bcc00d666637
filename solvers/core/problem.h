// The two problem types every backend solves: the box-constrained MLCP (Dirkse–Ferris, `eq:MLCP1`) and the
// nonlinear MCP. Each owns its validation and the one merit function by which every backend is judged.
// The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>

#include "solvers/core/types.h"

namespace smcbench {

// Thrown when a problem, file or option is malformed. The message names the field and, where there is one,
// the index ("BoxMLCP: q[3] is NaN"). A valid problem that a solver cannot solve is a status, never this.
class InvalidInputError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Natural-map residual r(z) = ‖z − Π_[l,u](z − F(z))‖∞, absolute and relative to the problem's scale
// (1 + ‖q‖∞ for a box-MLCP), and the same residual of the row-equilibrated problem: rows of M and q divided by
// the row scales d_i (BoxMLCP::row_scale), in units of z, relative to 1 + ‖z‖∞. All are zero exactly at a
// solution; "solved" requires rel and scaled ≤ tolerance (docs/verdict.md). The scaled one sees an error in z
// whatever the size of M: with W = O(h) the unscaled one lets through errors of order rel/h.
struct Residual {
  double abs = kInf;
  double rel = kInf;
  double scaled = kInf;
};

// The acceptance rule of a box-MLCP: "solved" means the relative residual and the residual in units of z are both
// within the tolerance (docs/verdict.md); a NaN never passes. The one rule of Solver::Finish, the polish, sessions,
// the verdict, the conformance checks and the backends' own stopping tests.
inline bool PassesBoxMlcpTolerance(const Residual& r, double tolerance) {
  return r.rel <= tolerance && r.scaled <= tolerance;
}
// The acceptance rule of an MCP: the scale-free residual alone (Residual::scaled from McpMerit), since the relative
// one is not invariant under row scaling.
inline bool PassesMcpTolerance(const Residual& r, double tolerance) { return r.scaled <= tolerance; }

// ‖z − Π_[l,u](z − w)‖∞ for a given w = F(z). Returns +∞ if any entry is NaN, so a NaN never passes a test.
double NaturalResidualNorm(const Vector& z, const Vector& w, const Vector& l, const Vector& u);
// ‖z − Π_[l,u](z − D⁻¹w)‖∞ / (1 + ‖z‖∞) with D⁻¹ = diag(inv_row_scale): Residual::scaled. +∞ on NaN.
double ScaledNaturalResidualNorm(const Vector& z, const Vector& w, const Vector& l, const Vector& u,
                                 const Vector& inv_row_scale);

// Π_[l,u](0): the cold-start point used when no warm start is given.
void ProjectZeroOntoBox(const Vector& l, const Vector& u, Vector* z);

// Find z ∈ [l,u], w, v ≥ 0 with M z + q = w − v, (z − l)ᵀw = 0, (u − z)ᵀv = 0.
// Bounds may be ±∞: l = 0, u = ∞ is an LCP; l = −∞, u = ∞ a free (equality) row; l = −1, u = 1 a relay row.
// M is stored dense or sparse, never both. Construction validates everything and throws InvalidInputError.
class BoxMLCP {
 public:
  BoxMLCP(DenseMatrix M, Vector q, Vector l, Vector u, std::string name = {});
  BoxMLCP(SparseMatrix M, Vector q, Vector l, Vector u, std::string name = {});

  // Standard LCP: l = 0, u = +∞.
  static BoxMLCP LCP(DenseMatrix M, Vector q, std::string name = {});
  // Relay / sign problem with the same box on every row (the paper's l = −1, u = 1 by default).
  static BoxMLCP Relay(DenseMatrix M, Vector q, double lower = -1.0, double upper = 1.0, std::string name = {});

  int size() const { return static_cast<int>(q_.size()); }
  bool is_sparse() const { return is_sparse_; }
  // Inline checks: backends read M on every solve; the throw is out of line.
  const DenseMatrix& dense_matrix() const {  // throws std::logic_error if sparse
    if (is_sparse_) ThrowWrongStorage("dense_matrix", "sparse");
    return dense_;
  }
  const SparseMatrix& sparse_matrix() const {  // throws std::logic_error if dense
    if (!is_sparse_) ThrowWrongStorage("sparse_matrix", "dense");
    return sparse_;
  }
  // Identifies the current M: a fresh process-wide number at construction and at every set_M, kept by copies
  // (which hold the same M). Backends key per-matrix caches (factorizations, diagonals) on it; two problems with
  // the same id have the same M.
  std::uint64_t matrix_id() const { return matrix_id_; }
  const Vector& q() const { return q_; }
  const Vector& l() const { return l_; }
  const Vector& u() const { return u_; }
  const std::string& name() const { return name_; }
  void set_name(std::string name) { name_ = std::move(name); }
  // Replaces q in place (time-steppers: M fixed, q changes every step). Validates size and finiteness like the
  // constructor and recomputes the relative scale; no allocation.
  void set_q(const Eigen::Ref<const Vector>& q) { SetQ<Eigen::Dynamic>(q.data(), q.size()); }
  // The same for a fixed-size vector (the stepper's kernels): loops of compile-time length, inlined.
  template <int N, int Options>
  [[gnu::always_inline]] inline void set_q(const Eigen::Matrix<double, N, 1, Options, N, 1>& q) {
    SetQ<N>(q.data(), q.size());
  }
  // The same for a caller that knows size() == N at compile time (a solve session's small-problem path).
  template <int N>
  [[gnu::always_inline]] inline void set_q(const double* q) {
    SetQ<N>(q, N);
  }
  // Replaces M (same size and storage kind; validated like the constructor) and gives it a new matrix_id().
  void set_M(DenseMatrix M);
  void set_M(SparseMatrix M);

  // Dense problems up to this size use plain loops for M z (cheaper than Eigen's dynamic-size kernels).
  static constexpr int kSmallSize = 4;
  // out = M z + q; out is resized if needed (no allocation when it already has size()).
  void Affine(const Vector& z, Vector* out) const;
  // out = M z (no q).
  void Multiply(const Vector& z, Vector* out) const;
  // The merit function. w receives M z + q (pre-sized by the caller or resized here once). Dense m ≤ kSmallSize
  // inline (it runs after every solve, and for the paper's m = 1, 2 a call costs more than the arithmetic).
  Residual NaturalResidual(const Vector& z, Vector* w) const {
    if (is_sparse_ || size() > kSmallSize || w->size() != size()) return NaturalResidualGeneric(z, w);
    const double* a = dense_.data();
    switch (size()) {
      case 1: return SmallDenseResidual<1>(a, z.data(), w->data());
      case 2: return SmallDenseResidual<2>(a, z.data(), w->data());
      case 3: return SmallDenseResidual<3>(a, z.data(), w->data());
      default: return SmallDenseResidual<4>(a, z.data(), w->data());
    }
  }
  // NaturalResidual when the caller knows M is dense, size() == N and w->size() == N (Solver::Solve dispatches
  // on the size once, so the loops are unrolled and nothing is tested again).
  template <int N>
  Residual NaturalResidualFixed(const Vector& z, Vector* w) const {
    return SmallDenseResidual<N>(dense_.data(), z.data(), w->data());
  }
  // The absolute natural residual alone (NaturalResidualFixed(...).abs, the same operations in the same order, so
  // the same bits), for a caller that only tests it and needs neither w nor the relative and scaled residuals: a
  // backend's acceptance test of a finite z (enum's guess), about half the merit function's instructions. A NaN
  // anywhere gives kInf, as there.
  template <int N>
  double NaturalResidualAbsFixed(const double* z) const {
    const double *a = dense_.data(), *q = q_.data(), *l = l_.data(), *u = u_.data();
    double r = 0.0;
    int nan = 0;  // an int, so that the three tests below are or-ed without branches (and without clang's warning)
    for (int i = 0; i < N; ++i) {
      double sum = 0.0;
      for (int j = 0; j < N; ++j) sum += a[i + j * N] * z[j];
      const double wi = sum + q[i];
      const double above_lower = z[i] - l[i];
      const double above_upper = z[i] - u[i];
      const double e = wi > above_lower ? above_lower : (wi < above_upper ? above_upper : wi);
      nan |= static_cast<int>(std::isnan(e)) | static_cast<int>(std::isnan(wi)) | static_cast<int>(std::isnan(z[i]));
      r = std::max(r, std::abs(e));
    }
    return nan ? kInf : r;
  }
  // Scale used for the relative residual: 1 + ‖q‖∞.
  double residual_scale() const { return 1.0 + q_inf_norm_; }

  // Row scales d_i = max_j |M_ij| (a zero row: the largest |M_ij| of M; M = 0: 1), computed with M. Why this
  // scale: a positive row scaling leaves the solution set unchanged, and after it |Δ(w_i/d_i)| ≤ n‖Δz‖∞, so the
  // equilibrated residual is in units of z and invariant under row scaling and under scaling (M, q) together.
  const Vector& row_scale() const { return row_scale_; }
  const Vector& inv_row_scale() const { return inv_row_scale_; }
  // The row-equilibrated problem (D⁻¹M, D⁻¹q, l, u), computed by division so that a 1×1 problem keeps the bits of
  // q/M; a fresh matrix_id. Allocates (a copy of M). Its own row scales are 1.
  BoxMLCP Equilibrated() const;
  // For an Equilibrated() copy of `original` (same M, l, u): q ← D⁻¹ original.q(). `original` is valid, so
  // nothing is checked again; no allocation.
  // N: size() known at compile time (a solve of a dense problem up to kSmallSize rows), the loop unrolled.
  template <int N = Eigen::Dynamic>
  void AssignEquilibratedQ(const BoxMLCP& original) {
    const Eigen::Index n = N != Eigen::Dynamic ? N : q_.size();
    const double *in = original.q_.data(), *d = original.row_scale_.data();
    double* out = q_.data();
    double norm = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      out[i] = in[i] / d[i];
      norm = std::max(norm, std::abs(out[i]));
    }
    q_inf_norm_ = norm;
  }

  // Matrix-class queries (not cached; O(nnz)). Symmetric within rel_tol·max|M_ij| (ClassifySymmetry of
  // matrix_class.h, which also names the offending pair).
  bool IsSymmetric(double rel_tol = 1e-12) const;
  // Dense copy of M (allocates); for backends that only work densely on small sparse inputs.
  DenseMatrix ToDense() const;
  double MatrixInfNorm() const;  // max row sum of |M_ij|

 private:
  void Validate();
  void ValidateMatrix();
  // set_q's body, one pass with plain loops (time-steppers call it every step): x − x is 0 exactly for finite x,
  // so one test covers NaN and ±∞; the failure (message naming the index) is out of line, before q_ is touched.
  template <int N>
  [[gnu::always_inline]] inline void SetQ(const double* in, Eigen::Index size) {
    const Eigen::Index n = N != Eigen::Dynamic ? N : q_.size();
    double probe = 0.0, norm = 0.0;
    if (size == q_.size()) {
      for (Eigen::Index i = 0; i < n; ++i) {
        probe += in[i] - in[i];
        norm = std::max(norm, std::abs(in[i]));
      }
    }
    if (size != q_.size() || !(probe == 0.0)) RejectQ(in, size);
    double* out = q_.data();
    for (Eigen::Index i = 0; i < n; ++i) out[i] = in[i];
    q_inf_norm_ = norm;
  }
  [[noreturn]] void RejectQ(const double* in, Eigen::Index size) const;
  Residual NaturalResidualGeneric(const Vector& z, Vector* w) const;
  // The Residual of M z + q for dense n×n M, n = N fixed at compile time: one pass, no calls; the same
  // operations in the same order as Multiply + Affine + NaturalResidualNorm (+ ScaledNaturalResidualNorm), so
  // the same bits.
  template <int N>
  Residual SmallDenseResidual(const double* a, const double* z, double* w) const {
    const double *q = q_.data(), *l = l_.data(), *u = u_.data(), *inv_d = inv_row_scale_.data();
    double r = 0.0, rs = 0.0, z_norm = 0.0;
    int nan = 0;  // an int, so that the three tests below are or-ed without branches (and without clang's warning)
    for (int i = 0; i < N; ++i) {
      double sum = 0.0;
      for (int j = 0; j < N; ++j) sum += a[i + j * N] * z[j];
      const double wi = sum + q[i];
      w[i] = wi;
      const double above_lower = z[i] - l[i];
      const double above_upper = z[i] - u[i];
      const double e = wi > above_lower ? above_lower : (wi < above_upper ? above_upper : wi);
      const double ws = wi * inv_d[i];
      const double es = ws > above_lower ? above_lower : (ws < above_upper ? above_upper : ws);
      nan = nan || std::isnan(e) || std::isnan(wi) || std::isnan(z[i]);
      r = std::max(r, std::abs(e));
      rs = std::max(rs, std::abs(es));
      z_norm = std::max(z_norm, std::abs(z[i]));
    }
    if (nan) return {kInf, kInf, kInf};
    return {r, r / residual_scale(), rs / (1.0 + z_norm)};
  }
  void ComputeRowScales();
  [[noreturn]] static void ThrowWrongStorage(const char* accessor, const char* kind);
  static std::uint64_t NextMatrixId();

  bool is_sparse_ = false;
  std::uint64_t matrix_id_ = 0;
  DenseMatrix dense_;
  SparseMatrix sparse_;
  Vector q_, l_, u_;
  Vector row_scale_, inv_row_scale_;  // per M (ComputeRowScales)
  double q_inf_norm_ = 0.0;
  std::string name_;
};

// Nonlinear MCP: find z ∈ [l,u] with −F(z) ∈ N_[l,u](z), F supplied with its Jacobian by the caller.
// Subclass it (time-steppers do) or use FunctionMCP. Evaluate/Jacobian must not allocate when sizes are right.
class MCP {
 public:
  enum class JacobianKind { kDense, kSparse };

  MCP(Vector l, Vector u, std::string name = {});
  virtual ~MCP() = default;

  int size() const { return static_cast<int>(l_.size()); }
  const Vector& l() const { return l_; }
  const Vector& u() const { return u_; }
  const std::string& name() const { return name_; }

  // F(z) → F (pre-sized).
  virtual void Evaluate(const Vector& z, Vector* F) const = 0;
  virtual JacobianKind jacobian_kind() const { return JacobianKind::kDense; }
  // ∂F/∂z at z. Only the variant matching jacobian_kind() is called; the other throws std::logic_error.
  virtual void JacobianDense(const Vector& z, DenseMatrix* J) const;
  virtual void JacobianSparse(const Vector& z, SparseMatrix* J) const;

  // The merit function; F receives F(z). No row scale for a nonlinear F: Residual::scaled equals rel.
  Residual NaturalResidual(const Vector& z, Vector* F, double scale) const;

  // The units of the variables, c_i > 0 (McpScaledResidual): empty (the default) means 1 for every variable, as
  // for a box-MLCP. A problem that states its units (z = S y) keeps its verdict when they change.
  const Vector& variable_scale() const { return variable_scale_; }
  // InvalidInputError unless empty, or of size n with every entry finite and > 0 (naming the index).
  void set_variable_scale(Vector c);

 private:
  Vector l_, u_;
  Vector variable_scale_;
  std::string name_;
};

// The MCP's scale-free residual, the box-MLCP's Residual::scaled with M replaced by the Jacobian J = ∇F(z) at the
// answer (docs/verdict.md): row i is divided by its row scale d_i = max_j |J_ij|·c_j (McpRowScales), variables are
// measured in their units c (empty: 1), and
//   scaled = max_i |z_i − Π_[l_i,u_i](z_i − c_i·F_i/d_i)| / c_i  /  (1 + max_i |z_i| / c_i).
// With c = 1 and F = Mz + q it is exactly Residual::scaled of the box. It is unchanged by a positive scaling of the
// rows of F, and by a change of units z = S y (S positive diagonal) stated through c. +∞ on NaN.
double McpScaledResidual(const Vector& z, const Vector& F, const Vector& l, const Vector& u, const Vector& row_scale,
                         const Vector& variable_scale);
// d_i = max_j |J_ij|·c_j (c empty: 1). A zero row takes the largest d_k of the other rows (J = 0: 1), as the box's
// BoxMLCP::row_scale does; a NaN/Inf entry makes d_i = +∞ (the residual is then not trusted: McpScaledResidual
// returns +∞ for it). *d is resized if needed (no allocation when it has the size).
void McpRowScales(const DenseMatrix& J, const Vector& variable_scale, Vector* d);
void McpRowScales(const SparseMatrix& J, const Vector& variable_scale, Vector* d);

// MCP from callables, for tests and small user problems.
class FunctionMCP final : public MCP {
 public:
  using Function = std::function<void(const Vector& z, Vector* F)>;
  using DenseJacobian = std::function<void(const Vector& z, DenseMatrix* J)>;
  FunctionMCP(Vector l, Vector u, Function F, DenseJacobian J, std::string name = {});
  void Evaluate(const Vector& z, Vector* F) const override { F_(z, F); }
  void JacobianDense(const Vector& z, DenseMatrix* J) const override { J_(z, J); }

 private:
  Function F_;
  DenseJacobian J_;
};

// Shared bound checks (used by BoxMLCP, MCP and file readers): no NaN, l ≤ u, l < +∞, u > −∞.
void ValidateBounds(const char* owner, const Vector& l, const Vector& u);
// Throws if any entry of v is NaN or ±∞, naming owner, field and index.
void ValidateFinite(const char* owner, const char* field, const Vector& v);

}  // namespace smcbench

// The two problem types every backend solves: the box-constrained MLCP (Dirkse–Ferris, `eq:MLCP1`) and the
// nonlinear MCP. Each owns its validation and the one merit function by which every backend is judged.
#pragma once

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
// (1 + ‖q‖∞ for a box-MLCP). It is zero exactly at a solution.
struct Residual {
  double abs = kInf;
  double rel = kInf;
};

// ‖z − Π_[l,u](z − w)‖∞ for a given w = F(z). Returns +∞ if any entry is NaN, so a NaN never passes a test.
double NaturalResidualNorm(const Vector& z, const Vector& w, const Vector& l, const Vector& u);

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
  const DenseMatrix& dense_matrix() const;    // throws std::logic_error if sparse
  const SparseMatrix& sparse_matrix() const;  // throws std::logic_error if dense
  const Vector& q() const { return q_; }
  const Vector& l() const { return l_; }
  const Vector& u() const { return u_; }
  const std::string& name() const { return name_; }
  void set_name(std::string name) { name_ = std::move(name); }
  // Replaces q in place (time-steppers: M fixed, q changes every step). Validates size and finiteness like the
  // constructor and recomputes the relative scale; no allocation.
  void set_q(const Eigen::Ref<const Vector>& q);

  // Dense problems up to this size use plain loops for M z (cheaper than Eigen's dynamic-size kernels).
  static constexpr int kSmallSize = 4;
  // out = M z + q; out is resized if needed (no allocation when it already has size()).
  void Affine(const Vector& z, Vector* out) const;
  // out = M z (no q).
  void Multiply(const Vector& z, Vector* out) const;
  // The merit function. w receives M z + q (pre-sized by the caller or resized here once).
  Residual NaturalResidual(const Vector& z, Vector* w) const;
  // Scale used for the relative residual: 1 + ‖q‖∞.
  double residual_scale() const { return 1.0 + q_inf_norm_; }

  // Matrix-class queries (not cached; O(nnz)). Symmetric within rel_tol·max|M_ij|.
  bool IsSymmetric(double rel_tol = 1e-12) const;
  // Dense copy of M (allocates); for backends that only work densely on small sparse inputs.
  DenseMatrix ToDense() const;
  double MatrixInfNorm() const;  // max row sum of |M_ij|

 private:
  void Validate();

  bool is_sparse_ = false;
  DenseMatrix dense_;
  SparseMatrix sparse_;
  Vector q_, l_, u_;
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

  // The merit function; F receives F(z).
  Residual NaturalResidual(const Vector& z, Vector* F, double scale) const;

 private:
  Vector l_, u_;
  std::string name_;
};

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

#include "solvers/core/problem.h"

#include <atomic>
#include <cmath>
#include <sstream>

#include "solvers/core/matrix_class.h"

namespace smcbench {
namespace {

[[noreturn]] void Fail(const char* owner, const std::string& what) {
  throw InvalidInputError(std::string(owner) + ": " + what);
}

std::string At(const char* field, Eigen::Index i) {
  std::ostringstream s;
  s << field << "[" << i << "]";
  return s.str();
}

std::string At(const char* field, Eigen::Index i, Eigen::Index j) {
  std::ostringstream s;
  s << field << "(" << i << "," << j << ")";
  return s.str();
}

void CheckFiniteValue(const char* owner, double value, const std::string& where) {
  if (std::isnan(value)) Fail(owner, where + " is NaN");
  if (std::isinf(value)) Fail(owner, where + " is infinite");
}

void CheckSizes(const char* owner, Eigen::Index rows, Eigen::Index cols, const Vector& q, const Vector& l,
                const Vector& u) {
  if (rows == 0 || cols == 0) Fail(owner, "empty problem (M is 0x0); a problem needs at least one unknown");
  if (rows != cols) {
    Fail(owner, "M is " + std::to_string(rows) + "x" + std::to_string(cols) + " but must be square");
  }
  const auto check = [&](const char* field, const Vector& v) {
    if (v.size() != rows) {
      Fail(owner, std::string(field) + " has size " + std::to_string(v.size()) + " but M is " +
                      std::to_string(rows) + "x" + std::to_string(cols));
    }
  };
  check("q", q);
  check("l", l);
  check("u", u);
}

}  // namespace

void ValidateFinite(const char* owner, const char* field, const Vector& v) {
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) CheckFiniteValue(owner, v[i], At(field, i));
  }
}

void ValidateBounds(const char* owner, const Vector& l, const Vector& u) {
  if (l.size() != u.size()) {
    Fail(owner, "l has size " + std::to_string(l.size()) + " but u has size " + std::to_string(u.size()));
  }
  for (Eigen::Index i = 0; i < l.size(); ++i) {
    if (std::isnan(l[i])) Fail(owner, At("l", i) + " is NaN");
    if (std::isnan(u[i])) Fail(owner, At("u", i) + " is NaN");
    if (l[i] == kInf) Fail(owner, At("l", i) + " is +inf (no feasible point)");
    if (u[i] == -kInf) Fail(owner, At("u", i) + " is -inf (no feasible point)");
    if (l[i] > u[i]) {
      std::ostringstream s;
      s << "l[" << i << "] = " << l[i] << " > u[" << i << "] = " << u[i];
      Fail(owner, s.str());
    }
  }
}

double NaturalResidualNorm(const Vector& z, const Vector& w, const Vector& l, const Vector& u) {
  // z_i − Π_[l_i,u_i](z_i − w_i) evaluated as mid(z_i − l_i, w_i, z_i − u_i): the same number in exact
  // arithmetic, but without the cancellation z − (z − w) that rounds a large-|z| residual to 0 in floating point
  // (an interior z ≈ 1e16 with w = 1 would otherwise "pass"). With infinite bounds, z − l = +∞ / z − u = −∞.
  double r = 0.0;
  for (Eigen::Index i = 0; i < z.size(); ++i) {
    const double above_lower = z[i] - l[i];
    const double above_upper = z[i] - u[i];
    const double wi = w[i];
    const double e = wi > above_lower ? above_lower : (wi < above_upper ? above_upper : wi);
    if (std::isnan(e) || std::isnan(wi) || std::isnan(z[i])) return kInf;
    r = std::max(r, std::abs(e));
  }
  return r;
}

double ScaledNaturalResidualNorm(const Vector& z, const Vector& w, const Vector& l, const Vector& u,
                                 const Vector& inv_row_scale) {
  double r = 0.0, z_norm = 0.0;
  for (Eigen::Index i = 0; i < z.size(); ++i) {
    const double above_lower = z[i] - l[i];
    const double above_upper = z[i] - u[i];
    const double wi = w[i] * inv_row_scale[i];
    const double e = wi > above_lower ? above_lower : (wi < above_upper ? above_upper : wi);
    if (std::isnan(e) || std::isnan(wi) || std::isnan(z[i])) return kInf;
    r = std::max(r, std::abs(e));
    z_norm = std::max(z_norm, std::abs(z[i]));
  }
  return r / (1.0 + z_norm);
}

void ProjectZeroOntoBox(const Vector& l, const Vector& u, Vector* z) {
  z->resize(l.size());
  for (Eigen::Index i = 0; i < l.size(); ++i) (*z)[i] = std::min(std::max(0.0, l[i]), u[i]);
}

std::uint64_t BoxMLCP::NextMatrixId() {
  static std::atomic<std::uint64_t> next{1};  // 0 is never an id: caches may use it as "empty"
  return next.fetch_add(1, std::memory_order_relaxed);
}

void BoxMLCP::ThrowWrongStorage(const char* accessor, const char* kind) {
  throw std::logic_error(std::string("BoxMLCP::") + accessor + "() called on a " + kind + " problem");
}

BoxMLCP::BoxMLCP(DenseMatrix M, Vector q, Vector l, Vector u, std::string name)
    : is_sparse_(false), dense_(std::move(M)), q_(std::move(q)), l_(std::move(l)), u_(std::move(u)),
      name_(std::move(name)) {
  Validate();
}

BoxMLCP::BoxMLCP(SparseMatrix M, Vector q, Vector l, Vector u, std::string name)
    : is_sparse_(true), sparse_(std::move(M)), q_(std::move(q)), l_(std::move(l)), u_(std::move(u)),
      name_(std::move(name)) {
  sparse_.makeCompressed();
  Validate();
}

BoxMLCP BoxMLCP::LCP(DenseMatrix M, Vector q, std::string name) {
  const Eigen::Index n = q.size();
  return BoxMLCP(std::move(M), std::move(q), Vector::Zero(n), Vector::Constant(n, kInf), std::move(name));
}

BoxMLCP BoxMLCP::Relay(DenseMatrix M, Vector q, double lower, double upper, std::string name) {
  const Eigen::Index n = q.size();
  return BoxMLCP(std::move(M), std::move(q), Vector::Constant(n, lower), Vector::Constant(n, upper),
                 std::move(name));
}

void BoxMLCP::Validate() {
  ValidateMatrix();
  ValidateFinite("BoxMLCP", "q", q_);
  ValidateBounds("BoxMLCP", l_, u_);
  q_inf_norm_ = q_.size() ? q_.cwiseAbs().maxCoeff() : 0.0;
}

void BoxMLCP::ComputeRowScales() {
  const Eigen::Index n = q_.size();
  row_scale_.setZero(n);
  if (is_sparse_) {
    for (int k = 0; k < sparse_.outerSize(); ++k) {
      for (SparseMatrix::InnerIterator it(sparse_, k); it; ++it) {
        row_scale_[it.row()] = std::max(row_scale_[it.row()], std::abs(it.value()));
      }
    }
  } else {
    row_scale_ = dense_.cwiseAbs().rowwise().maxCoeff();
  }
  // A zero row takes the matrix's scale, so scaling (M, q) together still leaves the equilibrated problem alone.
  const double matrix_scale = n ? row_scale_.maxCoeff() : 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!(row_scale_[i] > 0.0)) row_scale_[i] = matrix_scale > 0.0 ? matrix_scale : 1.0;
  }
  inv_row_scale_ = row_scale_.cwiseInverse();
}

BoxMLCP BoxMLCP::Equilibrated() const {
  const Vector scaled_q = q_.cwiseQuotient(row_scale_);
  if (is_sparse_) {
    SparseMatrix m = sparse_;
    for (int k = 0; k < m.outerSize(); ++k) {
      for (SparseMatrix::InnerIterator it(m, k); it; ++it) it.valueRef() /= row_scale_[it.row()];
    }
    return BoxMLCP(std::move(m), scaled_q, l_, u_, name_);
  }
  DenseMatrix m = dense_;
  for (Eigen::Index j = 0; j < m.cols(); ++j) m.col(j).array() /= row_scale_.array();
  return BoxMLCP(std::move(m), scaled_q, l_, u_, name_);
}

void BoxMLCP::ValidateMatrix() {
  constexpr const char* kOwner = "BoxMLCP";
  matrix_id_ = NextMatrixId();
  if (is_sparse_) {
    CheckSizes(kOwner, sparse_.rows(), sparse_.cols(), q_, l_, u_);
    for (int k = 0; k < sparse_.outerSize(); ++k) {
      for (SparseMatrix::InnerIterator it(sparse_, k); it; ++it) {
        // The message is only formatted on failure: validation runs on every construction.
        if (!std::isfinite(it.value())) CheckFiniteValue(kOwner, it.value(), At("M", it.row(), it.col()));
      }
    }
  } else {
    CheckSizes(kOwner, dense_.rows(), dense_.cols(), q_, l_, u_);
    for (Eigen::Index j = 0; j < dense_.cols(); ++j) {
      for (Eigen::Index i = 0; i < dense_.rows(); ++i) {
        if (!std::isfinite(dense_(i, j))) CheckFiniteValue(kOwner, dense_(i, j), At("M", i, j));
      }
    }
  }
  ComputeRowScales();
}

void BoxMLCP::RejectQ(const double* in, Eigen::Index size) const {
  if (size != q_.size()) {
    Fail("BoxMLCP", "set_q: q has size " + std::to_string(size) + " but the problem has " +
                        std::to_string(q_.size()) + " unknowns");
  }
  for (Eigen::Index i = 0; i < size; ++i) {
    if (!std::isfinite(in[i])) CheckFiniteValue("BoxMLCP", in[i], At("q", i));
  }
  throw std::logic_error("BoxMLCP::RejectQ: q is valid");  // unreachable: set_q calls it only for a bad q
}

void BoxMLCP::set_M(DenseMatrix M) {
  if (is_sparse_) Fail("BoxMLCP", "set_M: the problem stores M sparse; pass a sparse matrix");
  if (M.rows() != size() || M.cols() != size()) {
    Fail("BoxMLCP", "set_M: M is " + std::to_string(M.rows()) + "x" + std::to_string(M.cols()) +
                        " but the problem has " + std::to_string(size()) + " unknowns");
  }
  DenseMatrix previous = std::move(dense_);
  dense_ = std::move(M);
  try {
    ValidateMatrix();
  } catch (...) {
    dense_ = std::move(previous);  // a rejected M is never kept (its id stays fresh: harmless)
    throw;
  }
}

void BoxMLCP::set_M(SparseMatrix M) {
  if (!is_sparse_) Fail("BoxMLCP", "set_M: the problem stores M dense; pass a dense matrix");
  if (M.rows() != size() || M.cols() != size()) {
    Fail("BoxMLCP", "set_M: M is " + std::to_string(M.rows()) + "x" + std::to_string(M.cols()) +
                        " but the problem has " + std::to_string(size()) + " unknowns");
  }
  SparseMatrix previous = std::move(sparse_);
  sparse_ = std::move(M);
  sparse_.makeCompressed();
  try {
    ValidateMatrix();
  } catch (...) {
    sparse_ = std::move(previous);
    throw;
  }
}

void BoxMLCP::Multiply(const Vector& z, Vector* out) const {
  if (is_sparse_) {
    out->noalias() = sparse_ * z;
    return;
  }
  const Eigen::Index n = dense_.rows();
  if (n <= kSmallSize) {
    if (out->size() != n) out->resize(n);  // like Eigen's assignment below; no allocation once sized
    // The paper's one-step problems have m = 1, 2: Eigen's dynamic-size product costs more than the arithmetic.
    const double* a = dense_.data();
    for (Eigen::Index i = 0; i < n; ++i) {
      double sum = 0.0;
      for (Eigen::Index j = 0; j < n; ++j) sum += a[i + j * n] * z[j];
      (*out)[i] = sum;
    }
    return;
  }
  out->noalias() = dense_ * z;
}

void BoxMLCP::Affine(const Vector& z, Vector* out) const {
  Multiply(z, out);
  *out += q_;
}

Residual BoxMLCP::NaturalResidualGeneric(const Vector& z, Vector* w) const {
  if (w->size() != size()) w->resize(size());
  Affine(z, w);
  Residual r;
  r.abs = NaturalResidualNorm(z, *w, l_, u_);
  r.rel = r.abs / residual_scale();
  r.scaled = ScaledNaturalResidualNorm(z, *w, l_, u_, inv_row_scale_);
  return r;
}

bool BoxMLCP::IsSymmetric(double rel_tol) const {
  const SymmetryOptions options{rel_tol};
  const SymmetryResult r = is_sparse_ ? ClassifySymmetry(sparse_, options) : ClassifySymmetry(dense_, options);
  return r.answer == MatrixClassAnswer::kYes;
}

DenseMatrix BoxMLCP::ToDense() const { return is_sparse_ ? DenseMatrix(sparse_) : dense_; }

double BoxMLCP::MatrixInfNorm() const {
  if (is_sparse_) {
    Vector row_sums = Vector::Zero(size());
    for (int k = 0; k < sparse_.outerSize(); ++k) {
      for (SparseMatrix::InnerIterator it(sparse_, k); it; ++it) row_sums[it.row()] += std::abs(it.value());
    }
    return row_sums.maxCoeff();
  }
  return dense_.cwiseAbs().rowwise().sum().maxCoeff();
}

MCP::MCP(Vector l, Vector u, std::string name) : l_(std::move(l)), u_(std::move(u)), name_(std::move(name)) {
  if (l_.size() == 0) throw InvalidInputError("MCP: empty problem (n = 0); a problem needs at least one unknown");
  ValidateBounds("MCP", l_, u_);
}

void MCP::JacobianDense(const Vector&, DenseMatrix*) const {
  throw std::logic_error("MCP " + name_ + ": no dense Jacobian provided");
}

void MCP::JacobianSparse(const Vector&, SparseMatrix*) const {
  throw std::logic_error("MCP " + name_ + ": no sparse Jacobian provided");
}

Residual MCP::NaturalResidual(const Vector& z, Vector* F, double scale) const {
  if (F->size() != size()) F->resize(size());
  Evaluate(z, F);
  Residual r;
  r.abs = NaturalResidualNorm(z, *F, l_, u_);
  r.rel = r.abs / scale;
  r.scaled = r.rel;
  return r;
}

void MCP::set_variable_scale(Vector c) {
  if (c.size() != 0 && c.size() != size()) {
    throw InvalidInputError("MCP: variable_scale has size " + std::to_string(c.size()) + " but the problem has " +
                            std::to_string(size()) + " unknowns (give n positive units, or none)");
  }
  for (Eigen::Index i = 0; i < c.size(); ++i) {
    if (!std::isfinite(c[i]) || !(c[i] > 0.0)) {
      std::ostringstream s;
      s << "MCP: variable_scale[" << i << "] = " << c[i] << " must be finite and > 0 (the unit of z_" << i << ")";
      throw InvalidInputError(s.str());
    }
  }
  variable_scale_ = std::move(c);
}

double McpScaledResidual(const Vector& z, const Vector& F, const Vector& l, const Vector& u, const Vector& row_scale,
                         const Vector& variable_scale) {
  const Eigen::Index n = z.size();
  const bool units = variable_scale.size() == n;
  double r = 0.0, z_norm = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double c = units ? variable_scale[i] : 1.0;
    const double d = row_scale[i];
    if (!(d < kInf) || std::isnan(F[i]) || std::isnan(z[i])) return kInf;
    const double step = c * (F[i] / d);
    const double projected = std::min(std::max(z[i] - step, l[i]), u[i]);
    r = std::max(r, std::abs(z[i] - projected) / c);
    z_norm = std::max(z_norm, std::abs(z[i]) / c);
  }
  return std::isnan(r) ? kInf : r / (1.0 + z_norm);
}

namespace {
// The shared tail of McpRowScales: zero rows take the largest other row scale (all zero: 1).
void FillZeroRowScales(Vector* d) {
  double largest = 0.0;
  for (Eigen::Index i = 0; i < d->size(); ++i) {
    if ((*d)[i] < kInf) largest = std::max(largest, (*d)[i]);
  }
  if (largest == 0.0) largest = 1.0;
  for (Eigen::Index i = 0; i < d->size(); ++i) {
    if ((*d)[i] == 0.0) (*d)[i] = largest;
  }
}
}  // namespace

void McpRowScales(const DenseMatrix& J, const Vector& variable_scale, Vector* d) {
  const Eigen::Index n = J.rows();
  const bool units = variable_scale.size() == J.cols();
  if (d->size() != n) d->resize(n);
  d->setZero();
  for (Eigen::Index j = 0; j < J.cols(); ++j) {
    const double c = units ? variable_scale[j] : 1.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double a = std::abs(J(i, j)) * c;
      (*d)[i] = std::isfinite(a) ? std::max((*d)[i], a) : kInf;
    }
  }
  FillZeroRowScales(d);
}

void McpRowScales(const SparseMatrix& J, const Vector& variable_scale, Vector* d) {
  const Eigen::Index n = J.rows();
  const bool units = variable_scale.size() == J.cols();
  if (d->size() != n) d->resize(n);
  d->setZero();
  for (Eigen::Index j = 0; j < J.outerSize(); ++j) {
    const double c = units ? variable_scale[j] : 1.0;
    for (SparseMatrix::InnerIterator it(J, j); it; ++it) {
      const double a = std::abs(it.value()) * c;
      double& di = (*d)[it.row()];
      di = std::isfinite(a) ? std::max(di, a) : kInf;
    }
  }
  FillZeroRowScales(d);
}

FunctionMCP::FunctionMCP(Vector l, Vector u, Function F, DenseJacobian J, std::string name)
    : MCP(std::move(l), std::move(u), std::move(name)), F_(std::move(F)), J_(std::move(J)) {
  if (!F_) throw InvalidInputError("FunctionMCP: F is empty");
  if (!J_) throw InvalidInputError("FunctionMCP: Jacobian is empty");
}

}  // namespace smcbench

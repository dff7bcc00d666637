#include "solvers/siconos/mcp_standard_form.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace smcbench {

// The variables' order and bounds, computed before the MCP base is constructed (it takes the bounds).
struct McpStandardForm::Layout {
  int num_equations = 0;
  std::vector<int> row_of, var_of, multiplier_of;
  std::vector<double> sign;
  Vector base, l, u;
};

McpStandardForm::Layout McpStandardForm::MakeLayout(const MCP& original) {
  McpStandardForm::Layout out;
  const int n = original.size();
  const Vector& l = original.l();
  const Vector& u = original.u();
  out.var_of.assign(n, -1);
  out.multiplier_of.assign(n, -1);
  out.base = Vector::Zero(n);
  // Free rows first (the equations), then the sign-constrained rows in their order, then the multipliers.
  for (int pass = 0; pass < 2; ++pass) {
    for (int i = 0; i < n; ++i) {
      const bool lower = std::isfinite(l[i]), upper = std::isfinite(u[i]);
      if (l[i] == u[i]) {
        out.base[i] = l[i];
        continue;
      }
      const bool free = !lower && !upper;
      if (free != (pass == 0)) continue;
      out.var_of[i] = static_cast<int>(out.row_of.size());
      out.row_of.push_back(i);
      out.sign.push_back(!lower && upper ? -1.0 : 1.0);
      out.base[i] = lower ? l[i] : (upper ? u[i] : 0.0);
    }
    if (pass == 0) out.num_equations = static_cast<int>(out.row_of.size());
  }
  int count = static_cast<int>(out.row_of.size());
  for (int i = 0; i < n; ++i) {
    if (l[i] < u[i] && std::isfinite(l[i]) && std::isfinite(u[i])) out.multiplier_of[i] = count++;
  }
  out.l = Vector::Zero(count);
  out.u = Vector::Constant(count, kInf);
  out.l.head(out.num_equations).setConstant(-kInf);
  return out;
}

McpStandardForm::McpStandardForm(const MCP& original) : McpStandardForm(original, MakeLayout(original)) {}

McpStandardForm::McpStandardForm(const MCP& original, const Layout& layout)
    : MCP(layout.l, layout.u, original.name()),
      original_(original),
      num_equations_(layout.num_equations),
      row_of_(layout.row_of),
      var_of_(layout.var_of),
      multiplier_of_(layout.multiplier_of),
      sign_(layout.sign),
      base_(layout.base),
      primaries_(static_cast<int>(layout.row_of.size())),
      z_(original.size()),
      F_(original.size()) {}

void McpStandardForm::ToOriginal(const Vector& x, Vector* z) const {
  const int n = original_.size();
  if (z->size() != n) z->resize(n);
  for (int i = 0; i < n; ++i) {
    const int a = var_of_[i];
    (*z)[i] = a < 0 ? base_[i] : base_[i] + sign_[a] * x[a];
  }
}

void McpStandardForm::FromOriginal(const Vector& z, Vector* x) const {
  if (x->size() != size()) x->resize(size());
  original_.Evaluate(z, &F_);
  for (int a = 0; a < primaries_; ++a) {
    const int i = row_of_[a];
    (*x)[a] = sign_[a] * (z[i] - base_[i]);
  }
  for (int i = 0; i < original_.size(); ++i) {
    if (multiplier_of_[i] >= 0) (*x)[multiplier_of_[i]] = std::max(0.0, -F_[i]);
  }
}

void McpStandardForm::Evaluate(const Vector& x, Vector* F) const {
  ToOriginal(x, &z_);
  original_.Evaluate(z_, &F_);
  for (int a = 0; a < primaries_; ++a) (*F)[a] = sign_[a] * F_[row_of_[a]];
  for (int i = 0; i < original_.size(); ++i) {
    const int k = multiplier_of_[i];
    if (k < 0) continue;
    (*F)[var_of_[i]] += x[k];
    (*F)[k] = (original_.u()[i] - original_.l()[i]) - x[var_of_[i]];
  }
}

void McpStandardForm::JacobianDense(const Vector& x, DenseMatrix* J) const {
  const int n = original_.size(), N = size();
  if (J->rows() != N || J->cols() != N) J->resize(N, N);
  ToOriginal(x, &z_);
  jacobian_error_.clear();
  Eigen::Index rows = n, cols = n;
  if (original_.jacobian_kind() == MCP::JacobianKind::kSparse) {
    original_.JacobianSparse(z_, &Js_);
    rows = Js_.rows();
    cols = Js_.cols();
    if (rows == n && cols == n) J_ = DenseMatrix(Js_);
  } else {
    if (J_.rows() != n || J_.cols() != n) J_.resize(n, n);
    original_.JacobianDense(z_, &J_);
    rows = J_.rows();
    cols = J_.cols();
  }
  if (rows != n || cols != n) {
    std::ostringstream s;
    s << "the MCP Jacobian has the wrong size: " << rows << "x" << cols << ", expected " << n << "x" << n;
    jacobian_error_ = s.str();
    J->setConstant(kNaN);
    return;
  }
  J->setZero();
  for (int b = 0; b < primaries_; ++b) {
    for (int a = 0; a < primaries_; ++a) (*J)(a, b) = sign_[a] * J_(row_of_[a], row_of_[b]) * sign_[b];
  }
  for (int i = 0; i < n; ++i) {
    const int k = multiplier_of_[i];
    if (k < 0) continue;
    (*J)(var_of_[i], k) = 1.0;
    (*J)(k, var_of_[i]) = -1.0;
  }
}

}  // namespace smcbench

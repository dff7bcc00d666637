// Box-MLCP ↔ Siconos' relay and standard-MLCP forms (see standard_form.h for the rewriting and why it is exact).
#include "solvers/siconos/standard_form.h"

#include <cmath>
#include <stdexcept>

namespace smcbench {
namespace {

StandardForm::RowKind Classify(double l, double u) {
  if (l == u) return StandardForm::RowKind::kFixed;
  const bool lower = std::isfinite(l), upper = std::isfinite(u);
  if (lower && upper) return StandardForm::RowKind::kBox;
  if (lower) return StandardForm::RowKind::kLower;
  if (upper) return StandardForm::RowKind::kUpper;
  return StandardForm::RowKind::kFree;
}

}  // namespace

std::string_view ToString(StandardForm::RowKind kind) {
  switch (kind) {
    case StandardForm::RowKind::kFixed: return "fixed";
    case StandardForm::RowKind::kFree: return "free";
    case StandardForm::RowKind::kLower: return "lower";
    case StandardForm::RowKind::kUpper: return "upper";
    case StandardForm::RowKind::kBox: return "box";
  }
  return "?";
}

StandardForm::RowCounts StandardForm::Count(const Vector& l, const Vector& u) {
  RowCounts c;
  for (Eigen::Index i = 0; i < l.size(); ++i) {
    switch (Classify(l[i], u[i])) {
      case RowKind::kFixed: ++c.fixed; break;
      case RowKind::kFree: ++c.free; break;
      case RowKind::kLower: ++c.lower; break;
      case RowKind::kUpper: ++c.upper; break;
      case RowKind::kBox: ++c.box; break;
    }
  }
  return c;
}

void StandardForm::Build(const BoxMLCP& problem, Kind kind) {
  const int n = problem.size();
  const Vector& l = problem.l();
  const Vector& u = problem.u();
  const DenseMatrix& M = problem.dense_matrix();
  kind_ = kind;
  var_of_.assign(n, -1);
  multiplier_of_.assign(n, -1);
  row_of_.clear();
  sign_.clear();
  if (base_.size() != n) base_.resize(n);

  // Primary variables: free rows first (mixed form), then the sign-constrained rows in their original order.
  if (kind == Kind::kMixed) {
    for (int i = 0; i < n; ++i) {
      if (Classify(l[i], u[i]) != RowKind::kFree) continue;
      var_of_[i] = static_cast<int>(row_of_.size());
      row_of_.push_back(i);
      sign_.push_back(1.0);
      base_[i] = 0.0;
    }
  }
  num_equalities_ = static_cast<int>(row_of_.size());
  int num_box = 0;
  for (int i = 0; i < n; ++i) {
    const RowKind k = Classify(l[i], u[i]);
    if (k == RowKind::kFixed) {
      base_[i] = l[i];
      continue;
    }
    if (k == RowKind::kFree && kind == Kind::kMixed) continue;  // already placed
    if (kind == Kind::kBox && k != RowKind::kBox) {
      throw std::logic_error("StandardForm: box form needs finite bounds, row " + std::to_string(i) + " is " +
                             std::string(ToString(k)));
    }
    var_of_[i] = static_cast<int>(row_of_.size());
    row_of_.push_back(i);
    const bool upper = k == RowKind::kUpper;
    sign_.push_back(upper ? -1.0 : 1.0);
    base_[i] = kind == Kind::kBox ? 0.0 : (upper ? u[i] : l[i]);
    if (k == RowKind::kBox && kind == Kind::kMixed) ++num_box;
  }
  const int p = static_cast<int>(row_of_.size());
  const int N = p + num_box;

  // q̂ = q + M z̄ carries the fixed rows (and the shifted bounds) into the remaining ones.
  if (w_.size() != n) w_.resize(n);
  w_.noalias() = M * base_;
  w_ += problem.q();

  if (M_.rows() != N || M_.cols() != N) M_.resize(N, N);
  if (q_.size() != N) q_.resize(N);
  M_.setZero();
  for (int b = 0; b < p; ++b) {
    const int rb = row_of_[b];
    for (int a = 0; a < p; ++a) M_(a, b) = sign_[a] * sign_[b] * M(row_of_[a], rb);
  }
  for (int a = 0; a < p; ++a) q_[a] = sign_[a] * w_[row_of_[a]];
  int next = p;
  if (kind == Kind::kMixed) {
    for (int i = 0; i < n; ++i) {
      if (var_of_[i] < 0 || Classify(l[i], u[i]) != RowKind::kBox) continue;
      multiplier_of_[i] = next;
      M_(var_of_[i], next) = 1.0;
      M_(next, var_of_[i]) = -1.0;
      q_[next] = u[i] - l[i];
      ++next;
    }
    lower_.resize(0);
    upper_.resize(0);
  } else {
    if (lower_.size() != N) lower_.resize(N);
    if (upper_.size() != N) upper_.resize(N);
    for (int a = 0; a < p; ++a) {
      lower_[a] = l[row_of_[a]];
      upper_[a] = u[row_of_[a]];
    }
  }
}

void StandardForm::FromBox(const BoxMLCP& problem, const Vector& z, Vector* x) {
  const int N = size();
  if (x->size() != N) x->resize(N);
  const int p = static_cast<int>(row_of_.size());
  for (int a = 0; a < p; ++a) (*x)[a] = sign_[a] * (z[row_of_[a]] - base_[row_of_[a]]);
  if (N == p) return;
  // Box multipliers: y = max(0, −w), the part of w = Mz + q that the upper bound has to absorb.
  problem.Affine(z, &w_);
  for (int i = 0; i < problem.size(); ++i) {
    if (multiplier_of_[i] >= 0) (*x)[multiplier_of_[i]] = std::max(0.0, -w_[i]);
  }
}

void StandardForm::ToBox(const BoxMLCP& problem, const Vector& x, Vector* z) const {
  const int n = problem.size();
  if (z->size() != n) z->resize(n);
  for (int i = 0; i < n; ++i) {
    const int a = var_of_[i];
    (*z)[i] = a < 0 ? problem.l()[i] : base_[i] + sign_[a] * x[a];
  }
}

}  // namespace smcbench

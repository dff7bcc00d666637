#include "solvers/avi/avi_reduction.h"

#include <string>
#include <utility>
#include <vector>

namespace smcbench {

std::string_view ToString(AviReductionScaling value) {
  switch (value) {
    case AviReductionScaling::kAsStated: return "as stated";
    case AviReductionScaling::kNormalized: return "normalized";
  }
  return "?";
}

AviReduction ReduceToBoxMlcp(const AffineVI& avi, AviReductionScaling scaling) {
  const int n = avi.size(), m = avi.inequality_count(), p = avi.equality_count(), total = n + m + p;
  double sigma = 1.0;
  Vector inequality_scale = Vector::Ones(m), equality_scale = Vector::Ones(p);
  if (scaling == AviReductionScaling::kNormalized) {
    const double m_max = avi.M().cwiseAbs().maxCoeff();
    const double q_max = avi.q().cwiseAbs().maxCoeff();
    sigma = m_max > 0.0 ? m_max : (q_max > 0.0 ? q_max : 1.0);
    for (int i = 0; i < m; ++i) inequality_scale[i] = avi.H().row(i).cwiseAbs().maxCoeff();
    for (int j = 0; j < p; ++j) equality_scale[j] = avi.E().row(j).cwiseAbs().maxCoeff();
  }
  DenseMatrix M = DenseMatrix::Zero(total, total);
  Vector q(total), l(total), u = Vector::Constant(total, kInf);
  // Divisions, not multiplications by reciprocals: a scale that is a power of two then changes no bit.
  M.topLeftCorner(n, n) = avi.M() / sigma;
  q.head(n) = avi.q() / sigma;
  l.head(n).setConstant(-kInf);
  for (int i = 0; i < m; ++i) {
    const Vector row = avi.H().row(i).transpose() / inequality_scale[i];
    M.block(n + i, 0, 1, n) = row.transpose();
    M.block(0, n + i, n, 1) = -row;
    q[n + i] = -avi.K()[i] / inequality_scale[i];
    l[n + i] = 0.0;
  }
  for (int j = 0; j < p; ++j) {
    const Vector row = avi.E().row(j).transpose() / equality_scale[j];
    M.block(n + m + j, 0, 1, n) = row.transpose();
    M.block(0, n + m + j, n, 1) = -row;
    q[n + m + j] = -avi.f()[j] / equality_scale[j];
    l[n + m + j] = -kInf;
  }
  return AviReduction{BoxMLCP(std::move(M), std::move(q), std::move(l), std::move(u),
                              avi.name().empty() ? std::string() : avi.name() + "/reduced"),
                      scaling, n, m, p, sigma, std::move(inequality_scale), std::move(equality_scale)};
}

AviSolution SplitReducedSolution(const AviReduction& reduction, const Vector& z) {
  const int n = reduction.n, m = reduction.m, p = reduction.p;
  if (z.size() != n + m + p) {
    throw InvalidInputError("AviReduction: z has size " + std::to_string(z.size()) + " but the reduced problem has " +
                            std::to_string(n + m + p) + " rows (n + m + p)");
  }
  AviSolution out;
  out.lambda = z.head(n);
  out.mu = reduction.sigma * z.segment(n, m).cwiseQuotient(reduction.inequality_scale);
  out.nu = reduction.sigma * z.tail(p).cwiseQuotient(reduction.equality_scale);
  return out;
}

Vector JoinReducedSolution(const AviReduction& reduction, const AviSolution& solution) {
  const int n = reduction.n, m = reduction.m, p = reduction.p;
  const auto check = [](const char* field, const Vector& v, int size, bool may_be_empty) {
    if (v.size() == size || (may_be_empty && v.size() == 0)) return;
    throw InvalidInputError("AviSolution: " + std::string(field) + " has size " + std::to_string(v.size()) +
                            " but the AVI has " + std::to_string(size));
  };
  check("lambda", solution.lambda, n, false);
  check("mu", solution.mu, m, true);
  check("nu", solution.nu, p, true);
  Vector z = Vector::Zero(n + m + p);
  z.head(n) = solution.lambda;
  if (solution.mu.size() > 0) z.segment(n, m) = solution.mu.cwiseProduct(reduction.inequality_scale) / reduction.sigma;
  if (solution.nu.size() > 0) z.tail(p) = solution.nu.cwiseProduct(reduction.equality_scale) / reduction.sigma;
  return z;
}

AffineVI AviFromBox(const BoxMLCP& box) {
  if (box.is_sparse()) throw InvalidInputError("AviFromBox: M is sparse; the AVI type stores dense matrices");
  const int n = box.size();
  std::vector<std::pair<int, double>> rows;  // (signed index + 1, right-hand side): +(i+1) lower, −(i+1) upper
  std::vector<std::pair<int, double>> equalities;
  for (int i = 0; i < n; ++i) {
    const double lo = box.l()[i], hi = box.u()[i];
    if (lo == hi) {
      equalities.emplace_back(i, lo);
      continue;
    }
    if (lo > -kInf) rows.emplace_back(i + 1, lo);
    if (hi < kInf) rows.emplace_back(-(i + 1), -hi);
  }
  DenseMatrix H = DenseMatrix::Zero(static_cast<Eigen::Index>(rows.size()), n);
  Vector K(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const int signed_index = rows[r].first;
    const auto row = static_cast<Eigen::Index>(r);
    H(row, (signed_index > 0 ? signed_index : -signed_index) - 1) = signed_index > 0 ? 1.0 : -1.0;
    K[row] = rows[r].second;
  }
  DenseMatrix E = DenseMatrix::Zero(static_cast<Eigen::Index>(equalities.size()), n);
  Vector f(static_cast<Eigen::Index>(equalities.size()));
  for (std::size_t r = 0; r < equalities.size(); ++r) {
    E(static_cast<Eigen::Index>(r), equalities[r].first) = 1.0;
    f[static_cast<Eigen::Index>(r)] = equalities[r].second;
  }
  return AffineVI(box.dense_matrix(), box.q(), std::move(H), std::move(K), std::move(E), std::move(f), box.name());
}

}  // namespace smcbench

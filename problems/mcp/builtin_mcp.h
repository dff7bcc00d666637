// The CRTP base of the built-in MCPs: a problem writes F and the entries of its Jacobian ONCE, as templates on the
// scalar type, and gets Evaluate / JacobianDense / JacobianSparse in double and EvaluateQuad / JacobianQuad in
// __float128 from them, so the reference certifier refines exactly the function the backends solve.
#pragma once

#include <string>
#include <vector>
#include <utility>

#include "solvers/core/extended_precision_mcp.h"

namespace smcbench {

// Problem must provide
//   template <class T> void Function(const T* z, T* F) const;                  // every F_i written
//   template <class T, class Add> void Jacobian(const T* z, Add&& add) const;  // add(i, j, ∂F_i/∂z_j)
// Jacobian emits the same (i, j) pattern at every z (zeros included) so a sparse J keeps its pattern; an entry
// emitted twice is summed.
template <class Problem>
class BuiltinMcp : public ExtendedPrecisionMCP {
 public:
  BuiltinMcp(Vector l, Vector u, std::string name, JacobianKind kind = JacobianKind::kDense,
             SolutionSetProperty property = SolutionSetProperty::kNone)
      : ExtendedPrecisionMCP(std::move(l), std::move(u), std::move(name)), kind_(kind), property_(property) {}

  void Evaluate(const Vector& z, Vector* F) const override { self().Function(z.data(), F->data()); }
  JacobianKind jacobian_kind() const override { return kind_; }
  // Both storages work whatever jacobian_kind() says (tests compare them); backends call the advertised one.
  void JacobianDense(const Vector& z, DenseMatrix* J) const override {
    const int n = size();
    if (J->rows() != n || J->cols() != n) J->resize(n, n);
    J->setZero();
    self().Jacobian(z.data(), [J](int i, int j, double v) { (*J)(i, j) += v; });
  }
  // Same pattern as last time: values rewritten in place (no allocation); otherwise built from triplets once.
  void JacobianSparse(const Vector& z, SparseMatrix* J) const override {
    const int n = size();
    if (J->rows() == n && J->cols() == n && J->nonZeros() > 0 && J->isCompressed()) {
      J->coeffs().setZero();
      self().Jacobian(z.data(), [J](int i, int j, double v) { J->coeffRef(i, j) += v; });
      return;
    }
    std::vector<Eigen::Triplet<double, int>> entries;
    self().Jacobian(z.data(), [&entries](int i, int j, double v) { entries.emplace_back(i, j, v); });
    J->resize(n, n);
    J->setFromTriplets(entries.begin(), entries.end());
    J->makeCompressed();
  }
  void EvaluateQuad(const Quad* z, Quad* F) const override { self().Function(z, F); }
  void JacobianQuad(const Quad* z, Quad* J) const override {
    const int n = size();
    for (int k = 0; k < n * n; ++k) J[k] = 0;
    self().Jacobian(z, [J, n](int i, int j, Quad v) { J[i + j * n] += v; });
  }
  void JacobianQuadEntries(const Quad* z, std::vector<QuadEntry>* entries) const override {
    entries->clear();
    self().Jacobian(z, [entries](int i, int j, Quad v) { entries->push_back({i, j, v}); });
  }
  SolutionSetProperty solution_set_property() const override { return property_; }

 private:
  const Problem& self() const { return static_cast<const Problem&>(*this); }

  JacobianKind kind_;
  SolutionSetProperty property_;
};

}  // namespace smcbench

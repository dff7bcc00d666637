// The MCP verdict's invariance, over every registered backend that solves nonlinear MCPs (asked of the registry:
// info().mcp): a positive scaling of F's rows leaves an MCP's solution set unchanged, and so does a change of units
// z = S y stated through MCP::variable_scale. So every backend of ours must reach the same verdict (JudgeMCP against
// the planted, unique solution) on the transformed problem as on the problem as given: solved or not, and when
// solved, within the forward-error allowance in the variables' units; no backend, external codes included, may give
// a wrong answer on any copy. Verdicts are compared, not bits.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "solvers/core/verdict.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

constexpr double kTol = 1e-10;

// Strongly monotone F(z) = A z + κ∘z³ + b (A's symmetric part positive definite, κ ≥ 0), so the MCP has exactly one
// solution, planted as z*; seen through row scales r and units s: G(y) = r∘F(s∘y) on [l/s, u/s], variable_scale
// 1/s (none when s = 1), solution y* = z*/s.
class PlantedMcp final : public MCP {
 public:
  PlantedMcp(DenseMatrix A, Vector kappa, Vector b, const Vector& l, const Vector& u, Vector r, Vector s,
             bool sparse, std::string name)
      : MCP(l.cwiseQuotient(s), u.cwiseQuotient(s), std::move(name)), A_(std::move(A)), kappa_(std::move(kappa)),
        b_(std::move(b)), r_(std::move(r)), s_(std::move(s)), sparse_(sparse), z_(s_.size()) {}
  JacobianKind jacobian_kind() const override { return sparse_ ? JacobianKind::kSparse : JacobianKind::kDense; }
  void Evaluate(const Vector& y, Vector* G) const override {
    z_ = s_.cwiseProduct(y);
    G->noalias() = A_ * z_;
    G->array() += kappa_.array() * z_.array().cube() + b_.array();
    G->array() *= r_.array();
  }
  void JacobianDense(const Vector& y, DenseMatrix* J) const override {
    z_ = s_.cwiseProduct(y);
    *J = A_;
    J->diagonal().array() += 3.0 * kappa_.array() * z_.array().square();
    *J = r_.asDiagonal() * (*J) * s_.asDiagonal();
  }
  void JacobianSparse(const Vector& y, SparseMatrix* J) const override {
    DenseMatrix dense(size(), size());
    JacobianDense(y, &dense);
    *J = dense.sparseView();
  }

 private:
  DenseMatrix A_;
  Vector kappa_, b_, r_, s_;
  bool sparse_;
  mutable Vector z_;  // workspace
};

// One planted problem: its data and solution, from which every transformed copy is made.
struct Planted {
  std::string name;
  DenseMatrix A;
  Vector kappa, b, l, u, z_star;
  double condition = 0.0;  // μ = ‖(D⁻¹ J_FF)⁻¹‖∞ at z*, F its free rows: the same in every copy
  bool sparse = false;     // the Jacobian is given sparse (every other problem)

  PlantedMcp Copy(const Vector& r, const Vector& s, const std::string& what) const {
    PlantedMcp mcp(A, kappa, b, l, u, r, s, sparse, name + " " + what);
    if (s != Vector::Ones(s.size())) mcp.set_variable_scale(s.cwiseInverse());
    return mcp;
  }
};

Planted MakePlanted(int n, int seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Planted p;
  p.name = "n" + std::to_string(n) + "-seed" + std::to_string(seed);
  p.sparse = seed % 2 == 0;
  if (p.sparse) p.name += "-sparse";
  DenseMatrix B(n, n), K(n, n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      B(i, j) = normal(rng);
      K(i, j) = normal(rng);
    }
  }
  p.A = B.transpose() * B / n + (K - K.transpose()) * 0.5;
  p.A.diagonal().array() += 0.5;
  p.kappa.resize(n);
  p.l.resize(n);
  p.u.resize(n);
  p.z_star.resize(n);
  Vector F_star(n);
  for (int i = 0; i < n; ++i) {
    p.kappa[i] = 0.2 + unit(rng);
    // Rows cycle through an LCP row, a box, a free row and an upper-bounded one; the solution state is drawn.
    const int kind = (i + seed) % 4;
    p.l[i] = kind == 0 ? 0.0 : (kind == 1 ? -1.0 - unit(rng) : -kInf);
    p.u[i] = kind == 1 ? 1.0 + unit(rng) : (kind == 3 ? 2.0 * unit(rng) : kInf);
    const double pick = unit(rng);
    if (std::isfinite(p.l[i]) && pick < 0.4) {
      p.z_star[i] = p.l[i];
      F_star[i] = 0.1 + unit(rng);
    } else if (std::isfinite(p.u[i]) && pick > 0.6) {
      p.z_star[i] = p.u[i];
      F_star[i] = -0.1 - unit(rng);
    } else {
      const double lo = std::isfinite(p.l[i]) ? p.l[i] : -2.0, hi = std::isfinite(p.u[i]) ? p.u[i] : 2.0;
      p.z_star[i] = lo + (hi - lo) * (0.1 + 0.8 * unit(rng));
      F_star[i] = 0.0;
    }
  }
  p.b = F_star - p.A * p.z_star - (p.kappa.array() * p.z_star.array().cube()).matrix();
  // μ at z* in double (the definition in verdict.h with c = 1; these Jacobians are well conditioned).
  DenseMatrix J = p.A;
  J.diagonal().array() += 3.0 * p.kappa.array() * p.z_star.array().square();
  std::vector<int> free_rows;
  for (int i = 0; i < n; ++i) {
    if (p.z_star[i] > p.l[i] && p.z_star[i] < p.u[i]) free_rows.push_back(i);
  }
  const int nf = static_cast<int>(free_rows.size());
  if (nf > 0) {
    DenseMatrix block(nf, nf);
    for (int a = 0; a < nf; ++a) {
      const double d = J.row(free_rows[a]).cwiseAbs().maxCoeff();
      for (int c = 0; c < nf; ++c) block(a, c) = J(free_rows[a], free_rows[c]) / d;
    }
    p.condition = DenseMatrix(block.inverse()).cwiseAbs().rowwise().sum().maxCoeff();
  }
  return p;
}

std::vector<Planted> PlantedSet() {
  std::vector<Planted> set;
  for (int n : {1, 2, 3, 5, 8}) {
    for (int seed : {1, 2, 3}) set.push_back(MakePlanted(n, seed));
  }
  return set;
}

// Per-row factors cycling through the given values (offset picks where the cycle starts).
Vector Cycle(int n, const std::vector<double>& values, int offset) {
  Vector v(n);
  for (int i = 0; i < n; ++i) v[i] = values[(i + offset) % values.size()];
  return v;
}

std::vector<std::string> McpBackends() {
  std::vector<std::string> names;
  for (std::string_view name : SolverNames()) {
    if (CreateSolver(name)->info().mcp) names.emplace_back(name);
  }
  return names;
}

class McpScalingInvariance : public ::testing::TestWithParam<std::string> {};

TEST_P(McpScalingInvariance, VerdictIsTheSameUnderRowScalingAndAChangeOfUnits) {
  const std::string backend = GetParam();
  const bool external = CreateSolver(backend)->info().external;
  int solved = 0;
  for (const Planted& p : PlantedSet()) {
    const int n = static_cast<int>(p.z_star.size());
    const Vector ones = Vector::Ones(n);
    struct Transform {
      std::string what;
      Vector r, s;
    };
    const std::vector<Transform> transforms = {
        {"as given", ones, ones},
        {"rows 1e8/1e-8/1", Cycle(n, {1e8, 1e-8, 1.0}, 0), ones},
        {"rows 1e-8/1/1e8", Cycle(n, {1e-8, 1.0, 1e8}, 0), ones},
        {"units 1e4/1e-4/1", ones, Cycle(n, {1e4, 1e-4, 1.0}, 0)},
        {"units 1e-4/1e4", ones, Cycle(n, {1e-4, 1e4}, 1)},
        {"rows 1e8/1e-8 and units 1e-4/1e4", Cycle(n, {1e8, 1e-8}, 0), Cycle(n, {1e-4, 1e4}, 0)},
    };
    std::vector<Verdict> verdicts;
    std::ostringstream trail;
    for (const Transform& t : transforms) {
      const PlantedMcp mcp = p.Copy(t.r, t.s, t.what);
      ReferenceSolution reference;
      reference.certificate = Certificate::kUnique;
      reference.z = p.z_star.cwiseQuotient(t.s);
      reference.condition = p.condition;
      const std::unique_ptr<Solver> solver = CreateSolver(backend);
      SolverOptions options;
      options.tolerance = kTol;
      const SolveResult result = solver->Solve(mcp, options);
      const Judgement j = JudgeMCP(mcp, ExpectedOutcome::kSolvable, {reference}, false, result.status, result.z, kTol);
      EXPECT_FALSE(IsWrong(j.verdict)) << backend << " on " << mcp.name() << ": " << ToString(j.verdict)
                                       << ", forward error " << j.forward_error << " > " << j.forward_allowance
                                       << ", scale-free residual " << j.residual.scaled;
      verdicts.push_back(j.verdict);
      trail << "\n  " << t.what << ": " << ToString(j.verdict) << " (" << ToString(result.status) << " "
            << result.message << "; forward error " << j.forward_error << ")";
    }
    // Our backends work in the stated units and on the row-scaled F, so their verdict cannot change. An external
    // code (info().external) runs its own algorithm on the problem as written: it must never be wrong, but whether it
    // solves a rescaled problem is a property of that code, which the invariance is measured on, not required of.
    if (!external) {
      for (const Verdict v : verdicts) EXPECT_EQ(v, verdicts[0]) << backend << " on " << p.name << trail.str();
    }
    solved += verdicts[0] == Verdict::kSolved;
  }
  EXPECT_GT(solved, 0) << backend << " solved none of the strongly monotone problems";
}

INSTANTIATE_TEST_SUITE_P(EveryMcpBackend, McpScalingInvariance, ::testing::ValuesIn(McpBackends()),
                         [](const auto& info) {
                           std::string name = info.param;
                           for (char& c : name) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return name;
                         });

}  // namespace
}  // namespace smcbench

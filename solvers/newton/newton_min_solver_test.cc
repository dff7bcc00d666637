// Tests of `newton-min`: box-MLCPs with a planted solution, nonlinear MCPs from the literature with their published
// solutions, a problem where the pure min-Newton method cycles and the line search rescues it, every failure
// status, dense/sparse and FB/min agreement. Residuals are recomputed here from the data, never taken from the solver.
#include "solvers/newton/newton_min_solver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "solvers/newton/semismooth_newton_solver.h"
#include "tests/support/malloc_counter.h"
#include "tests/support/small_mcps.h"

namespace smcbench {
namespace {

// ---------------------------------------------------------------- problems with a planted solution

enum class Bounds { kLower, kUpper, kBox, kFree };

// A box-MLCP with solution z*: M nonsymmetric with positive definite symmetric part (a P-matrix, so z* is unique),
// bounds cycled through `kinds`, a state per row (at a bound with F of the right sign, or inside with F = 0), q
// derived from F(z*) = M z* + q.
struct Planted {
  DenseMatrix M;
  Vector q, l, u, z_star;
};

Planted PlantSolution(int n, const std::vector<Bounds>& kinds, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> unif(0.0, 1.0);
  DenseMatrix B(n, n), K(n, n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) B(i, j) = normal(rng), K(i, j) = normal(rng);
  }
  Planted p;
  p.M = B.transpose() * B / n + 0.5 * (K - K.transpose()) / std::sqrt(double(n));
  p.M.diagonal().array() += 0.5;
  p.l.resize(n);
  p.u.resize(n);
  p.z_star.resize(n);
  Vector F(n);
  for (int i = 0; i < n; ++i) {
    const Bounds kind = kinds[i % kinds.size()];
    p.l[i] = kind == Bounds::kLower || kind == Bounds::kBox ? -1.0 - unif(rng) : -kInf;
    p.u[i] = kind == Bounds::kUpper || kind == Bounds::kBox ? 1.0 + unif(rng) : kInf;
    const double pick = unif(rng);
    if (std::isfinite(p.l[i]) && pick < 0.4) {
      p.z_star[i] = p.l[i];
      F[i] = 0.1 + unif(rng);
    } else if (std::isfinite(p.u[i]) && pick > 0.6) {
      p.z_star[i] = p.u[i];
      F[i] = -0.1 - unif(rng);
    } else {
      p.z_star[i] = -0.8 + 1.6 * unif(rng);
      F[i] = 0.0;
    }
  }
  p.q = F - p.M * p.z_star;
  return p;
}

double BoxResidual(const BoxMLCP& p, const Vector& z) {
  Vector w(p.size());
  p.Affine(z, &w);
  return NaturalResidualNorm(z, w, p.l(), p.u());
}

// The verdict's scale-free residual of an MCP, recomputed here: J at z, its row scales, McpScaledResidual.
double McpResidual(const MCP& mcp, const Vector& z) {
  const int n = mcp.size();
  Vector F(n), d;
  mcp.Evaluate(z, &F);
  if (mcp.jacobian_kind() == MCP::JacobianKind::kSparse) {
    SparseMatrix J(n, n);
    mcp.JacobianSparse(z, &J);
    McpRowScales(J, mcp.variable_scale(), &d);
  } else {
    DenseMatrix J(n, n);
    mcp.JacobianDense(z, &J);
    McpRowScales(J, mcp.variable_scale(), &d);
  }
  return McpScaledResidual(z, F, mcp.l(), mcp.u(), d, mcp.variable_scale());
}

// ---------------------------------------------------------------- nonlinear MCPs of the literature

// F(x) = atan(x − 3), x ≥ 0, solution 3. Newton on atan diverges from |x − 3| > 1.39, so the pure min-Newton method
// from 0 goes 0 → 3 + 10·atan(3) ≈ 15.5 → far below 0 → the bound 0 (a unit row) → ... and cycles.
FunctionMCP ArctanMcp() {
  return FunctionMCP(
      Vector::Zero(1), Vector::Constant(1, kInf), [](const Vector& x, Vector* F) { (*F)[0] = std::atan(x[0] - 3.0); },
      [](const Vector& x, DenseMatrix* J) { (*J)(0, 0) = 1.0 / (1.0 + (x[0] - 3.0) * (x[0] - 3.0)); }, "arctan");
}

// F(z) = A z + γ∘z³ + b (A nonsymmetric positive definite, γ ≥ 0: strongly monotone, unique solution z*), b planted
// from a box-MLCP's z* and F(z*); F's rows multiplied by row_factor and the variables measured in units c
// (z = c∘y: F(y) of the problem in y), so a scaled copy has the same solution y* = z*/c. Dense or sparse Jacobian.
class CubicMcp final : public MCP {
 public:
  CubicMcp(const Planted& p, double gamma, bool sparse_jacobian, Vector row_factor = {}, Vector units = {})
      : MCP(OnesIfEmpty(units, p.z_star.size()).cwiseInverse().cwiseProduct(p.l),
            OnesIfEmpty(units, p.z_star.size()).cwiseInverse().cwiseProduct(p.u), "cubic"),
        A_(p.M),
        gamma_(gamma),
        sparse_(sparse_jacobian),
        rows_(OnesIfEmpty(row_factor, p.z_star.size())),
        c_(OnesIfEmpty(units, p.z_star.size())) {
    b_ = (p.M * p.z_star + p.q) - A_ * p.z_star - gamma_ * p.z_star.array().cube().matrix();
    if (units.size()) set_variable_scale(c_.cwiseInverse());  // y = z/c: a unit of y is 1/c of z's
    x_.resize(size());
  }
  void Evaluate(const Vector& y, Vector* F) const override {
    x_ = c_.cwiseProduct(y);
    F->noalias() = A_ * x_;
    F->array() += gamma_ * x_.array().cube() + b_.array();
    F->array() *= rows_.array();
  }
  JacobianKind jacobian_kind() const override { return sparse_ ? JacobianKind::kSparse : JacobianKind::kDense; }
  void JacobianDense(const Vector& y, DenseMatrix* J) const override {
    *J = A_;
    J->diagonal().array() += 3.0 * gamma_ * (c_.cwiseProduct(y)).array().square();
    *J = rows_.asDiagonal() * (*J) * c_.asDiagonal();
  }
  void JacobianSparse(const Vector& y, SparseMatrix* J) const override {
    DenseMatrix dense(size(), size());
    JacobianDense(y, &dense);
    *J = dense.sparseView();
  }

 private:
  static Vector OnesIfEmpty(const Vector& v, Eigen::Index n) { return v.size() ? v : Vector(Vector::Ones(n)); }
  DenseMatrix A_;
  double gamma_;
  bool sparse_;
  Vector rows_, c_, b_;
  mutable Vector x_;
};

// ---------------------------------------------------------------- options and capabilities

TEST(NewtonMinSolver, InfoAndOptions) {
  NewtonMinSolver solver;
  EXPECT_EQ(solver.info().name, "newton-min");
  EXPECT_TRUE(solver.info().mcp);
  EXPECT_TRUE(solver.info().sparse);
  std::string error;
  EXPECT_TRUE(solver.SetOption("globalization", "none", &error)) << error;
  EXPECT_EQ(solver.options().globalization, NewtonMinOptions::kNoGlobalization);
  EXPECT_FALSE(solver.SetOption("globalization", "trust-region", &error));
  EXPECT_NE(error.find("fb-line-search"), std::string::npos) << error;
  EXPECT_FALSE(solver.SetOption("armijo_sigma", "0.7", &error));
  EXPECT_NE(error.find("armijo_sigma"), std::string::npos) << error;
  EXPECT_EQ(solver.options().armijo_sigma, 1e-4);  // a rejected value is not kept
  NewtonMinOptions bad;
  bad.descent_power = 2.0;
  const SolveResult r = NewtonMinSolver(bad).Solve(BoxMLCP::LCP(DenseMatrix::Identity(1, 1), -Vector::Ones(1)));
  EXPECT_EQ(r.status, SolveStatus::kInvalidOptions);
  EXPECT_NE(r.message.find("descent_power"), std::string::npos) << r.message;
}

// ---------------------------------------------------------------- box-MLCPs

TEST(NewtonMinSolver, MurtyLcpTextbookSolution) {
  // Murty (1988, Example 1.1 family): M = [[2, 1], [1, 2]], q = (−5, −6): z = (4/3, 7/3), w = 0 (both free).
  DenseMatrix M(2, 2);
  M << 2, 1, 1, 2;
  Vector q(2);
  q << -5, -6;
  const BoxMLCP p = BoxMLCP::LCP(M, q);
  const SolveResult r = NewtonMinSolver().Solve(p);
  ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
  EXPECT_NEAR(r.z[0], 4.0 / 3.0, 1e-12);
  EXPECT_NEAR(r.z[1], 7.0 / 3.0, 1e-12);
  // q = (1, −1): z = (0, 1/2), w = (3/2, 0): one row at its bound, one free.
  q << 1, -1;
  const SolveResult r2 = NewtonMinSolver().Solve(BoxMLCP::LCP(M, q));
  ASSERT_EQ(r2.status, SolveStatus::kSolved) << r2.message;
  EXPECT_EQ(r2.z[0], 0.0);
  EXPECT_NEAR(r2.z[1], 0.5, 1e-12);
}

TEST(NewtonMinSolver, RelayRowsSaturateAtTheirBounds) {
  // The paper's relay problem with M = h·I: z = Π_[−1,1](−q/h); q chosen to put rows above, below and inside.
  const double h = 0.01;
  Vector q(3);
  q << -0.05, 0.02, -0.004;  // −q/h = 5, −2, 0.4
  const BoxMLCP p = BoxMLCP::Relay(h * DenseMatrix::Identity(3, 3), q);
  const SolveResult r = NewtonMinSolver().Solve(p);
  ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
  EXPECT_EQ(r.z[0], 1.0);
  EXPECT_EQ(r.z[1], -1.0);
  EXPECT_NEAR(r.z[2], 0.4, 1e-12);
}

TEST(NewtonMinSolver, PlantedSolutionsWithEveryKindOfRow) {
  for (const std::vector<Bounds>& kinds : std::vector<std::vector<Bounds>>{
           {Bounds::kLower}, {Bounds::kBox}, {Bounds::kLower, Bounds::kBox, Bounds::kFree, Bounds::kUpper}}) {
    for (int n : {1, 2, 5, 20, 60}) {
      const Planted k = PlantSolution(n, kinds, 100 + n);
      const BoxMLCP p(k.M, k.q, k.l, k.u);
      SolverOptions raw;
      raw.polish = false;  // judge the backend's own answer
      const SolveResult r = NewtonMinSolver().Solve(p, raw);
      ASSERT_EQ(r.status, SolveStatus::kSolved) << "n " << n << ": " << r.message;
      EXPECT_LE(BoxResidual(p, r.z), 1e-10 * (1 + p.q().cwiseAbs().maxCoeff()));
      EXPECT_LE((r.z - k.z_star).cwiseAbs().maxCoeff(), 1e-8) << "n " << n;
      EXPECT_TRUE((r.z.array() >= p.l().array()).all() && (r.z.array() <= p.u().array()).all());
    }
  }
}

TEST(NewtonMinSolver, DenseAndSparseAgree) {
  const Planted k = PlantSolution(80, {Bounds::kLower, Bounds::kBox, Bounds::kFree}, 7);
  const BoxMLCP dense(k.M, k.q, k.l, k.u);
  const BoxMLCP sparse(SparseMatrix(k.M.sparseView()), k.q, k.l, k.u);
  std::vector<Vector> answers;
  for (const BoxMLCP* p : {&dense, &sparse}) {
    for (auto linear_solver : {NewtonOptions::kDenseLinearSolver, NewtonOptions::kSparseLinearSolver}) {
      NewtonMinOptions o;
      o.linear_solver = linear_solver;
      SolverOptions raw;
      raw.polish = false;
      const SolveResult r = NewtonMinSolver(o).Solve(*p, raw);
      ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
      answers.push_back(r.z);
    }
  }
  for (const Vector& z : answers) EXPECT_LE((z - k.z_star).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(NewtonMinSolver, LargeSparseTridiagonalLcp) {
  // M = tridiag(−1, 4, −1), n = 5000, z* alternating between the bound and the interior.
  const int n = 5000;
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 4.0);
    if (i > 0) t.emplace_back(i, i - 1, -1.0);
    if (i + 1 < n) t.emplace_back(i, i + 1, -1.0);
  }
  SparseMatrix M(n, n);
  M.setFromTriplets(t.begin(), t.end());
  Vector z_star(n), w_star(n);
  for (int i = 0; i < n; ++i) {
    z_star[i] = i % 2 ? 0.0 : 1.0 + 0.001 * i;
    w_star[i] = i % 2 ? 0.5 : 0.0;
  }
  const Vector q = w_star - M * z_star;
  const BoxMLCP p = BoxMLCP(M, q, Vector::Zero(n), Vector::Constant(n, kInf));
  SolverOptions raw;
  raw.polish = false;
  const SolveResult r = NewtonMinSolver().Solve(p, raw);
  ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
  EXPECT_LE((r.z - z_star).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_GT(r.GetDetail("max_system_size"), 0.0);
}

TEST(NewtonMinSolver, WarmStartAtTheSolutionTakesNoIteration) {
  const Planted k = PlantSolution(10, {Bounds::kBox}, 3);
  const BoxMLCP p(k.M, k.q, k.l, k.u);
  SolverOptions warm;
  warm.warm_start = k.z_star;
  const SolveResult r = NewtonMinSolver().Solve(p, warm);
  ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
  EXPECT_EQ(r.iterations, 0);
}

TEST(NewtonMinSolver, AgreesWithTheFischerBurmeisterNewton) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const Planted k = PlantSolution(30, {Bounds::kLower, Bounds::kBox, Bounds::kUpper, Bounds::kFree}, seed);
    const BoxMLCP p(k.M, k.q, k.l, k.u);
    const SolveResult a = NewtonMinSolver().Solve(p);
    const SolveResult b = SemismoothNewtonSolver().Solve(p);
    ASSERT_EQ(a.status, SolveStatus::kSolved) << a.message;
    ASSERT_EQ(b.status, SolveStatus::kSolved) << b.message;
    EXPECT_LE((a.z - b.z).cwiseAbs().maxCoeff(), 1e-9);
  }
}

// ---------------------------------------------------------------- nonlinear MCPs

TEST(NewtonMinSolverMcp, JosephyFromSeveralStarts) {
  const FunctionMCP mcp = JosephyMcp();
  Vector expected(4);
  expected << std::sqrt(6.0) / 2, 0, 0, 0.5;
  for (const Vector& start : {Vector(Vector::Zero(4)), Vector(Vector::Ones(4))}) {
    SolverOptions o;
    o.warm_start = start;
    const SolveResult r = NewtonMinSolver().Solve(mcp, o);
    ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
    EXPECT_LE((r.z - expected).cwiseAbs().maxCoeff(), 1e-8);
    EXPECT_LE(McpResidual(mcp, r.z), 1e-10);
    const SolveResult fb = SemismoothNewtonSolver().Solve(mcp, o);
    ASSERT_EQ(fb.status, SolveStatus::kSolved) << fb.message;
    EXPECT_LE((r.z - fb.z).cwiseAbs().maxCoeff(), 1e-8);
  }
}

TEST(NewtonMinSolverMcp, JosephyFromTenEndsStalledWhereTheFischerBurmeisterNewtonSolvesIt) {
  // From x = 10·1 the first min-Newton steps lead to x ≈ (0.29, 1.49, 0, 0), near a minimizer of the merit that is
  // not a solution (F1 ≈ −0.4 with x1 > 0); the merit stagnates and the answer is refused, not claimed. `newton`
  // takes FB's own steps from the start, stays out of that basin and solves it.
  const FunctionMCP mcp = JosephyMcp();
  SolverOptions o;
  o.warm_start = Vector::Constant(4, 10.0);
  const SolveResult r = NewtonMinSolver().Solve(mcp, o);
  EXPECT_EQ(r.status, SolveStatus::kStalled) << r.message;
  EXPECT_NE(r.message.find("stagnated"), std::string::npos) << r.message;
  EXPECT_GT(McpResidual(mcp, r.z), 1e-3);
  Vector expected(4);
  expected << std::sqrt(6.0) / 2, 0, 0, 0.5;
  const SolveResult fb = SemismoothNewtonSolver().Solve(mcp, o);
  ASSERT_EQ(fb.status, SolveStatus::kSolved) << fb.message;
  EXPECT_LE((fb.z - expected).cwiseAbs().maxCoeff(), 1e-8);
  // That basin is one of the start's row scales (J at 10·1 is about ten times J at the solution): with F as stated,
  // newton-min solves it too.
  NewtonMinOptions unscaled;
  unscaled.merit_scaling = NewtonMinOptions::kNoRowScaling;
  const SolveResult r2 = NewtonMinSolver(unscaled).Solve(mcp, o);
  ASSERT_EQ(r2.status, SolveStatus::kSolved) << r2.message;
  EXPECT_LE((r2.z - expected).cwiseAbs().maxCoeff(), 1e-8);
}

TEST(NewtonMinSolverMcp, KojimaShindoEndsAtOneOfItsTwoSolutions) {
  const FunctionMCP mcp = KojimaShindoMcp();
  Vector first(4), second(4);
  first << 1, 0, 3, 0;
  second << std::sqrt(6.0) / 2, 0, 0, 0.5;
  // The published solutions are solutions: F recomputed there.
  for (const Vector& s : {first, second}) EXPECT_LE(McpResidual(mcp, s), 1e-15);
  int reached_first = 0, reached_second = 0;
  for (const Vector& start : {Vector(Vector::Zero(4)), Vector(Vector::Ones(4)), Vector(Vector::Constant(4, 10.0)),
                              Vector((Vector(4) << 1, 0, 2.5, 0.2).finished())}) {
    SolverOptions o;
    o.warm_start = start;
    const SolveResult r = NewtonMinSolver().Solve(mcp, o);
    ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
    EXPECT_LE(McpResidual(mcp, r.z), 1e-10);
    const double to_first = (r.z - first).cwiseAbs().maxCoeff(), to_second = (r.z - second).cwiseAbs().maxCoeff();
    EXPECT_LE(std::min(to_first, to_second), 1e-8) << r.z.transpose();
    reached_first += to_first <= 1e-8;
    reached_second += to_second <= 1e-8;
  }
  EXPECT_GE(reached_first, 1);  // the start next to (1, 0, 3, 0) ends there
  EXPECT_EQ(reached_first + reached_second, 4);  // every start ends at exactly one of the two (they are 1.8 apart)
}

TEST(NewtonMinSolverMcp, CubicMcpDenseAndSparseAgreeWithTheFischerBurmeisterNewton) {
  const Planted k = PlantSolution(40, {Bounds::kLower, Bounds::kBox, Bounds::kFree, Bounds::kUpper}, 11);
  for (bool sparse : {false, true}) {
    for (auto linear_solver : {NewtonOptions::kDenseLinearSolver, NewtonOptions::kSparseLinearSolver}) {
      const CubicMcp mcp(k, 0.5, sparse);
      NewtonMinOptions o;
      o.linear_solver = linear_solver;
      const SolveResult r = NewtonMinSolver(o).Solve(mcp);
      ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
      EXPECT_LE(McpResidual(mcp, r.z), 1e-10);
      EXPECT_LE((r.z - k.z_star).cwiseAbs().maxCoeff(), 1e-8);
      const SolveResult fb = SemismoothNewtonSolver().Solve(mcp);
      ASSERT_EQ(fb.status, SolveStatus::kSolved) << fb.message;
      EXPECT_LE((r.z - fb.z).cwiseAbs().maxCoeff(), 1e-8);
    }
  }
}

// F(z) = A z + z³ + b with A = tridiag(−1, 4, −1) and a sparse Jacobian; b planted from z* (even rows at the lower
// bound 0 with F* = 1, odd rows inside [−1, 2] with F* = 0): strongly monotone, z* is the unique solution.
class TridiagonalCubicMcp final : public MCP {
 public:
  explicit TridiagonalCubicMcp(int n) : MCP(Bounds(n, false), Bounds(n, true), "tridiagonal-cubic"), z_star_(n) {
    Vector F_star(n);
    for (int i = 0; i < n; ++i) {
      z_star_[i] = i % 2 ? 0.5 + 0.4 * std::sin(i) : 0.0;
      F_star[i] = i % 2 ? 0.0 : 1.0;
    }
    b_ = Vector::Zero(n);
    Evaluate(z_star_, &b_);  // A z* + z*³ (b is still 0)
    b_ = F_star - b_;
    std::vector<Eigen::Triplet<double>> t;
    for (int i = 0; i < n; ++i) {
      t.emplace_back(i, i, 4.0);
      if (i > 0) t.emplace_back(i, i - 1, -1.0);
      if (i + 1 < n) t.emplace_back(i, i + 1, -1.0);
    }
    A_.resize(n, n);
    A_.setFromTriplets(t.begin(), t.end());
  }
  const Vector& z_star() const { return z_star_; }
  void Evaluate(const Vector& z, Vector* F) const override {
    const int n = size();
    for (int i = 0; i < n; ++i) {
      (*F)[i] = 4.0 * z[i] + z[i] * z[i] * z[i] + b_[i] - (i > 0 ? z[i - 1] : 0.0) - (i + 1 < n ? z[i + 1] : 0.0);
    }
  }
  JacobianKind jacobian_kind() const override { return JacobianKind::kSparse; }
  void JacobianSparse(const Vector& z, SparseMatrix* J) const override {
    *J = A_;
    for (int i = 0; i < size(); ++i) J->coeffRef(i, i) += 3.0 * z[i] * z[i];
  }

 private:
  static Vector Bounds(int n, bool upper) {
    Vector v(n);
    for (int i = 0; i < n; ++i) v[i] = upper ? (i % 2 ? 2.0 : kInf) : (i % 2 ? -1.0 : 0.0);
    return v;
  }
  SparseMatrix A_;
  Vector z_star_, b_;
};

TEST(NewtonMinSolverMcp, LargeSparseMcpAgreesWithTheFischerBurmeisterNewton) {
  const TridiagonalCubicMcp mcp(10000);
  const SolveResult r = NewtonMinSolver().Solve(mcp);
  ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
  EXPECT_LE(McpResidual(mcp, r.z), 1e-10);
  EXPECT_LE((r.z - mcp.z_star()).cwiseAbs().maxCoeff(), 1e-9);
  const SolveResult fb = SemismoothNewtonSolver().Solve(mcp);
  ASSERT_EQ(fb.status, SolveStatus::kSolved) << fb.message;
  EXPECT_LE((r.z - fb.z).cwiseAbs().maxCoeff(), 1e-9);
  std::printf("[ info ] n = 10000 sparse MCP: newton-min %d iterations %.1f ms, newton %d iterations %.1f ms\n",
              r.iterations, 1e3 * r.solve_seconds, fb.iterations, 1e3 * fb.solve_seconds);
}

TEST(NewtonMinSolverMcp, RowScalingAndUnitsDoNotChangeTheRun) {
  // The backend works in the verdict's units: scaling F's rows by 1e±8 and stating the variables' units leaves
  // the answer (in the original variables) and the iteration count unchanged.
  const Planted k = PlantSolution(12, {Bounds::kLower, Bounds::kBox, Bounds::kFree}, 5);
  const CubicMcp plain(k, 0.5, false);
  Vector rows(12), units(12);
  for (int i = 0; i < 12; ++i) {
    rows[i] = i % 2 ? 1e8 : 1e-8;
    units[i] = i % 3 ? 1e3 : 1e-2;
  }
  const CubicMcp scaled_rows(k, 0.5, false, rows);
  const CubicMcp scaled_units(k, 0.5, false, Vector(), units);
  const SolveResult a = NewtonMinSolver().Solve(plain);
  const SolveResult b = NewtonMinSolver().Solve(scaled_rows);
  const SolveResult c = NewtonMinSolver().Solve(scaled_units);  // its cold start Π(0) is the others' divided by c
  ASSERT_EQ(a.status, SolveStatus::kSolved) << a.message;
  ASSERT_EQ(b.status, SolveStatus::kSolved) << b.message;
  ASSERT_EQ(c.status, SolveStatus::kSolved) << c.message;
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.iterations, c.iterations);
  EXPECT_LE((a.z - k.z_star).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_LE((b.z - k.z_star).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_LE((c.z.cwiseProduct(units) - k.z_star).cwiseAbs().maxCoeff(), 1e-8);
}

// An MCP seen through row factors r and units c: G(y) = r∘F(c∘y) on [l/c, u/c], variable_scale 1/c, so z = c∘y.
class RescaledMcp final : public MCP {
 public:
  RescaledMcp(const MCP& base, Vector rows, Vector units)
      : MCP(base.l().cwiseQuotient(units), base.u().cwiseQuotient(units), base.name()),
        base_(base),
        rows_(std::move(rows)),
        c_(std::move(units)),
        x_(c_.size()) {
    set_variable_scale(c_.cwiseInverse());
  }
  void Evaluate(const Vector& y, Vector* G) const override {
    x_ = c_.cwiseProduct(y);
    base_.Evaluate(x_, G);
    G->array() *= rows_.array();
  }
  void JacobianDense(const Vector& y, DenseMatrix* J) const override {
    x_ = c_.cwiseProduct(y);
    base_.JacobianDense(x_, J);
    *J = rows_.asDiagonal() * (*J) * c_.asDiagonal();
  }

 private:
  const MCP& base_;
  Vector rows_, c_;
  mutable Vector x_;
};

TEST(NewtonMinSolverMcp, UnitsOfTheVariablesDoNotChangeTheRun) {
  // The backend measures its steps, norms and tests in the units c, so the iterates are the same, up to rounding, in
  // every unit system and under any row scaling: the same status, iteration count, kinds of step and answer in z.
  // The cubic MCP takes min-Newton steps only; Josephy's NCP from 0 also takes an FB-Newton step, and from 10·1 it
  // crawls by gradient steps until the merit stagnates (kStalled).
  const Planted k = PlantSolution(12, {Bounds::kLower, Bounds::kBox, Bounds::kFree, Bounds::kUpper}, 6);
  const CubicMcp cubic(k, 2.0, false);
  const FunctionMCP josephy = JosephyMcp();
  struct Case {
    const MCP* base;
    double start;  // z₀ = start·1 (NaN: the cold start)
    SolveStatus status;
    bool falls_back;  // takes FB-Newton or gradient steps
  };
  const Case cases[] = {{&cubic, kNaN, SolveStatus::kSolved, false},
                        {&josephy, kNaN, SolveStatus::kSolved, true},
                        {&josephy, 10.0, SolveStatus::kStalled, true}};
  for (const Case& c : cases) {
    const MCP& base = *c.base;
    const int n = base.size();
    Vector row_factors(n), up(n), down(n);
    for (int i = 0; i < n; ++i) {
      row_factors[i] = i % 2 ? 1e-8 : 1e8;
      up[i] = i % 2 ? 1e-4 : 1e4;
      down[i] = i % 2 ? 1e4 : 1e-4;
    }
    for (auto linear_solver : {NewtonOptions::kDenseLinearSolver, NewtonOptions::kSparseLinearSolver}) {
      NewtonMinOptions o;
      o.linear_solver = linear_solver;
      SolverOptions start;
      if (!std::isnan(c.start)) start.warm_start = Vector::Constant(n, c.start);
      const SolveResult reference = NewtonMinSolver(o).Solve(base, start);
      ASSERT_EQ(reference.status, c.status) << base.name() << ": " << reference.message;
      if (c.status == SolveStatus::kSolved) {
        EXPECT_LE(McpResidual(base, reference.z), 1e-10) << base.name();
      }
      if (c.falls_back) {
        EXPECT_GE(reference.GetDetail("fb_newton_steps") + reference.GetDetail("gradient_steps"), 1.0) << base.name();
      }
      const double z_norm = reference.z.cwiseAbs().maxCoeff();
      for (const Vector& rows : {Vector(Vector::Ones(n)), row_factors}) {
        for (const Vector& units : {Vector(Vector::Ones(n)), up, down}) {
          const RescaledMcp mcp(base, rows, units);
          SolverOptions y_start;
          if (!std::isnan(c.start)) y_start.warm_start = start.warm_start.cwiseQuotient(units);
          const SolveResult r = NewtonMinSolver(o).Solve(mcp, y_start);
          const std::string what = base.name() + " from " + std::to_string(c.start) + ", rows " +
                                   std::to_string(rows[0]) + ", units " + std::to_string(units[0]) +
                                   (linear_solver == NewtonOptions::kDenseLinearSolver ? ", dense" : ", sparse");
          EXPECT_EQ(r.status, reference.status) << what << ": " << r.message;
          EXPECT_EQ(r.iterations, reference.iterations) << what;
          EXPECT_LE((r.z.cwiseProduct(units) - reference.z).cwiseAbs().maxCoeff(), 1e-9 * z_norm) << what;
          EXPECT_EQ(r.GetDetail("gradient_steps"), reference.GetDetail("gradient_steps")) << what;
          EXPECT_EQ(r.GetDetail("fb_newton_steps"), reference.GetDetail("fb_newton_steps")) << what;
        }
      }
    }
  }
}

TEST(NewtonMinSolverMcp, TheLineSearchRescuesACyclingMinNewton) {
  const FunctionMCP mcp = ArctanMcp();
  NewtonMinOptions pure;
  pure.globalization = NewtonMinOptions::kNoGlobalization;
  SolverOptions budget;
  budget.max_iterations = 30;
  const SolveResult cycling = NewtonMinSolver(pure).Solve(mcp, budget);
  EXPECT_EQ(cycling.status, SolveStatus::kIterationLimit) << cycling.message;
  EXPECT_NE(cycling.message.find("residual"), std::string::npos);
  const SolveResult rescued = NewtonMinSolver().Solve(mcp, budget);
  ASSERT_EQ(rescued.status, SolveStatus::kSolved) << rescued.message;
  EXPECT_NEAR(rescued.z[0], 3.0, 1e-10);
  // The safeguard acted: a rejected or shortened min-Newton step.
  EXPECT_GE(
      rescued.GetDetail("fb_newton_steps") + rescued.GetDetail("gradient_steps") + rescued.GetDetail("backtracks"),
      1.0);
}

// ---------------------------------------------------------------- failures are statuses

TEST(NewtonMinSolverMcp, BillupsStallsWithTheResidualInTheMessage) {
  const SolveResult r = NewtonMinSolver().Solve(BillupsMcp());
  EXPECT_EQ(r.status, SolveStatus::kStalled) << r.message;
  EXPECT_NE(r.message.find("best scale-free residual"), std::string::npos) << r.message;
}

TEST(NewtonMinSolver, SingularSystemWithoutDescentDirection) {
  // Free row F(z) = z² + 1 at z = 0: J = 0 and ∇Psi = J·F = 0, no direction exists.
  const FunctionMCP mcp(
      Vector::Constant(1, -kInf), Vector::Constant(1, kInf),
      [](const Vector& z, Vector* F) { (*F)[0] = z[0] * z[0] + 1; },
      [](const Vector& z, DenseMatrix* J) { (*J)(0, 0) = 2 * z[0]; }, "no-root");
  const SolveResult r = NewtonMinSolver().Solve(mcp);
  EXPECT_EQ(r.status, SolveStatus::kSingular) << r.message;
  EXPECT_EQ(r.iterations, 1);
  NewtonMinOptions pure;
  pure.globalization = NewtonMinOptions::kNoGlobalization;
  EXPECT_EQ(NewtonMinSolver(pure).Solve(mcp).status, SolveStatus::kSingular);
}

TEST(NewtonMinSolver, IterationAndTimeLimits) {
  const Planted k = PlantSolution(50, {Bounds::kBox}, 10);
  const BoxMLCP p(k.M, k.q, k.l, k.u);
  SolverOptions one;
  one.max_iterations = 1;
  one.polish = false;
  const SolveResult r = NewtonMinSolver().Solve(p, one);
  EXPECT_EQ(r.status, SolveStatus::kIterationLimit) << r.message;
  EXPECT_EQ(r.iterations, 1);
  SolverOptions instant;
  instant.time_limit_seconds = 1e-12;
  EXPECT_EQ(NewtonMinSolver().Solve(p, instant).status, SolveStatus::kTimeLimit);
}

TEST(NewtonMinSolverMcp, NanOrAMalformedJacobianIsANumericalFailure) {
  const FunctionMCP nan_f(
      Vector::Zero(2), Vector::Constant(2, kInf), [](const Vector&, Vector* F) { F->setConstant(std::nan("")); },
      [](const Vector&, DenseMatrix* J) { J->setIdentity(); }, "nan");
  SolveResult r = NewtonMinSolver().Solve(nan_f);
  EXPECT_EQ(r.status, SolveStatus::kNumericalFailure);
  EXPECT_NE(r.message.find("NaN"), std::string::npos) << r.message;
  const FunctionMCP wrong_size(
      Vector::Zero(2), Vector::Constant(2, kInf), [](const Vector& z, Vector* F) { *F = z; },
      [](const Vector&, DenseMatrix* J) { J->setIdentity(3, 3); }, "wrong-size");
  r = NewtonMinSolver().Solve(wrong_size);
  EXPECT_EQ(r.status, SolveStatus::kNumericalFailure);
  EXPECT_NE(r.message.find("wrong size"), std::string::npos) << r.message;
  const FunctionMCP nan_jacobian(
      Vector::Zero(1), Vector::Constant(1, kInf), [](const Vector& z, Vector* F) { (*F)[0] = z[0] - 1; },
      [](const Vector&, DenseMatrix* J) { (*J)(0, 0) = std::nan(""); }, "nan-jacobian");
  r = NewtonMinSolver().Solve(nan_jacobian);
  EXPECT_EQ(r.status, SolveStatus::kNumericalFailure);
}

// ---------------------------------------------------------------- the workspace is reused

TEST(NewtonMinSolver, RepeatedSolvesDoNotAllocate) {
  if (!test_support::CanCountMallocs()) GTEST_SKIP() << "malloc is owned by the sanitizer runtime";
  const Planted k = PlantSolution(40, {Bounds::kLower, Bounds::kBox, Bounds::kFree}, 9);
  const BoxMLCP dense(k.M, k.q, k.l, k.u);
  const BoxMLCP sparse(SparseMatrix(k.M.sparseView()), k.q, k.l, k.u);
  SolverOptions raw;  // the base's generic polish allocates above BoxMLCP::kSmallSize by design (polish.h)
  raw.polish = false;
  for (const BoxMLCP* p : {&dense, &sparse}) {
    NewtonMinOptions o;
    o.linear_solver = p->is_sparse() ? NewtonOptions::kSparseLinearSolver : NewtonOptions::kDenseLinearSolver;
    NewtonMinSolver solver(o);
    SolveResult result;
    solver.Solve(*p, raw, &result);
    ASSERT_EQ(result.status, SolveStatus::kSolved) << result.message;
    test_support::StartCountingMallocs();
    for (int rep = 0; rep < 3; ++rep) solver.Solve(*p, raw, &result);
    const long mallocs = test_support::StopCountingMallocs();
    if (!p->is_sparse()) {
      EXPECT_EQ(mallocs, 0) << "dense";
    }
    // UMFPACK mallocs its own factors (C code); our code makes no operator new call.
    EXPECT_EQ(test_support::OperatorNewCalls(), 0) << (p->is_sparse() ? "sparse" : "dense");
    EXPECT_EQ(result.status, SolveStatus::kSolved);
  }
  const CubicMcp mcp(k, 0.3, false);
  NewtonMinSolver solver;
  SolveResult result;
  solver.Solve(mcp, SolverOptions{}, &result);
  ASSERT_EQ(result.status, SolveStatus::kSolved) << result.message;
  test_support::StartCountingMallocs();
  for (int rep = 0; rep < 3; ++rep) solver.Solve(mcp, SolverOptions{}, &result);
  EXPECT_EQ(test_support::StopCountingMallocs(), 0) << "dense MCP";
  EXPECT_EQ(result.status, SolveStatus::kSolved);
}

}  // namespace
}  // namespace smcbench

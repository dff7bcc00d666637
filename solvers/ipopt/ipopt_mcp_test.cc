// Tests of the `ipopt` backend on nonlinear MCPs: problems with a known solution (literature, or built from z*
// with a strongly monotone F, whose solution is unique), every check recomputing the scale-free residual
// (McpScaledResidual with J at the answer) instead of trusting the solver, and every status the backend maps.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "solvers/ipopt/ipopt_details.h"
#include "solvers/ipopt/ipopt_qp_solver.h"
#include "tests/support/small_mcps.h"

namespace smcbench {
namespace {

constexpr double kTol = 1e-10;

// The verdict's measure at z, computed here from F and J.
double ScaledResidual(const MCP& p, const Vector& z) {
  Vector F(p.size()), d;
  p.Evaluate(z, &F);
  if (p.jacobian_kind() == MCP::JacobianKind::kSparse) {
    SparseMatrix J;
    p.JacobianSparse(z, &J);
    McpRowScales(J, p.variable_scale(), &d);
  } else {
    DenseMatrix J(p.size(), p.size());
    p.JacobianDense(z, &J);
    McpRowScales(J, p.variable_scale(), &d);
  }
  return McpScaledResidual(z, F, p.l(), p.u(), d, p.variable_scale());
}

// F(z) = R (A z + c∘z³ + b) with A's symmetric part positive definite and c ≥ 0 (strongly monotone, so the
// solution z* is unique), b chosen so that z* solves the MCP with every kind of row: lower, box, free, upper,
// at a bound or strictly inside; R > 0 a diagonal row scaling (the solution set does not change).
class CubicMcp final : public MCP {
 public:
  CubicMcp(int n, unsigned seed, bool sparse, Vector row_scale = {})
      : MCP(Vector::Zero(n), Vector::Zero(n), "cubic"), sparse_(sparse) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0), any(-1.0, 1.0);
    if (sparse) {
      A_ = DenseMatrix::Zero(n, n);
      for (int i = 0; i < n; ++i) {
        A_(i, i) = 4.0;
        if (i > 0) A_(i, i - 1) = -1.0;
        if (i + 1 < n) A_(i, i + 1) = 2.0;
      }
    } else {
      DenseMatrix B(n, n), C(n, n);
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
          B(i, j) = any(rng);
          C(i, j) = any(rng);
        }
      }
      A_ = B * B.transpose() / n + DenseMatrix::Identity(n, n) + 0.5 * (C - C.transpose());
    }
    A_sparse_ = A_.sparseView();
    c_ = Vector::Constant(n, 0.5);
    R_ = row_scale.size() == n ? row_scale : Vector::Ones(n);
    Vector l(n), u(n), F_star(n);
    z_star_.resize(n);
    for (int i = 0; i < n; ++i) {
      const double at = unit(rng), size = 0.5 + unit(rng);
      switch (i % 4) {
        case 0:  // lower: 0 ≤ z ⟂ F ≥ 0
          l[i] = 0.0;
          u[i] = kInf;
          z_star_[i] = at < 0.5 ? 0.0 : size;
          F_star[i] = at < 0.5 ? size : 0.0;
          break;
        case 1:  // box [−1, 1]
          l[i] = -1.0;
          u[i] = 1.0;
          z_star_[i] = at < 0.33 ? -1.0 : (at < 0.66 ? 1.0 : any(rng) * 0.9);
          F_star[i] = at < 0.33 ? size : (at < 0.66 ? -size : 0.0);
          break;
        case 2:  // free: F = 0
          l[i] = -kInf;
          u[i] = kInf;
          z_star_[i] = any(rng);
          F_star[i] = 0.0;
          break;
        default:  // upper: z ≤ 0.5
          l[i] = -kInf;
          u[i] = 0.5;
          z_star_[i] = at < 0.5 ? 0.5 : 0.5 - size;
          F_star[i] = at < 0.5 ? -size : 0.0;
          break;
      }
    }
    b_ = F_star - A_ * z_star_ - (c_.array() * z_star_.array().cube()).matrix();
    bounds_l_ = l;
    bounds_u_ = u;
  }
  // MCP's bounds are fixed at construction: the factory below builds the real problem from these.
  const Vector& bounds_l() const { return bounds_l_; }
  const Vector& bounds_u() const { return bounds_u_; }
  const Vector& z_star() const { return z_star_; }

  void Evaluate(const Vector& z, Vector* F) const override {
    F->noalias() = A_ * z;
    F->array() += c_.array() * z.array().cube() + b_.array();
    F->array() *= R_.array();
  }
  JacobianKind jacobian_kind() const override { return sparse_ ? JacobianKind::kSparse : JacobianKind::kDense; }
  void JacobianDense(const Vector& z, DenseMatrix* J) const override {
    *J = A_;
    J->diagonal().array() += 3.0 * c_.array() * z.array().square();
    *J = R_.asDiagonal() * (*J);
  }
  void JacobianSparse(const Vector& z, SparseMatrix* J) const override {
    *J = A_sparse_;
    for (int i = 0; i < size(); ++i) J->coeffRef(i, i) += 3.0 * c_[i] * z[i] * z[i];
    *J = R_.asDiagonal() * (*J);
  }

 private:
  bool sparse_;
  DenseMatrix A_;
  SparseMatrix A_sparse_;
  Vector c_, b_, R_, z_star_, bounds_l_, bounds_u_;
};

// The same F on the right bounds (MCP keeps l, u from its constructor), optionally in other units z = S y.
class BoundedCubic final : public MCP {
 public:
  BoundedCubic(const CubicMcp& f, Vector units = {}) : MCP(Scaled(f.bounds_l(), units), Scaled(f.bounds_u(), units)),
                                                      f_(f), S_(units.size() ? units : Vector::Ones(f.size())) {
    // y_i = z_i / S_i: one unit of z_i is 1/S_i in y_i, the scale the problem states for it.
    if (units.size()) set_variable_scale(units.cwiseInverse());
  }
  // In units S: z = S y, so y's bounds are l/S and F_y(y) = F(S y).
  void Evaluate(const Vector& y, Vector* F) const override { f_.Evaluate(S_.cwiseProduct(y), F); }
  JacobianKind jacobian_kind() const override { return f_.jacobian_kind(); }
  void JacobianDense(const Vector& y, DenseMatrix* J) const override {
    f_.JacobianDense(S_.cwiseProduct(y), J);
    *J = (*J) * S_.asDiagonal();
  }
  void JacobianSparse(const Vector& y, SparseMatrix* J) const override {
    f_.JacobianSparse(S_.cwiseProduct(y), J);
    *J = (*J) * S_.asDiagonal();
  }
  Vector ToZ(const Vector& y) const { return S_.cwiseProduct(y); }

 private:
  static Vector Scaled(const Vector& b, const Vector& units) {
    return units.size() ? Vector(b.cwiseQuotient(units)) : b;
  }
  const CubicMcp& f_;
  Vector S_;
};

TEST(IpoptMcp, InfoSaysMcp) {
  IpoptQpSolver solver;
  EXPECT_TRUE(solver.info().mcp);
}

TEST(IpoptMcp, JosephyFromPublishedStarts) {
  const FunctionMCP mcp = JosephyMcp();
  const Vector expected = JosephySolution();
  // MCPLIB's start is (1, 1, 1, 1); the cold start Π(0) = 0 as well.
  for (const double start : {0.0, 1.0}) {
    IpoptQpSolver solver;
    SolverOptions o;
    o.warm_start = Vector::Constant(4, start);
    const SolveResult r = solver.Solve(mcp, o);
    ASSERT_EQ(r.status, SolveStatus::kSolved) << "start " << start << ": " << r.message;
    EXPECT_LE(ScaledResidual(mcp, r.z), kTol);
    EXPECT_LE((r.z - expected).cwiseAbs().maxCoeff(), 1e-8) << r.z.transpose();
  }
}

// Billups' example: F(x) = (x − 1)² − 1.01, x ≥ 0, solution 1 + √1.01. The gap program needs F(x) = w ≥ 0: from
// x = 0 (F = −0.01, and F decreases as x grows towards 1) it is locally infeasible, which proves nothing about the
// MCP (numerical_failure, never infeasible); from x = 1, on the far side of F's minimum, Ipopt reaches the solution.
TEST(IpoptMcp, BillupsLocallyInfeasibleFromZeroSolvedFromOne) {
  const FunctionMCP mcp = BillupsMcp();
  IpoptQpSolver solver;
  const SolveResult from_zero = solver.Solve(mcp);
  EXPECT_EQ(from_zero.status, SolveStatus::kNumericalFailure) << from_zero.message;
  EXPECT_NE(from_zero.message.find("locally infeasible"), std::string::npos) << from_zero.message;
  SolverOptions o;
  o.warm_start = Vector::Ones(1);
  const SolveResult r = solver.Solve(mcp, o);
  ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
  EXPECT_NEAR(r.z[0], 1.0 + std::sqrt(1.01), 1e-9);
}

// Every kind of row (lower, box, free, upper, at a bound or inside), dense and sparse Jacobians, both Hessian
// choices: the unique solution z*.
TEST(IpoptMcp, CubicWithEveryRowKindDenseAndSparseBothHessians) {
  for (const bool sparse : {false, true}) {
    for (const auto hessian : {IpoptOptions::kGapHessian, IpoptOptions::kLimitedMemory}) {
      const CubicMcp f(sparse ? 60 : 24, 7, sparse);
      const BoundedCubic mcp(f);
      IpoptOptions io;
      io.mcp_hessian = hessian;
      IpoptQpSolver solver;
      solver.set_options(io);
      const SolveResult r = solver.Solve(mcp);
      ASSERT_EQ(r.status, SolveStatus::kSolved) << "sparse " << sparse << " hessian " << hessian << ": "
                                                << r.message;
      EXPECT_LE(ScaledResidual(mcp, r.z), kTol);
      EXPECT_LE((r.z - f.z_star()).cwiseAbs().maxCoeff(), 1e-8);
      EXPECT_EQ(kIpoptMcpHessianDetail.Get(r), hessian);
    }
  }
}

// The refinement alone finishes what Ipopt's interior point leaves at its own tolerance: with a loose Ipopt tol
// and no refinement the answer is not accepted, with it the same run is solved.
TEST(IpoptMcp, NewtonRefinementTakesOverFromALooseIpoptTolerance) {
  const CubicMcp f(24, 3, false);
  const BoundedCubic mcp(f);
  IpoptOptions io;
  io.tol = 1e-3;
  io.early_polish = false;
  io.polish = false;
  IpoptQpSolver raw;
  raw.set_options(io);
  const SolveResult r0 = raw.Solve(mcp);
  EXPECT_NE(r0.status, SolveStatus::kSolved);
  io.polish = true;
  IpoptQpSolver refined;
  refined.set_options(io);
  const SolveResult r1 = refined.Solve(mcp);
  ASSERT_EQ(r1.status, SolveStatus::kSolved) << r1.message;
  EXPECT_EQ(r1.GetDetail("refine_accepted"), 1.0);
  EXPECT_LE((r1.z - f.z_star()).cwiseAbs().maxCoeff(), 1e-8);
}

// Scale-free: F's rows scaled by 1e±8 and the variables' units changed (stated through variable_scale) leave the
// answer and the verdict unchanged.
TEST(IpoptMcp, InvariantUnderRowScalingAndUnits) {
  const int n = 24;
  Vector R(n), S(n);
  for (int i = 0; i < n; ++i) {
    R[i] = i % 2 ? 1e8 : 1e-8;
    S[i] = i % 3 ? 1e3 : 1e-2;
  }
  const CubicMcp plain_f(n, 5, false), scaled_f(n, 5, false, R);
  const BoundedCubic plain(plain_f), rows(scaled_f), units(plain_f, S);
  IpoptQpSolver solver;
  const SolveResult r0 = solver.Solve(plain);
  const SolveResult r1 = solver.Solve(rows);
  const SolveResult r2 = solver.Solve(units);
  ASSERT_EQ(r0.status, SolveStatus::kSolved) << r0.message;
  ASSERT_EQ(r1.status, SolveStatus::kSolved) << r1.message;
  // The base's verdict on this branch still measures the unscaled residual, which a change of units moves: the
  // backend's own claim (its scale-free measure) is checked here, and its answer below.
  EXPECT_TRUE(r2.status == SolveStatus::kSolved || r2.message.find("backend reported success") != std::string::npos)
      << r2.message;
  EXPECT_LE(ScaledResidual(rows, r1.z), kTol);
  EXPECT_LE(ScaledResidual(units, r2.z), kTol);
  EXPECT_LE((r1.z - plain_f.z_star()).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_LE((units.ToZ(r2.z) - plain_f.z_star()).cwiseAbs().maxCoeff(), 1e-8);
  // Ipopt's iterations do not depend on the scaling either (the program is posed in the scaled units).
  EXPECT_NEAR(r1.iterations, r0.iterations, 2);
}

// Free rows only: a nonlinear system F(z) = 0 (z0³ + z1 = 2, z0 = z1: the unique real root (1, 1)).
TEST(IpoptMcp, FreeRowsAreEquations) {
  const FunctionMCP mcp(
      Vector::Constant(2, -kInf), Vector::Constant(2, kInf),
      [](const Vector& z, Vector* F) {
        (*F)[0] = z[0] * z[0] * z[0] + z[1] - 2.0;
        (*F)[1] = z[0] - z[1];
      },
      [](const Vector& z, DenseMatrix* J) { *J << 3.0 * z[0] * z[0], 1.0, 1.0, -1.0; }, "cubic-system");
  IpoptQpSolver solver;
  SolverOptions o;
  o.warm_start = Vector::Constant(2, 3.0);
  const SolveResult r = solver.Solve(mcp, o);
  ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
  EXPECT_NEAR(r.z[0], 1.0, 1e-10);
  EXPECT_NEAR(r.z[1], 1.0, 1e-10);
}

// An LCP posed as an MCP (F affine) is the box backend's gap program: the same answer as ipopt on the box-MLCP.
TEST(IpoptMcp, AffineFAgreesWithTheBoxBackend) {
  DenseMatrix M(3, 3);
  M << 2, 1, 0, -1, 2, 1, 0, -1, 2;
  Vector q(3);
  q << -1, 1, -2;
  const BoxMLCP box = BoxMLCP::LCP(M, q);
  const FunctionMCP mcp(
      box.l(), box.u(), [&](const Vector& z, Vector* F) { *F = M * z + q; },
      [&](const Vector&, DenseMatrix* J) { *J = M; }, "lcp");
  IpoptQpSolver solver;
  const SolveResult rb = solver.Solve(box);
  const SolveResult rm = solver.Solve(mcp);
  ASSERT_EQ(rb.status, SolveStatus::kSolved) << rb.message;
  ASSERT_EQ(rm.status, SolveStatus::kSolved) << rm.message;
  EXPECT_LE((rb.z - rm.z).cwiseAbs().maxCoeff(), 1e-9);
}

// ---------------------------------------------------------------- every status the backend maps

TEST(IpoptMcp, IterationLimit) {
  const CubicMcp f(24, 9, false);
  const BoundedCubic mcp(f);
  IpoptOptions io;
  io.polish = false;
  IpoptQpSolver solver;
  solver.set_options(io);
  SolverOptions o;
  o.max_iterations = 1;
  const SolveResult r = solver.Solve(mcp, o);
  EXPECT_EQ(r.status, SolveStatus::kIterationLimit) << r.message;
  EXPECT_NE(r.message.find("iteration limit"), std::string::npos) << r.message;
}

TEST(IpoptMcp, TimeLimit) {
  const CubicMcp f(24, 9, false);
  const BoundedCubic mcp(f);
  IpoptQpSolver solver;
  SolverOptions o;
  o.time_limit_seconds = 1e-9;
  const SolveResult r = solver.Solve(mcp, o);
  EXPECT_EQ(r.status, SolveStatus::kTimeLimit) << r.message;
}

TEST(IpoptMcp, NanInFAtTheStartIsANumericalFailureNamingTheEntry) {
  const FunctionMCP mcp(
      Vector::Zero(2), Vector::Constant(2, kInf),
      [](const Vector& z, Vector* F) {
        (*F)[0] = z[0] - 1.0;
        (*F)[1] = std::log(z[1]) + 1.0;  // −∞ at the cold start 0
      },
      [](const Vector& z, DenseMatrix* J) { *J << 1.0, 0.0, 0.0, 1.0 / z[1]; }, "log");
  IpoptQpSolver solver;
  const SolveResult r = solver.Solve(mcp);
  EXPECT_EQ(r.status, SolveStatus::kNumericalFailure);
  EXPECT_NE(r.message.find("F[1]"), std::string::npos) << r.message;
}

// F is NaN away from the solution's neighbourhood (x > 3): Ipopt's steps that reach there are shortened, and the
// solution x = 1 of F(x) = x − 1 on [0, ∞) is still found from x = 2.5.
TEST(IpoptMcp, NanInFAwayFromTheSolutionIsAvoided) {
  const FunctionMCP mcp(
      Vector::Zero(1), Vector::Constant(1, kInf),
      [](const Vector& x, Vector* F) { (*F)[0] = x[0] > 3.0 ? kNaN : x[0] - 1.0; },
      [](const Vector&, DenseMatrix* J) { (*J)(0, 0) = 1.0; }, "nan-beyond-3");
  IpoptQpSolver solver;
  SolverOptions o;
  o.warm_start = Vector::Constant(1, 2.5);
  const SolveResult r = solver.Solve(mcp, o);
  ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
  EXPECT_NEAR(r.z[0], 1.0, 1e-10);
}

TEST(IpoptMcp, WrongSizeJacobianIsANumericalFailureNamingTheSize) {
  const FunctionMCP mcp(
      Vector::Zero(2), Vector::Constant(2, kInf), [](const Vector& z, Vector* F) { *F = z.array() - 1.0; },
      [](const Vector&, DenseMatrix* J) { *J = DenseMatrix::Identity(3, 2); }, "wrong-jacobian");
  IpoptQpSolver solver;
  const SolveResult r = solver.Solve(mcp);
  EXPECT_EQ(r.status, SolveStatus::kNumericalFailure);
  EXPECT_NE(r.message.find("3x2"), std::string::npos) << r.message;
}

// No solution: F(x) = −1/(1 + x²) < 0 on [0, ∞). Never solved, never a claim of infeasibility (no certificate for a
// nonlinear F).
TEST(IpoptMcp, NoSolutionIsNotSolvedAndNotInfeasible) {
  const FunctionMCP mcp(
      Vector::Zero(1), Vector::Constant(1, kInf),
      [](const Vector& x, Vector* F) { (*F)[0] = -1.0 / (1.0 + x[0] * x[0]); },
      [](const Vector& x, DenseMatrix* J) {
        (*J)(0, 0) = 2.0 * x[0] / ((1.0 + x[0] * x[0]) * (1.0 + x[0] * x[0]));
      },
      "no-solution");
  IpoptQpSolver solver;
  SolverOptions o;
  o.max_iterations = 200;
  const SolveResult r = solver.Solve(mcp, o);
  EXPECT_NE(r.status, SolveStatus::kSolved);
  EXPECT_NE(r.status, SolveStatus::kInfeasible);
  EXPECT_FALSE(r.message.empty());
}

// F(x) = (x − 2)² + 0.1 > 0 on [0, ∞): the solution is x = 0, but the gap x·F(x) has a local minimizer at
// x = (8 + √14.8)/6 ≈ 1.975 with x·F(x) ≈ 0.2 > 0 (G ≈ 0.1 in the program's units, F/d with d = |F'(3)| = 2). From
// x = 3, Ipopt with the limited-memory Hessian converges there: without the refinement that is a stationary point
// with a positive gap (stalled, the gap in the message); the refinement's active set (F/d ≫ x) then takes it to the
// solution. (With the gap-only Hessian, which lacks F's curvature weighted by the nonzero multiplier there, Ipopt
// does not converge to that point within its iteration limit.)
TEST(IpoptMcp, StationaryPointWithPositiveGapIsStalledUnlessRefined) {
  const FunctionMCP mcp(
      Vector::Zero(1), Vector::Constant(1, kInf),
      [](const Vector& x, Vector* F) { (*F)[0] = (x[0] - 2.0) * (x[0] - 2.0) + 0.1; },
      [](const Vector& x, DenseMatrix* J) { (*J)(0, 0) = 2.0 * (x[0] - 2.0); }, "positive-gap");
  SolverOptions o;
  o.warm_start = Vector::Constant(1, 3.0);
  IpoptOptions io;
  io.polish = false;
  io.mcp_hessian = IpoptOptions::kLimitedMemory;
  IpoptQpSolver raw;
  raw.set_options(io);
  const SolveResult stalled = raw.Solve(mcp, o);
  ASSERT_EQ(stalled.status, SolveStatus::kStalled) << stalled.message;
  EXPECT_NE(stalled.message.find("complementarity gap G = 0.099"), std::string::npos) << stalled.message;
  EXPECT_NEAR(stalled.z[0], (8.0 + std::sqrt(14.8)) / 6.0, 1e-4);
  io.polish = true;
  IpoptQpSolver refined;
  refined.set_options(io);
  const SolveResult r = refined.Solve(mcp, o);
  ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
  EXPECT_EQ(r.z[0], 0.0);
  // The default (gap-only Hessian) with the refinement: solved as well, by refining an iterate, after far more
  // Ipopt iterations.
  IpoptQpSolver by_default;
  const SolveResult d = by_default.Solve(mcp, o);
  ASSERT_EQ(d.status, SolveStatus::kSolved) << d.message;
  EXPECT_EQ(d.z[0], 0.0);
  EXPECT_GT(d.iterations, 10 * r.iterations);
}

// Ipopt keeps the sparse Jacobian's pattern at the start: an entry that appears later (here ∂F0/∂z1 = z0, not
// stored at z0 = 0) is a numerical failure naming it, never a wrong structure handed to Ipopt.
class GrowingPatternMcp final : public MCP {
 public:
  GrowingPatternMcp() : MCP(Vector::Constant(2, -kInf), Vector::Constant(2, kInf), "growing-pattern") {}
  void Evaluate(const Vector& z, Vector* F) const override {
    (*F)[0] = z[0] + z[0] * z[1] - 2.0;
    (*F)[1] = z[1] - 1.0;
  }
  JacobianKind jacobian_kind() const override { return JacobianKind::kSparse; }
  void JacobianSparse(const Vector& z, SparseMatrix* J) const override {
    DenseMatrix D(2, 2);
    D << 1.0 + z[1], z[0], 0.0, 1.0;
    *J = D.sparseView();
  }
};

TEST(IpoptMcp, SparseJacobianEntryOutsideTheStartingPatternIsNamed) {
  const GrowingPatternMcp mcp;
  IpoptQpSolver solver;
  SolverOptions o;
  o.warm_start = Vector::Zero(2);
  const SolveResult r = solver.Solve(mcp, o);
  // The refinement does not need a fixed pattern: it may still finish the job (solution (1, 1)).
  if (r.solved()) {
    EXPECT_NEAR(r.z[0], 1.0, 1e-10);
  } else {
    EXPECT_EQ(r.status, SolveStatus::kNumericalFailure) << r.message;
    EXPECT_NE(r.message.find("(0, 1)"), std::string::npos) << r.message;
  }
  IpoptOptions io;
  io.polish = false;
  solver.set_options(io);
  const SolveResult raw = solver.Solve(mcp, o);
  EXPECT_EQ(raw.status, SolveStatus::kNumericalFailure) << raw.message;
  EXPECT_NE(raw.message.find("(0, 1)"), std::string::npos) << raw.message;
}

// An exception from F inside Ipopt's iterations reaches the caller (Ipopt would swallow it), as from every backend.
// An evaluation error of F inside Ipopt's callbacks (a std::runtime_error) ends the solve with numerical_failure and
// its message (Solver::Solve's policy for the caller's code), and leaves the instance able to solve the next problem.
TEST(IpoptMcp, ExceptionFromFInsideIpoptIsAStatusAndTheInstanceStaysUsable) {
  int calls = 0;
  const FunctionMCP mcp(
      Vector::Zero(1), Vector::Constant(1, kInf),
      [&calls](const Vector& x, Vector* F) {
        if (++calls > 3) throw std::runtime_error("F failed");
        (*F)[0] = x[0] - 1.0;
      },
      [](const Vector&, DenseMatrix* J) { (*J)(0, 0) = 1.0; }, "throws");
  IpoptQpSolver solver;
  SolverOptions o;
  o.warm_start = Vector::Constant(1, 3.0);
  const SolveResult failed = solver.Solve(mcp, o);
  EXPECT_EQ(failed.status, SolveStatus::kNumericalFailure);
  EXPECT_NE(failed.message.find("F failed"), std::string::npos) << failed.message;
  calls = -1000;  // the same instance solves the next problem normally
  const SolveResult r = solver.Solve(mcp, o);
  ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
  EXPECT_NEAR(r.z[0], 1.0, 1e-12);
}

TEST(IpoptMcp, SolvedStartNeedsNoIpoptRun) {
  const FunctionMCP mcp = JosephyMcp();
  SolverOptions o;
  o.warm_start.resize(4);
  o.warm_start << std::sqrt(6.0) / 2, 0, 0, 0.5;
  IpoptQpSolver solver;
  const SolveResult r = solver.Solve(mcp, o);
  ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
  EXPECT_EQ(r.iterations, 0);
  EXPECT_EQ(kIpoptMcpEarlyStopDetail.Get(r), IpoptMcpEarlyStop::kSolvedAtStart);
}

TEST(IpoptMcp, InvalidMcpOptionsAreRefused) {
  IpoptQpSolver solver;
  std::string error;
  EXPECT_FALSE(solver.SetOption("mcp_newton_steps", "-1", &error));
  EXPECT_NE(error.find("mcp_newton_steps"), std::string::npos) << error;
  EXPECT_FALSE(solver.SetOption("mcp_hessian", "exact", &error));
  EXPECT_TRUE(solver.SetOption("mcp_hessian", "limited-memory", &error)) << error;
}

}  // namespace
}  // namespace smcbench

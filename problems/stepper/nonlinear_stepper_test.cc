// Tests of the nonlinear time-stepper (classes (3) and (4), `eq:toto1`): the one-step MCP and its Jacobian, Lemma
// (youpi) on S9, finite-time arrival on S10, Algorithm 1 (MCP) against Algorithm 2 (Newton + MLCP) with every
// backend, agreement with the linear stepper on class-(2) systems, Newton failure reporting and bad input.
// Residuals and closed forms are recomputed here, never taken from the stepper's own statuses.
// The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "problems/stepper/linear_stepper.h"
#include "problems/stepper/metrics.h"
#include "problems/stepper/nonlinear_scenes.h"
#include "problems/stepper/nonlinear_stepper.h"
#include "problems/stepper/stepper_test_util.h"
#include "problems/stepper/streaming_test_util.h"
#include "problems/stepper/trajectory.h"
#include "solvers/registry/registry.h"
#include "solvers/siconos/external_backends.h"
#include "tests/support/malloc_counter.h"

namespace smcbench {
namespace {

using stepper_test::Mat;
using stepper_test::Vec;

double Sign(double v) { return v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0); }

NonlinearStepperOptions Options(NonlinearAlgorithm algorithm, double tol = 1e-12) {
  NonlinearStepperOptions o;
  o.algorithm = algorithm;
  o.newton_tolerance = tol;
  o.stepper.solver.tolerance = tol;
  return o;
}

// A 2-D class-(4) system with everything nonlinear (pendulum-like f, state-dependent g, nonlinear surfaces), m = 2.
NonlinearSignSystem Nonlinear2D() {
  NonlinearSignSystem s;
  s.n = 2;
  s.m = 2;
  s.f = [](double t, const Vector& x, Eigen::Ref<Vector> f) {
    f[0] = x[1];
    f[1] = -std::sin(x[0]) + 0.1 * std::cos(t);
  };
  s.f_jacobian = [](double, const Vector& x, Eigen::Ref<DenseMatrix> J) {
    J << 0.0, 1.0, -std::cos(x[0]), 0.0;
  };
  // g(x) = [[1 + 0.2 x1², 0.1], [0.1 x2, 1 + 0.1 x1 x2]]
  s.g = [](const Vector& x, Eigen::Ref<DenseMatrix> G) {
    G << 1.0 + 0.2 * x[0] * x[0], 0.1, 0.1 * x[1], 1.0 + 0.1 * x[0] * x[1];
  };
  // (∇g·s)_{kp} = Σ_l ∂g_kl/∂x_p s_l
  s.g_jacobian_s = [](const Vector& x, const Vector& sv, Eigen::Ref<DenseMatrix> J) {
    J(0, 0) = 0.4 * x[0] * sv[0];
    J(0, 1) = 0.0;
    J(1, 0) = 0.1 * x[1] * sv[1];
    J(1, 1) = 0.1 * sv[0] + 0.1 * x[0] * sv[1];
  };
  // h(x) = (x1 + x2 + 0.1 x1³, x2 + 0.2 sin x1)
  s.h = [](const Vector& x, Eigen::Ref<Vector> y) {
    y[0] = x[0] + x[1] + 0.1 * x[0] * x[0] * x[0];
    y[1] = x[1] + 0.2 * std::sin(x[0]);
  };
  s.h_jacobian = [](const Vector& x, Eigen::Ref<DenseMatrix> H) {
    H << 1.0 + 0.3 * x[0] * x[0], 1.0, 0.2 * std::cos(x[0]), 1.0;
  };
  return s;
}

// Natural residual of the one-step MCP `eq:MCP3` recomputed from scratch (not through OneStepMCP), for steps
// k → k+1 of a recorded trajectory of x' ∈ f − g Sgn(h): max over the x rows of |R| and over the s rows of
// |s − Π_[−1,1](s + h(x))|.
double IndependentStepResidual(const NonlinearSignSystem& sys, const NonlinearScheme& sc, const Trajectory& tr,
                               std::int64_t k) {
  const int n = sys.n, m = sys.m;
  const Vector xk = tr.x.col(k), x = tr.x.col(k + 1), s = tr.s.col(k + 1);
  const Vector xt = sc.theta * x + (1 - sc.theta) * xk, xg = sc.gamma * x + (1 - sc.gamma) * xk;
  Vector f = Vector::Zero(n), y(m);
  DenseMatrix G(n, m);
  if (sys.f) sys.f(tr.t[k] + sc.theta * sc.h, xt, f);
  sys.g(xg, G);
  sys.h(x, y);
  const Vector R = (1 + sc.h * sc.rho) * (x - xk) - sc.h * f + sc.h * G * s;
  double r = R.cwiseAbs().maxCoeff();
  for (int i = 0; i < m; ++i) r = std::max(r, std::abs(s[i] - std::clamp(s[i] + y[i], -1.0, 1.0)));
  return r;
}

// ------------------------------------------------------------------------------------------------------------
// The one-step MCP

TEST(OneStepMCP, JacobianMatchesCentralDifferences) {
  NonlinearScheme sc;
  sc.h = 0.1, sc.theta = 0.7, sc.gamma = 0.4, sc.rho = 0.3;
  OneStepMCP mcp(Nonlinear2D(), sc);
  mcp.SetStep(0.3, Vec({0.4, -0.2}));
  const Vector z = Vec({0.35, -0.1, 0.3, -0.6});
  DenseMatrix J;
  mcp.JacobianDense(z, &J);
  ASSERT_EQ(J.rows(), 4);
  DenseMatrix Jfd(4, 4);
  Vector Fp(4), Fm(4);
  for (int j = 0; j < 4; ++j) {
    const double eps = 1e-6;
    Vector zp = z, zm = z;
    zp[j] += eps, zm[j] -= eps;
    mcp.Evaluate(zp, &Fp);
    mcp.Evaluate(zm, &Fm);
    Jfd.col(j) = (Fp - Fm) / (2 * eps);
  }
  EXPECT_LT((J - Jfd).cwiseAbs().maxCoeff(), 1e-8) << "J=\n" << J << "\nFD=\n" << Jfd;
  // The lower-left block is −∇h (the report's `eq:JacMCLP` prints +∇h).
  EXPECT_LT(J(2, 0), 0.0);
  EXPECT_TRUE(J.bottomRightCorner(2, 2).isZero(0.0));
  // Bounds: x free, s ∈ [−1, 1].
  EXPECT_EQ(mcp.l()[0], -kInf);
  EXPECT_EQ(mcp.u()[1], kInf);
  EXPECT_EQ(mcp.l()[2], -1.0);
  EXPECT_EQ(mcp.u()[3], 1.0);
}

TEST(OneStepMCP, ResidualIsTheTimeStepOfTheScheme) {
  // F's x block at (x_{k+1}, s) is (1 + hρ)(x_{k+1} − x_k) − h f(x_{k+θ}, t_{k+θ}) + h g(x_{k+γ}) s, with
  // t_{k+θ} = θ t_{k+1} + (1 − θ) t_k (not the report's t_{k+1}): check with f = t (∇f = 0).
  NonlinearSignSystem s = ToNonlinear([] {
    AffineGainSignSystem a;
    a.B = Mat({{0.0}});
    a.C = Mat({{1.0}});
    a.forcing = [](double t, Eigen::Ref<Vector> g) { g[0] = t; };
    return a;
  }());
  NonlinearScheme sc;
  sc.h = 0.5, sc.theta = 0.25, sc.gamma = 1.0;
  OneStepMCP mcp(s, sc);
  mcp.SetStep(2.0, Vec({1.0}));
  Vector F(2);
  mcp.Evaluate(Vec({1.0, 0.0}), &F);
  EXPECT_DOUBLE_EQ(F[0], -0.5 * (2.0 + 0.25 * 0.5));  // −h f(t_{k+θ}) with t_{k+θ} = 2.125
  EXPECT_DOUBLE_EQ(F[1], -1.0);
}

// ------------------------------------------------------------------------------------------------------------
// S9 `hypomonotone`: Lemma (youpi)

// Runs S9 from x0 with step h (ρ = 0) and checks the lemma on the recorded trajectory:
// (a) while |x_k| > h the step is the closed form `eq:solu-hypo1` x_{k+1} = (x_k − h sgn x_k)/(1 + h sgn x_k),
//     s_{k+1} = sgn x_k (to 1e-14: Lemke returns 1 − 6ε on an upper bound), x_{k+1} to 1e-14 relative;
// (b) the first k₀ with |x_k₀| ≤ h is followed by x_{k₀+1} = 0 with s_{k₀+1} = x_k₀/h, and x stays at 0 with a
//     zero discrete derivative. "0" means: within a few ulps of |x_k₀| + h for Algorithm 2 (the Newton iterate
//     x_k − W s with s = x_k/W, and s from a pivoting backend, are not bit-exact), or within zero_tol for a
//     backend that stops at its tolerance (Algorithm 1's semismooth Newton). Returns k₀.
struct YoupiStats {
  double max_closed_form_rel = 0.0;   // max |x_{k+1} − closed form| / |closed form|
  double max_abs_x_at_rest = 0.0;     // max |x_k| after arrival
  long rest_steps = 0, exact_zero_steps = 0;
};

std::int64_t CheckLemmaYoupi(const Trajectory& tr, double h, double x0, double zero_tol = 0.0,
                             YoupiStats* stats = nullptr) {
  YoupiStats local;
  YoupiStats& st = stats ? *stats : local;
  std::int64_t k0 = -1;
  double last_nonzero = std::abs(x0);
  for (std::int64_t k = 0; k < tr.steps_taken; ++k) {
    const double xk = tr.x(0, k), xn = tr.x(0, k + 1), sn = tr.s(0, k + 1);
    if (k0 < 0 && std::abs(xk) > h) {
      const double sg = Sign(xk);
      const double closed = (xk - h * sg) / (1.0 + h * sg);
      EXPECT_NEAR(xn, closed, 1e-14 * std::abs(closed)) << "step " << k + 1 << " from x_k = " << xk;
      st.max_closed_form_rel = std::max(st.max_closed_form_rel, std::abs(xn - closed) / std::abs(closed));
      EXPECT_NEAR(sn, sg, 1e-14) << "step " << k + 1;
      last_nonzero = std::abs(xn);
    } else {
      if (k0 < 0) {
        k0 = k;
        EXPECT_NEAR(sn, xk / h, 1e-12) << "s_{k0+1} = x_k0 / h";
      }
      st.max_abs_x_at_rest = std::max(st.max_abs_x_at_rest, std::abs(xn));
      ++st.rest_steps;
      st.exact_zero_steps += xn == 0.0;
      EXPECT_LE(std::abs(xn), std::max(zero_tol, 4 * std::numeric_limits<double>::epsilon() * (last_nonzero + h)))
          << "x_" << k + 1 << " after arrival at step " << k0 + 1;
      if (k > k0) { EXPECT_LE(std::abs(sn), std::max(1e-12, zero_tol / h)) << "s_" << k + 1 << " at rest"; }
    }
  }
  return k0;
}

// k₀ predicted by iterating the closed form from x0.
std::int64_t PredictedK0(double x0, double h) {
  double x = x0;
  std::int64_t k = 0;
  while (std::abs(x) > h) {
    const double sg = Sign(x);
    x = (x - h * sg) / (1.0 + h * sg);
    ++k;
  }
  return k;
}

TEST(LemmaYoupi, ClosedFormStepsThenRestAtZeroWithAlgorithm2) {
  stepper_test::ReferenceSolver reference;
  auto lemke = CreateSolver("lemke");
  for (Solver* solver : {static_cast<Solver*>(&reference), lemke.get()}) {
    YoupiStats stats;
    for (double h : {0.01, 0.05, 0.1, 0.3, 0.5, 0.9}) {
      for (double x0 : {1.5, 3.0, -0.5, -0.95, 0.05}) {
        SCOPED_TRACE(std::string(solver->info().name) + " h=" + std::to_string(h) + " x0=" + std::to_string(x0));
        NonlinearScene scene = HypomonotoneScene();
        scene.scheme.h = h;
        NonlinearStepper stepper(scene.system, scene.scheme);
        const std::int64_t N = PredictedK0(x0, h) + 20;
        const Trajectory tr = stepper.Run(Vec({x0}), N, solver, Options(NonlinearAlgorithm::kNewtonMlcp));
        ASSERT_TRUE(tr.ok()) << tr.first_failure_message;
        EXPECT_EQ(CheckLemmaYoupi(tr, h, x0, 0.0, &stats), PredictedK0(x0, h));
      }
    }
    std::printf("[ info     ] Lemma youpi, Algorithm 2 with %s: closed form to %.1e relative; %ld of %ld steps at "
                "rest exactly 0, max |x| at rest %.1e\n",
                std::string(solver->info().name).c_str(), stats.max_closed_form_rel, stats.exact_zero_steps,
                stats.rest_steps, stats.max_abs_x_at_rest);
  }
}

TEST(LemmaYoupi, ClosedFormStepsThenRestAtZeroWithAlgorithm1) {
  auto newton = CreateSolver("newton");
  YoupiStats stats;
  for (double h : {0.05, 0.1, 0.5, 0.9}) {
    for (double x0 : {1.5, -0.5}) {
      SCOPED_TRACE("h=" + std::to_string(h) + " x0=" + std::to_string(x0));
      NonlinearScene scene = HypomonotoneScene();
      scene.scheme.h = h;
      NonlinearStepper stepper(scene.system, scene.scheme);
      const std::int64_t N = PredictedK0(x0, h) + 20;
      const Trajectory tr = stepper.Run(Vec({x0}), N, newton.get(), Options(NonlinearAlgorithm::kMcp, 1e-14));
      ASSERT_TRUE(tr.ok()) << tr.first_failure_message;
      // The backend stops at relative natural residual 1e-14 (scale 1 + |x_k|): x_{k+1} = 0 to that tolerance.
      EXPECT_EQ(CheckLemmaYoupi(tr, h, x0, 1e-14 * (1 + std::abs(x0)), &stats), PredictedK0(x0, h));
    }
  }
  std::printf("[ info     ] Lemma youpi, Algorithm 1 (newton, tol 1e-14): closed form to %.1e relative; %ld of %ld "
              "steps at rest exactly 0, max |x| at rest %.1e\n",
              stats.max_closed_form_rel, stats.exact_zero_steps, stats.rest_steps, stats.max_abs_x_at_rest);
}

TEST(LemmaYoupi, FailsForInitialStatesBelowMinusOne) {
  // The lemma claims arrival "for all x0 ∈ R"; for x0 < −1 the gain x + 1 of the sign is negative and both the
  // inclusion (x' = x + 1) and the scheme diverge: x_{k+1} = (x_k + h)/(1 − h) < x_k is the step's unique solution.
  stepper_test::ReferenceSolver reference;
  NonlinearScene scene = HypomonotoneScene();
  NonlinearStepper stepper(scene.system, scene.scheme);
  const Trajectory tr = stepper.Run(Vec({-1.5}), 30, &reference, Options(NonlinearAlgorithm::kNewtonMlcp));
  ASSERT_TRUE(tr.ok()) << tr.first_failure_message;
  for (std::int64_t k = 0; k < 30; ++k) {
    const double closed = (tr.x(0, k) + 0.1) / (1.0 - 0.1);
    EXPECT_NEAR(tr.x(0, k + 1), closed, 1e-14 * std::abs(closed));
    EXPECT_LT(tr.x(0, k + 1), tr.x(0, k));
  }
  // x0 = −1 is an equilibrium of both.
  const Trajectory rest = stepper.Run(Vec({-1.0}), 10, &reference, Options(NonlinearAlgorithm::kNewtonMlcp));
  ASSERT_TRUE(rest.ok());
  EXPECT_NEAR(rest.x_final[0], -1.0, 1e-15);
}

TEST(LemmaYoupi, RhoShiftStillArrivesAndStays) {
  // `neuf` with ρ ≥ 1: (1 + hρ)(x_{k+1} − x_k) = −h(x_{k+1} + 1)s_{k+1}. Arrival once |x_k| ≤ h/(1 + hρ), where
  // s = (1 + hρ)x_k/h; before that x_{k+1} = ((1 + hρ)x_k − h sgn x_k)/(1 + hρ + h sgn x_k).
  stepper_test::ReferenceSolver reference;
  auto newton = CreateSolver("newton");
  for (double rho : {1.0, 2.0}) {
    for (double h : {0.1, 0.5, 2.0}) {  // ρ ≥ 1 makes the step strongly monotone even for h ≥ 1
      SCOPED_TRACE("rho=" + std::to_string(rho) + " h=" + std::to_string(h));
      NonlinearScene scene = HypomonotoneScene(rho);
      scene.scheme.h = h;
      NonlinearStepper stepper(scene.system, scene.scheme);
      const Trajectory tr = stepper.Run(Vec({1.5}), 60, &reference, Options(NonlinearAlgorithm::kNewtonMlcp));
      ASSERT_TRUE(tr.ok()) << tr.first_failure_message;
      const double a = 1.0 + h * rho;
      bool arrived = false;
      for (std::int64_t k = 0; k < 60; ++k) {
        const double xk = tr.x(0, k), xn = tr.x(0, k + 1);
        if (!arrived && std::abs(xk) > h / a) {
          const double closed = (a * xk - h * Sign(xk)) / (a + h * Sign(xk));
          EXPECT_NEAR(xn, closed, 1e-14 * std::abs(closed)) << "step " << k + 1;
        } else {
          arrived = true;
          EXPECT_LE(std::abs(xn), 1e-15) << "step " << k + 1;
        }
      }
      EXPECT_TRUE(arrived);
      const Trajectory tr1 = stepper.Run(Vec({1.5}), 60, newton.get(), Options(NonlinearAlgorithm::kMcp));
      ASSERT_TRUE(tr1.ok()) << tr1.first_failure_message;
      EXPECT_LT((tr1.x - tr.x).cwiseAbs().maxCoeff(), 1e-9);
    }
  }
}

// ------------------------------------------------------------------------------------------------------------
// S10 `arctan`

TEST(Arctan, ReachesZeroInFiniteTimeAndStays) {
  const NonlinearScene scene = ArctanScene();
  const double h = scene.scheme.h;
  NonlinearStepper stepper(scene.system, scene.scheme);
  stepper_test::ReferenceSolver reference;
  auto newton = CreateSolver("newton");
  std::int64_t arrivals[2] = {-1, -1};
  for (NonlinearAlgorithm algorithm : {NonlinearAlgorithm::kNewtonMlcp, NonlinearAlgorithm::kMcp}) {
    SCOPED_TRACE(std::string(ToString(algorithm)));
    const bool mcp = algorithm == NonlinearAlgorithm::kMcp;
    Solver* solver = mcp ? newton.get() : static_cast<Solver*>(&reference);
    const double tol = 1e-12;
    const Trajectory tr = stepper.Run(scene.x0, scene.num_steps(), solver, Options(algorithm, tol));
    ASSERT_TRUE(tr.ok()) << tr.first_failure_message;
    ASSERT_EQ(tr.steps_taken, 200);
    // Every step solves its one-step problem (recomputed independently; scale 1 + |x_k| ≤ 3).
    for (std::int64_t k = 0; k < tr.steps_taken; ++k) {
      EXPECT_LE(IndependentStepResidual(scene.system, scene.scheme, tr, k), 3 * tol) << "step " << k + 1;
    }
    // What "0" means: Algorithm 2 lands within ulps (s = x_k/W, x = x_k − W s); Algorithm 1's semismooth Newton
    // stops once the residual is ≤ tol, so x is 0 to ~tol and s, whose residual is h g(x) s in the x row, to
    // ~tol/h.
    const double x_zero = mcp ? 3 * tol : 1e-15, s_zero = mcp ? 3 * tol / h : 1e-12;
    std::int64_t arrival = -1;
    for (std::int64_t k = 0; k <= tr.steps_taken && arrival < 0; ++k) {
      if (std::abs(tr.x(0, k)) <= x_zero) arrival = k;
    }
    ASSERT_GT(arrival, 0);
    arrivals[mcp] = arrival;
    // As in Lemma youpi: x lands on 0 on the step after the first |x_k| ≤ h g(0) = h (s = x_k/h there).
    EXPECT_LE(std::abs(tr.x(0, arrival - 1)), h);
    EXPECT_GT(std::abs(tr.x(0, arrival - 2)), h);
    EXPECT_NEAR(tr.s(0, arrival), tr.x(0, arrival - 1) / h, 1e-10);
    // The exact solution reaches 0 at t* = 14/3.
    const double t_arrival = tr.t[arrival];
    EXPECT_NEAR(t_arrival, 14.0 / 3.0, h) << "arrival step " << arrival;
    for (std::int64_t k = arrival; k <= tr.steps_taken; ++k) {
      EXPECT_LE(std::abs(tr.x(0, k)), x_zero) << "x_" << k;
      if (k > arrival) {
        EXPECT_LE(std::abs(tr.s(0, k)), s_zero) << "s_" << k;
        EXPECT_LE(std::abs(tr.x(0, k) - tr.x(0, k - 1)) / h, 2 * x_zero / h) << "discrete derivative at " << k;
      }
    }
    // Before arrival s = 1 (to an ulp) on every step.
    for (std::int64_t k = 1; k < arrival; ++k) EXPECT_NEAR(tr.s(0, k), 1.0, 1e-15) << "s_" << k;
    // Error against the exact solution.
    const SolutionErrors e = ComputeErrors(tr, scene.exact(scene.x0));
    ASSERT_TRUE(e.x.has_value());
    std::printf("[ info     ] arctan %s: arrival step %lld (t = %.4f, exact %.4f), max |x| after %.1e, "
                "x error max %.3e L1 %.3e L2 %.3e\n",
                std::string(ToString(algorithm)).c_str(), static_cast<long long>(arrival), t_arrival, 14.0 / 3.0,
                tr.x.row(0).tail(tr.steps_taken + 1 - arrival).cwiseAbs().maxCoeff(), e.x->max, e.x->l1, e.x->l2);
    EXPECT_LT(e.x->max, 0.05);
  }
  EXPECT_EQ(arrivals[0], arrivals[1]);
}

TEST(Hypomonotone, FirstOrderAgainstTheExactSolution) {
  // Not a claim of the report; measured for the record (and so a regression in the scheme shows up as an order).
  stepper_test::ReferenceSolver reference;
  double previous = 0.0;
  for (double h : {0.1, 0.05, 0.025, 0.0125}) {
    NonlinearScene scene = HypomonotoneScene();
    scene.scheme.h = h;
    NonlinearStepper stepper(scene.system, scene.scheme);
    const Trajectory tr = stepper.Run(scene.x0, NumSteps(scene.T, h), &reference,
                                      Options(NonlinearAlgorithm::kNewtonMlcp));
    ASSERT_TRUE(tr.ok());
    const SolutionErrors e = ComputeErrors(tr, scene.exact(scene.x0));
    std::printf("[ info     ] hypomonotone h=%-7g x error max %.3e L1 %.3e L2 %.3e\n", h, e.x->max, e.x->l1,
                e.x->l2);
    if (previous > 0.0) { EXPECT_NEAR(std::log2(previous / e.x->max), 1.0, 0.25); }
    previous = e.x->max;
  }
}

// ------------------------------------------------------------------------------------------------------------
// Algorithm 1 against Algorithm 2, every backend

struct Scenario {
  std::string name;
  NonlinearSignSystem system;
  NonlinearScheme scheme;
  Vector x0;
  std::int64_t steps;
};

std::vector<Scenario> Scenarios() {
  std::vector<Scenario> out;
  const NonlinearScene s9 = HypomonotoneScene();
  out.push_back({"S9 hypomonotone", s9.system, s9.scheme, s9.x0, s9.num_steps()});
  const NonlinearScene s9r = HypomonotoneScene(1.0);
  out.push_back({"S9 hypomonotone rho=1", s9r.system, s9r.scheme, s9r.x0, s9r.num_steps()});
  const NonlinearScene s10 = ArctanScene();
  out.push_back({"S10 arctan", s10.system, s10.scheme, s10.x0, s10.num_steps()});
  NonlinearScheme half = s10.scheme;
  half.theta = 0.5, half.gamma = 0.5;
  out.push_back({"S10 arctan theta=gamma=1/2", s10.system, half, s10.x0, s10.num_steps()});
  NonlinearScheme sc2;
  sc2.h = 0.05, sc2.theta = 1.0, sc2.gamma = 1.0;
  out.push_back({"2-D class (4), m = 2", Nonlinear2D(), sc2, Vec({1.0, 0.5}), 100});
  return out;
}

TEST(Algorithms, McpAndNewtonMlcpAgreeWithEveryBackend) {
  auto newton = CreateSolver("newton");
  for (const Scenario& sc : Scenarios()) {
    NonlinearStepper stepper(sc.system, sc.scheme);
    const Trajectory a1 = stepper.Run(sc.x0, sc.steps, newton.get(), Options(NonlinearAlgorithm::kMcp));
    ASSERT_TRUE(a1.ok()) << sc.name << ": " << a1.first_failure_message;
    for (std::int64_t k = 0; k < a1.steps_taken; ++k) {
      ASSERT_LE(IndependentStepResidual(sc.system, sc.scheme, a1, k), 1e-10) << sc.name << " step " << k + 1;
    }
    for (std::string_view name : SolverNames()) {
      if (IsExternalBackend(name)) continue;
      SCOPED_TRACE(sc.name + " / " + std::string(name));
      auto solver = CreateSolver(name);
      const Trajectory a2 = stepper.Run(sc.x0, sc.steps, solver.get(), Options(NonlinearAlgorithm::kNewtonMlcp));
      const NewtonStats& stats = stepper.newton_stats();
      std::printf("[ info     ] %-28s %-7s %s: Newton iterations total %lld max %d, backend iterations %lld, "
                  "max residual %.1e, max |x1 - x2| %.1e\n",
                  sc.name.c_str(), std::string(name).c_str(), a2.ok() ? "ok" : "FAILED",
                  static_cast<long long>(stats.total_iterations), stats.max_iterations,
                  static_cast<long long>(a2.total_iterations), a2.max_residual,
                  a2.ok() ? (a2.x - a1.x).cwiseAbs().maxCoeff() : NAN);
      ASSERT_TRUE(a2.ok()) << a2.first_failure_message;
      EXPECT_LT((a2.x - a1.x).cwiseAbs().maxCoeff(), 1e-9);
      EXPECT_LT((a2.s - a1.s).cwiseAbs().maxCoeff(), 1e-9);
      EXPECT_LT((a2.y - a1.y).cwiseAbs().maxCoeff(), 1e-9);
      for (std::int64_t k = 0; k < a2.steps_taken; ++k) {
        ASSERT_LE(IndependentStepResidual(sc.system, sc.scheme, a2, k), 1e-10) << "step " << k + 1;
      }
    }
  }
}

// ------------------------------------------------------------------------------------------------------------
// Class (2) as class (3) with A = 0: the nonlinear path must reproduce the linear stepper.

TEST(ClassThree, WithZeroAReproducesTheLinearStepper) {
  struct Case {
    const char* name;
    LinearSignSystem linear;
    Vector x0;
    double h, theta;
    std::int64_t steps;
  };
  const Case cases[] = {
      {"S2 galias-yu theta=1", stepper_test::GaliasYuScene(), Vec({0.0, 2.21}), 0.1, 1.0, 100},
      {"S2 galias-yu theta=1/2", stepper_test::GaliasYuScene(), Vec({0.0, 2.21}), 0.3, 0.5, 30},
      {"S3 multi-surface", stepper_test::MultiSurfaceScene(), Vec({1.0, -1.0}), 0.02, 1.0, 75},
      {"S7 lyapunov (forcing)", stepper_test::LyapunovScene(), Vec({1.0}), 0.1, 1.0, 100},
      {"S8 observer tau=0.5", stepper_test::ObserverScene(0.5), Vec({2.0, 0.0, 0.0, 0.0}), 0.1, 1.0, 100},
  };
  stepper_test::ReferenceSolver reference;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const Trajectory lin = LinearStepper(DiscretizeTheta(c.linear, c.h, c.theta, SignTreatment::kImplicit))
                               .Run(c.x0, c.steps, &reference, StepperOptions{});
    ASSERT_TRUE(lin.ok());
    AffineGainSignSystem a;
    a.E = c.linear.E;
    a.B = c.linear.B;
    a.C = c.linear.C;
    a.forcing = c.linear.forcing;
    NonlinearScheme sc;
    sc.h = c.h, sc.theta = c.theta, sc.gamma = 1.0;
    NonlinearStepper stepper(ToNonlinear(a), sc);
    const Trajectory nl = stepper.Run(c.x0, c.steps, &reference, Options(NonlinearAlgorithm::kNewtonMlcp));
    ASSERT_TRUE(nl.ok()) << nl.first_failure_message;
    EXPECT_LT((nl.x - lin.x).cwiseAbs().maxCoeff(), 1e-10);
    EXPECT_LT((nl.s - lin.s).cwiseAbs().maxCoeff(), 1e-9);
    // Affine f, constant g: R is affine in (x, s), so one Newton iteration solves every step (`Sec:Spec`).
    EXPECT_LE(stepper.newton_stats().max_iterations, 1);
  }
}

// ------------------------------------------------------------------------------------------------------------
// The explicit sign

TEST(ExplicitSign, SemiExplicitEulerIsTheClosedFormAndChatters) {
  NonlinearScene scene = HypomonotoneScene();
  scene.scheme.sign = SignTreatment::kExplicit;
  scene.scheme.theta = scene.scheme.gamma = 0.0;
  NonlinearStepper stepper(scene.system, scene.scheme);
  const Trajectory tr = stepper.Run(scene.x0, 40, nullptr, Options(NonlinearAlgorithm::kNewtonMlcp));
  ASSERT_TRUE(tr.ok()) << tr.first_failure_message;
  const double h = scene.scheme.h;
  int sign_changes = 0;
  for (std::int64_t k = 0; k < 40; ++k) {
    const double xk = tr.x(0, k);
    // x_{k+1} = x_k − h (x_k + 1) sgn(x_k): one Newton iteration of the linear step equation, exact up to rounding.
    EXPECT_NEAR(tr.x(0, k + 1), xk - h * (xk + 1.0) * Sign(xk), 1e-15);
    EXPECT_EQ(tr.s(0, k + 1), Sign(xk));
    if (k > 0 && tr.s(0, k + 1) * tr.s(0, k) < 0) ++sign_changes;
  }
  EXPECT_LE(stepper.newton_stats().max_iterations, 1);
  // It never rests: around 0 it oscillates with amplitude ~h.
  EXPECT_GT(sign_changes, 20);
  EXPECT_GT(tr.x.row(0).tail(10).cwiseAbs().maxCoeff(), 0.2 * h);
  // Fully implicit state with explicit sign: x_{k+1} = (x_k − h s)/(1 + h s), s = sgn(x_k), by Newton.
  scene.scheme.theta = scene.scheme.gamma = 1.0;
  NonlinearStepper implicit_state(scene.system, scene.scheme);
  const Trajectory tr2 = implicit_state.Run(scene.x0, 40, nullptr, Options(NonlinearAlgorithm::kNewtonMlcp));
  ASSERT_TRUE(tr2.ok()) << tr2.first_failure_message;
  for (std::int64_t k = 0; k < 40; ++k) {
    const double xk = tr2.x(0, k), sg = Sign(xk);
    EXPECT_NEAR(tr2.x(0, k + 1), (xk - h * sg) / (1.0 + h * sg), 1e-14);
  }
}

// ------------------------------------------------------------------------------------------------------------
// Failures are statuses with the step index

TEST(Failures, NewtonIterationLimitIsReportedWithTheStep) {
  const NonlinearScene scene = HypomonotoneScene();
  NonlinearStepper stepper(scene.system, scene.scheme);
  stepper_test::ReferenceSolver reference;
  NonlinearStepperOptions o = Options(NonlinearAlgorithm::kNewtonMlcp);
  o.newton_max_iterations = 1;
  // Step 1 starts Newton from (x_0, s_0 = 0): the first MLCP switches s to 1, x^1 is not yet the step's solution
  // (the bilinear term h x s needs a second iteration).
  const Trajectory tr = stepper.Run(scene.x0, scene.num_steps(), &reference, o);
  EXPECT_FALSE(tr.ok());
  EXPECT_TRUE(tr.stopped_early);
  EXPECT_EQ(tr.first_failed_step, 1);
  EXPECT_EQ(tr.steps_taken, 1);
  EXPECT_EQ(tr.first_failure_status, SolveStatus::kIterationLimit);
  EXPECT_EQ(tr.status[1], SolveStatus::kIterationLimit);
  EXPECT_GT(tr.first_failure_residual, o.newton_tolerance);
  EXPECT_NE(tr.first_failure_message.find("step 1"), std::string::npos) << tr.first_failure_message;
  EXPECT_NE(tr.first_failure_message.find("1 iteration"), std::string::npos) << tr.first_failure_message;
  // Continue past failures: the run completes and counts them; the steps that need one iteration only (s_k
  // already right and x affine in the step) pass.
  o.stepper.on_failure = FailurePolicy::kContinue;
  const Trajectory all = stepper.Run(scene.x0, scene.num_steps(), &reference, o);
  EXPECT_EQ(all.steps_taken, scene.num_steps());
  EXPECT_EQ(all.first_failed_step, 1);
  EXPECT_GT(all.failed_steps, 0);
  EXPECT_LT(all.failed_steps, all.steps_taken);
}

TEST(Failures, BackendFailureIsReportedWithTheStepAndIteration) {
  // Algorithm 1 with a backend that does not solve MCPs: kNotApplicable at step 1.
  const NonlinearScene scene = ArctanScene();
  NonlinearStepper stepper(scene.system, scene.scheme);
  auto lemke = CreateSolver("lemke");
  const Trajectory tr = stepper.Run(scene.x0, 10, lemke.get(), Options(NonlinearAlgorithm::kMcp));
  EXPECT_EQ(tr.first_failed_step, 1);
  EXPECT_EQ(tr.first_failure_status, SolveStatus::kNotApplicable);
  EXPECT_NE(tr.first_failure_message.find("step 1"), std::string::npos) << tr.first_failure_message;
  // Algorithm 2 with PSOR allowed 1 sweep at tolerance 1e-14, polish off (the exact polish would finish the job
  // PSOR's one sweep started): the MLCP of some step is not solved.
  auto psor = CreateSolver("psor");
  NonlinearStepperOptions o = Options(NonlinearAlgorithm::kNewtonMlcp, 1e-14);
  o.stepper.solver.max_iterations = 1;
  o.stepper.solver.polish = false;
  NonlinearStepper s2(Nonlinear2D(), [] {
    NonlinearScheme sc;
    sc.h = 0.05;
    return sc;
  }());
  const Trajectory tr2 = s2.Run(Vec({1.0, 0.5}), 100, psor.get(), o);
  ASSERT_FALSE(tr2.ok());
  EXPECT_GE(tr2.first_failed_step, 1);
  EXPECT_NE(tr2.first_failure_message.find("step " + std::to_string(tr2.first_failed_step) + ", Newton iteration"),
            std::string::npos)
      << tr2.first_failure_message;
  EXPECT_NE(tr2.first_failure_message.find("psor"), std::string::npos);
}

TEST(Failures, SingularNewtonMatrixIsKSingular) {
  // g(x) = x + 4 (A = 1, B = 4), h = γ = 1: M_α = 1 + hγ A s^α vanishes once s^α = −1. From x0 = −3 the first
  // MLCP (W = 1, b = −3) gives s^1 = −1, x^1 = −2, which does not solve the step; the second linearization is
  // singular.
  AffineGainSignSystem a;
  a.A = {Mat({{1.0}})};
  a.B = Mat({{4.0}});
  a.C = Mat({{1.0}});
  NonlinearScheme sc;
  sc.h = 1.0;
  NonlinearStepper stepper(ToNonlinear(a), sc);
  stepper_test::ReferenceSolver reference;
  const Trajectory tr = stepper.Run(Vec({-3.0}), 5, &reference, Options(NonlinearAlgorithm::kNewtonMlcp));
  ASSERT_FALSE(tr.ok());
  EXPECT_EQ(tr.first_failed_step, 1);
  EXPECT_EQ(tr.first_failure_status, SolveStatus::kSingular) << tr.first_failure_message;
  EXPECT_NE(tr.first_failure_message.find("step 1, Newton iteration 2"), std::string::npos)
      << tr.first_failure_message;
  EXPECT_NE(tr.first_failure_message.find("singular"), std::string::npos);
}

// ------------------------------------------------------------------------------------------------------------
// Bad input names the field

template <typename Fn>
std::string ErrorOf(Fn&& fn) {
  try {
    fn();
  } catch (const InvalidInputError& e) {
    return e.what();
  }
  return "<no InvalidInputError>";
}

TEST(BadInput, SchemeFieldsAreNamed) {
  const NonlinearScene scene = HypomonotoneScene();
  const auto with = [&](auto mutate) {
    NonlinearScheme sc = scene.scheme;
    mutate(sc);
    return ErrorOf([&] { NonlinearStepper(scene.system, sc); });
  };
  EXPECT_NE(with([](NonlinearScheme& s) { s.h = 0.0; }).find("h must be"), std::string::npos);
  EXPECT_NE(with([](NonlinearScheme& s) { s.h = -0.1; }).find("h must be"), std::string::npos);
  EXPECT_NE(with([](NonlinearScheme& s) { s.h = NAN; }).find("h must be"), std::string::npos);
  EXPECT_NE(with([](NonlinearScheme& s) { s.theta = 1.5; }).find("theta"), std::string::npos);
  EXPECT_NE(with([](NonlinearScheme& s) { s.theta = -0.1; }).find("theta"), std::string::npos);
  EXPECT_NE(with([](NonlinearScheme& s) { s.gamma = 2.0; }).find("gamma"), std::string::npos);
  EXPECT_NE(with([](NonlinearScheme& s) { s.gamma = NAN; }).find("gamma"), std::string::npos);
  EXPECT_NE(with([](NonlinearScheme& s) { s.rho = -1.0; }).find("rho"), std::string::npos);
}

TEST(BadInput, SystemAndRunArgumentsAreNamed) {
  AffineGainSignSystem a;
  a.A = {Mat({{1.0, 0.0}})};  // 1x2 but n = 1
  a.B = Mat({{1.0}});
  a.C = Mat({{1.0}});
  EXPECT_NE(ErrorOf([&] { ToNonlinear(a); }).find("A[0] is 1x2 but must be 1x1"), std::string::npos);
  a.A = {Mat({{1.0}}), Mat({{1.0}})};  // two A_i, m = 1
  EXPECT_NE(ErrorOf([&] { ToNonlinear(a); }).find("A holds 2 matrices"), std::string::npos);
  a.A = {Mat({{1.0}})};
  a.C = Mat({{1.0, 2.0}});
  EXPECT_NE(ErrorOf([&] { ToNonlinear(a); }).find("C is 1x2 but must be 1x1"), std::string::npos);
  a.C = Mat({{1.0}});
  a.D = Vec({0.0, 1.0});
  EXPECT_NE(ErrorOf([&] { ToNonlinear(a); }).find("D has size 2"), std::string::npos);
  a.D = Vector();
  a.E = Mat({{NAN}});
  EXPECT_NE(ErrorOf([&] { ToNonlinear(a); }).find("E(0,0) is NaN"), std::string::npos);

  NonlinearSignSystem s = ArctanScene().system;
  s.h = nullptr;
  EXPECT_NE(ErrorOf([&] { NonlinearStepper(s, ArctanScene().scheme); }).find("h is not set"), std::string::npos);
  s = ArctanScene().system;
  s.m = 0;
  EXPECT_NE(ErrorOf([&] { NonlinearStepper(s, ArctanScene().scheme); }).find("m must be >= 1"), std::string::npos);
  s = ArctanScene().system;
  s.f = [](double, const Vector&, Eigen::Ref<Vector> f) { f.setZero(); };
  EXPECT_NE(ErrorOf([&] { NonlinearStepper(s, ArctanScene().scheme); }).find("f_jacobian"), std::string::npos);

  const NonlinearScene scene = ArctanScene();
  NonlinearStepper stepper(scene.system, scene.scheme);
  stepper_test::ReferenceSolver reference;
  const NonlinearStepperOptions ok = Options(NonlinearAlgorithm::kNewtonMlcp);
  EXPECT_NE(ErrorOf([&] { stepper.Run(Vec({1.0, 2.0}), 5, &reference, ok); }).find("x0 has size 2"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { stepper.Run(Vec({NAN}), 5, &reference, ok); }).find("x0"), std::string::npos);
  EXPECT_NE(ErrorOf([&] { stepper.Run(Vec({1.0}), -1, &reference, ok); }).find("num_steps"), std::string::npos);
  EXPECT_NE(ErrorOf([&] { stepper.Run(Vec({1.0}), 5, nullptr, ok); }).find("solver is null"), std::string::npos);
  NonlinearStepperOptions bad = ok;
  bad.newton_max_iterations = 0;
  EXPECT_NE(ErrorOf([&] { stepper.Run(Vec({1.0}), 5, &reference, bad); }).find("newton_max_iterations"),
            std::string::npos);
  bad = ok;
  bad.newton_tolerance = 0.0;
  EXPECT_NE(ErrorOf([&] { stepper.Run(Vec({1.0}), 5, &reference, bad); }).find("newton_tolerance"),
            std::string::npos);
  bad = ok;
  bad.stepper.solver.tolerance = -1.0;
  EXPECT_NE(ErrorOf([&] { stepper.Run(Vec({1.0}), 5, &reference, bad); }).find("solver options"),
            std::string::npos);
  // A callable that is NaN at x0.
  NonlinearSignSystem nan_g = scene.system;
  nan_g.g = [](const Vector&, Eigen::Ref<DenseMatrix> G) { G(0, 0) = NAN; };
  NonlinearStepper nan_stepper(nan_g, scene.scheme);
  EXPECT_NE(ErrorOf([&] { nan_stepper.Run(Vec({1.0}), 5, &reference, ok); }).find("g(x0)(0,0) is NaN"),
            std::string::npos);
}

// ------------------------------------------------------------------------------------------------------------
// Trajectory layout, CSV, metrics

TEST(NonlinearStepper, TrajectoryLayoutCsvAndMetrics) {
  const NonlinearScene scene = HypomonotoneScene();
  NonlinearStepper stepper(scene.system, scene.scheme);
  stepper_test::ReferenceSolver reference;
  const Trajectory tr = stepper.Run(scene.x0, scene.num_steps(), &reference, Options(NonlinearAlgorithm::kNewtonMlcp));
  ASSERT_TRUE(tr.ok());
  EXPECT_EQ(tr.steps_taken, 20);
  EXPECT_EQ(tr.x.cols(), 21);
  EXPECT_EQ(tr.t[0], 0.0);
  EXPECT_DOUBLE_EQ(tr.t[20], 2.0);
  EXPECT_EQ(tr.s(0, 0), 0.0);
  EXPECT_EQ(tr.status[0], SolveStatus::kNotRun);
  EXPECT_EQ(tr.status[1], SolveStatus::kSolved);
  EXPECT_EQ(tr.y(0, 5), tr.x(0, 5));  // y = h(x) = x
  EXPECT_NE(tr.description.find("newton-mlcp"), std::string::npos);
  EXPECT_EQ(stepper.newton_stats().iterations.size(), 21u);
  EXPECT_EQ(stepper.newton_stats().iterations[0], 0);
  std::ostringstream csv;
  WriteTrajectoryCsv(tr, csv);
  EXPECT_EQ(csv.str().substr(0, csv.str().find('\n')), "t,x1,s1,y1,iterations,residual");
  const TrajectoryMetrics metrics = ComputeMetrics(tr, 1e-12);
  EXPECT_EQ(metrics.reaching_step, PredictedK0(1.5, 0.1) + 1);
  EXPECT_EQ(metrics.surfaces[0].sign_changes_after, 0);
  // Unrecorded run: same final state, no history.
  NonlinearStepperOptions o = Options(NonlinearAlgorithm::kNewtonMlcp);
  o.stepper.record = false;
  const Trajectory bare = stepper.Run(scene.x0, scene.num_steps(), &reference, o);
  EXPECT_FALSE(bare.recorded);
  EXPECT_TRUE(bare.x_final == tr.x_final);
  EXPECT_EQ(bare.steps_taken, 20);
  EXPECT_TRUE(stepper.newton_stats().iterations.empty());
  // Zero steps.
  const Trajectory none = stepper.Run(scene.x0, 0, &reference, Options(NonlinearAlgorithm::kNewtonMlcp));
  EXPECT_EQ(none.steps_taken, 0);
  EXPECT_TRUE(none.x_final == scene.x0);
}

// ------------------------------------------------------------------------------------------------------------
// Allocation: a repeated run reuses every buffer (counted at the malloc level, so Eigen's allocations count).

TEST(NonlinearStepper, RepeatedRunsDoNotAllocateExceptTheMlcpCopies) {
  if (!test_support::CanCountMallocs()) GTEST_SKIP() << "malloc belongs to the sanitizer runtime in this build";
  auto newton = CreateSolver("newton");
  stepper_test::ReferenceSolver reference;
  for (const Scenario& sc : Scenarios()) {
    SCOPED_TRACE(sc.name);
    NonlinearStepper stepper(sc.system, sc.scheme);
    Trajectory tr;
    // Algorithm 1 and the explicit sign: nothing per step, nothing per run after the first.
    const NonlinearStepperOptions o1 = Options(NonlinearAlgorithm::kMcp);
    stepper.Run(sc.x0, sc.steps, newton.get(), o1, &tr);
    ASSERT_TRUE(tr.ok()) << tr.first_failure_message;
    EXPECT_EQ(test_support::CountMallocs([&] { stepper.Run(sc.x0, sc.steps, newton.get(), o1, &tr); }), 0);
    // Algorithm 2: M changes every Newton iteration. The stepper keeps one problem and replaces M in place:
    // set_M takes its matrix by value, one copy of W = 1 allocation per iteration. The backend's base layer then
    // sees a new matrix_id and builds its row-equilibrated copy of the problem (Solver::EquilibratedFor, outside
    // the stepper): measured here as the allocations of one solve after a set_M. Nothing else allocates.
    const NonlinearStepperOptions o2 = Options(NonlinearAlgorithm::kNewtonMlcp);
    stepper.Run(sc.x0, sc.steps, &reference, o2, &tr);
    ASSERT_TRUE(tr.ok());
    const long a2 = test_support::CountMallocs([&] { stepper.Run(sc.x0, sc.steps, &reference, o2, &tr); });
    const std::int64_t iterations = stepper.newton_stats().total_iterations;
    BoxMLCP probe = BoxMLCP::Relay(DenseMatrix::Identity(sc.system.m, sc.system.m), Vector::Zero(sc.system.m));
    SolveResult probe_result;
    reference.Solve(probe, o2.stepper.solver, &probe_result);
    DenseMatrix other = 2.0 * DenseMatrix::Identity(sc.system.m, sc.system.m);
    const long per_new_matrix = test_support::CountMallocs([&] {
      probe.set_M(other);  // the one copy the stepper also makes
      reference.Solve(probe, o2.stepper.solver, &probe_result);
    });
    std::printf("[ info     ] %-28s Algorithm 2: %ld allocations over %lld Newton iterations (a new M: %ld)\n",
                sc.name.c_str(), a2, static_cast<long long>(iterations), per_new_matrix);
    EXPECT_LE(a2, per_new_matrix * iterations);
  }
  NonlinearScene scene = HypomonotoneScene();
  scene.scheme.sign = SignTreatment::kExplicit;
  NonlinearStepper explicit_stepper(scene.system, scene.scheme);
  Trajectory tr;
  const NonlinearStepperOptions o = Options(NonlinearAlgorithm::kNewtonMlcp);
  explicit_stepper.Run(scene.x0, 50, nullptr, o, &tr);
  EXPECT_EQ(test_support::CountMallocs([&] { explicit_stepper.Run(scene.x0, 50, nullptr, o, &tr); }), 0);
}

// StepperOptions::sink: every row handed out while the run goes, bit for bit the recorded run's, for both
// algorithms, the explicit-sign Newton and a run that stops on a failure (its last row carries the status).
TEST(NonlinearStepper, StreamedRowsEqualTheRecordedRun) {
  const NonlinearScene arctan = ArctanScene();
  stepper_test::ReferenceSolver reference;
  auto newton = CreateSolver("newton");
  struct Case {
    const char* name;
    NonlinearSignSystem system;
    NonlinearScheme scheme;
    Vector x0;
    Solver* solver;
    NonlinearStepperOptions options;
  };
  NonlinearScheme explicit_scheme = arctan.scheme;
  explicit_scheme.sign = SignTreatment::kExplicit;
  NonlinearScheme two_d = arctan.scheme;
  two_d.h = 0.01;
  const NonlinearScene hypomonotone = HypomonotoneScene();
  NonlinearStepperOptions one_newton_iteration = Options(NonlinearAlgorithm::kNewtonMlcp);
  one_newton_iteration.newton_max_iterations = 1;  // fails at step 1 (see Failures above)
  const std::vector<Case> cases = {
      {"algorithm 2", arctan.system, arctan.scheme, arctan.x0, &reference, Options(NonlinearAlgorithm::kNewtonMlcp)},
      {"algorithm 1", arctan.system, arctan.scheme, arctan.x0, newton.get(), Options(NonlinearAlgorithm::kMcp)},
      {"explicit sign", arctan.system, explicit_scheme, arctan.x0, nullptr, Options(NonlinearAlgorithm::kNewtonMlcp)},
      {"m = 2, 5000 rows", Nonlinear2D(), two_d, Vec({0.5, -0.3}), &reference,
       Options(NonlinearAlgorithm::kNewtonMlcp)},
      {"failure", hypomonotone.system, hypomonotone.scheme, hypomonotone.x0, &reference, one_newton_iteration},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    NonlinearStepper stepper(c.system, c.scheme);
    const std::int64_t steps = c.system.m == 2 ? 5000 : 200;
    const Trajectory recorded = stepper.Run(c.x0, steps, c.solver, c.options);
    stepper_test::CollectingSink sink;
    NonlinearStepperOptions streaming = c.options;
    streaming.stepper.record = false;
    streaming.stepper.sink = &sink;
    const Trajectory streamed = stepper.Run(c.x0, steps, c.solver, streaming);
    stepper_test::ExpectSameRows(recorded, sink);
    EXPECT_EQ(streamed.x_final, recorded.x_final);
    EXPECT_EQ(streamed.first_failed_step, recorded.first_failed_step);
  }
}

TEST(NonlinearStepper, AlgorithmNamesRoundTrip) {
  for (NonlinearAlgorithm a : {NonlinearAlgorithm::kMcp, NonlinearAlgorithm::kNewtonMlcp}) {
    EXPECT_TRUE(NonlinearAlgorithmFromString(ToString(a)) == a);
  }
  EXPECT_FALSE(NonlinearAlgorithmFromString("lemke").has_value());
}

}  // namespace
}  // namespace smcbench

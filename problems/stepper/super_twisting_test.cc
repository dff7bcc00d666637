// The super-twisting steppers: the closed form of the implicit step against an independent bisection and against the
// MCP route on our backends; the claims of docs/smc.md ("Higher-order sliding modes") on the runs themselves.
#include "problems/stepper/super_twisting.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "solvers/registry/registry.h"
#include "tests/support/malloc_counter.h"

namespace smcbench {
namespace {

// The gains of the scenes: L = 1 (d = 0.5 sin 2t), k2 = 2 > L and k1² = 12.25 ≥ 4L(k2 + L)/(k2 − L) = 12.
SuperTwistingSystem Gains(bool disturbed) {
  SuperTwistingSystem system;
  system.k1 = 3.5;
  system.k2 = 2.0;
  if (disturbed) system.disturbance.sinusoids.push_back({0.5, 2.0, 0.0});
  return system;
}

Trajectory RunScheme(const SuperTwistingSystem& system, SignTreatment sign, double h, double T, Solver* solver = nullptr,
                     SuperTwistingSolution solution = SuperTwistingSolution::kClosedForm) {
  SuperTwistingOptions options;
  options.solution = solution;
  Trajectory out;
  RunSuperTwisting(system, sign, h, (Vector(2) << 1.0, 0.0).finished(), std::llround(T / h), solver, options, &out);
  return out;
}

// Least-squares slope of log(value) over log(h).
double Slope(const std::vector<double>& h, const std::vector<double>& value) {
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < h.size(); ++i) mx += std::log(h[i]), my += std::log(value[i]);
  mx /= static_cast<double>(h.size());
  my /= static_cast<double>(h.size());
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    sxy += (std::log(h[i]) - mx) * (std::log(value[i]) - my);
    sxx += (std::log(h[i]) - mx) * (std::log(h[i]) - mx);
  }
  return sxy / sxx;
}

TEST(SuperTwistingStep, ClosedFormSolvesTheGeneralizedEquationAsBisectionDoes) {
  std::mt19937 rng(26);
  std::uniform_real_distribution<double> W(-2.0, 2.0), A(0.0, 0.5), B(1e-4, 0.5);
  for (int trial = 0; trial < 1000; ++trial) {
    const double w = W(rng), a = A(rng), b = B(rng);
    const SuperTwistingStepSolution x = SolveSuperTwistingStep(w, a, b);
    ASSERT_GE(x.selection, -1.0);
    ASSERT_LE(x.selection, 1.0);
    if (x.sigma != 0.0) {
      ASSERT_EQ(x.selection, x.sigma > 0 ? 1.0 : -1.0);
    }
    const double root = std::copysign(std::sqrt(std::abs(x.sigma)), x.sigma);
    EXPECT_NEAR(x.sigma + a * root + b * x.selection, w, 1e-14 * (1 + std::abs(w)));
    // Independent: g(σ) = σ + a|σ|^{1/2} sgn σ + b sgn σ is increasing; its zero-crossing of g − w by bisection.
    const auto g = [&](double s) { return s + a * std::copysign(std::sqrt(std::abs(s)), s) + b * (s > 0 ? 1 : -1); };
    double lo = -4, hi = 4;
    for (int i = 0; i < 200; ++i) (g(0.5 * (lo + hi)) > w ? hi : lo) = 0.5 * (lo + hi);
    if (std::abs(w) <= b) {
      EXPECT_EQ(x.sigma, 0.0);
      EXPECT_NEAR(0.5 * (lo + hi), 0.0, 1e-12);
    } else {
      EXPECT_NEAR(x.sigma, 0.5 * (lo + hi), 1e-12);
    }
  }
}

TEST(SuperTwistingStep, McpRouteOnNewtonAndAutoAgreesWithTheClosedForm) {
  for (const char* name : {"newton", "auto"}) {
    auto solver = CreateSolver(name);
    ASSERT_TRUE(solver->info().mcp) << name;
    SuperTwistingStepMcp mcp(0.05, 2e-4);
    for (double w : {-1.0, -0.01, -2e-4, -1e-5, 0.0, 3e-5, 2e-4, 0.0123, 0.7}) {
      mcp.SetStep(w);
      const SolveResult r = solver->Solve(mcp);
      ASSERT_TRUE(r.solved()) << name << " w = " << w << ": " << r.message;
      const SuperTwistingStepSolution x = SolveSuperTwistingStep(w, 0.05, 2e-4);
      EXPECT_NEAR(r.z[0] * std::abs(r.z[0]), x.sigma, 1e-10) << name << " w = " << w;
      EXPECT_NEAR(r.z[1], x.selection, 1e-8) << name << " w = " << w;
    }
    // Whole runs, disturbed and not: the two routes give the same trajectory.
    for (bool disturbed : {false, true}) {
      const Trajectory closed = RunScheme(Gains(disturbed), SignTreatment::kImplicit, 0.01, 4.0);
      const Trajectory via_mcp =
          RunScheme(Gains(disturbed), SignTreatment::kImplicit, 0.01, 4.0, solver.get(), SuperTwistingSolution::kMcp);
      ASSERT_TRUE(via_mcp.ok()) << name << ": " << via_mcp.first_failure_message;
      EXPECT_LE((closed.x - via_mcp.x).cwiseAbs().maxCoeff(), 1e-8) << name;
      EXPECT_LE((closed.u - via_mcp.u).leftCols(closed.u.cols() - 1).cwiseAbs().maxCoeff(), 1e-6) << name;
    }
  }
}

// BPE 2020: without disturbance the implicit scheme reaches the origin (σ, v) = (0, 0) in finitely many steps and
// stays there; the controller's input is then exactly 0 (no chattering).
TEST(SuperTwistingRun, ImplicitUndisturbedReachesTheOriginExactlyAndStays) {
  for (double h : {0.04, 0.01, 0.0025}) {
    const Trajectory tr = RunScheme(Gains(false), SignTreatment::kImplicit, h, 10.0);
    ASSERT_TRUE(tr.ok());
    const SuperTwistingPrecision p = ComputeSuperTwistingPrecision(tr, 0.0);
    ASSERT_GE(p.convergence_step, 1) << h;
    EXPECT_LT(tr.time(p.convergence_step), 5.0) << h;
    for (std::int64_t k = p.convergence_step + 1; k <= tr.steps_taken; ++k) {
      ASSERT_EQ(tr.x(0, k), 0.0) << "h = " << h << ", k = " << k;
      ASSERT_EQ(tr.x(1, k), 0.0) << "h = " << h << ", k = " << k;
      ASSERT_EQ(tr.u(0, k - 1), 0.0) << "h = " << h << ", k = " << k;
    }
  }
}

// The issue's run (h = 0.05, k₁ = 0.8, k₂ = 4, x₀ = (3, 0)): sliding starts at a step with σ_k ≠ 0, and the
// state then goes through the docs' mechanism: σ_{k+1} = σ̂ = 0 and v_{k+1} = −σ_k/h, the next step has w = −σ_k
// and, sliding again, v_{k+2} = −σ_{k+1}/h = 0. Before the stepper computed v_{k+1} = −σ_k/h in the sliding branch,
// v_k − h k₂ (w/b) left 3.5e-18 there, shrinking by ~1e-16 per step to 3.95e-323 and never to 0.
TEST(SuperTwistingRun, ImplicitUndisturbedSlidingStepsGiveExactZeros) {
  SuperTwistingSystem system;
  system.k1 = 0.8;
  system.k2 = 4.0;
  const double h = 0.05, b = h * h * system.k2;
  SuperTwistingOptions options;
  Trajectory tr;
  RunSuperTwisting(system, SignTreatment::kImplicit, h, (Vector(2) << 3.0, 0.0).finished(), 400, nullptr, options,
                   &tr);
  ASSERT_TRUE(tr.ok());
  std::int64_t origin = -1;  // the first row with σ = v = 0
  for (std::int64_t k = 0; k <= tr.steps_taken && origin < 0; ++k) {
    if (tr.x(0, k) == 0.0 && tr.x(1, k) == 0.0) origin = k;
  }
  ASSERT_GT(origin, 1) << "the run never reached (0, 0) exactly";
  EXPECT_LT(tr.time(origin), 10.0);
  // The two steps before: the sliding step from σ ≠ 0 gives σ = 0 and v = −σ/h; the next one gives v = 0.
  const std::int64_t k = origin - 2;
  EXPECT_NE(tr.x(0, k), 0.0);
  EXPECT_LE(std::abs(tr.x(0, k) + h * tr.x(1, k)), b);
  EXPECT_EQ(tr.x(0, k + 1), 0.0);
  EXPECT_EQ(tr.x(1, k + 1), -tr.x(0, k) / h);
  for (std::int64_t j = origin; j <= tr.steps_taken; ++j) {
    ASSERT_EQ(tr.x(0, j), 0.0) << "k = " << j;
    ASSERT_EQ(tr.x(1, j), 0.0) << "k = " << j;
    ASSERT_EQ(tr.u(0, j - 1), 0.0) << "k = " << j;
  }
  EXPECT_EQ(tr.x_final[0], 0.0);
  EXPECT_EQ(tr.x_final[1], 0.0);
}

// docs/smc.md's statement of how close the MCP route comes to the closed form, at the default tolerance (1e-10) of
// newton and auto, on the scenes' gains (h = 0.01, x₀ = (1, 0), T = 4) and on the issue's run above: the largest
// |x_closed − x_mcp| over every step. The printed numbers are the docs'.
TEST(SuperTwistingRun, McpRouteAgreementWithTheClosedFormAtTheDefaultTolerance) {
  SuperTwistingSystem issue_gains;
  issue_gains.k1 = 0.8;
  issue_gains.k2 = 4.0;
  struct Case {
    const char* what;
    SuperTwistingSystem system;
    double h;
    Vector x0;
    std::int64_t steps;
  };
  const std::vector<Case> cases = {{"scene gains, d = 0", Gains(false), 0.01, (Vector(2) << 1.0, 0.0).finished(), 400},
                                   {"scene gains, disturbed", Gains(true), 0.01, (Vector(2) << 1.0, 0.0).finished(), 400},
                                   {"h 0.05 k1 0.8 k2 4 x0 (3, 0)", issue_gains, 0.05, (Vector(2) << 3.0, 0.0).finished(),
                                    400}};
  for (const char* name : {"newton", "auto"}) {
    auto solver = CreateSolver(name);
    for (const Case& c : cases) {
      SuperTwistingOptions closed_options, mcp_options;
      mcp_options.solution = SuperTwistingSolution::kMcp;
      Trajectory closed, via_mcp;
      RunSuperTwisting(c.system, SignTreatment::kImplicit, c.h, c.x0, c.steps, nullptr, closed_options, &closed);
      RunSuperTwisting(c.system, SignTreatment::kImplicit, c.h, c.x0, c.steps, solver.get(), mcp_options, &via_mcp);
      ASSERT_TRUE(via_mcp.ok()) << name << ", " << c.what << ": " << via_mcp.first_failure_message;
      const double gap = (closed.x - via_mcp.x).cwiseAbs().maxCoeff();
      std::printf("MCP route vs closed form, %s, %s: max |dx| = %.2e\n", name, c.what, gap);
      EXPECT_LE(gap, 2e-7) << name << ", " << c.what;
    }
  }
}

// Explicit Euler chatters: over the tail, max|σ| = O(h²) and max|σ'| = O(h) (Levant 2003, the accuracy of sampled
// homogeneous sliding modes: |σ| ≤ μ₀h², |σ'| ≤ μ₁h), with and without the disturbance. The implicit controller,
// which does not know d, lands on σ̂ = 0 at every step of the tail and the plant then drifts by ∫d over the step:
// |σ| ≤ h sup|d| = O(h) exactly, and σ' = (∫d over a step − the previous one)/h = O(h) with constant ≈ L.
TEST(SuperTwistingRun, TailPrecisionAgainstH) {
  const std::vector<double> h = {0.01, 0.005, 0.0025};
  struct Case {
    bool disturbed;
    SignTreatment sign;
    double sigma_order;
  };
  for (const Case c : {Case{false, SignTreatment::kExplicit, 2.0}, Case{true, SignTreatment::kExplicit, 2.0},
                       Case{true, SignTreatment::kImplicit, 1.0}}) {
    std::vector<double> sigma, sigma_dot;
    for (double step : h) {
      const Trajectory tr = RunScheme(Gains(c.disturbed), c.sign, step, 20.0);
      ASSERT_TRUE(tr.ok());
      const SuperTwistingPrecision p = ComputeSuperTwistingPrecision(tr, 0.0);
      sigma.push_back(p.max_abs_sigma_tail);
      sigma_dot.push_back(p.max_abs_sigma_dot_tail);
      ASSERT_GT(p.max_abs_sigma_tail, 0.0);
      // The implicit tail's bound, sup|d| = 0.5 and L = 1: |σ| ≤ 0.5 h, |σ'| ≤ L h (up to the O(h²) of the chord).
      if (c.sign == SignTreatment::kImplicit) {
        EXPECT_LE(p.max_abs_sigma_tail, 0.5 * step * (1 + 1e-9));
        EXPECT_LE(p.max_abs_sigma_dot_tail, 1.0 * step * (1 + step));
      }
    }
    const std::string what = std::string(c.sign == SignTreatment::kExplicit ? "explicit" : "implicit") +
                             (c.disturbed ? ", disturbed" : "");
    EXPECT_GE(Slope(h, sigma), c.sigma_order - 0.3) << what;
    EXPECT_LE(Slope(h, sigma), c.sigma_order + 0.3) << what;
    EXPECT_GE(Slope(h, sigma_dot), 0.7) << what;
    EXPECT_LE(Slope(h, sigma_dot), 1.3) << what;
  }
}

TEST(SuperTwistingRun, StreamedPrecisionEqualsTheRecordedOne) {
  SuperTwistingPrecisionAccumulator streamed(1e-3, 500, 0.01);
  SuperTwistingOptions options;
  options.stepper.sink = &streamed;
  options.stepper.record = true;
  Trajectory tr;
  RunSuperTwisting(Gains(true), SignTreatment::kExplicit, 0.01, (Vector(2) << 1.0, 0.0).finished(), 500, nullptr,
                   options, &tr);
  const SuperTwistingPrecision a = streamed.Result(), b = ComputeSuperTwistingPrecision(tr, 1e-3);
  EXPECT_EQ(a.convergence_step, b.convergence_step);
  EXPECT_GT(a.convergence_step, 0);
  EXPECT_EQ(a.max_abs_sigma_tail, b.max_abs_sigma_tail);
  EXPECT_EQ(a.max_abs_sigma_dot_tail, b.max_abs_sigma_dot_tail);
}

TEST(SuperTwistingRun, ClosedFormLoopDoesNotAllocatePerStep) {
  if (!test_support::CanCountMallocs()) GTEST_SKIP() << "allocations cannot be counted in this build";
  SuperTwistingOptions options;
  options.stepper.record = false;
  Trajectory tr;
  const Vector x0 = (Vector(2) << 1.0, 0.0).finished();
  const auto run = [&](std::int64_t steps) {
    return test_support::CountMallocs(
        [&] { RunSuperTwisting(Gains(true), SignTreatment::kImplicit, 0.01, x0, steps, nullptr, options, &tr); });
  };
  run(10);  // sizes the trajectory's storage
  // The set-up allocates the same for any length: the steps themselves allocate nothing.
  EXPECT_EQ(run(100), run(10000));
}

TEST(SuperTwistingRun, BadInputNamesTheField) {
  SuperTwistingSystem system = Gains(false);
  system.k2 = 0.0;
  try {
    RunScheme(system, SignTreatment::kImplicit, 0.01, 1.0);
    FAIL() << "k2 = 0 accepted";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("k2"), std::string::npos) << e.what();
  }
  auto lemke = CreateSolver("lemke");
  try {
    RunScheme(Gains(false), SignTreatment::kImplicit, 0.01, 1.0, lemke.get(), SuperTwistingSolution::kMcp);
    FAIL() << "an MLCP-only backend accepted for the MCP route";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("MCP"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace smcbench

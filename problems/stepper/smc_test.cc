// Siconos' θ-weighted equivalent-control SMC, the control input u of a run and the plant disturbance,
// each checked against an implementation written here with plain Eigen (own ZOH by a Taylor series, own relay
// projection by enumeration), never against the stepper's own output.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>
#include <unsupported/Eigen/MatrixFunctions>

#include "problems/stepper/linear_stepper.h"
#include "problems/stepper/metrics.h"
#include "problems/stepper/stepper_test_util.h"

namespace smcbench {
namespace {

using stepper_test::Mat;
using stepper_test::Vec;

// e^{Fs} and Ψ(s) = ∫₀ˢ e^{Fτ}dτ by their Taylor series (‖Fs‖ ≤ 2 here: 60 terms are far past convergence).
struct OwnZoh {
  DenseMatrix Ad, Psi;
};
OwnZoh OwnExp(const DenseMatrix& F, double s) {
  const auto n = F.rows();
  DenseMatrix term = DenseMatrix::Identity(n, n) * s;  // F^k s^{k+1} / (k+1)!
  DenseMatrix Psi = term;
  for (int k = 1; k < 60; ++k) {
    term = F * term * (s / (k + 1));
    Psi += term;
  }
  return {DenseMatrix::Identity(n, n) + F * Psi, Psi};
}

// The relay one-step problem σ = σ_free + M λ, λ ∈ [−α, α]^m, −σ ∈ N(λ), by enumeration of the 3^m faces (m ≤ 3).
Vector OwnRelay(const DenseMatrix& M, const Vector& sigma_free, double alpha) {
  const auto m = M.rows();
  int codes = 1;
  for (Eigen::Index i = 0; i < m; ++i) codes *= 3;
  for (int code = 0; code < codes; ++code) {
    Vector lambda = Vector::Zero(m);
    std::vector<Eigen::Index> free;
    int c = code;
    for (Eigen::Index i = 0; i < m; ++i, c /= 3) {
      if (c % 3 == 0) free.push_back(i);
      else lambda[i] = c % 3 == 1 ? -alpha : alpha;
    }
    if (!free.empty()) {
      const auto f = static_cast<Eigen::Index>(free.size());
      DenseMatrix A(f, f);
      Vector b(f);
      for (Eigen::Index a = 0; a < f; ++a) {
        b[a] = -sigma_free[free[a]];
        for (Eigen::Index i = 0; i < m; ++i) {
          if (std::find(free.begin(), free.end(), i) == free.end()) b[a] -= M(free[a], i) * lambda[i];
        }
        for (Eigen::Index e = 0; e < f; ++e) A(a, e) = M(free[a], free[e]);
      }
      const Vector z = A.fullPivLu().solve(b);
      for (Eigen::Index a = 0; a < f; ++a) lambda[free[a]] = z[a];
    }
    const Vector sigma = sigma_free + M * lambda;
    bool ok = true;
    for (Eigen::Index i = 0; i < m && ok; ++i) {
      const double slack = 1e-12 * (1.0 + std::abs(sigma_free[i]));
      if (lambda[i] < -alpha - 1e-12 || lambda[i] > alpha + 1e-12) ok = false;
      else if (lambda[i] == -alpha) ok = sigma[i] >= -slack;  // at −α: σ ≥ 0
      else if (lambda[i] == alpha) ok = sigma[i] <= slack;    // at +α: σ ≤ 0
      else ok = std::abs(sigma[i]) <= slack;                  // interior: σ = 0
    }
    if (ok) return lambda;
  }
  ADD_FAILURE() << "OwnRelay: no face fits";
  return Vector::Zero(m);
}

// Siconos' LinearSMC / ExplicitLinearSMC step in the order CommonSMC::computeUeq and actuate() take it.
struct OwnRun {
  std::vector<Vector> x, u;
};
OwnRun OwnSiconosRun(const ZohSmcSystem& sys, double theta, double h, const Vector& x0, int steps, bool implicit) {
  const OwnZoh zoh = OwnExp(sys.F, h);
  const DenseMatrix Bd = zoh.Psi * sys.G;
  const DenseMatrix K = (sys.C * sys.G).fullPivLu().solve(sys.C * sys.F);  // (CB)⁻¹CA
  const auto n = sys.F.rows();
  const DenseMatrix W = DenseMatrix::Identity(n, n) + theta * (Bd * K);
  OwnRun run;
  Vector x = x0;
  run.x.push_back(x);
  for (int k = 0; k < steps; ++k) {
    Vector ueq = (theta - 1.0) * (K * x);
    const Vector rhs = zoh.Ad * x + (theta - 1.0) * (Bd * (K * x));
    const Vector predicted = W.fullPivLu().solve(rhs);
    ueq -= theta * (K * predicted);
    Vector us;
    if (implicit) {
      us = OwnRelay(sys.C * Bd, sys.C * (zoh.Ad * x + Bd * ueq), sys.alpha);
    } else {
      const Vector sigma = sys.C * x;
      us = Vector::Zero(sigma.size());
      for (Eigen::Index i = 0; i < sigma.size(); ++i) us[i] = sigma[i] > 0 ? -sys.alpha : (sigma[i] < 0 ? sys.alpha : 0.0);
    }
    const Vector u = ueq + us;
    run.u.push_back(u);
    x = zoh.Ad * x + Bd * u;
    run.x.push_back(x);
  }
  return run;
}

Trajectory RunStepper(const OneStepData& data, const Vector& x0, int steps) {
  stepper_test::ReferenceSolver solver;
  LinearStepper stepper(data);
  StepperOptions options;
  options.solver.tolerance = 1e-13;
  return stepper.Run(x0, steps, &solver, options);
}

// max_k ‖a_k − b_k‖∞ / max(1, ‖b_k‖∞) over x and u (S6's sliding motion grows to |x| ≈ 100 by t = 100: the
// comparison is relative there, absolute below 1).
double MaxDifference(const Trajectory& tr, const OwnRun& own, bool compare_u) {
  double worst = 0.0;
  const auto relative = [](const Vector& a, const Vector& b) {
    return (a - b).lpNorm<Eigen::Infinity>() / std::max(1.0, b.lpNorm<Eigen::Infinity>());
  };
  for (std::size_t k = 0; k < own.x.size(); ++k) {
    const auto c = static_cast<Eigen::Index>(k);
    worst = std::max(worst, relative(tr.x.col(c), own.x[k]));
    if (compare_u && k < own.u.size()) worst = std::max(worst, relative(tr.u.col(c), own.u[k]));
  }
  return worst;
}

TEST(SiconosEquivalentControl, MatchesAnIndependentImplementationOver2000Steps) {
  struct Case {
    ZohSmcSystem sys;
    Vector x0;
    const char* name;
  };
  const Case cases[] = {{stepper_test::ZohSisoScene(), Vec({0.55, 0.55}), "S5"},
                        {stepper_test::ZohMimoScene(), Vec({0.05, -0.5, 0.02}), "S6"}};
  constexpr int kSteps = 2000;
  constexpr double h = 0.05;
  for (const Case& c : cases) {
    for (double theta : {0.5, 0.0, 1.0}) {
      for (bool implicit : {true, false}) {
        ZohSmcSystem sys = c.sys;
        sys.equivalent_control = EquivalentControl{theta};
        const OneStepData data =
            DiscretizeZoh(sys, h, implicit ? SignTreatment::kImplicit : SignTreatment::kExplicit);
        const Trajectory tr = RunStepper(data, c.x0, kSteps);
        ASSERT_TRUE(tr.ok()) << c.name;
        ASSERT_TRUE(tr.has_input);
        const OwnRun own = OwnSiconosRun(sys, theta, h, c.x0, kSteps, implicit);
        EXPECT_LE(MaxDifference(tr, own, true), 1e-12)
            << c.name << " theta " << theta << (implicit ? " implicit" : " explicit");
        EXPECT_TRUE(std::isnan(tr.u(0, kSteps))) << "no step applies the last row's input";
      }
    }
  }
}

TEST(SiconosEquivalentControl, ThetaZeroWithCGOneIsThePaperScheme) {
  // S5 has CG = 1: u = −(CF x_k + α s) either way, so both schemes give the same one-step data.
  ZohSmcSystem sys = stepper_test::ZohSisoScene();
  const OneStepData paper = DiscretizeZoh(sys, 0.3, SignTreatment::kImplicit);
  sys.equivalent_control = EquivalentControl{0.0};
  const OneStepData siconos = DiscretizeZoh(sys, 0.3, SignTreatment::kImplicit);
  EXPECT_LE((paper.R - siconos.R).lpNorm<Eigen::Infinity>(), 1e-15);
  EXPECT_LE((paper.S - siconos.S).lpNorm<Eigen::Infinity>(), 1e-15);
  EXPECT_LE((paper.input_x - siconos.input_x).lpNorm<Eigen::Infinity>(), 1e-15);
}

TEST(SiconosEquivalentControl, AbsentKeyLeavesThePaperSchemeBitForBit) {
  // The paper's formulas (`ZOH1`, `eq:ZOHGAMMA`) evaluated here in the same operations: without the
  // equivalent-control key, DiscretizeZoh must equal them to the last bit.
  for (const ZohSmcSystem& sys : {stepper_test::ZohSisoScene(), stepper_test::ZohMimoScene()}) {
    const double h = 0.3;
    const auto n = sys.F.rows(), m = sys.G.cols();
    const DenseMatrix CG = sys.C * sys.G;
    const DenseMatrix K = CG.transpose().partialPivLu().solve(sys.G.transpose()).transpose();
    DenseMatrix block = DenseMatrix::Zero(n + m, n + m);
    block.topLeftCorner(n, n) = h * sys.F;
    block.topRightCorner(n, m) = h * K;
    const DenseMatrix expo = block.exp();
    const DenseMatrix Gamma = expo.topRightCorner(n, m);
    const DenseMatrix R = expo.topLeftCorner(n, n) - Gamma * (sys.C * sys.F);
    const OneStepData d = DiscretizeZoh(sys, h, SignTreatment::kImplicit);
    EXPECT_TRUE(d.R == R);
    EXPECT_TRUE(d.S == DenseMatrix(sys.alpha * Gamma));
    EXPECT_FALSE(d.has_disturbance());
    EXPECT_EQ(d.description, "zoh, implicit sign");
    // And the trajectory against an independent run of the paper's scheme (own exponential, own relay).
    const OwnZoh zoh = OwnExp(sys.F, h);
    const DenseMatrix CGinv = CG.inverse();
    const Vector x0 = n == 2 ? Vec({0.55, 0.55}) : Vec({0.05, -0.5, 0.02});
    const Trajectory tr = RunStepper(d, x0, 200);
    Vector x = x0;
    double worst = 0.0;
    for (int k = 0; k < 200; ++k) {
      const DenseMatrix M = sys.C * zoh.Psi * sys.G * CGinv * sys.alpha;
      const Vector ux = -CGinv * (sys.C * sys.F * x);
      const Vector lambda = OwnRelay(M, sys.C * (zoh.Ad * x + zoh.Psi * sys.G * ux), 1.0);  // λ = −s
      const Vector u = ux + CGinv * (sys.alpha * lambda);
      worst = std::max(worst, (tr.u.col(k) - u).lpNorm<Eigen::Infinity>());
      x = zoh.Ad * x + zoh.Psi * sys.G * u;
      worst = std::max(worst, (tr.x.col(k + 1) - x).lpNorm<Eigen::Infinity>());
    }
    EXPECT_LE(worst, 1e-12);
  }
}

TEST(ControlInput, IsConsistentWithTheStateUpdate) {
  // x_{k+1} − e^{Fh} x_k = Ψ G u_k to rounding, with the exponential computed here.
  const double h = 0.05;
  for (bool siconos : {false, true}) {
    for (SignTreatment sign : {SignTreatment::kImplicit, SignTreatment::kExplicit}) {
      ZohSmcSystem sys = stepper_test::ZohMimoScene();
      if (siconos) sys.equivalent_control = EquivalentControl{0.5};
      const Trajectory tr = RunStepper(DiscretizeZoh(sys, h, sign), Vec({0.05, -0.5, 0.02}), 400);
      const OwnZoh zoh = OwnExp(sys.F, h);
      double worst = 0.0;
      for (Eigen::Index k = 0; k < 400; ++k) {
        const Vector lhs = tr.x.col(k + 1) - zoh.Ad * tr.x.col(k);
        const Vector rhs = zoh.Psi * sys.G * tr.u.col(k);
        worst = std::max(worst, (lhs - rhs).lpNorm<Eigen::Infinity>() / (1.0 + tr.x.col(k).lpNorm<Eigen::Infinity>()));
      }
      EXPECT_LE(worst, 1e-13) << (siconos ? "siconos " : "paper ") << (sign == SignTreatment::kImplicit ? "implicit" : "explicit");
    }
  }
  // S1's implicit-Euler controller: x_{k+1} − x_k = h u_k with u_k = −s_{k+1}.
  LinearSignSystem s1 = stepper_test::SignScene();
  s1.control_input = true;
  const Trajectory tr = RunStepper(DiscretizeTheta(s1, 0.01, 1.0, SignTreatment::kImplicit), Vec({1.01}), 200);
  ASSERT_TRUE(tr.has_input);
  for (Eigen::Index k = 0; k < 200; ++k) {
    EXPECT_NEAR(tr.x(0, k + 1) - tr.x(0, k), 0.01 * tr.u(0, k), 1e-15) << k;
    EXPECT_EQ(tr.u(0, k), -tr.s(0, k + 1));
  }
  // Without control_input a class-(2) run has no input columns.
  const Trajectory plain =
      RunStepper(DiscretizeTheta(stepper_test::SignScene(), 0.01, 1.0, SignTreatment::kImplicit), Vec({1.01}), 5);
  EXPECT_FALSE(plain.has_input);
  EXPECT_EQ(plain.u.rows(), 0);
}

// ∫₀ʰ e^{F(h−τ)} W d(t + τ) dτ by composite 8-point Gauss–Legendre on 64 panels, e^{F·} by OwnExp.
Vector OwnDisturbanceStep(const ZohSmcSystem& sys, double t, double h) {
  static const double kNodes[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
  static const double kWeights[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
  const int panels = 64;
  const double width = h / panels;
  Vector sum = Vector::Zero(sys.F.rows());
  Vector w(sys.F.rows());
  for (int p = 0; p < panels; ++p) {
    const double mid = (p + 0.5) * width;
    for (int i = 0; i < 4; ++i) {
      for (double sign : {-1.0, 1.0}) {
        const double tau = mid + sign * kNodes[i] * width / 2;
        sys.disturbance.Evaluate(t + tau, w);
        sum += kWeights[i] * width / 2 * (OwnExp(sys.F, h - tau).Ad * w);
      }
    }
  }
  return sum;
}

TEST(Disturbance, StepIsTheExactForcedResponse) {
  ZohSmcSystem sys = stepper_test::ZohSisoScene();
  sys.disturbance.W = Mat({{0.3}, {1.0}});  // unmatched
  sys.disturbance.constant = Vec({0.2});
  sys.disturbance.sinusoids = {{Vec({0.5}), 50.0, 0.3}, {Vec({-0.1}), 3.0, 0.0}};
  const double h = 0.05;
  const OneStepData d = DiscretizeZoh(sys, h, SignTreatment::kImplicit);
  ASSERT_TRUE(d.has_disturbance());
  for (double t : {0.0, 0.37, 12.5}) {
    Vector w = Vector::Zero(2);
    d.AddDisturbance(t, w);
    EXPECT_LE((w - OwnDisturbanceStep(sys, t, h)).lpNorm<Eigen::Infinity>(), 1e-13) << t;
  }
  // The controller does not see it: the one-step matrix and q's maps are those of the undisturbed plant.
  ZohSmcSystem quiet = sys;
  quiet.disturbance = {};
  const OneStepData dq = DiscretizeZoh(quiet, h, SignTreatment::kImplicit);
  EXPECT_TRUE(d.R == dq.R);
  EXPECT_TRUE(d.S == dq.S);
}

TEST(Disturbance, ImplicitDoesNotChatterExplicitDoes) {
  // S5 with Siconos' controller under a matched d(t) = 0.5 sin(50 t) (|d| < α = 1): the implicit switching part
  // stays inside (−α, α) and keeps its sign; the explicit one switches ±α every step.
  ZohSmcSystem sys = stepper_test::ZohSisoScene();
  sys.equivalent_control = EquivalentControl{0.5};
  sys.disturbance.W = sys.G;
  sys.disturbance.sinusoids = {{Vec({0.5}), 50.0, 0.0}};
  const double h = 0.01;
  const int steps = 1000;
  const Trajectory imp = RunStepper(DiscretizeZoh(sys, h, SignTreatment::kImplicit), Vec({0.55, 0.55}), steps);
  const Trajectory exp = RunStepper(DiscretizeZoh(sys, h, SignTreatment::kExplicit), Vec({0.55, 0.55}), steps);
  const ChatteringMetrics ci = ComputeChattering(imp, 1e-9);
  const ChatteringMetrics ce = ComputeChattering(exp, 1e-9);
  ASSERT_GE(ci.from_step, 0);
  ASSERT_GE(ce.from_step, 0);
  // The implicit input follows the disturbance and nothing more: its variation is that of d over the same steps,
  // its largest jump that of d over one step (≤ h ω A = 0.25), its switching part changes sign twice per period of
  // d. The explicit one jumps by ≈ 2α, about every second step.
  double d_variation = 0.0;
  for (std::int64_t k = ci.from_step; k + 1 < steps; ++k) {
    d_variation += std::abs(0.5 * std::sin(50.0 * (k + 1) * h) - 0.5 * std::sin(50.0 * k * h));
  }
  const double periods = (steps - ci.from_step) * h * 50.0 / (2.0 * M_PI);
  EXPECT_LE(ci.u_total_variation, 1.1 * d_variation);
  EXPECT_LE(ci.u_max_jump, 1.1 * h * 50.0 * 0.5);
  EXPECT_LE(ci.switching_sign_changes, 2.0 * periods + 2.0);
  EXPECT_GE(ce.u_max_jump, 1.5 * sys.alpha);
  EXPECT_GT(ce.u_total_variation, 5.0 * ci.u_total_variation);
  EXPECT_GT(ce.switching_sign_changes, 3 * ci.switching_sign_changes);
  EXPECT_GT(ce.switching_sign_changes, (steps - ce.from_step) / 2);
  // Both bands are O(h) (the controller does not know d); the explicit one is larger.
  EXPECT_LT(ci.sigma_band, ce.sigma_band);
  // The disturbance really acts: without it the implicit scheme sits on σ = 0.
  EXPECT_GT(ci.sigma_band, 1e-6);
}

TEST(ChatteringMetrics, CountsAsDefinedOnAHandMadeTrajectory) {
  Trajectory tr;
  tr.n = 1;
  tr.m = 1;
  tr.h = 1.0;
  tr.recorded = true;
  tr.steps_taken = tr.num_steps = 5;
  tr.t = {0, 1, 2, 3, 4, 5};
  tr.x = Mat({{3, 1, -0.5, 0.25, -0.25, 0.25}});
  tr.y = tr.x;
  tr.s = Mat({{0, 1, 1, -1, 1, -1}});
  tr.has_input = true;
  tr.u = Mat({{-1, -1, 1, -1, 1, std::nan("")}});
  tr.iterations.assign(6, 0);
  tr.residual.assign(6, 0.0);
  tr.status.assign(6, SolveStatus::kSolved);
  const ChatteringMetrics c = ComputeChattering(tr, 1e-9);
  EXPECT_EQ(c.from_step, 2);  // y crosses 0 between rows 1 and 2
  EXPECT_EQ(c.rows, 4);
  EXPECT_EQ(c.sigma_band, 0.5);
  EXPECT_EQ(c.switching_sign_changes, 3);  // rows 3, 4, 5: −1, 1, −1 after the 1 of row 2
  EXPECT_EQ(c.u_total_variation, 4.0);     // |−1 − 1| + |1 − (−1)|, row 5's u unknown
  EXPECT_EQ(c.u_max_jump, 2.0);
  EXPECT_EQ(c.u_max_abs, 1.0);
}

}  // namespace
}  // namespace smcbench

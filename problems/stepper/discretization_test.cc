// Discretizations: θ-method R, p, S by hand on 1-D cases (and the report's missing factor h in p), forcing
// weighting, ZOH Φ/Γ against an independent quadrature, and clear errors on bad input.
// The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.
#include "problems/stepper/discretization.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "problems/stepper/linear_stepper.h"
#include "problems/stepper/stepper_test_util.h"

namespace smcbench {
namespace {

using stepper_test::Mat;
using stepper_test::Vec;
using ::testing::HasSubstr;

constexpr double kEps = 2.220446049250313e-16;

LinearSignSystem Scalar(double a, double b, double g) {
  LinearSignSystem s;
  s.E = Mat({{a}});
  s.B = Mat({{b}});
  s.C = Mat({{1.0}});
  s.D = Vec({0.25});
  s.g = Vec({g});
  return s;
}

TEST(DiscretizeTheta, ScalarCaseMatchesHandComputedValues) {
  // x' = a x + g − b sgn(x + D), a = −2, b = 3, g = 0.5, h = 0.1:
  //   R = (1 + h(1−θ)a)/(1 − hθa),  S = h b/(1 − hθa),  p = h g/(1 − hθa).
  const double a = -2.0, b = 3.0, g = 0.5, h = 0.1;
  struct Expect {
    double theta, R, S, p;
  };
  const Expect cases[] = {
      {0.0, 0.8, 0.3, 0.05},                   // 1 − hθa = 1
      {0.5, 0.9 / 1.1, 0.3 / 1.1, 0.05 / 1.1}, // 1 − hθa = 1.1
      {1.0, 1.0 / 1.2, 0.3 / 1.2, 0.05 / 1.2}, // 1 − hθa = 1.2
  };
  for (const Expect& e : cases) {
    SCOPED_TRACE(e.theta);
    const OneStepData d = DiscretizeTheta(Scalar(a, b, g), h, e.theta, SignTreatment::kImplicit);
    EXPECT_NEAR(d.R(0, 0), e.R, 4 * kEps);
    EXPECT_NEAR(d.S(0, 0), e.S, 4 * kEps);
    EXPECT_NEAR(d.p[0], e.p, 4 * kEps);
    EXPECT_EQ(d.C(0, 0), 1.0);
    EXPECT_EQ(d.D[0], 0.25);
    EXPECT_EQ(d.h, h);
    EXPECT_NEAR(d.OneStepMatrix()(0, 0), e.S, 4 * kEps);  // M = C S
    EXPECT_FALSE(d.has_forcing());
  }
}

TEST(DiscretizeTheta, MatricesSatisfyTheDefiningEquations) {
  // (I − hθE) R = I + h(1−θ)E, (I − hθE) S = hB, (I − hθE) p = h g on a 3-D non-normal system.
  LinearSignSystem s;
  s.E = Mat({{-1.0, 2.0, 0.5}, {0.0, -3.0, 1.0}, {0.3, 0.0, -0.5}});
  s.B = Mat({{1.0, 0.0}, {0.0, 2.0}, {1.0, 1.0}});
  s.C = Mat({{1.0, 0.0, 1.0}, {0.0, 1.0, -1.0}});
  s.g = Vec({0.1, -0.2, 0.3});
  const double h = 0.07;
  for (double theta : {0.0, 0.3, 0.5, 1.0}) {
    const OneStepData d = DiscretizeTheta(s, h, theta, SignTreatment::kImplicit);
    const DenseMatrix I = DenseMatrix::Identity(3, 3);
    const DenseMatrix W = I - h * theta * s.E;
    EXPECT_LT((W * d.R - (I + h * (1 - theta) * s.E)).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_LT((W * d.S - h * s.B).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_LT((W * d.p - h * s.g).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_EQ(d.D, Vector::Zero(2));
  }
}

// One step of x' = E x + g with no active sign term (B = 0) from the exact equilibrium x* = −E⁻¹g must stay
// there: with p = h(I − hθE)⁻¹g it does; with the report's printed p = (I − hθE)⁻¹g it would not.
TEST(DiscretizeTheta, ConstantForcingCarriesTheFactorH) {
  LinearSignSystem s;
  s.E = Mat({{-2.0, 1.0}, {0.0, -1.0}});
  s.B = DenseMatrix::Zero(2, 1);
  s.C = Mat({{1.0, 0.0}});
  s.g = Vec({1.0, 2.0});
  const Vector x_star = -s.E.partialPivLu().solve(s.g);
  for (double theta : {0.0, 0.5, 1.0}) {
    const OneStepData d = DiscretizeTheta(s, 0.3, theta, SignTreatment::kExplicit);
    const Vector x1 = d.R * x_star + d.p;
    EXPECT_LT((x1 - x_star).cwiseAbs().maxCoeff(), 1e-14) << "theta " << theta;
    const Vector report_p = d.p / 0.3;  // the report's formula, without h
    EXPECT_GT((d.R * x_star + report_p - x_star).cwiseAbs().maxCoeff(), 0.1);
  }
}

// Error at T of x' = −x + sin t (no sign term) for θ-weighted time-dependent forcing: order 2 at θ = ½,
// order 1 at θ = 1 — evidence that g(t_k), g(t_{k+1}) are weighted as documented.
double ForcedErrorAtT(double theta, double h) {
  LinearSignSystem s;
  s.E = Mat({{-1.0}});
  s.B = DenseMatrix::Zero(1, 1);
  s.C = Mat({{1.0}});
  s.forcing = [](double t, Eigen::Ref<Vector> g) { g[0] = std::sin(t); };
  const double T = 2.0;
  LinearStepper stepper(DiscretizeTheta(s, h, theta, SignTreatment::kExplicit));
  StepperOptions options;
  options.record = false;
  const Trajectory tr = stepper.Run(Vec({1.0}), NumSteps(T, h), nullptr, options);
  // x(t) = (x0 + ½) e^{−t} + ½(sin t − cos t) for x0 = 1.
  const double exact = 1.5 * std::exp(-T) + 0.5 * (std::sin(T) - std::cos(T));
  return std::abs(tr.x_final[0] - exact);
}

TEST(DiscretizeTheta, TimeDependentForcingIsThetaWeighted) {
  const double r_half = ForcedErrorAtT(0.5, 0.02) / ForcedErrorAtT(0.5, 0.01);
  const double r_one = ForcedErrorAtT(1.0, 0.02) / ForcedErrorAtT(1.0, 0.01);
  EXPECT_NEAR(r_half, 4.0, 0.1);
  EXPECT_NEAR(r_one, 2.0, 0.1);
  const OneStepData d = DiscretizeTheta(stepper_test::LyapunovScene(), 0.1, 0.5, SignTreatment::kImplicit);
  ASSERT_TRUE(d.has_forcing());
  EXPECT_NEAR(d.P(0, 0), 0.1 / 1.05, 4 * kEps);  // P = h (I − hθE)⁻¹
  EXPECT_EQ(d.forcing_theta, 0.5);
}

TEST(DiscretizeExplicitEuler, IsThetaZeroWithExplicitSign) {
  const OneStepData d = DiscretizeExplicitEuler(stepper_test::GaliasYuScene(), 0.3);
  EXPECT_EQ(d.sign, SignTreatment::kExplicit);
  const DenseMatrix expected_R = DenseMatrix::Identity(2, 2) + 0.3 * stepper_test::GaliasYuScene().E;
  EXPECT_LT((d.R - expected_R).cwiseAbs().maxCoeff(), 1e-16);
  EXPECT_LT((d.S - 0.3 * stepper_test::GaliasYuScene().B).cwiseAbs().maxCoeff(), 1e-16);
}

// ---------------------------------------------------------------------------------------------------------
// Independent ZOH reference: e^{Fτ} by Taylor series with scaling and squaring, ∫₀ʰ e^{Fτ}dτ by composite
// 20-point Gauss–Legendre quadrature (nodes from Newton's method on P_20).

DenseMatrix ExpTaylor(const DenseMatrix& A) {
  const double norm = A.cwiseAbs().rowwise().sum().maxCoeff();
  int squarings = 0;
  while (norm / std::ldexp(1.0, squarings) > 0.125) ++squarings;
  const DenseMatrix X = A / std::ldexp(1.0, squarings);
  DenseMatrix term = DenseMatrix::Identity(A.rows(), A.cols());
  DenseMatrix sum = term;
  for (int k = 1; k <= 25; ++k) {
    term = term * X / static_cast<double>(k);
    sum += term;
  }
  for (int i = 0; i < squarings; ++i) sum = sum * sum;
  return sum;
}

void GaussLegendre(int n, std::vector<double>* nodes, std::vector<double>* weights) {
  nodes->assign(n, 0.0);
  weights->assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    double x = std::cos(M_PI * (i + 0.75) / (n + 0.5));
    double dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-17) break;
    }
    (*nodes)[i] = x;
    (*weights)[i] = 2.0 / ((1.0 - x * x) * dp * dp);
  }
}

DenseMatrix IntegralOfExp(const DenseMatrix& F, double h) {
  std::vector<double> nodes, weights;
  GaussLegendre(20, &nodes, &weights);
  const int pieces = 8;
  DenseMatrix sum = DenseMatrix::Zero(F.rows(), F.cols());
  const double width = h / pieces;
  for (int p = 0; p < pieces; ++p) {
    const double mid = (p + 0.5) * width;
    for (size_t i = 0; i < nodes.size(); ++i) {
      sum += (0.5 * width * weights[i]) * ExpTaylor(F * (mid + 0.5 * width * nodes[i]));
    }
  }
  return sum;
}

void CheckZohAgainstQuadrature(const ZohSmcSystem& sys, double h) {
  const OneStepData d = DiscretizeZoh(sys, h, SignTreatment::kImplicit);
  const DenseMatrix Psi = IntegralOfExp(sys.F, h);
  const DenseMatrix CGinv = (sys.C * sys.G).inverse();
  const DenseMatrix Gamma = Psi * sys.G * CGinv;                                 // `eq:ZOHGAMMA`
  const DenseMatrix Phi = ExpTaylor(sys.F * h) - Psi * sys.G * CGinv * sys.C * sys.F;
  // The reference itself loses ~2^squarings ulps in its squaring phase; 1e-13 relative still rules out any
  // truncated series or wrong block (those are off by 1e-4 or more).
  const double scale = 1.0 + Phi.cwiseAbs().maxCoeff();
  EXPECT_LT((d.R - Phi).cwiseAbs().maxCoeff(), 1e-13 * scale) << "h " << h;
  EXPECT_LT((d.S - sys.alpha * Gamma).cwiseAbs().maxCoeff(), 1e-13 * scale) << "h " << h;
  EXPECT_EQ(d.p, Vector::Zero(sys.n()));
  EXPECT_EQ(d.D, Vector::Zero(sys.m()));
}

TEST(DiscretizeZoh, MatchesQuadratureOfTheExponentialOnS5AndS6) {
  CheckZohAgainstQuadrature(stepper_test::ZohSisoScene(), 0.3);
  CheckZohAgainstQuadrature(stepper_test::ZohMimoScene(), 0.3);
  CheckZohAgainstQuadrature(stepper_test::ZohMimoScene(), 1.7);  // a few squarings
  ZohSmcSystem scaled = stepper_test::ZohMimoScene();
  scaled.alpha = 2.5;
  CheckZohAgainstQuadrature(scaled, 0.05);
}

TEST(DiscretizeZoh, ScalarClosedForm) {
  // x' = a x + u, u = −(a x + s): Γ = (e^{ah} − 1)/a, Φ = e^{ah} − Γ a = 1.
  ZohSmcSystem s;
  s.F = Mat({{0.7}});
  s.G = Mat({{1.0}});
  s.C = Mat({{1.0}});
  const double h = 0.4;
  const OneStepData d = DiscretizeZoh(s, h, SignTreatment::kExplicit);
  EXPECT_NEAR(d.S(0, 0), std::expm1(0.7 * h) / 0.7, 1e-15);
  EXPECT_NEAR(d.R(0, 0), 1.0, 1e-15);
  EXPECT_EQ(d.sign, SignTreatment::kExplicit);
}

TEST(ClosedLoop, EquivalentControlMakesTheSurfaceInvariant) {
  // C E = CF − CG(CG)⁻¹CF = 0 and C B = α I.
  ZohSmcSystem z = stepper_test::ZohMimoScene();
  z.alpha = 1.5;
  const LinearSignSystem s = ClosedLoop(z);
  EXPECT_LT((s.C * s.E).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_LT((s.C * s.B - 1.5 * DenseMatrix::Identity(2, 2)).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(Discretize, DispatchesOnModelAndMethod) {
  const LinearModel zoh = stepper_test::ZohSisoScene();
  EXPECT_EQ(Discretize(zoh, Method::kZoh, 0.3, 1.0).sign, SignTreatment::kImplicit);
  EXPECT_EQ(Discretize(zoh, Method::kZohExplicit, 0.3, 1.0).sign, SignTreatment::kExplicit);
  // θ-method on the closed loop.
  const OneStepData euler = Discretize(zoh, Method::kImplicit, 0.3, 1.0);
  const OneStepData direct =
      DiscretizeTheta(ClosedLoop(stepper_test::ZohSisoScene()), 0.3, 1.0, SignTreatment::kImplicit);
  EXPECT_EQ(euler.R, direct.R);
  const LinearModel lin = stepper_test::GaliasYuScene();
  EXPECT_EQ(Discretize(lin, Method::kExplicit, 0.3, 0.0).sign, SignTreatment::kExplicit);
  EXPECT_THAT([&] { Discretize(lin, Method::kZoh, 0.3, 1.0); },
              ::testing::ThrowsMessage<InvalidInputError>(HasSubstr("needs a ZOH plant")));
}

TEST(Method, NamesRoundTrip) {
  for (Method m : {Method::kImplicit, Method::kExplicit, Method::kZoh, Method::kZohExplicit}) {
    EXPECT_EQ(MethodFromString(ToString(m)), m);
  }
  EXPECT_EQ(ToString(Method::kZohExplicit), "zoh-explicit");
  EXPECT_FALSE(MethodFromString("semi-implicit").has_value());
}

TEST(NumSteps, RoundsTOverH) {
  EXPECT_EQ(NumSteps(2.0, 0.2), 10);
  EXPECT_EQ(NumSteps(1.5, 0.02), 75);
  EXPECT_EQ(NumSteps(10.0, 0.3), 33);
  EXPECT_EQ(NumSteps(0.0, 0.1), 0);
  EXPECT_THAT([] { NumSteps(-1.0, 0.1); }, ::testing::ThrowsMessage<InvalidInputError>(HasSubstr("T must be")));
  EXPECT_THAT([] { NumSteps(NAN, 0.1); }, ::testing::ThrowsMessage<InvalidInputError>(HasSubstr("T must be")));
  EXPECT_THAT([] { NumSteps(1.0, 0.0); }, ::testing::ThrowsMessage<InvalidInputError>(HasSubstr("h must be")));
  EXPECT_THAT([] { NumSteps(1e300, 1e-300); }, ::testing::ThrowsMessage<InvalidInputError>(HasSubstr("too many")));
}

// ---------------------------------------------------------------------------------------------------------
// Bad input → InvalidInputError naming the field.

template <typename Fn>
void ExpectError(Fn&& fn, const std::string& fragment) {
  EXPECT_THAT(fn, ::testing::ThrowsMessage<InvalidInputError>(HasSubstr(fragment)));
}

TEST(DiscretizeTheta, RejectsBadInput) {
  const LinearSignSystem good = stepper_test::GaliasYuScene();
  const auto theta = [](const LinearSignSystem& s, double h, double th) {
    return [=] { DiscretizeTheta(s, h, th, SignTreatment::kImplicit); };
  };
  ExpectError(theta(good, 0.0, 1.0), "h must be a positive finite time step, got 0");
  ExpectError(theta(good, -0.1, 1.0), "h must be");
  ExpectError(theta(good, NAN, 1.0), "h must be");
  ExpectError(theta(good, INFINITY, 1.0), "h must be");
  ExpectError(theta(good, 0.1, 1.5), "theta must lie in [0, 1], got 1.5");
  ExpectError(theta(good, 0.1, -0.1), "theta must lie in [0, 1]");
  ExpectError(theta(good, 0.1, NAN), "theta must lie in [0, 1], got nan");

  LinearSignSystem bad = good;
  bad.B = Mat({{0.0}, {1.0}, {2.0}});
  ExpectError(theta(bad, 0.1, 1.0), "LinearSignSystem: B is 3x1 but must be 2x1");
  bad = good;
  bad.C = Mat({{1.0, 1.0, 1.0}});
  ExpectError(theta(bad, 0.1, 1.0), "LinearSignSystem: C is 1x3 but must be 1x2");
  bad = good;
  bad.E = Mat({{0.0, 1.0, 0.0}, {0.0, -1.0, 0.0}});
  ExpectError(theta(bad, 0.1, 1.0), "LinearSignSystem: E is 2x3 but must be 2x2");
  bad = good;
  bad.D = Vec({0.0, 0.0});
  ExpectError(theta(bad, 0.1, 1.0), "LinearSignSystem: D has size 2 but must have size 1");
  bad = good;
  bad.g = Vec({1.0});
  ExpectError(theta(bad, 0.1, 1.0), "LinearSignSystem: g has size 1 but must have size 2");
  bad = good;
  bad.E(1, 0) = NAN;
  ExpectError(theta(bad, 0.1, 1.0), "LinearSignSystem: E(1,0) is NaN");
  bad = good;
  bad.B(0, 0) = INFINITY;
  ExpectError(theta(bad, 0.1, 1.0), "LinearSignSystem: B(0,0) is infinite");
  bad = good;
  bad.D = Vec({NAN});
  ExpectError(theta(bad, 0.1, 1.0), "D[0] is NaN");
  bad = LinearSignSystem{};
  ExpectError(theta(bad, 0.1, 1.0), "LinearSignSystem: E is empty");
  // I − hθE singular: E = 1/(hθ).
  LinearSignSystem stiff = Scalar(10.0, 1.0, 0.0);
  ExpectError(theta(stiff, 0.1, 1.0), "DiscretizeTheta: I - h*theta*E is singular");
  EXPECT_NO_THROW(DiscretizeTheta(stiff, 0.1, 0.5, SignTreatment::kImplicit));
}

TEST(DiscretizeZoh, RejectsBadInput) {
  const ZohSmcSystem good = stepper_test::ZohSisoScene();
  const auto zoh = [](const ZohSmcSystem& s, double h) {
    return [=] { DiscretizeZoh(s, h, SignTreatment::kImplicit); };
  };
  ExpectError(zoh(good, 0.0), "DiscretizeZoh: h must be");
  ZohSmcSystem bad = good;
  bad.G = Mat({{1.0}, {-1.0}});  // C G = 0
  ExpectError(zoh(bad, 0.3), "ZohSmcSystem: CG is singular");
  bad = good;
  bad.alpha = 0.0;
  ExpectError(zoh(bad, 0.3), "ZohSmcSystem: alpha must be a positive finite number, got 0");
  bad = good;
  bad.F(0, 1) = NAN;
  ExpectError(zoh(bad, 0.3), "ZohSmcSystem: F(0,1) is NaN");
  bad = good;
  bad.G = Mat({{0.0, 1.0}, {1.0, 0.0}});
  ExpectError(zoh(bad, 0.3), "ZohSmcSystem: G is 2x2 but must be 2x1");
  bad = good;
  bad.F = 1e3 * DenseMatrix::Identity(2, 2);
  ExpectError(zoh(bad, 1.0), "overflowed");
}

// Siconos' twisting controllers apply u = −α s alone: a double integrator with C G = 0 is then fine, and its ZOH
// step is x_{k+1} = e^{Fh} x_k − α Ψ G s_{k+1} with e^{Fh} = [[1, h], [0, 1]], Ψ G = (h²/2, h) by hand.
TEST(DiscretizeZoh, SwitchingOnlyNeedsNoEquivalentControl) {
  ZohSmcSystem plant;
  plant.F = Mat({{0.0, 1.0}, {0.0, 0.0}});
  plant.G = Mat({{0.0}, {1.0}});
  plant.C = Mat({{1.0, 0.0}});  // C G = 0
  plant.alpha = 2.0;
  ExpectError([&] { DiscretizeZoh(plant, 0.1, SignTreatment::kImplicit); }, "ZohSmcSystem: CG is singular");
  plant.switching_only = true;
  const double h = 0.1;
  const OneStepData d = DiscretizeZoh(plant, h, SignTreatment::kImplicit);
  EXPECT_LE((d.R - Mat({{1.0, h}, {0.0, 1.0}})).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LE((d.S - Mat({{2.0 * h * h / 2.0}, {2.0 * h}})).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_EQ(d.input_x, DenseMatrix::Zero(1, 2));
  EXPECT_EQ(d.input_s, Mat({{-2.0}}));
  const LinearSignSystem closed = ClosedLoop(plant);  // the θ-method's view: E = F, B = α G
  EXPECT_EQ(closed.E, plant.F);
  EXPECT_EQ(closed.B, 2.0 * plant.G);
  plant.equivalent_control = EquivalentControl{0.5};
  ExpectError([&] { plant.Validate(); }, "switching_only and equivalent_control exclude each other");
}

TEST(PolytopeLaw, ShapesSignAndEmptinessAreChecked) {
  LinearSignSystem sys = stepper_test::SignScene();  // m = 1
  sys.law.H = Mat({{1.0, 0.0}});
  sys.law.K = Vec({-1.0});
  ExpectError([&] { sys.Validate(); }, "LinearSignSystem: law.H is 1x2 but must be 1x1");
  sys.law.H = Mat({{1.0}, {-1.0}});
  ExpectError([&] { sys.Validate(); }, "LinearSignSystem: law.K has size 1 but must have size 2");
  sys.law.K = Vec({-1.0, -1.0});
  ExpectError([&] { DiscretizeTheta(sys, 0.1, 1.0, SignTreatment::kExplicit); },
              "OneStepData: law: a polytope law needs an implicit method");
  sys.law.K = Vec({1.0, 1.0});  // s ≥ 1 and −s ≥ 1
  ExpectError([&] { LinearStepper stepper(DiscretizeTheta(sys, 0.1, 1.0, SignTreatment::kImplicit)); }, "is empty");
  sys.law.K = Vec({-1.0, -1.0});  // the box itself, as a polytope: the same run as the box law
  LinearStepper polytope(DiscretizeTheta(sys, 0.1, 1.0, SignTreatment::kImplicit));
  LinearStepper box(DiscretizeTheta(stepper_test::SignScene(), 0.1, 1.0, SignTreatment::kImplicit));
  ASSERT_NE(polytope.avi(), nullptr);
  EXPECT_EQ(box.avi(), nullptr);
  stepper_test::ReferenceSolver reference;
  const Trajectory a = polytope.Run(Vec({1.01}), 20, &reference);
  const Trajectory b = box.Run(Vec({1.01}), 20, &reference);
  ASSERT_TRUE(a.ok() && b.ok()) << a.first_failure_message;
  EXPECT_LE((a.x - b.x).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(OneStepData, ValidateNamesTheField) {
  OneStepData d = DiscretizeTheta(stepper_test::GaliasYuScene(), 0.1, 1.0, SignTreatment::kImplicit);
  d.S = DenseMatrix::Zero(3, 1);
  ExpectError([&] { d.Validate(); }, "OneStepData: S is 3x1 but must be 2x1");
  d = DiscretizeTheta(stepper_test::GaliasYuScene(), 0.1, 1.0, SignTreatment::kImplicit);
  d.p[1] = NAN;
  ExpectError([&] { LinearStepper stepper(d); }, "OneStepData: p[1] is NaN");
}

}  // namespace
}  // namespace smcbench

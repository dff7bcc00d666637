// The AVI type's validation (each error names its field), the phase-1 simplex's point of P (checked here against
// the constraints), the boundedness test on polytopes whose answer is known by hand, and the vertex finder.
#include "solvers/avi/affine_vi.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "solvers/avi/planted_avi_test_util.h"
#include "tests/support/eigen_literals.h"

namespace smcbench {
namespace {

using test_support::Mat;
using test_support::Vec;

using ::testing::HasSubstr;

// The square [−1, 1]² as H λ ≥ K.
DenseMatrix SquareH() { return Mat({{1, 0}, {-1, 0}, {0, 1}, {0, -1}}); }
Vector SquareK() { return Vec({-1, -1, -1, -1}); }

std::string ErrorOf(const std::function<void()>& build) {
  try {
    build();
  } catch (const InvalidInputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(AffineVIValidation, EachErrorNamesItsField) {
  const DenseMatrix I = DenseMatrix::Identity(2, 2);
  const Vector q = Vec({1, 2});
  const double nan = kNaN;
  struct Case {
    std::string what;
    std::function<void()> build;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"empty M", [&] { AffineVI(DenseMatrix(), Vector(), SquareH(), SquareK()); }, "AffineVI: M is 0x0"},
      {"non-square M", [&] { AffineVI(DenseMatrix::Ones(2, 3), q, SquareH(), SquareK()); },
       "M is 2x3 but must be square"},
      {"q size", [&] { AffineVI(I, Vec({1, 2, 3}), SquareH(), SquareK()); }, "q has size 3 but M is 2x2"},
      {"H columns", [&] { AffineVI(I, q, DenseMatrix::Ones(2, 3), Vec({0, 0})); }, "H is 2x3 but must have n = 2"},
      {"K size", [&] { AffineVI(I, q, SquareH(), Vec({0, 0})); }, "K has size 2 but H has 4 rows"},
      {"NaN in M", [&] { AffineVI(Mat({{1, nan}, {0, 1}}), q, SquareH(), SquareK()); }, "M(0,1) is NaN"},
      {"Inf in H", [&] { AffineVI(I, q, Mat({{1, 0}, {kInf, 0}}), Vec({0, 0})); }, "H(1,0) is infinite"},
      {"NaN in q", [&] { AffineVI(I, Vec({nan, 0}), SquareH(), SquareK()); }, "q[0] is NaN"},
      {"Inf in K", [&] { AffineVI(I, q, SquareH(), Vec({-1, -kInf, -1, -1})); }, "K[1] is infinite"},
      {"E columns", [&] { AffineVI(I, q, SquareH(), SquareK(), Mat({{1}}), Vec({0})); },
       "E is 1x1 but must have n = 2"},
      {"f size", [&] { AffineVI(I, q, SquareH(), SquareK(), Mat({{1, 1}}), Vec({0, 0})); }, "f has size 2 but E has 1"},
      {"NaN in f", [&] { AffineVI(I, q, SquareH(), SquareK(), Mat({{1, 1}}), Vec({nan})); }, "f[0] is NaN"},
      {"zero row of H", [&] { AffineVI(I, q, Mat({{1, 0}, {0, 0}}), Vec({0, -1})); }, "H row 1 is zero"},
      {"zero row of E", [&] { AffineVI(I, q, SquareH(), SquareK(), Mat({{0, 0}}), Vec({0})); }, "E row 0 is zero"},
      // λ₁ ≥ 1 and −λ₁ ≥ 0: no point.
      {"empty P", [&] { AffineVI(I, q, Mat({{1, 0}, {-1, 0}}), Vec({1, 0})); }, "P = {λ : Hλ ≥ K, Eλ = f} is empty"},
      // The square with λ₁ + λ₂ = 3: the line misses it.
      {"empty P by an equality",
       [&] { AffineVI(I, q, SquareH(), SquareK(), Mat({{1, 1}}), Vec({3})); }, "is empty"},
  };
  for (const Case& c : cases) EXPECT_THAT(ErrorOf(c.build), HasSubstr(c.expected)) << c.what;

  AffineVI avi(I, q, SquareH(), SquareK(), "square");
  EXPECT_THAT(ErrorOf([&] { avi.set_q(Vec({1})); }), HasSubstr("q has size 1 but M is 2x2"));
  EXPECT_THAT(ErrorOf([&] { avi.set_q(Vec({1, nan})); }), HasSubstr("q[1] is NaN"));
  avi.set_q(Vec({3, 4}));
  EXPECT_EQ(avi.q(), Vec({3, 4}));
  EXPECT_EQ(avi.name(), "square");
}

// max over rows of K_i − H_iλ and |E_jλ − f_j|, computed here.
double Violation(const AffineVI& avi, const Vector& x) {
  double v = 0.0;
  for (int i = 0; i < avi.inequality_count(); ++i) v = std::max(v, avi.K()[i] - avi.H().row(i).dot(x));
  for (int j = 0; j < avi.equality_count(); ++j) v = std::max(v, std::abs(avi.E().row(j).dot(x) - avi.f()[j]));
  return v;
}

TEST(AffineVIValidation, FeasiblePointLiesInP) {
  const DenseMatrix I = DenseMatrix::Identity(2, 2);
  // A single point as two opposite half-planes per coordinate, far from the origin and badly scaled rows.
  const AffineVI point(I, Vec({0, 0}), Mat({{1e6, 0}, {-1e6, 0}, {0, 1e-6}, {0, -1e-6}}),
                       Vec({3e6, -3e6, -5e-6, 5e-6}));
  EXPECT_NEAR(point.feasible_point()[0], 3.0, 1e-12);
  EXPECT_NEAR(point.feasible_point()[1], -5.0, 1e-9);
  // No constraint at all: P = R², any point.
  const AffineVI whole(I, Vec({1, 1}), DenseMatrix(), Vector());
  EXPECT_EQ(whole.inequality_count(), 0);
  EXPECT_EQ(whole.H().cols(), 2);
  EXPECT_EQ(whole.feasible_point().size(), 2);
  // Random polytopes with a known interior point.
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const PlantedAvi planted = MakePlantedAvi(4, 6, 2, 1, seed);
    EXPECT_LE(Violation(planted.avi, planted.avi.feasible_point()), 1e-9) << planted.avi.name();
    EXPECT_LE(Violation(planted.avi, planted.solution.lambda), 1e-12) << planted.avi.name();
  }
}

TEST(AffineVIValidation, BoundednessOfKnownPolytopes) {
  const DenseMatrix I2 = DenseMatrix::Identity(2, 2);
  const Vector q2 = Vec({0, 0});
  EXPECT_EQ(AffineVI(I2, q2, SquareH(), SquareK()).boundedness(), PolytopeBoundedness::kBounded);
  // The half-plane λ₁ ≥ 0.
  EXPECT_EQ(AffineVI(I2, q2, Mat({{1, 0}}), Vec({0})).boundedness(), PolytopeBoundedness::kUnbounded);
  // The simplex λ ≥ 0, λ₁ + λ₂ ≤ 1, with a redundant row through its vertex (0, 0).
  EXPECT_EQ(AffineVI(I2, q2, Mat({{1, 0}, {0, 1}, {-1, -1}, {1, 1}}), Vec({0, 0, -1, 0})).boundedness(),
            PolytopeBoundedness::kBounded);
  // Implicit twisting's parallelogram |λ₁| ≤ 1, |λ₂ − (h/2)λ₁| ≤ 1 (Siconos' Twisting tutorial), h = 0.1.
  const double half_h = 0.05;
  EXPECT_EQ(AffineVI(I2, q2, Mat({{1, 0}, {-1, 0}, {-half_h, 1}, {half_h, -1}}), SquareK()).boundedness(),
            PolytopeBoundedness::kBounded);
  // The line λ₁ = λ₂, cut to a segment by −1 ≤ λ₁ ≤ 1, and a ray by λ₁ ≥ 0 alone.
  EXPECT_EQ(AffineVI(I2, q2, Mat({{1, 0}, {-1, 0}}), Vec({-1, -1}), Mat({{1, -1}}), Vec({0})).boundedness(),
            PolytopeBoundedness::kBounded);
  EXPECT_EQ(AffineVI(I2, q2, Mat({{1, 0}}), Vec({0}), Mat({{1, -1}}), Vec({0})).boundedness(),
            PolytopeBoundedness::kUnbounded);
  EXPECT_EQ(AffineVI(I2, q2, DenseMatrix(), Vector()).boundedness(), PolytopeBoundedness::kUnbounded);
  EXPECT_EQ(ToString(PolytopeBoundedness::kBounded), "bounded");
  EXPECT_EQ(ToString(PolytopeBoundedness::kUnbounded), "unbounded");
  EXPECT_EQ(ToString(PolytopeBoundedness::kNotDecided), "not decided");
}

TEST(AffineVIValidation, BoundednessNotDecidedAboveTheLimit) {
  const int n = kMaxBoundednessCheckSize + 1;
  DenseMatrix H(2 * n, n);
  H << DenseMatrix::Identity(n, n), -DenseMatrix::Identity(n, n);
  const AffineVI avi(DenseMatrix::Identity(n, n), Vector::Zero(n), H, Vector::Constant(2 * n, -1.0));
  EXPECT_EQ(avi.boundedness(), PolytopeBoundedness::kNotDecided);
  EXPECT_LE(Violation(avi, avi.feasible_point()), 1e-9);
}

}  // namespace
}  // namespace smcbench

namespace smcbench {
namespace {

// What a vertex is, checked from the data: n rows of [H; E] whose matrix has full rank, each active at the point,
// every row of E among them, and the point in P.
void ExpectVertex(const AffineVI& avi, const PolytopeVertex& v) {
  const int n = avi.size(), m = avi.inequality_count();
  ASSERT_TRUE(v.found) << avi.name() << ": " << v.why;
  ASSERT_EQ(static_cast<int>(v.rows.size()), n) << avi.name();
  DenseMatrix rows(n, n);
  for (int k = 0; k < n; ++k) {
    const int r = v.rows[static_cast<std::size_t>(k)];
    rows.row(k) = r < m ? avi.H().row(r) : avi.E().row(r - m);
    const double residual = r < m ? avi.H().row(r).dot(v.point) - avi.K()[r]
                                  : avi.E().row(r - m).dot(v.point) - avi.f()[r - m];
    EXPECT_LE(std::abs(residual), 1e-12 * (1.0 + v.point.cwiseAbs().maxCoeff())) << avi.name() << " row " << r;
  }
  EXPECT_EQ(Eigen::FullPivLU<DenseMatrix>(rows).rank(), n) << avi.name();
  for (int j = 0; j < avi.equality_count(); ++j) {
    EXPECT_NE(std::find(v.rows.begin(), v.rows.end(), m + j), v.rows.end()) << avi.name() << " equality " << j;
  }
  EXPECT_GE((avi.H() * v.point - avi.K()).minCoeff(), -1e-12) << avi.name();
}

TEST(FindPolytopeVertex, PlantedPolytopesWithAndWithoutEqualities) {
  for (int n : {1, 2, 4, 7}) {
    for (int p : {0, 1, 2}) {
      if (p >= n) continue;
      const PlantedAvi planted = MakePlantedAvi(n, 4, std::min(1, n - p), p, 5);
      ExpectVertex(planted.avi, FindPolytopeVertex(planted.avi.H(), planted.avi.K(), planted.avi.E(),
                                                   planted.avi.f(), &planted.avi.feasible_point()));
      // From the phase-1 simplex's own point as well.
      ExpectVertex(planted.avi, FindPolytopeVertex(planted.avi.H(), planted.avi.K(), planted.avi.E(), planted.avi.f()));
    }
  }
}

// Implicit twisting's parallelogram from its centre: no row active at the start, two steps to a corner.
TEST(FindPolytopeVertex, ParallelogramFromItsCentre) {
  DenseMatrix H(4, 2);
  H << 1, 0, -1, 0, -0.05, 1, 0.05, -1;
  const AffineVI avi(DenseMatrix::Identity(2, 2), Vec({0, 0}), H, Vector::Constant(4, -1.0), "parallelogram");
  const Vector centre = Vec({0, 0});
  const PolytopeVertex v = FindPolytopeVertex(avi.H(), avi.K(), avi.E(), avi.f(), &centre);
  ExpectVertex(avi, v);
  EXPECT_NEAR(std::abs(v.point[0]), 1.0, 1e-15);  // a corner: |λ₁| = 1, |λ₂ − 0.05λ₁| = 1
  EXPECT_NEAR(std::abs(v.point[1] - 0.05 * v.point[0]), 1.0, 1e-15);
}

// A degenerate vertex (three rows through the origin in the plane) as the start: two of its rows are chosen.
TEST(FindPolytopeVertex, DegenerateVertexKeepsTwoIndependentRows) {
  const AffineVI avi(DenseMatrix::Identity(2, 2), Vec({1, 1}), Mat({{1, 0}, {0, 1}, {1, -1}, {-1, 0}, {0, -1}}),
                     Vec({0, 0, 0, -1, -1}), "degenerate-triangle");
  const Vector origin = Vec({0, 0});
  const PolytopeVertex v = FindPolytopeVertex(avi.H(), avi.K(), avi.E(), avi.f(), &origin);
  ExpectVertex(avi, v);
  EXPECT_EQ(v.point, origin);
}

// No vertex: a strip (λ₂ free), a half-space, and a polytope whose equality leaves a free direction.
TEST(FindPolytopeVertex, PolytopesContainingALineHaveNone) {
  const AffineVI strip(DenseMatrix::Identity(2, 2), Vec({0, 0}), Mat({{1, 0}, {-1, 0}}), Vec({-1, -1}), "strip");
  const AffineVI half_space(DenseMatrix::Identity(3, 3), Vec({0, 0, 0}), Mat({{1, 1, 1}}), Vec({0}), "half-space");
  const AffineVI plane(DenseMatrix::Identity(3, 3), Vec({0, 0, 0}), Mat({{1, 0, 0}}), Vec({0}), Mat({{0, 1, 0}}),
                       Vec({2}), "slab-in-a-plane");
  for (const AffineVI* avi : {&strip, &half_space, &plane}) {
    const PolytopeVertex v = FindPolytopeVertex(avi->H(), avi->K(), avi->E(), avi->f());
    EXPECT_FALSE(v.found) << avi->name();
    EXPECT_TRUE(v.contains_line) << avi->name();
    EXPECT_THAT(v.why, HasSubstr("no vertex")) << avi->name();
  }
}

}  // namespace
}  // namespace smcbench

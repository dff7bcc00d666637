// siconos-avi-caoferris: Siconos' Cao–Ferris stage 3 at our vertex, through SolveAvi (the AVI itself) and
// Solver::Solve (a box as the polytope l <= z <= u). Truths are independent of Siconos: the projection onto
// implicit twisting's parallelogram worked out by hand (docs/avi.md), planted AVIs with a known unique λ*,
// degenerate vertices whose answer is known, and lemke on the same AVIs through the reduction. Also why the adapter
// exists: Siconos' own avi_caoferris exits (code 1) in this build, which a worker process turns into a status.
#include "solvers/siconos/siconos_avi_solver.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

// Siconos Numerics C API, for its own avi_caoferris (the call the adapter cannot make).
#include "AVI_Solvers.h"
#include "AVI_cst.h"
#include "AffineVariationalInequalities.h"
#include "NumericsMatrix.h"
#include "SiconosSets.h"
#include "SolverOptions.h"
#include "solvers/avi/avi_solver.h"
#include "solvers/avi/planted_avi_test_util.h"
#include "solvers/registry/registry.h"
#include "solvers/isolation/child_process.h"
#include "tests/support/eigen_literals.h"

// Siconos 4.4 leaks a few bytes per call in some solvers; the in-process calls here are Siconos' (as in
// siconos_solver_test.cc, whose suppression is linked into the same binary).

namespace smcbench {
namespace {

using test_support::Mat;
using test_support::Vec;

constexpr double kTol = 1e-10;

double MaxAbs(const Vector& v) { return v.size() ? v.cwiseAbs().maxCoeff() : 0.0; }

TEST(SiconosAviCaoFerris, IsRegisteredAsABoxBackendThatTakesAvisDirectly) {
  auto solver = CreateSolver("siconos-avi-caoferris");
  ASSERT_NE(solver, nullptr);
  EXPECT_TRUE(solver->info().box);
  EXPECT_TRUE(solver->info().external);
  EXPECT_NE(dynamic_cast<DirectAviBackend*>(solver.get()), nullptr);
}

// docs/avi.md's example: the projection of c = (2, 3) onto |λ₁| ≤ 1, |λ₂ − 0.05λ₁| ≤ 1 is λ = (1, 1.05) (on the
// corner λ₁ = 1, λ₂ − 0.05λ₁ = 1), with μ = (0, 1.0975, 0, 1.95): c − λ = (1, 1.95) = 1.0975·(1, 0) +
// 1.95·(−0.05, 1), the outer normals of the two active rows.
TEST(SiconosAviCaoFerris, TwistingProjectionOfTheDocs) {
  DenseMatrix H(4, 2);
  H << 1, 0, -1, 0, -0.05, 1, 0.05, -1;
  const AffineVI avi(DenseMatrix::Identity(2, 2), -Vec({2, 3}), H, Vector::Constant(4, -1.0), "twisting-projection");
  for (const char* isolate : {"always", "never"}) {
    SCOPED_TRACE(isolate);
    auto solver = CreateSolver("siconos-avi-caoferris");
    std::string error;
    ASSERT_TRUE(solver->SetOption("isolate", isolate, &error)) << error;
    const AviResult r = SolveAvi(avi, *solver);
    ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
    EXPECT_EQ(r.judgement.verdict, Verdict::kSolved);
    EXPECT_EQ(r.reduced.GetDetail("siconos_info"), 0.0);
    EXPECT_EQ(r.reduced.backend_code, std::optional<int>(0));  // what bench records
    EXPECT_EQ(AnswerProcessOf(r.reduced),
              std::string(isolate) == "always" ? AnswerProcess::kWorker : AnswerProcess::kThisProcess);
    EXPECT_LE((r.solution.lambda - Vec({1, 1.05})).cwiseAbs().maxCoeff(), 1e-14);
    // μ is stage 3's own (its basic u), mapped back: not recomputed by SolveAvi.
    ASSERT_EQ(r.solution.mu.size(), 4);
    EXPECT_LE((r.solution.mu - Vec({0, 1.0975, 0, 1.95})).cwiseAbs().maxCoeff(), 1e-13);
  }
}

// Planted AVIs (λ*, its face and μ* ≥ 0 chosen, q derived): strictly monotone, so λ* is the only solution. With
// and without equality rows (each a pair of rows for stage 3, ν = u₊ − u₋), several active rows.
TEST(SiconosAviCaoFerris, PlantedAvisGiveThePlantedSolution) {
  auto solver = CreateSolver("siconos-avi-caoferris");
  int solved = 0;
  for (int n : {2, 3, 5, 8}) {
    for (int p : {0, 1}) {
      for (std::uint64_t seed : {1u, 2u, 3u}) {
        const int active = std::min(2, n - p);
        const PlantedAvi planted = MakePlantedAvi(n, 3, active, p, seed);
        SolverOptions options;
        options.tolerance = kTol;
        const AviResult r = SolveAvi(planted.avi, *solver, options);
        SCOPED_TRACE(planted.avi.name() + ": " + std::string(ToString(r.status)) + " " + r.message);
        ASSERT_EQ(r.status, SolveStatus::kSolved);
        ASSERT_EQ(r.solution.lambda.size(), planted.solution.lambda.size());
        ASSERT_EQ(r.solution.mu.size(), planted.solution.mu.size());
        ASSERT_EQ(r.solution.nu.size(), planted.solution.nu.size());
        ++solved;
        const double scale = 1.0 + MaxAbs(planted.solution.lambda);
        EXPECT_LE(MaxAbs(r.solution.lambda - planted.solution.lambda), 1e-9 * scale);
        EXPECT_LE(MaxAbs(r.solution.mu - planted.solution.mu), 1e-8 * (1.0 + MaxAbs(planted.solution.mu)));
        EXPECT_LE(MaxAbs(r.solution.nu - planted.solution.nu), 1e-8 * (1.0 + MaxAbs(planted.solution.nu)));
      }
    }
  }
  EXPECT_EQ(solved, 24);
}

// Degenerate vertices: P = {0 ≤ λ₂ ≤ λ₁ ≤ 1} has three active rows at (0, 0) and at (1, 1). With M = I, λ is the
// projection of −q onto P: of (−1, −1) it is (0, 0); of (0.5, 2) it is (1, 1) (its projection on the line
// λ₁ = λ₂ is (1.25, 1.25), outside, and c − λ = (−0.5, 1) = 0.5·(−1, 1) + 0.5·(0, 1) is in the normal cone).
TEST(SiconosAviCaoFerris, DegenerateVertices) {
  const DenseMatrix H = Mat({{1, 0}, {0, 1}, {1, -1}, {-1, 0}, {0, -1}});
  const Vector K = Vec({0, 0, 0, -1, -1});
  auto solver = CreateSolver("siconos-avi-caoferris");
  for (const auto& [q, expected] : {std::pair<Vector, Vector>{Vec({1, 1}), Vec({0, 0})},
                                    std::pair<Vector, Vector>{Vec({-0.5, -2}), Vec({1, 1})}}) {
    const AffineVI avi(DenseMatrix::Identity(2, 2), q, H, K, "degenerate-triangle");
    const AviResult r = SolveAvi(avi, *solver);
    ASSERT_EQ(r.status, SolveStatus::kSolved) << r.message;
    EXPECT_EQ(r.judgement.verdict, Verdict::kSolved);
    EXPECT_LE((r.solution.lambda - expected).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_GE(r.solution.mu.minCoeff(), 0.0);
  }
}

// No vertex: a strip in the plane (λ₂ free), a half-space, and a box-MLCP with a free row. Refused with the reason;
// nothing reaches Siconos.
TEST(SiconosAviCaoFerris, NoVertexIsNotApplicable) {
  auto solver = CreateSolver("siconos-avi-caoferris");
  const AffineVI strip(DenseMatrix::Identity(2, 2), Vec({1, -1}), Mat({{1, 0}, {-1, 0}}), Vec({-1, -1}), "strip");
  const AffineVI half_space(DenseMatrix::Identity(3, 3), Vec({1, 2, 3}), Mat({{1, 1, 1}}), Vec({0}), "half-space");
  for (const AffineVI* avi : {&strip, &half_space}) {
    const AviResult r = SolveAvi(*avi, *solver);
    EXPECT_EQ(r.status, SolveStatus::kNotApplicable) << avi->name();
    EXPECT_THAT(r.message, ::testing::HasSubstr("no vertex")) << avi->name();
    EXPECT_TRUE(std::isnan(r.reduced.GetDetail("siconos_info")));
    EXPECT_EQ(r.reduced.backend_code, std::nullopt);  // Siconos never called
  }
  const BoxMLCP mixed(DenseMatrix::Identity(2, 2), Vec({1, -1}), Vec({0, -kInf}), Vec({kInf, kInf}));
  const SolveResult r = solver->Solve(mixed);
  EXPECT_EQ(r.status, SolveStatus::kNotApplicable);
  EXPECT_THAT(r.message, ::testing::HasSubstr("row 1 has no finite bound"));
}

// A box-MLCP is the AVI over {l ≤ z ≤ u}: the same answer as lemke's on a P-matrix box (unique z), through both
// entry points (Solve on the box, SolveAvi on AviFromBox's AVI), with a fixed row among them.
TEST(SiconosAviCaoFerris, BoxAsPolytopeAgreesWithLemke) {
  const DenseMatrix M = Mat({{4, 1, 0, 1}, {-1, 3, 1, 0}, {0, 1, 5, -2}, {2, 0, 1, 4}});
  const BoxMLCP box(M, Vec({-3, 2, -1, 5}), Vec({-1, 0, 0.25, 0}), Vec({1, kInf, 0.25, 2}), "box-with-fixed-row");
  auto solver = CreateSolver("siconos-avi-caoferris");
  auto lemke = CreateSolver("lemke");
  const SolveResult reference = lemke->Solve(box);
  ASSERT_TRUE(reference.solved()) << reference.message;
  const SolveResult r = solver->Solve(box);
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_EQ(r.GetDetail("siconos_info"), 0.0);
  EXPECT_EQ(r.backend_code, std::optional<int>(0));
  EXPECT_EQ(r.GetDetail("standard_size"), 7.0);  // rows of P: 2 + 1 + 2 (the fixed row) + 2
  EXPECT_LE((r.z - reference.z).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(r.z[2], 0.25);
  const AviResult a = SolveAvi(AviFromBox(box), *solver);
  ASSERT_EQ(a.status, SolveStatus::kSolved) << a.message;
  EXPECT_LE((a.solution.lambda - reference.z).cwiseAbs().maxCoeff(), 1e-12);
}

// Agreement with lemke through the reduction on planted AVIs whose M is positive semidefinite and singular (λ not
// unique): both solve, and both give the same Mλ (every solution of a monotone symmetric AVI has the same Mλ).
TEST(SiconosAviCaoFerris, SingularMonotoneAvisAgreeWithLemkeOnMLambda) {
  auto solver = CreateSolver("siconos-avi-caoferris");
  auto lemke = CreateSolver("lemke");
  for (std::uint64_t seed : {1u, 2u, 3u, 4u}) {
    const PlantedAvi planted = MakePlantedAvi(4, 3, 2, 0, seed, /*strictly_monotone=*/false);
    const AviResult mine = SolveAvi(planted.avi, *solver);
    const AviResult theirs = SolveAvi(planted.avi, *lemke);
    ASSERT_EQ(mine.status, SolveStatus::kSolved) << planted.avi.name() << ": " << mine.message;
    ASSERT_EQ(theirs.status, SolveStatus::kSolved) << planted.avi.name();
    const Vector a = planted.avi.M() * mine.solution.lambda, b = planted.avi.M() * theirs.solution.lambda;
    EXPECT_LE((a - b).cwiseAbs().maxCoeff(), 1e-8 * (1.0 + MaxAbs(b))) << planted.avi.name();
  }
}

// A ray is Siconos' info 1, reported as a ray that proves nothing: λ ≥ 0 with M = 0, q = −1 has no solution.
TEST(SiconosAviCaoFerris, NoSolutionIsARayNotInfeasible) {
  auto solver = CreateSolver("siconos-avi-caoferris");
  const AffineVI avi(DenseMatrix::Zero(1, 1), Vec({-1}), Mat({{1}}), Vec({0}), "unbounded-no-solution");
  const AviResult r = SolveAvi(avi, *solver);
  EXPECT_FALSE(r.solved());
  EXPECT_NE(r.status, SolveStatus::kInfeasible);
  EXPECT_EQ(r.status, SolveStatus::kRayTermination) << r.message;
  EXPECT_THAT(r.message, ::testing::HasSubstr("not a proof"));
}

// Why the adapter finds the vertex itself: Siconos' own avi_caoferris, on docs/avi.md's twisting projection, ends the
// process that calls it (Debian's 4.4 has no lp_solve: siconos_find_vertex prints a message and calls exit). Run in a
// worker process, as the adapters run Siconos, that exit is a status for the caller and never the caller's end.
void CallSiconosOwnAviCaoFerris(int fd, void* /*context*/) {
  double M[4] = {1, 0, 0, 1};
  double q[2] = {-2, -3};
  double H[8] = {-1, 1, 0.05, -0.05, 0, 0, -1, 1};  // Siconos' Hλ ≤ K, column-major: our rows negated
  double K[4] = {1, 1, 1, 1};
  polyhedron poly{};
  poly.id = SICONOS_SET_POLYHEDRON;
  poly.size_ineq = 4;
  poly.H = NM_create_from_data(NM_DENSE, 4, 2, H);
  poly.K = K;
  AffineVariationalInequalities avi{};
  avi.size = 2;
  avi.M = NM_create_from_data(NM_DENSE, 2, 2, M);
  avi.q = q;
  avi.poly.split = &poly;
  ::SolverOptions* options = solver_options_create(SICONOS_AVI_CAOFERRIS);
  double z[2] = {0, 0}, w[2] = {0, 0};
  const int info = avi_caoferris(&avi, z, w, options);
  ChildProcess::WriteAll(fd, &info, sizeof info);  // reached only if Siconos returned
}

TEST(SiconosAviCaoFerris, SiconosOwnAviCaoFerrisExitsAndAWorkerMakesThatAStatus) {
  ChildProcess worker;
  std::string error;
  ASSERT_TRUE(worker.Start(&CallSiconosOwnAviCaoFerris, nullptr, /*keep_output=*/false, &error)) << error;
  int info = -1;
  const ChildProcess::Io io = worker.Read(&info, sizeof info, ChildProcess::Clock::now() + std::chrono::seconds(60));
  ASSERT_EQ(io, ChildProcess::Io::kClosed) << "Siconos' avi_caoferris returned " << info;
  int signal = -1;
  const std::string how = worker.Reap(&signal);
  EXPECT_EQ(signal, 0) << how;
  EXPECT_THAT(how, ::testing::HasSubstr("exited with code"));
  EXPECT_THAT(how, ::testing::Not(::testing::HasSubstr("code 0")));
  std::printf("[ info     ] Siconos' own avi_caoferris in a worker: %s\n", how.c_str());
}

}  // namespace
}  // namespace smcbench

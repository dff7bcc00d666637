// SolveAvi over every registered box backend, and the AVI verdict: planted strictly monotone AVIs (λ unique, the
// forward error judged against a certified reference), a singular M whose λ is not unique (residual rule alone),
// the verdict's invariance under scaling (M, q) and the rows of (H, K), an AVI without a solution, warm starts, a
// backend on P directly, and the one-step problems of Siconos' implicit-twisting regression test.
#include "solvers/avi/avi_solver.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>  // erand48, as in Siconos' twisting test
#include <memory>
#include <string>

#include "solvers/avi/planted_avi_test_util.h"
#include "solvers/registry/registry.h"
#include "tests/support/eigen_literals.h"
#include "tests/support/malloc_counter.h"

namespace smcbench {
namespace {

using test_support::Mat;
using test_support::Vec;

// Backends that solve every reduction of a strictly monotone AVI here (exact pivoting on a positive semidefinite
// reduced matrix; the exhaustive enumeration): the others may refuse or fail, never answer wrongly.
const char* const kSolvesMonotoneAvis[] = {"lemke", "enum"};

bool MustSolve(std::string_view name) {
  for (const char* n : kSolvesMonotoneAvis) {
    if (name == n) return true;
  }
  return false;
}

TEST(SolveAvi, EveryBoxBackendOnPlantedAvis) {
  std::vector<PlantedAvi> problems;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) problems.push_back(MakePlantedAvi(4, 3, 2, 1, seed));
  problems.push_back(MakePlantedAvi(3, 5, 3, 0, 11));  // a vertex of P: three active rows, no equality
  std::vector<AviReference> references;
  for (const PlantedAvi& p : problems) {
    references.push_back(CertifyAvi(p.avi, {p.solution}));
    ASSERT_TRUE(references.back().verified()) << p.avi.name();
    ASSERT_TRUE(references.back().lambda_unique) << p.avi.name();
  }
  for (const std::string_view name : SolverNames()) {
    const std::unique_ptr<Solver> solver = CreateSolver(name);
    if (!solver->info().box) continue;
    int solved = 0;
    std::string first_failure;
    for (std::size_t k = 0; k < problems.size(); ++k) {
      const AviResult r = SolveAvi(problems[k].avi, *solver, {}, &references[k]);
      EXPECT_FALSE(IsWrong(r.judgement.verdict))
          << name << " on " << problems[k].avi.name() << ": " << ToString(r.judgement.verdict);
      EXPECT_EQ(r.solver, name);
      if (r.judgement.verdict == Verdict::kSolved) {
        ++solved;
        EXPECT_TRUE(r.judgement.forward_error_applicable);
        EXPECT_LE(r.judgement.forward_error, r.judgement.forward_allowance);
      } else {
        EXPECT_FALSE(r.solved()) << name;  // a status other than solved, with its message
        EXPECT_FALSE(r.message.empty()) << name;
      }
      if (r.judgement.verdict != Verdict::kSolved && first_failure.empty()) {
        first_failure = std::string(ToString(r.status)) + ": " + r.message.substr(0, 80);
      }
      if (MustSolve(name)) {
        EXPECT_EQ(r.judgement.verdict, Verdict::kSolved) << name << ": " << r.message;
      }
    }
    std::printf("%-24s solved %d of %zu planted AVIs %s\n", std::string(name).c_str(), solved, problems.size(),
                first_failure.c_str());
  }
}

TEST(SolveAvi, CertifiedReferenceIsThePlantedSolution) {
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const PlantedAvi planted = MakePlantedAvi(3, 2, 1, 1, seed);
    // From the cold point alone (no candidate): the certifier's own search finds it.
    const AviReference reference = CertifyAvi(planted.avi, {});
    ASSERT_TRUE(reference.verified()) << planted.avi.name();
    EXPECT_EQ(reference.strictly_monotone, MatrixClassAnswer::kYes);
    EXPECT_TRUE(reference.lambda_unique);
    EXPECT_LE((reference.solution.lambda - planted.solution.lambda).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_LE((reference.solution.mu - planted.solution.mu).cwiseAbs().maxCoeff(), 1e-13);
    // Judged against itself: solved with zero forward error; a λ moved by 1e-3 with its multipliers: inaccurate
    // or wrongly claimed, never solved.
    const AviJudgement self =
        JudgeAvi(planted.avi, ExpectedOutcome::kSolvable, &reference, SolveStatus::kSolved, reference.solution, 1e-10);
    EXPECT_EQ(self.verdict, Verdict::kSolved);
    EXPECT_EQ(self.forward_error, 0.0);
    AviSolution moved = reference.solution;
    moved.lambda[0] += 1e-3;
    const AviJudgement wrong =
        JudgeAvi(planted.avi, ExpectedOutcome::kSolvable, &reference, SolveStatus::kSolved, moved, 1e-10);
    EXPECT_TRUE(IsWrong(wrong.verdict)) << ToString(wrong.verdict);
  }
}

// M = diag(1, 0) on the square [−1, 1]², q = (0.5, 0): λ₁ = −0.5, and every λ₂ ∈ [−1, 1] solves it (F₂ ≡ 0), with
// μ = 0. λ is not unique, so the forward error does not apply: the residual rule alone decides.
TEST(SolveAvi, SingularMatrixJudgedByTheResidualAlone) {
  const AffineVI avi(Mat({{1, 0}, {0, 0}}), Vec({0.5, 0}), Mat({{1, 0}, {-1, 0}, {0, 1}, {0, -1}}),
                     Vec({-1, -1, -1, -1}), "segment-of-solutions");
  const AviReference reference = CertifyAvi(avi, {AviSolution{Vec({-0.5, 0.3}), Vector::Zero(4), {}}});
  ASSERT_TRUE(reference.verified());
  EXPECT_NE(reference.strictly_monotone, MatrixClassAnswer::kYes);
  EXPECT_FALSE(reference.lambda_unique);
  for (const double t : {-1.0, -0.2, 0.3, 1.0}) {
    const AviJudgement j = JudgeAvi(avi, ExpectedOutcome::kSolvable, &reference, SolveStatus::kSolved,
                                    AviSolution{Vec({-0.5, t}), Vector::Zero(4), {}}, 1e-10);
    EXPECT_EQ(j.verdict, Verdict::kSolved) << t;
    EXPECT_FALSE(j.forward_error_applicable);
    EXPECT_TRUE(std::isnan(j.forward_error));
  }
  // A λ₁ off by 1e-4: the residual sees it.
  const AviJudgement off = JudgeAvi(avi, ExpectedOutcome::kSolvable, &reference, SolveStatus::kSolved,
                                    AviSolution{Vec({-0.5001, 0.3}), Vector::Zero(4), {}}, 1e-10);
  EXPECT_EQ(off.verdict, Verdict::kWronglyClaimed);
  // Outside P (λ₂ = 1.5): primal infeasibility, wrongly claimed.
  const AviJudgement outside = JudgeAvi(avi, ExpectedOutcome::kSolvable, &reference, SolveStatus::kSolved,
                                        AviSolution{Vec({-0.5, 1.5}), Vector::Zero(4), {}}, 1e-10);
  EXPECT_EQ(outside.verdict, Verdict::kWronglyClaimed);
  EXPECT_NEAR(outside.primal_infeasibility, 0.5 / 2.5, 1e-15);
  for (const char* name : kSolvesMonotoneAvis) {
    const std::unique_ptr<Solver> solver = CreateSolver(name);
    const AviResult r = SolveAvi(avi, *solver, {}, &reference);
    EXPECT_EQ(r.judgement.verdict, Verdict::kSolved) << name << ": " << r.message;
    EXPECT_NEAR(r.solution.lambda[0], -0.5, 1e-12) << name;
  }
}

// Positive semidefinite singular M (rank 1, as the one-step matrix of a controller acting through one channel):
// λ is not unique, but for a monotone AVI with symmetric M every solution has the same Mλ (Mλ is what moves the
// state x, the quantity twisting's verdict is about). Every backend that solves it gives the same Mλ.
TEST(SolveAvi, SingularMonotoneAvisAgreeOnMLambda) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const PlantedAvi planted = MakePlantedAvi(3, 3, 1, 0, seed, /*strictly_monotone=*/false);
    const AviReference reference = CertifyAvi(planted.avi, {planted.solution});
    ASSERT_TRUE(reference.verified()) << planted.avi.name();
    const Vector m_lambda = planted.avi.M() * planted.solution.lambda;
    for (const std::string_view name : SolverNames()) {
      const std::unique_ptr<Solver> solver = CreateSolver(name);
      if (!solver->info().box) continue;
      const AviResult r = SolveAvi(planted.avi, *solver, {}, &reference);
      EXPECT_FALSE(IsWrong(r.judgement.verdict)) << name << " on " << planted.avi.name();
      if (!reference.lambda_unique) {
        EXPECT_FALSE(r.judgement.forward_error_applicable);
      }
      if (r.judgement.verdict != Verdict::kSolved) continue;
      EXPECT_LE((planted.avi.M() * r.solution.lambda - m_lambda).cwiseAbs().maxCoeff(), 1e-7)
          << name << " on " << planted.avi.name();
    }
  }
}

// Scaling (M, q) by α and row i of (H, K) by β_i leaves P and the solutions λ unchanged, and the stated multipliers
// become αμ_i/β_i: the verdict's residuals are the same to rounding.
TEST(SolveAvi, VerdictIsScaleFree) {
  const PlantedAvi planted = MakePlantedAvi(4, 3, 2, 1, 7);
  const AffineVI& a = planted.avi;
  AviSolution answer = planted.solution;
  answer.lambda[1] += 1e-7;  // not a solution: a residual well above rounding
  const AviJudgement base = JudgeAvi(a, ExpectedOutcome::kSolvable, nullptr, SolveStatus::kSolved, answer, 1e-10);
  for (const double alpha : {1e-8, 1e6}) {
    Vector beta(a.inequality_count());
    for (int i = 0; i < beta.size(); ++i) beta[i] = i % 2 ? 1e-5 : 1e4;
    const double gamma = 1e3;  // the equality row's scale
    const AffineVI scaled(alpha * a.M(), alpha * a.q(), beta.asDiagonal() * a.H(), beta.cwiseProduct(a.K()),
                          gamma * a.E(), gamma * a.f());
    const AviSolution mapped{answer.lambda, alpha * answer.mu.cwiseQuotient(beta), alpha * answer.nu / gamma};
    const AviJudgement j = JudgeAvi(scaled, ExpectedOutcome::kSolvable, nullptr, SolveStatus::kSolved, mapped, 1e-10);
    EXPECT_EQ(j.verdict, base.verdict);
    EXPECT_NEAR(j.residual.rel, base.residual.rel, 1e-6 * base.residual.rel) << alpha;
    EXPECT_NEAR(j.residual.scaled, base.residual.scaled, 1e-6 * base.residual.scaled) << alpha;
    EXPECT_NEAR(j.primal_infeasibility, base.primal_infeasibility, 1e-12) << alpha;
    EXPECT_NEAR(j.complementarity, base.complementarity, 1e-6 * base.complementarity) << alpha;
    // And lemke finds the same λ on the scaled problem.
    const std::unique_ptr<Solver> lemke = CreateSolver("lemke");
    const AviResult r = SolveAvi(scaled, *lemke);
    EXPECT_EQ(r.judgement.verdict, Verdict::kSolved) << r.message;
    EXPECT_LE((r.solution.lambda - planted.solution.lambda).cwiseAbs().maxCoeff(), 1e-9);
  }
  EXPECT_GT(base.residual.scaled, 1e-9);
  EXPECT_GT(base.complementarity, 1e-9);  // λ₂ moved off the active faces
  EXPECT_EQ(base.verdict, Verdict::kWronglyClaimed);
}

// P = {λ ≥ 0} (unbounded), M = 0, q = −1: −1 + N_P(λ) never contains 0, so there is no solution. The expected
// outcome is unknown (P unbounded): no backend may claim solved; enum's certified "infeasible" is correct when the
// caller knows the AVI is infeasible.
TEST(SolveAvi, NoSolutionIsNeverSolved) {
  const AffineVI avi(Mat({{0}}), Vec({-1}), Mat({{1}}), Vec({0}), "ray");
  EXPECT_EQ(avi.boundedness(), PolytopeBoundedness::kUnbounded);
  EXPECT_EQ(ExpectedAviOutcome(avi), ExpectedOutcome::kUnknown);
  for (const std::string_view name : SolverNames()) {
    const std::unique_ptr<Solver> solver = CreateSolver(name);
    if (!solver->info().box) continue;
    const AviResult r = SolveAvi(avi, *solver);
    EXPECT_FALSE(r.solved()) << name;
    EXPECT_FALSE(IsWrong(r.judgement.verdict)) << name;
    if (r.status == SolveStatus::kInfeasible) {
      const AviJudgement j = JudgeAvi(avi, ExpectedOutcome::kInfeasible, nullptr, r.status, r.solution, 1e-10);
      EXPECT_EQ(j.verdict, Verdict::kCorrectlyRefused) << name;
    }
  }
}

TEST(SolveAvi, WarmStartsOfLambdaOrOfEveryUnknown) {
  const PlantedAvi planted = MakePlantedAvi(3, 2, 1, 1, 5);
  const std::unique_ptr<Solver> solver = CreateSolver("newton");
  const int total = planted.avi.size() + planted.avi.inequality_count() + planted.avi.equality_count();
  SolverOptions options;
  options.warm_start = planted.solution.lambda;
  const AviResult from_lambda = SolveAvi(planted.avi, *solver, options);
  EXPECT_NE(from_lambda.status, SolveStatus::kInvalidOptions) << from_lambda.message;
  options.warm_start.resize(total);
  options.warm_start << planted.solution.lambda, planted.solution.mu, planted.solution.nu;
  const AviResult from_all = SolveAvi(planted.avi, *solver, options);
  EXPECT_EQ(from_all.judgement.verdict, Verdict::kSolved) << from_all.message;
  options.warm_start = Vector::Zero(total - 1);
  EXPECT_EQ(SolveAvi(planted.avi, *solver, options).status, SolveStatus::kInvalidOptions);
}

}  // namespace
}  // namespace smcbench

namespace smcbench {
namespace {

// docs/avi.md's example, as printed there: the projection of c = (2, 3) onto implicit twisting's parallelogram
// |λ₁| ≤ 1, |λ₂ − (h/2)λ₁| ≤ 1 (h = 0.1) is the AVI with M = I, q = −c. By hand: the vertex where λ₁ = 1 and
// λ₂ − 0.05λ₁ = 1 meet, λ = (1, 1.05), and c − λ = (1, 1.95) = 1.0975·(1, 0) + 1.95·(−0.05, 1) is in its normal cone.
TEST(SolveAvi, DocsExample) {
  DenseMatrix H(4, 2);
  H << 1, 0, -1, 0, -0.05, 1, 0.05, -1;  // rows of Hλ ≥ K
  const AffineVI avi(DenseMatrix::Identity(2, 2), -Eigen::Vector2d(2, 3), H, Vector::Constant(4, -1.0),
                     "twisting-projection");
  std::unique_ptr<Solver> lemke = CreateSolver("lemke");
  const AviResult r = SolveAvi(avi, *lemke);
  // r.solution.lambda = (1, 1.05), r.solution.mu = (0, 1.0975, 0, 1.95), r.judgement.verdict = solved.
  EXPECT_EQ(r.judgement.verdict, Verdict::kSolved);
  EXPECT_NEAR(r.solution.lambda[0], 1.0, 1e-14);
  EXPECT_NEAR(r.solution.lambda[1], 1.05, 1e-14);
  EXPECT_NEAR(r.solution.mu[0], 0.0, 1e-14);
  EXPECT_NEAR(r.solution.mu[1], 1.0975, 1e-14);
  EXPECT_NEAR(r.solution.mu[2], 0.0, 1e-14);
  EXPECT_NEAR(r.solution.mu[3], 1.95, 1e-14);
  EXPECT_EQ(avi.boundedness(), PolytopeBoundedness::kBounded);
}

}  // namespace
}  // namespace smcbench

namespace smcbench {
namespace {

// A backend on P directly, for the test of SolveAvi's direct path: it answers a fixed λ (no multipliers) with the
// status it is given, as an external AVI code that returns λ alone would.
class FixedAnswerAviBackend final : public Solver, public DirectAviBackend {
 public:
  FixedAnswerAviBackend(Vector lambda, SolveStatus status) : lambda_(std::move(lambda)), status_(status) {}
  const SolverInfo& info() const override {
    static const SolverInfo kInfo{"fixed-avi-answer", "returns a given λ", "a test", true, false, false, true};
    return kInfo;
  }
  void SolveAviDirect(const AffineVI& /*avi*/, const SolverOptions& /*options*/, AviSolution* solution,
                      SolveResult* result) override {
    solution->lambda = lambda_;
    solution->mu.resize(0);
    solution->nu.resize(0);
    result->status = status_;
    result->iterations = 1;
    if (status_ != SolveStatus::kSolved) result->message = "as told";
  }

 protected:
  void DoSolve(const BoxMLCP& /*problem*/, const SolverOptions& /*options*/, SolveResult* result) override {
    result->status = SolveStatus::kNotApplicable;
    result->message = "AVIs only";
  }

 private:
  Vector lambda_;
  SolveStatus status_;
};

TEST(SolveAvi, DirectBackendGetsMultipliersAndTheRule) {
  const PlantedAvi planted = MakePlantedAvi(4, 3, 2, 1, 21);
  const AviReference reference = CertifyAvi(planted.avi, {planted.solution});
  FixedAnswerAviBackend right(planted.solution.lambda, SolveStatus::kSolved);
  const AviResult r = SolveAvi(planted.avi, right, {}, &reference);
  EXPECT_EQ(r.status, SolveStatus::kSolved) << r.message;
  EXPECT_EQ(r.judgement.verdict, Verdict::kSolved);
  EXPECT_EQ(r.solver, "fixed-avi-answer");
  EXPECT_LE((r.solution.mu - planted.solution.mu).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LE((r.solution.nu - planted.solution.nu).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LE(r.reduced.residual_scaled, 1e-14);
  // A wrong λ claimed solved: the shared rule makes it inaccurate (a failure, not a wrong verdict).
  Vector off = planted.solution.lambda;
  off[0] += 1e-3;
  FixedAnswerAviBackend wrong(off, SolveStatus::kSolved);
  const AviResult w = SolveAvi(planted.avi, wrong, {}, &reference);
  EXPECT_EQ(w.status, SolveStatus::kInaccurate);
  EXPECT_THAT(w.message, ::testing::HasSubstr("reported success"));
  EXPECT_EQ(w.judgement.verdict, Verdict::kFailed);
  // A λ of the wrong size claimed solved: numerical failure.
  FixedAnswerAviBackend short_answer(Vector::Zero(2), SolveStatus::kSolved);
  EXPECT_EQ(SolveAvi(planted.avi, short_answer).status, SolveStatus::kNumericalFailure);
  // The box path of such a backend is its own refusal.
  EXPECT_EQ(right.Solve(ReduceToBoxMlcp(planted.avi).problem).status, SolveStatus::kNotApplicable);
}

// A degenerate vertex: λ = 0 with three active rows λ₁ ≥ 0, λ₂ ≥ 0, λ₁ − λ₂ ≥ 0 and Mλ + q = (1, 1). The
// multipliers are not unique (μ = (1 − t, 1 + t, t), t ∈ [0, 1]); a least-squares basis can pick a negative one
// (Eigen's column-pivoted QR gives t = −1 here), and AviMultipliersAt must return a nonnegative choice.
TEST(AviMultipliersAt, NonnegativeAtADegenerateVertex) {
  const AffineVI avi(DenseMatrix::Identity(2, 2), Vec({1, 1}), Mat({{1, 0}, {0, 1}, {1, -1}, {-1, 0}, {0, -1}}),
                     Vec({0, 0, 0, -1, -1}));
  const AviSolution s = AviMultipliersAt(avi, Vec({0, 0}));
  ASSERT_EQ(s.mu.size(), 5);
  EXPECT_GE(s.mu.minCoeff(), 0.0);
  EXPECT_EQ(s.mu[3], 0.0);  // inactive rows carry none
  EXPECT_EQ(s.mu[4], 0.0);
  EXPECT_LE((avi.H().transpose() * s.mu - Vec({1, 1})).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_EQ(JudgeAvi(avi, ExpectedOutcome::kSolvable, nullptr, SolveStatus::kSolved, s, 1e-10).verdict,
            Verdict::kSolved);
}

}  // namespace
}  // namespace smcbench

namespace smcbench {
namespace {

// Siconos' regression test numerics/src/AVI/test/implicit_twisting.c, its one-step problems solved through the
// reduction: implicit twisting of a double integrator, TS = 10e-3, gains G = 10, β = 0.1, the parallelogram
// |λ₁| ≤ 1, |λ₂ − (TS/2)λ₁| ≤ 1, 10 000 steps. Each step is the AVI with M = G·TS·[[TS/2, β·TS/2], [1, β]] (rank 1,
// M + Mᵀ indefinite: λ is not unique, only x is judged) and q = (x₁ + TS·x₂, x₂); x_{k+1} = σ = Mλ + q.
// Siconos' acceptance test: σᵀ(v + λ) ≤ 1e-12 at each vertex v of P (P = −P: the VI at the vertices).
struct TwistingRun {
  int steps = 0;            // steps solved before the first that was not (kSteps: all)
  double worst = -kInf;     // max over steps and vertices of σᵀ(v + λ)
  double worst_relative = -kInf;  // the same divided by 1 + ‖q‖∞ of its step
  Eigen::Vector2d x;        // the state after the last solved step
};

TwistingRun RunImplicitTwisting(const Eigen::Vector2d& x0, Solver& solver, const SolverOptions& options) {
  constexpr double kTs = 10e-3, kG = 10.0, kBeta = 0.1;
  constexpr int kSteps = 10000;
  DenseMatrix M(2, 2);
  M << kG * kTs * kTs / 2.0, kBeta * kG * kTs * kTs / 2.0, kG * kTs, kBeta * kG * kTs;
  const DenseMatrix H = Mat({{1, 0}, {-kTs / 2.0, 1}, {-1, 0}, {kTs / 2.0, -1}});
  const DenseMatrix vertices =
      Mat({{-1, -1 - kTs / 2.0}, {-1, 1 - kTs / 2.0}, {1, 1 + kTs / 2.0}, {1, -1 + kTs / 2.0}});
  AffineVI avi(M, Vec({x0[0] + kTs * x0[1], x0[1]}), H, Vector::Constant(4, -1.0), "siconos-implicit-twisting");
  TwistingRun run;
  run.x = x0;
  for (; run.steps < kSteps; ++run.steps) {
    avi.set_q(Vec({run.x[0] + kTs * run.x[1], run.x[1]}));
    const AviResult r = SolveAvi(avi, solver, options);
    EXPECT_FALSE(IsWrong(r.judgement.verdict)) << solver.info().name << " step " << run.steps;
    if (r.judgement.verdict != Verdict::kSolved) break;
    const Vector sigma = avi.M() * r.solution.lambda + avi.q();
    for (int v = 0; v < 4; ++v) {
      const double c = sigma.dot(vertices.row(v).transpose() + r.solution.lambda);
      run.worst = std::max(run.worst, c);
      run.worst_relative = std::max(run.worst_relative, c / (1.0 + avi.q().cwiseAbs().maxCoeff()));
    }
    run.x = sigma;
  }
  return run;
}

// Siconos' own start, x₀ = 50·erand48 from the zero seed (about 2e-12: its test starts at the origin's doorstep),
// and its absolute test, which at that size asks more than our relative tolerance 1e-10 (λ = 0 passes it with
// σ ≈ 1e-11): with the tolerance tightened to 1e-14, lemke and enum solve all 10 000 steps and pass Siconos' test;
// the others may stop (a status, never a wrong answer).
TEST(SolveAvi, SiconosImplicitTwistingRegression) {
  unsigned short seed1[3] = {0, 0, 0}, seed2[3] = {0, 0, 0};
  const double x1 = 50 * erand48(seed1), x2 = 50 * erand48(seed2);
  SolverOptions options;
  options.tolerance = 1e-14;
  for (const std::string_view name : SolverNames()) {
    const std::unique_ptr<Solver> solver = CreateSolver(name);
    if (!solver->info().box || solver->info().external) continue;
    const TwistingRun run = RunImplicitTwisting(Eigen::Vector2d(x1, x2), *solver, options);
    std::printf("%-12s %5d steps solved, max σᵀ(v + λ) = %.2e\n", std::string(name).c_str(), run.steps, run.worst);
    if (name == "lemke" || name == "enum") {
      EXPECT_EQ(run.steps, 10000) << name;
    }
    if (run.steps == 10000) {
      EXPECT_LE(run.worst, 1e-12) << name;
    }
  }
}

// From x₀ = (10, −5) at the default tolerance: the trajectory reaches and keeps a neighbourhood of the origin, and
// Siconos' test holds relative to the step's scale (σᵀ(v + λ) ≤ 1e-10·(1 + ‖q‖∞)).
TEST(SolveAvi, ImplicitTwistingFromAFarStart) {
  for (const char* name : kSolvesMonotoneAvis) {
    const std::unique_ptr<Solver> solver = CreateSolver(name);
    const TwistingRun run = RunImplicitTwisting(Eigen::Vector2d(10.0, -5.0), *solver, {});
    std::printf("%-12s %5d steps solved, max σᵀ(v + λ)/(1 + ‖q‖) = %.2e, final x = (%.2e, %.2e)\n", name, run.steps,
                run.worst_relative, run.x[0], run.x[1]);
    EXPECT_EQ(run.steps, 10000) << name;
    EXPECT_LE(run.worst_relative, 1e-10) << name;
    EXPECT_LE(run.x.cwiseAbs().maxCoeff(), 1e-6) << name;
  }
}

}  // namespace
}  // namespace smcbench

namespace smcbench {
namespace {

// The prepared session answers as SolveAvi does (the same reduction, the same backend), step after step of the
// implicit-twisting loop, and allocates nothing after the first solve for an allocation-free backend.
TEST(AviSession, AnswersAsSolveAviWithoutAllocating) {
  constexpr double kTs = 10e-3, kG = 10.0, kBeta = 0.1;
  DenseMatrix M(2, 2);
  M << kG * kTs * kTs / 2.0, kBeta * kG * kTs * kTs / 2.0, kG * kTs, kBeta * kG * kTs;
  const DenseMatrix H = Mat({{1, 0}, {-kTs / 2.0, 1}, {-1, 0}, {kTs / 2.0, -1}});
  for (const char* name : kSolvesMonotoneAvis) {
    const std::unique_ptr<Solver> solver = CreateSolver(name);
    SolverOptions options;
    options.measure_time = false;
    AffineVI avi(M, Vec({10.0, -5.0}), H, Vector::Constant(4, -1.0));
    // The backend's own answer at every step, as SolveAvi's (M is rank one: another path may pick another λ).
    AviSession session(avi, *solver, options, SessionOptions{/*reuse_active_set=*/false});
    Vector q(2), x(2);
    x << 10.0, -5.0;
    for (int step = 0; step < 200; ++step) {
      q << x[0] + kTs * x[1], x[1];
      ASSERT_EQ(session.Solve(q), SolveStatus::kSolved) << name << " step " << step << ": " << session.result().message;
      avi.set_q(q);
      const AviResult reference = SolveAvi(avi, *solver, options);
      ASSERT_EQ(reference.status, SolveStatus::kSolved) << name;
      EXPECT_LE((session.solution().lambda - reference.solution.lambda).cwiseAbs().maxCoeff(), 1e-15) << name;
      EXPECT_LE((session.solution().mu - reference.solution.mu).cwiseAbs().maxCoeff(), 1e-12) << name;
      x = M * session.solution().lambda + q;
    }
    if (!test_support::CanCountMallocs()) continue;
    // The comparison above gave the backend other matrices: one solve to make its per-matrix copies again.
    q << x[0] + kTs * x[1], x[1];
    session.Solve(q);
    const long mallocs = test_support::CountMallocs([&] {
      for (int step = 0; step < 100; ++step) {
        q << x[0] + kTs * x[1], x[1];
        session.Solve(q);
        x.noalias() = M * session.solution().lambda;
        x += q;
      }
    });
    EXPECT_EQ(mallocs, 0) << name;
  }
  const std::unique_ptr<Solver> lemke = CreateSolver("lemke");
  AviSession session(AffineVI(M, Vec({1, 1}), H, Vector::Constant(4, -1.0)), *lemke);
  EXPECT_THROW(session.Solve(Vec({1, 2, 3})), InvalidInputError);
  EXPECT_THROW(session.Solve(Vec({1, kNaN})), InvalidInputError);
}

// A warm start given as stated, (λ, μ) of the previous answer, reaches the backend in the reduction's units
// (μ̃_i = μ_i h_i/σ): started at its own answer, a backend that starts where it is told (semismooth Newton) stops
// at once. Rows of (H, K) scaled by 2 and 3 and σ = 0.2 make a map that forgot a scale start elsewhere.
TEST(AviSession, WarmStartIsTheAnswerInTheReductionsUnits) {
  const DenseMatrix M = Mat({{0.2, 0.05}, {0.05, 0.1}});  // positive definite: λ unique
  const DenseMatrix H = Mat({{2, 0}, {-0.05, 1}, {-3, 0}, {0.05, -1}});  // |λ₁| ≤ 1, |λ₂ − 0.05λ₁| ≤ 1
  const Vector K = Vec({-2, -1, -3, -1});
  const Vector q = Vec({-0.5, 0.05});  // unconstrained minimizer (3, −2): λ₁ = 1 is active, μ > 0 there
  const AffineVI avi(M, q, H, K);
  const std::unique_ptr<Solver> newton = CreateSolver("newton");
  AviSession session(avi, *newton, {}, SessionOptions{/*reuse_active_set=*/false});
  ASSERT_EQ(session.Solve(q), SolveStatus::kSolved) << session.result().message;
  ASSERT_GT(session.result().iterations, 0);
  ASSERT_GT(session.solution().mu.maxCoeff(), 0.1);
  const AviSolution cold = session.solution();
  EXPECT_NEAR(cold.lambda[0], 1.0, 1e-12);
  // Warm from its own previous answer (the stepper's call: the session's solution() itself).
  ASSERT_EQ(session.Solve(q, &session.solution()), SolveStatus::kSolved) << session.result().message;
  EXPECT_EQ(session.result().iterations, 0);
  EXPECT_LE((session.solution().lambda - cold.lambda).cwiseAbs().maxCoeff(), 1e-14);
  // λ alone: the multipliers start at 0, not at the answer: Newton has to iterate.
  const AviSolution lambda_only{cold.lambda, {}, {}};
  ASSERT_EQ(session.Solve(q, &lambda_only), SolveStatus::kSolved);
  EXPECT_GT(session.result().iterations, 0);
  // Sizes other than n, m, p name the field.
  const AviSolution wrong{cold.lambda, Vec({1, 2}), {}};
  try {
    session.Solve(q, &wrong);
    ADD_FAILURE() << "a warm start with 2 multipliers for 4 rows was accepted";
  } catch (const InvalidInputError& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("warm_start.mu has size 2"));
  }
}

// The time-stepper's use: each step warm from the previous answer, the reduction's last active set tried first. On
// the implicit-twisting loop lemke then runs on far fewer steps (the reused set answers with 0 iterations), the plant
// sees the same input M λ as with cold steps, and the reused set allocates nothing.
TEST(AviSession, WarmStepsReuseTheActiveSetWithoutAllocating) {
  constexpr double kTs = 10e-3, kG = 10.0, kBeta = 0.1;
  DenseMatrix M(2, 2);
  M << kG * kTs * kTs / 2.0, kBeta * kG * kTs * kTs / 2.0, kG * kTs, kBeta * kG * kTs;
  const DenseMatrix H = Mat({{1, 0}, {-kTs / 2.0, 1}, {-1, 0}, {kTs / 2.0, -1}});
  const AffineVI avi(M, Vec({10.0, -5.0}), H, Vector::Constant(4, -1.0));
  const std::unique_ptr<Solver> lemke = CreateSolver("lemke");
  SolverOptions options;
  options.measure_time = false;
  AviSession cold(avi, *lemke, options, SessionOptions{/*reuse_active_set=*/false});
  AviSession warm(avi, *lemke, options);
  Vector x_cold = Vec({10.0, -5.0}), x_warm = x_cold, q(2);
  long cold_iterations = 0, warm_iterations = 0;
  for (int step = 0; step < 400; ++step) {
    q << x_cold[0] + kTs * x_cold[1], x_cold[1];
    ASSERT_EQ(cold.Solve(q), SolveStatus::kSolved) << "step " << step;
    cold_iterations += cold.result().iterations;
    x_cold = M * cold.solution().lambda + q;
    q << x_warm[0] + kTs * x_warm[1], x_warm[1];
    ASSERT_EQ(warm.Solve(q, step > 0 ? &warm.solution() : nullptr), SolveStatus::kSolved)
        << "step " << step << ": " << warm.result().message;
    warm_iterations += warm.result().iterations;
    x_warm = M * warm.solution().lambda + q;
    ASSERT_LE((x_warm - x_cold).cwiseAbs().maxCoeff(), 1e-12 * (1.0 + x_cold.cwiseAbs().maxCoeff())) << step;
  }
  std::printf("[ info     ] lemke on 400 twisting steps: %ld pivots cold, %ld warm (%lld of 400 by the reused set)\n",
              cold_iterations, warm_iterations, static_cast<long long>(warm.reused()));
  EXPECT_GT(warm.reused(), 200);
  EXPECT_LT(warm_iterations, cold_iterations / 2);
  if (!test_support::CanCountMallocs()) return;
  // The same 100 further steps through both sessions: a step the reused set answers allocates nothing, and warm
  // steps allocate no more than cold ones (lemke itself allocates on a few of these q, warm or cold).
  long reused_mallocs = 0, warm_mallocs = 0, cold_mallocs = 0;
  for (int step = 0; step < 100; ++step) {
    q << x_warm[0] + kTs * x_warm[1], x_warm[1];
    cold_mallocs += test_support::CountMallocs([&] { cold.Solve(q); });
    const long mallocs = test_support::CountMallocs([&] { warm.Solve(q, &warm.solution()); });
    warm_mallocs += mallocs;
    if (SessionPathOf(warm.result()) == SessionPath::kReusedActiveSet) reused_mallocs += mallocs;
    x_warm.noalias() = M * warm.solution().lambda;
    x_warm += q;
  }
  EXPECT_EQ(reused_mallocs, 0);
  EXPECT_LE(warm_mallocs, cold_mallocs);
}

}  // namespace
}  // namespace smcbench

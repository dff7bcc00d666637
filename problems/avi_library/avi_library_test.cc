// The `avi` suite: it builds deterministically, every reference passes the AVI verdict at a tight tolerance, each
// family is what its name says (recomputed here from the data), the captured twisting AVIs are the ones the run
// solved, the AVIs with no solution are refused, and no box backend is ever wrongly claimed solved on it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>
#include <string>

#include "problems/avi_library/avi_suite.h"
#include "problems/scenes/registry.h"
#include "solvers/avi/avi_solver.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

using ::testing::HasSubstr;

constexpr double kTightTolerance = 1e-12;

const AviProblemSet& QuickSuite() {
  static const AviProblemSet set = BuildAviSuite(true);
  return set;
}

bool HasTag(const AviLibraryProblem& p, const std::string& tag) {
  return std::find(p.tags.begin(), p.tags.end(), tag) != p.tags.end();
}

// Rows of H with H_iλ = K_i to 1e-9 (each row divided by its largest coefficient), recomputed from the data.
int ActiveRows(const AffineVI& avi, const Vector& lambda) {
  int active = 0;
  for (int i = 0; i < avi.inequality_count(); ++i) {
    const double scale = avi.H().row(i).cwiseAbs().maxCoeff();
    active += std::abs(avi.H().row(i).dot(lambda) - avi.K()[i]) / scale <= 1e-9;
  }
  return active;
}

TEST(AviSuite, EveryFamilyIsPresentAndEveryReferencePassesTheVerdict) {
  const AviProblemSet& set = QuickSuite();
  EXPECT_EQ(set.name, "avi");
  std::map<std::string, int> families;
  std::set<std::string> scenes;
  for (const AviLibraryProblem& p : set.problems) {
    SCOPED_TRACE(p.id);
    ASSERT_TRUE(p.problem);
    EXPECT_EQ(p.problem->name(), p.id);
    ++families[p.id.substr(0, p.id.find('/', 4))];
    if (p.expected == ExpectedOutcome::kInfeasible) {
      EXPECT_FALSE(p.reference.verified());
      continue;
    }
    EXPECT_EQ(p.expected, ExpectedOutcome::kSolvable);
    ASSERT_TRUE(p.reference.verified()) << p.metadata.at("certificate");
    const AviJudgement j = JudgeAvi(*p.problem, p.expected, &p.reference, SolveStatus::kSolved,
                                    p.reference.solution, kTightTolerance);
    EXPECT_EQ(j.verdict, Verdict::kSolved);
    EXPECT_LE(j.residual.rel, kTightTolerance);
    EXPECT_LE(j.complementarity, kTightTolerance);
    EXPECT_LE(j.primal_infeasibility, kTightTolerance);
    // λ is unique exactly where M + Mᵀ is positive definite or the enumeration proved it.
    if (HasTag(p, "strictly-monotone")) {
      EXPECT_TRUE(p.reference.lambda_unique);
    }
    if (HasTag(p, "twisting")) scenes.insert(p.metadata.at("scene"));
  }
  EXPECT_EQ(scenes.size(), std::size(kAviSuiteScenes));
  EXPECT_EQ(families["avi/twisting"], 12);  // 3 scenes × 4 steps
  EXPECT_EQ(families["avi/planted"], 6);
  EXPECT_EQ(families["avi/degenerate"], 2);
  EXPECT_EQ(families["avi/halfspaces"], 2);
  EXPECT_EQ(families["avi/cone"], 1);
  EXPECT_EQ(families["avi/infeasible"], 3);
}

TEST(AviSuite, BuildsTheSameBitsTwice) {
  const AviProblemSet again = BuildAviSuite(true);
  const AviProblemSet& set = QuickSuite();
  ASSERT_EQ(again.problems.size(), set.problems.size());
  for (std::size_t k = 0; k < set.problems.size(); ++k) {
    const AffineVI &a = *set.problems[k].problem, &b = *again.problems[k].problem;
    EXPECT_EQ(set.problems[k].id, again.problems[k].id);
    EXPECT_TRUE(a.M() == b.M() && a.q() == b.q() && a.H() == b.H() && a.K() == b.K() && a.E() == b.E() &&
                a.f() == b.f())
        << set.problems[k].id;
  }
}

// The planted polytopes have more faces than 2n and equality rows; the degenerate vertices more active rows than
// unknowns with some zero multipliers; the unbounded ones a recession direction; all recomputed from the data.
TEST(AviSuite, FamiliesHaveTheShapeTheyClaim) {
  for (const AviLibraryProblem& p : QuickSuite().problems) {
    SCOPED_TRACE(p.id);
    const AffineVI& avi = *p.problem;
    const int n = avi.size();
    if (HasTag(p, "planted")) {
      EXPECT_GT(avi.inequality_count(), 2 * n);
      EXPECT_GE(avi.equality_count(), 1);
      EXPECT_EQ(avi.boundedness(), PolytopeBoundedness::kBounded);
    }
    if (HasTag(p, "degenerate")) {
      const Vector& lambda = p.reference.solution.lambda;
      EXPECT_GT(ActiveRows(avi, lambda), n);
      // Only ⌈n/2⌉ active rows need a positive multiplier: the certified μ has a zero on an active row.
      const Vector& mu = p.reference.solution.mu;
      int active_with_zero = 0;
      for (int i = 0; i < avi.inequality_count(); ++i) {
        const double scale = avi.H().row(i).cwiseAbs().maxCoeff();
        active_with_zero += std::abs(avi.H().row(i).dot(lambda) - avi.K()[i]) / scale <= 1e-9 && mu[i] <= 1e-12;
      }
      EXPECT_GE(active_with_zero, 1);
    }
    if (HasTag(p, "halfspaces") || HasTag(p, "cone")) {
      EXPECT_EQ(avi.boundedness(), PolytopeBoundedness::kUnbounded);
      EXPECT_TRUE(HasTag(p, "unbounded"));
      EXPECT_EQ(p.expected, ExpectedOutcome::kSolvable);  // planted: the unbounded P does not decide it
    }
    if (HasTag(p, "twisting")) {
      EXPECT_EQ(avi.boundedness(), PolytopeBoundedness::kBounded);
      EXPECT_EQ(avi.size(), 2);
      EXPECT_EQ(avi.inequality_count(), 4);
    }
  }
}

// The captured AVI at step k is the one the run solved: the run's own s_k (recorded by the trajectory, not by the
// capture) solves it, and a run that starts from another state does not.
TEST(AviSuite, CapturedTwistingAvisAreTheOnesTheRunSolved) {
  for (const char* scene_name : kAviSuiteScenes) {
    SCOPED_TRACE(scene_name);
    const std::vector<AviLibraryProblem> captured = CaptureSceneAvis(scene_name, {1, 2, 40});
    ASSERT_EQ(captured.size(), 3u);
    const auto scene = LoadScene(scene_name);
    SimulationSettings settings = scene->defaults();
    settings.T = 45 * settings.h;
    auto lemke = CreateSolver("lemke");
    const Trajectory run = scene->Run(settings, lemke.get());
    ASSERT_GE(run.steps_taken, 40);
    for (const AviLibraryProblem& p : captured) {
      const int k = std::stoi(p.metadata.at("step"));
      const Vector s = run.s.col(k);
      const AviJudgement j = JudgeAvi(*p.problem, ExpectedOutcome::kSolvable, nullptr, SolveStatus::kSolved,
                                      AviMultipliersAt(*p.problem, s), 1e-10);
      EXPECT_EQ(j.verdict, Verdict::kSolved) << p.id << " residual " << j.residual.rel;
    }
    // Step 1's AVI against step 40's answer: not a solution (the q differ), so the check above has teeth.
    const AviJudgement other = JudgeAvi(*captured[0].problem, ExpectedOutcome::kSolvable, nullptr,
                                        SolveStatus::kSolved, AviMultipliersAt(*captured[0].problem, run.s.col(40)),
                                        1e-10);
    EXPECT_NE(other.verdict, Verdict::kSolved);
  }
  EXPECT_THROW(CaptureSceneAvis("sign", {1}), InvalidInputError);
}

// An empty P is refused where the AVI is built (it never reaches a backend): the suite's "no solution" AVIs have a
// non-empty P instead, and are refused by the backends.
TEST(AviSuite, EmptyPolytopeIsRefusedAtConstruction) {
  DenseMatrix H(2, 1);
  H << 1.0, -1.0;
  Vector K(2);
  K << 1.0, 0.0;  // λ ≥ 1 and λ ≤ 0
  try {
    AffineVI(DenseMatrix::Identity(1, 1), Vector::Zero(1), H, K, "empty");
    FAIL() << "an empty P was accepted";
  } catch (const InvalidInputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("is empty"));
  }
}

// The headline: on the whole suite, no box backend's "solved" is rejected by the AVI verdict (wrongly claimed 0
// for every backend), the AVIs with no solution are never solved, and Lemke (exact on the monotone reductions:
// M_red positive semidefinite, copositive-plus) solves every solvable one.
TEST(AviSuite, NoBoxBackendIsWronglyClaimedSolved) {
  const AviProblemSet& set = QuickSuite();
  for (std::string_view name : SolverNames()) {
    auto solver = CreateSolver(name);
    if (!solver->info().box) continue;
    std::map<Verdict, int> verdicts;
    for (const AviLibraryProblem& p : set.problems) {
      SolverOptions options;
      options.tolerance = 1e-10;
      options.time_limit_seconds = 10.0;
      const AviResult r = SolveAvi(*p.problem, *solver, options, &p.reference);
      const AviJudgement j = JudgeAvi(*p.problem, p.expected, &p.reference, r.status, r.solution, options.tolerance);
      ++verdicts[j.verdict];
      EXPECT_NE(j.verdict, Verdict::kWronglyClaimed) << name << " on " << p.id << ": " << r.message;
      if (p.expected == ExpectedOutcome::kInfeasible) {
        EXPECT_FALSE(r.solved()) << name << " on " << p.id;
      }
      if (name == "lemke" && p.expected == ExpectedOutcome::kSolvable) {
        EXPECT_EQ(j.verdict, Verdict::kSolved) << p.id << ": " << ToString(r.status) << " " << r.message;
      }
      if (name == "lemke" && p.expected == ExpectedOutcome::kInfeasible) {
        EXPECT_EQ(j.verdict, Verdict::kCorrectlyRefused) << p.id << ": " << ToString(r.status);
      }
    }
    std::printf("%-28s", std::string(name).c_str());
    for (const auto& [verdict, count] : verdicts) std::printf(" %s %d", std::string(ToString(verdict)).c_str(), count);
    std::printf("\n");
  }
}

TEST(AviProblemSet, ValidateNamesTheProblem) {
  AviProblemSet set = QuickSuite();
  set.problems[1].id = set.problems[0].id;
  try {
    set.Validate();
    FAIL();
  } catch (const InvalidInputError& e) {
    EXPECT_THAT(e.what(), HasSubstr(set.problems[0].id));
    EXPECT_THAT(e.what(), HasSubstr("duplicate"));
  }
  set = QuickSuite();
  set.problems[2].problem.reset();
  EXPECT_THROW(set.Validate(), InvalidInputError);
}

}  // namespace
}  // namespace smcbench

namespace smcbench {
namespace {

// siconos-avi-caoferris (Cao–Ferris at our vertex, Siconos' stage 3; built with Siconos only) against lemke
// through the reduction on the whole quick suite: where both solve and λ is certified unique, the same λ; where λ
// is not unique, the same Mλ for a symmetric M (monotone AVIs: every solution has it); every AVI it does not solve
// is one without a vertex (kNotApplicable naming it) or without a solution.
TEST(AviSuite, SiconosCaoFerrisAgreesWithLemke) {
  const auto names = SolverNames();
  if (std::find(names.begin(), names.end(), "siconos-avi-caoferris") == names.end()) {
    GTEST_SKIP() << "built without Siconos";
  }
  auto cao_ferris = CreateSolver("siconos-avi-caoferris");
  auto lemke = CreateSolver("lemke");
  SolverOptions options;
  options.tolerance = 1e-10;
  options.time_limit_seconds = 10.0;
  int agreed = 0;
  for (const AviLibraryProblem& p : QuickSuite().problems) {
    const AviResult mine = SolveAvi(*p.problem, *cao_ferris, options, &p.reference);
    const AviResult theirs = SolveAvi(*p.problem, *lemke, options, &p.reference);
    const std::string where = p.id + ": " + std::string(ToString(mine.status)) + " " + mine.message;
    if (!mine.solved()) {
      EXPECT_TRUE(mine.status == SolveStatus::kNotApplicable || p.expected == ExpectedOutcome::kInfeasible) << where;
      if (mine.status == SolveStatus::kNotApplicable) {
        EXPECT_THAT(mine.message, HasSubstr("no vertex")) << where;
      }
      continue;
    }
    ASSERT_TRUE(theirs.solved()) << where;
    const Vector& a = mine.solution.lambda;
    const Vector& b = theirs.solution.lambda;
    const double scale = 1.0 + b.cwiseAbs().maxCoeff();
    if (p.reference.lambda_unique) {
      EXPECT_LE((a - b).cwiseAbs().maxCoeff(), 1e-8 * scale) << where;
    } else if (p.problem->M().isApprox(p.problem->M().transpose())) {
      const Vector Ma = p.problem->M() * a, Mb = p.problem->M() * b;
      EXPECT_LE((Ma - Mb).cwiseAbs().maxCoeff(), 1e-8 * (1.0 + Mb.cwiseAbs().maxCoeff())) << where;
    }
    ++agreed;
  }
  EXPECT_GE(agreed, 20);
}

}  // namespace
}  // namespace smcbench

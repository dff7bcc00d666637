// Certified references of library problems against what is known independently: hand-solved problems, planted
// solutions of P-matrix problems (unique by construction), the PSD-singular and non-P families (several solutions
// by construction), infeasible constructions (no solution), the size limit; and AttachReferences over the
// `families` and `paper` suites, timed.
#include "problems/library/references.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>

#include "problems/library/capture.h"
#include "problems/suites/families.h"
#include "solvers/generators/random_problems.h"

namespace smcbench {
namespace {

bool HasTag(const LibraryProblem& p, const std::string& tag) {
  for (const std::string& t : p.tags) {
    if (t == tag) return true;
  }
  return false;
}

double MaxAbsDifference(const Vector& a, const Vector& b) { return (a - b).lpNorm<Eigen::Infinity>(); }

// M = [[2, 1], [1, 2]], q = (−3, −3): the LCP's solution is z = (1, 1) with w = 0 (both rows free, strictly
// inside z > 0): M is SPD, so it is the only one. Row scales d = (2, 2), D⁻¹M = [[1, ½], [½, 1]], whose inverse
// (4/3)[[1, −½], [−½, 1]] has ∞-norm 2: the condition μ.
LibraryProblem HandSolvedLcp(ExpectedOutcome expected = ExpectedOutcome::kSolvable) {
  DenseMatrix M(2, 2);
  M << 2, 1, 1, 2;
  Vector q(2);
  q << -3, -3;
  LibraryProblem p = MakeLibraryProblem("hand/lcp2", "generated:test", BoxMLCP::LCP(M, q));
  p.expected = expected;
  return p;
}

// w = −z − 1 ≥ 0 needs z ≤ −1, but z ≥ 0: no solution.
LibraryProblem HandInfeasibleLcp() {
  DenseMatrix M(1, 1);
  M << -1;
  Vector q(1);
  q << -1;
  LibraryProblem p = MakeLibraryProblem("hand/infeasible1", "generated:test", BoxMLCP::LCP(M, q));
  p.expected = ExpectedOutcome::kInfeasible;
  return p;
}

TEST(ComputeReference, HandSolvedLcpIsUniqueWithItsCondition) {
  for (bool ask_backends : {true, false}) {
    SCOPED_TRACE(ask_backends ? "with backends" : "without backends");
    const ReferenceSolution r = ComputeReference(HandSolvedLcp(), ReferenceOptions{64, ask_backends});
    EXPECT_EQ(r.certificate, Certificate::kUnique);
    ASSERT_EQ(r.z.size(), 2);
    EXPECT_EQ(r.z[0], 1.0);
    EXPECT_EQ(r.z[1], 1.0);
    EXPECT_NEAR(r.condition, 2.0, 1e-14);
  }
}

TEST(ComputeReference, PlantedPMatrixProblemIsUniqueAtThePlantedSolution) {
  for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay, BoundKind::kMixed}) {
    const LibraryProblem p = RandomFamilyProblem(MatrixFamily::kNonsymmetricPMatrix, bounds, 16, 3);
    SCOPED_TRACE(p.id);
    ASSERT_EQ(p.matrix.p_matrix, Tristate::kYes);
    ASSERT_EQ(p.solution.size(), 16);
    const ReferenceSolution r = ComputeReference(p);
    EXPECT_EQ(r.certificate, Certificate::kUnique);
    ASSERT_EQ(r.z.size(), 16);
    // The planted z* is exact for the q it was built with; q = w* − M z* is rounded once per entry, which moves
    // the exact solution by about μ·ε·‖q‖ (cond ≈ 100 for this family).
    EXPECT_LE(MaxAbsDifference(r.z, p.solution), 1e-12 * (1.0 + p.solution.lpNorm<Eigen::Infinity>()));
    EXPECT_GT(r.condition, 0.0);
  }
}

TEST(ComputeReference, PsdSingularFamilyIsNonUnique) {
  for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay}) {
    for (std::uint64_t seed : {1, 2}) {
      const LibraryProblem p = PsdSingularProblem(bounds, 8, seed);
      SCOPED_TRACE(p.id);
      const ReferenceSolution r = ComputeReference(p);
      // By construction z* + t·d solves the problem for small t: a unique certificate would be false.
      EXPECT_EQ(r.certificate, Certificate::kNonUnique);
      ASSERT_EQ(r.z.size(), 8);
      Vector w;
      EXPECT_LE(p.problem.NaturalResidual(r.z, &w).rel, 1e-14);  // z* is one of the solutions
    }
  }
}

// The construction's word beats the stored bits: a problem labelled non-unique never gets a unique certificate,
// even where Certify proves uniqueness (here a hand-solved SPD problem, labelled so on purpose).
TEST(ComputeReference, NonUniqueLabelOverridesUniqueness) {
  LibraryProblem p = HandSolvedLcp();
  p.tags.emplace_back(kNonUniqueLabel);
  const ReferenceSolution r = ComputeReference(p);
  EXPECT_EQ(r.certificate, Certificate::kNonUnique);
  ASSERT_EQ(r.z.size(), 2);
  EXPECT_EQ(r.z[0], 1.0);
  EXPECT_EQ(r.z[1], 1.0);
}

TEST(ComputeReference, InfeasibleProblemsGetNoneFound) {
  for (const LibraryProblem& p : {HandInfeasibleLcp(), NonPInfeasibleProblem(BoundKind::kLCP, 8, 1),
                                  NonPInfeasibleProblem(BoundKind::kMixed, 8, 2)}) {
    SCOPED_TRACE(p.id);
    ASSERT_EQ(p.expected, ExpectedOutcome::kInfeasible);
    const ReferenceSolution r = ComputeReference(p);
    EXPECT_EQ(r.certificate, Certificate::kNoneFound);
    EXPECT_FALSE(r.verified());
    EXPECT_EQ(r.z.size(), 0);
  }
}

// The check that keeps a wrongly built "infeasible" problem out of the suites: a verified solution on it throws.
TEST(ComputeReference, SolutionOnAProblemTaggedInfeasibleIsALogicError) {
  try {
    ComputeReference(HandSolvedLcp(ExpectedOutcome::kInfeasible));
    ADD_FAILURE() << "no exception";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("'hand/lcp2' is expected infeasible"), std::string::npos) << e.what();
  }
  ProblemSet set;
  set.problems.push_back(HandSolvedLcp(ExpectedOutcome::kInfeasible));
  EXPECT_THROW(AttachReferences(&set), std::logic_error);
}

TEST(ComputeReference, ProblemsAboveTheSizeLimitKeepNone) {
  GeneratorOptions g;
  g.size = 100;
  g.bounds = BoundKind::kRelay;
  GeneratedProblem generated = GenerateProblem(g);
  LibraryProblem p = MakeLibraryProblem("big/m100", "generated:test", std::move(generated.problem));
  p.solution = generated.z_star;
  EXPECT_EQ(ComputeReference(p).certificate, Certificate::kNone);
  ProblemSet set;
  set.problems.push_back(p);
  AttachReferences(&set);
  EXPECT_EQ(set.problems[0].reference.certificate, Certificate::kNone);
  EXPECT_EQ(set.problems[0].reference.z.size(), 0);
  // A larger limit certifies it.
  EXPECT_EQ(ComputeReference(p, ReferenceOptions{100, false}).certificate, Certificate::kUnique);
}

TEST(AttachReferences, FillsOnlyMissingReferences) {
  ProblemSet set;
  set.problems.push_back(HandSolvedLcp());
  set.problems.push_back(HandInfeasibleLcp());
  LibraryProblem kept = HandSolvedLcp();
  kept.id = "hand/kept";
  kept.reference.certificate = Certificate::kNoneFound;  // not what Certify says: proves it was not recomputed
  set.problems.push_back(kept);
  AttachReferences(&set);
  EXPECT_EQ(set.problems[0].reference.certificate, Certificate::kUnique);
  EXPECT_EQ(set.problems[1].reference.certificate, Certificate::kNoneFound);
  EXPECT_EQ(set.problems[2].reference.certificate, Certificate::kNoneFound);
  EXPECT_EQ(set.problems[2].reference.z.size(), 0);
  set.Validate();
}

// A reference read from a file has no proof (the format does not store it): AttachReferences proves it again from
// its z*, without recomputing the certificate; a wrong z* stays unproved.
TEST(AttachReferences, ProvesVerifiedReferencesThatCameWithoutTheirProof) {
  ProblemSet set;
  LibraryProblem stored = HandSolvedLcp();
  stored.reference.certificate = Certificate::kUnique;
  stored.reference.z = Vector::Ones(2);  // the exact solution (see HandSolvedLcp)
  stored.reference.condition = 2.0;
  set.problems.push_back(stored);
  LibraryProblem wrong = HandSolvedLcp();
  wrong.id = "hand/wrong";
  wrong.reference = stored.reference;
  wrong.reference.z[0] = 0.0;  // at the lower bound with w = −2: not a solution
  set.problems.push_back(wrong);
  ASSERT_TRUE(std::isnan(set.problems[0].reference.proved_radius));
  AttachReferences(&set);
  EXPECT_EQ(set.problems[0].reference.certificate, Certificate::kUnique);
  EXPECT_GE(set.problems[0].reference.proved_radius, 0.0);
  EXPECT_LE(set.problems[0].reference.proved_radius, 1e-28);  // z* exact: the quad sum's a-priori bound only
  EXPECT_TRUE(set.problems[0].reference.proved_unique);        // M = [[2, 1], [1, 2]] is SPD
  EXPECT_TRUE(std::isnan(set.problems[1].reference.proved_radius));
  EXPECT_FALSE(set.problems[1].reference.proved_unique);
  // The same through ProvedReference, which the Python reader uses.
  EXPECT_EQ(ProvedReference(stored).proved_radius, set.problems[0].reference.proved_radius);
}

double SecondsOf(const std::function<void()>& fn) {
  const auto start = std::chrono::steady_clock::now();
  fn();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string CertificateCounts(const ProblemSet& set) {
  std::map<std::string, int> counts;
  for (const LibraryProblem& p : set.problems) ++counts[std::string(ToString(p.reference.certificate))];
  std::string s;
  for (const auto& [name, count] : counts) s += (s.empty() ? "" : ", ") + name + " " + std::to_string(count);
  return s;
}

// Over the whole families suite: every certificate agrees with what the construction proves, and the planted
// solutions of the unique problems are within the forward-error allowance of z* (tolerance 1e-10, the bench's).
TEST(AttachReferences, FamiliesSuiteAgreesWithItsConstructions) {
  ProblemSet set = FamiliesSuite();
  const double seconds = SecondsOf([&] { AttachReferences(&set); });
  std::cout << "AttachReferences(families, " << set.problems.size() << " problems): " << seconds << " s; "
            << CertificateCounts(set) << "\n";
  RecordProperty("seconds", std::to_string(seconds));
  set.Validate();
  for (const LibraryProblem& p : set.problems) {
    SCOPED_TRACE(p.id);
    const ReferenceSolution& r = p.reference;
    ASSERT_NE(r.certificate, Certificate::kNone);  // every problem is at most 64 rows
    if (p.expected == ExpectedOutcome::kInfeasible) {
      EXPECT_FALSE(r.verified());
    }
    if (HasTag(p, "non-unique")) {
      EXPECT_FALSE(r.unique()) << ToString(r.certificate);
    }
    if (r.verified()) {
      Vector w;
      EXPECT_LE(p.problem.NaturalResidual(r.z, &w).rel, 1e-12);
    }
    if (p.matrix.p_matrix == Tristate::kYes && p.solution.size() != 0) {
      EXPECT_TRUE(r.unique()) << ToString(r.certificate);
      if (r.unique()) {
        EXPECT_LE(MaxAbsDifference(r.z, p.solution), ForwardErrorAllowance(r, 1e-10))
            << "condition " << r.condition;
      }
    }
  }
}

// The paper suite: one or two rows each, relay bounds (every bound finite: a solution always exists), and the
// captured z solved each problem to 1e-10, so every one gets a verified reference.
TEST(AttachReferences, PaperSuiteIsEveryOneVerified) {
  ProblemSet set = CapturePaperSuite();
  for (LibraryProblem& p : set.problems) p.reference = {};  // time the certification, whatever the capture did
  const double seconds = SecondsOf([&] { AttachReferences(&set); });
  std::cout << "AttachReferences(paper, " << set.problems.size() << " problems): " << seconds << " s; "
            << CertificateCounts(set) << "\n";
  RecordProperty("seconds", std::to_string(seconds));
  for (const LibraryProblem& p : set.problems) {
    SCOPED_TRACE(p.id);
    EXPECT_TRUE(p.reference.verified()) << ToString(p.reference.certificate);
  }
}

}  // namespace
}  // namespace smcbench

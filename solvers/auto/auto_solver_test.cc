// Tests of the `auto` backend: which backend it picks on each problem class, answers judged against planted
// solutions (solvers/generators, or built here with z* first), the fallback path, and that it never reports
// "infeasible" unless an exact backend proved it.
#include "solvers/auto/auto_solver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "problems/io/siconos_format.h"
#include "problems/suites/families.h"
#include "solvers/generators/random_problems.h"
#include "solvers/ipopt/ipopt_qp_solver.h"
#include "solvers/lemke/lemke_solver.h"
#include "solvers/pivoting/bpp_solver.h"
#include "solvers/psor/psor_solver.h"
#include "tests/support/small_mcps.h"

namespace smcbench {
namespace {

constexpr double kTol = 1e-10;

// The natural residual recomputed here from M, q, l, u, relative to 1 + ‖q‖∞.
double IndependentResidual(const BoxMLCP& p, const Vector& z) {
  const DenseMatrix M = p.ToDense();
  const Vector w = M * z + p.q();
  double r = 0.0;
  for (int i = 0; i < p.size(); ++i) {
    r = std::max(r, std::abs(z[i] - std::min(std::max(z[i] - w[i], p.l()[i]), p.u()[i])));
  }
  return r / (1.0 + p.q().cwiseAbs().maxCoeff());
}

GeneratedProblem Generate(MatrixFamily family, BoundKind bounds, int size, bool sparse = false) {
  GeneratorOptions g;
  g.family = family;
  g.bounds = bounds;
  g.size = size;
  g.seed = 13;
  g.sparse = sparse;
  return GenerateProblem(g);
}

// The candidate auto reports (detail "chosen"); fails the test when it reports none.
AutoCandidate Chosen(const SolveResult& r) {
  const std::optional<AutoCandidate> chosen = ChosenCandidateOf(r);
  EXPECT_TRUE(chosen.has_value()) << "no detail chosen";
  return chosen.value_or(AutoCandidate::kEnum);
}

// Solves a planted problem and checks the answer against z*, the backend auto reports, and that DelegateFor names
// the backend whose answer came back.
void ExpectChoice(const GeneratedProblem& gen, AutoCandidate expected, const AutoOptions& auto_options = {}) {
  AutoSolver solver(auto_options);
  SolverOptions options;
  options.tolerance = kTol;
  const SolveResult r = solver.Solve(gen.problem, options);
  const std::string where = gen.problem.name();
  ASSERT_TRUE(r.solved()) << where << ": " << ToString(r.status) << " " << r.message;
  EXPECT_EQ(r.solver, "auto") << where;
  EXPECT_EQ(Chosen(r), expected) << where << " went to " << ToString(Chosen(r));
  EXPECT_EQ(r.GetDetail("fallbacks"), 0.0) << where;
  EXPECT_LE(IndependentResidual(gen.problem, r.z), kTol) << where;
  // P-matrix families: z* is the only solution.
  EXPECT_LE((r.z - gen.z_star).cwiseAbs().maxCoeff(), 1e-8 * (1.0 + gen.z_star.cwiseAbs().maxCoeff())) << where;
  Solver* delegate = solver.DelegateFor(gen.problem, options);
  ASSERT_NE(delegate, nullptr);
  EXPECT_EQ(delegate, &solver.candidate(expected)) << where;
  EXPECT_EQ(delegate->info().name, ToString(expected)) << where;
}

TEST(AutoSolver, InfoAndCandidateNames) {
  AutoSolver solver;
  EXPECT_EQ(solver.info().name, "auto");
  EXPECT_TRUE(solver.info().dense);
  EXPECT_TRUE(solver.info().sparse);
  EXPECT_TRUE(solver.info().mcp);
  EXPECT_FALSE(solver.info().exact);  // its answer may come from psor or newton
  EXPECT_FALSE(solver.info().equilibrate);  // the chosen backend equilibrates
  for (const AutoCandidate c : {AutoCandidate::kEnum, AutoCandidate::kPsor, AutoCandidate::kLemke,
                                AutoCandidate::kNewton, AutoCandidate::kBpp}) {
    EXPECT_EQ(solver.candidate(c).info().name, ToString(c));
  }
  // Without a lookup the MCP-only candidates are absent.
  EXPECT_EQ(solver.FindCandidate(AutoCandidate::kNewtonMin), nullptr);
  EXPECT_EQ(solver.FindCandidate(AutoCandidate::kIpopt), nullptr);
  EXPECT_THROW(solver.candidate(AutoCandidate::kIpopt), std::logic_error);
  EXPECT_EQ(AutoCandidateName(0), "enum");
  EXPECT_EQ(AutoCandidateName(3), "newton");
  EXPECT_EQ(AutoCandidateName(4), "newton-min");
  EXPECT_EQ(AutoCandidateName(5), "ipopt");
  EXPECT_EQ(AutoCandidateIndex("ipopt"), 5);
  EXPECT_EQ(AutoCandidateName(6), "bpp");
  EXPECT_EQ(AutoCandidateName(-1), "");
  EXPECT_EQ(AutoCandidateName(kAutoCandidateCount), "");
}

TEST(AutoSolver, ChosenDetailByName) {
  // Every candidate's name reads back to it, and the detail stores exactly that candidate.
  for (int i = 0; i < kAutoCandidateCount; ++i) {
    const auto candidate = static_cast<AutoCandidate>(i);
    EXPECT_EQ(AutoCandidateFromString(ToString(candidate)), candidate) << i;
    SolveResult r;
    LabelAutoAnswer(candidate, 1, &r);
    EXPECT_EQ(ChosenCandidateOf(r), candidate) << i;
    ASSERT_EQ(r.num_details, 2);
    EXPECT_EQ(SolveResult::CodeText(r.details[0]), ToString(candidate)) << "JSON and Python print the name";
    EXPECT_EQ(SolveResult::CodeText(r.details[1]), "") << "fallbacks is a count, not a code";
  }
  EXPECT_EQ(AutoCandidateFromString("siconos-lemke"), std::nullopt);
  EXPECT_EQ(AutoCandidateFromString(""), std::nullopt);
  EXPECT_EQ(AutoCandidateFromString("auto"), std::nullopt);
  // Only a result labelled as auto's has a choice: a backend's own result, or a number past the last candidate, has
  // none.
  SolveResult r;
  LabelAutoAnswer(AutoCandidate::kLemke, 0, &r);
  r.solver = "lemke";
  EXPECT_EQ(ChosenCandidateOf(r), std::nullopt);
  r.solver = "auto";
  r.SetDetail("chosen", kAutoCandidateCount);
  EXPECT_EQ(ChosenCandidateOf(r), std::nullopt);
  EXPECT_EQ(SolveResult::CodeText(r.details[0]), "");
}

TEST(AutoSolver, SmallDenseRelayGoesToEnum) {
  ExpectChoice(Generate(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kRelay, 2), AutoCandidate::kEnum);
  ExpectChoice(Generate(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kRelay, 1), AutoCandidate::kEnum);
  ExpectChoice(Generate(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kLCP, 4), AutoCandidate::kEnum);
  ExpectChoice(Generate(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kRelay, 6), AutoCandidate::kEnum);
  ExpectChoice(Generate(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kLCP, 8), AutoCandidate::kEnum);
}

// Eight box rows are 3⁸ = 6561 active sets, past enum_max_active_sets (729): bpp, which on the strongly
// nonsymmetric relay answers in ~1 µs where enum searches for ~46 µs (auto_rule_measure classes). Raising the
// option brings enum back.
TEST(AutoSolver, ManyActiveSetsGoToBpp) {
  ExpectChoice(Generate(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kRelay, 8), AutoCandidate::kBpp);
  ExpectChoice(Generate(MatrixFamily::kSkewPMatrix, BoundKind::kRelay, 8), AutoCandidate::kBpp);
  AutoOptions more;
  more.enum_max_active_sets = 6561;
  ExpectChoice(Generate(MatrixFamily::kSkewPMatrix, BoundKind::kRelay, 8), AutoCandidate::kEnum, more);
}

// Skew-dominant M (the strongly nonsymmetric P-matrices of issue 34) from 32 rows: lemke first, where bpp's
// single-pivot phase ran for hundreds of sets; at 16 rows, and on the other classes, bpp. The measure is on M as
// stated: the SPD and nonsymmetric-P families are not skew-dominant, the skew family is.
TEST(AutoSolver, SkewDominantMatricesSkipBppFromThirtyTwoRows) {
  const auto first = [](const GeneratedProblem& gen, const AutoOptions& o = {}) {
    AutoSolver solver(o);
    return solver.ChoiceFor(gen.problem).order[0];
  };
  for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay, BoundKind::kMixed}) {
    ExpectChoice(Generate(MatrixFamily::kSkewPMatrix, bounds, 64), AutoCandidate::kLemke);
    ExpectChoice(Generate(MatrixFamily::kSkewPMatrix, bounds, 32), AutoCandidate::kLemke);
    EXPECT_EQ(first(Generate(MatrixFamily::kSkewPMatrix, bounds, 16)), AutoCandidate::kBpp);
    ExpectChoice(Generate(MatrixFamily::kNonsymmetricPMatrix, bounds, 64), AutoCandidate::kBpp);
    ExpectChoice(Generate(MatrixFamily::kSymmetricPositiveDefinite, bounds, 64), AutoCandidate::kBpp);
  }
  AutoOptions never;
  never.skew_lemke_min_size = 0;
  const GeneratedProblem skew = Generate(MatrixFamily::kSkewPMatrix, BoundKind::kRelay, 64);
  EXPECT_EQ(first(skew, never), AutoCandidate::kBpp);
  // There bpp's single pivots are cut at max(4, 64/4) = 16 and lemke answers: one fallback, solved.
  AutoSolver capped(never);
  const SolveResult r = capped.Solve(skew.problem);
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_EQ(ChosenCandidateOf(r), AutoCandidate::kLemke);
  EXPECT_EQ(r.GetDetail("fallbacks"), 1.0);
  std::string why;
  never.skew_lemke_min_size = -1;
  EXPECT_FALSE(never.IsValid(&why));
  EXPECT_NE(why.find("skew_lemke_min_size"), std::string::npos) << why;
}

// Murty's LCP of n rows: M̃(n) (1 on the diagonal, 2 below), q = −(2ⁿ⁺¹ − 2ⁿ⁻ⁱ), z* = 2ⁿ e₁ (exact in double).
BoxMLCP MurtyLcp(int n) {
  DenseMatrix M = DenseMatrix::Zero(n, n);
  Vector q(n);
  for (int i = 0; i < n; ++i) {
    M(i, i) = 1.0;
    for (int j = 0; j < i; ++j) M(i, j) = 2.0;
    q[i] = -(2.0 * std::ldexp(1.0, n) - std::ldexp(1.0, n - i));
  }
  return BoxMLCP::LCP(std::move(M), std::move(q));
}

// Lower triangular M with a positive diagonal, from 5 rows (before enum; up to 4 rows enum's fixed-size kernel): psor, whose first sweep in row order is
// the forward substitution, exact on Murty's LCPs; a mixed box with free rows is checked against the substitution
// computed here. One entry above the diagonal, and the matrix is no longer triangular: bpp, as any nonsymmetric
// P-matrix of its size.
TEST(AutoSolver, LowerTriangularGoesToPsor) {
  for (const int n : {5, 12}) {  // within enum's rows, and past them
    AutoSolver solver;
    const SolveResult r = solver.Solve(MurtyLcp(n));
    ASSERT_TRUE(r.solved()) << r.message;
    EXPECT_EQ(Chosen(r), AutoCandidate::kPsor) << n;
    Vector z_star = Vector::Zero(n);
    z_star[0] = std::ldexp(1.0, n);
    EXPECT_EQ(r.z, z_star) << n;
  }
  AutoSolver solver;

  const int m = 20;
  DenseMatrix L = DenseMatrix::Zero(m, m);
  Vector qm(m), l(m), u(m);
  for (int i = 0; i < m; ++i) {
    L(i, i) = 1.0 + 0.1 * i;
    for (int j = 0; j < i; ++j) L(i, j) = std::sin(1.0 + i * m + j);
    qm[i] = 2.0 * std::cos(3.0 * i);
    l[i] = i % 3 == 0 ? -kInf : -0.5;
    u[i] = i % 3 == 0 ? kInf : (i % 3 == 1 ? 0.5 : kInf);
  }
  Vector z(m);  // forward substitution: z_i = Π_[l_i,u_i](−(q_i + Σ_{j<i} L_ij z_j) / L_ii)
  for (int i = 0; i < m; ++i) {
    const double free_value = -(qm[i] + L.row(i).head(i).dot(z.head(i))) / L(i, i);
    z[i] = std::min(std::max(free_value, l[i]), u[i]);
  }
  const BoxMLCP mixed(L, qm, l, u);
  const SolveResult rm = solver.Solve(mixed);
  ASSERT_TRUE(rm.solved()) << rm.message;
  EXPECT_EQ(Chosen(rm), AutoCandidate::kPsor);
  EXPECT_LE((rm.z - z).cwiseAbs().maxCoeff(), 1e-12 * (1.0 + z.cwiseAbs().maxCoeff()));

  DenseMatrix not_triangular = L;
  not_triangular(0, m - 1) = 1e-3;
  EXPECT_EQ(solver.ChoiceFor(BoxMLCP(not_triangular, qm, l, u)).order[0], AutoCandidate::kBpp);
  EXPECT_EQ(solver.ChoiceFor(MurtyLcp(4)).order[0], AutoCandidate::kEnum);  // 4 rows: enum's kernel
}

// Murty's LCP transposed (Murty 1988 ch. 6; Siconos' lcp_exp_murty2.dat is n = 6): 1 on the diagonal, 2 above,
// q_i = −(2ⁿ⁺¹ − 2ⁱ⁺¹), z* = 2ⁿ e_n (exact in double).
BoxMLCP UpperMurtyLcp(int n) {
  DenseMatrix M = DenseMatrix::Zero(n, n);
  Vector q(n);
  for (int i = 0; i < n; ++i) {
    M(i, i) = 1.0;
    for (int j = i + 1; j < n; ++j) M(i, j) = 2.0;
    q[i] = -(std::ldexp(1.0, n + 1) - std::ldexp(1.0, i + 1));
  }
  return BoxMLCP::LCP(std::move(M), std::move(q));
}

// The sweep order auto's choice runs psor with on this problem (the delegate is auto's psor instance).
PsorOptions::SweepOrder DelegatedPsorSweep(AutoSolver& solver, const BoxMLCP& problem) {
  const auto* psor = dynamic_cast<const PsorSolver*>(solver.DelegateFor(problem, {}));
  EXPECT_NE(psor, nullptr);
  return psor != nullptr ? psor->options().sweep : PsorOptions::kForwardSweep;
}

// Upper triangular M with a positive diagonal, from 5 rows: psor with the backward sweep, whose first sweep is the
// back substitution: exact on Murty's transposed LCPs and on lcp_exp_murty2.dat; a mixed box with free rows is
// checked against the back substitution computed here. One entry below the diagonal, and the matrix is no longer
// triangular: bpp. 4 rows: enum's kernel, as before. The psor candidate's own options reach the backward instance
// (its sweep stays backward).
TEST(AutoSolver, UpperTriangularGoesToPsorWithTheBackwardSweep) {
  for (const int n : {5, 12}) {  // within enum's rows, and past them
    AutoSolver solver;
    const BoxMLCP murty = UpperMurtyLcp(n);
    const SolveResult r = solver.Solve(murty);
    ASSERT_TRUE(r.solved()) << r.message;
    EXPECT_EQ(Chosen(r), AutoCandidate::kPsor) << n;
    EXPECT_TRUE(solver.ChoiceFor(murty).psor_backward) << n;
    EXPECT_EQ(DelegatedPsorSweep(solver, murty), PsorOptions::kBackwardSweep) << n;
    EXPECT_LE(r.iterations, 2) << n;  // one sweep solves, a second one at most confirms
    Vector z_star = Vector::Zero(n);
    z_star[n - 1] = std::ldexp(1.0, n);
    EXPECT_EQ(r.z, z_star) << n;
  }
  {
    AutoSolver solver;
    const BoxMLCP file =
        ReadSiconosFile(std::string(SMCBENCH_PEER_DATA_DIR) + "/siconos/lcp/lcp_exp_murty2.dat", SiconosKind::kLCP);
    ASSERT_EQ(file.size(), 6);
    const SolveResult r = solver.Solve(file);
    ASSERT_TRUE(r.solved()) << r.message;
    EXPECT_EQ(Chosen(r), AutoCandidate::kPsor);
    EXPECT_EQ(DelegatedPsorSweep(solver, file), PsorOptions::kBackwardSweep);
    Vector z_star = Vector::Zero(6);
    z_star[5] = 64.0;
    EXPECT_EQ(r.z, z_star);
  }
  AutoSolver solver;
  const int m = 20;
  DenseMatrix U = DenseMatrix::Zero(m, m);
  Vector qm(m), l(m), u(m);
  for (int i = 0; i < m; ++i) {
    U(i, i) = 1.0 + 0.1 * i;
    for (int j = i + 1; j < m; ++j) U(i, j) = std::sin(1.0 + i * m + j);
    qm[i] = 2.0 * std::cos(3.0 * i);
    l[i] = i % 3 == 0 ? -kInf : -0.5;
    u[i] = i % 3 == 0 ? kInf : (i % 3 == 1 ? 0.5 : kInf);
  }
  Vector z = Vector::Zero(m);  // back substitution: z_i = Π_[l_i,u_i](−(q_i + Σ_{j>i} U_ij z_j) / U_ii)
  for (int i = m - 1; i >= 0; --i) {
    const double free_value = -(qm[i] + U.row(i).tail(m - 1 - i).dot(z.tail(m - 1 - i))) / U(i, i);
    z[i] = std::min(std::max(free_value, l[i]), u[i]);
  }
  const BoxMLCP mixed(U, qm, l, u);
  const SolveResult rm = solver.Solve(mixed);
  ASSERT_TRUE(rm.solved()) << rm.message;
  EXPECT_EQ(Chosen(rm), AutoCandidate::kPsor);
  EXPECT_EQ(DelegatedPsorSweep(solver, mixed), PsorOptions::kBackwardSweep);
  EXPECT_LE((rm.z - z).cwiseAbs().maxCoeff(), 1e-12 * (1.0 + z.cwiseAbs().maxCoeff()));

  // The psor candidate's options (here omega) reach the backward instance; its sweep stays backward.
  static_cast<PsorSolver&>(solver.candidate(AutoCandidate::kPsor)).mutable_options().omega = 0.9;
  const auto* backward = dynamic_cast<const PsorSolver*>(solver.DelegateFor(mixed, {}));
  ASSERT_NE(backward, nullptr);
  EXPECT_EQ(backward->options().omega, 0.9);
  EXPECT_EQ(backward->options().sweep, PsorOptions::kBackwardSweep);
  EXPECT_NE(backward, &solver.candidate(AutoCandidate::kPsor));

  DenseMatrix not_triangular = U;
  not_triangular(m - 1, 0) = 1e-3;
  const AutoChoice& other = solver.ChoiceFor(BoxMLCP(not_triangular, qm, l, u));
  EXPECT_EQ(other.order[0], AutoCandidate::kBpp);
  EXPECT_FALSE(other.psor_backward);
  EXPECT_EQ(solver.ChoiceFor(UpperMurtyLcp(4)).order[0], AutoCandidate::kEnum);  // 4 rows: enum's kernel
  EXPECT_FALSE(solver.ChoiceFor(MurtyLcp(12)).psor_backward);                     // lower: the forward sweep
  EXPECT_EQ(DelegatedPsorSweep(solver, MurtyLcp(12)), PsorOptions::kForwardSweep);
}

// Without bpp (bpp_max_size 0, or past it): SPD relay at m = 64 (condition ≈ 100) goes to psor, predicted (and
// measured, docs/auto.md) several times faster than lemke, whose LCP has 2m variables. The same matrix with LCP
// bounds gives lemke an LCP of size m: no longer predicted slower, so lemke. With bpp, bpp first and a session
// gets what it got without bpp.
TEST(AutoSolver, DenseSpdGoesToPsorWhenPredictedFaster) {
  AutoOptions no_bpp;
  no_bpp.bpp_max_size = 0;
  const GeneratedProblem relay = Generate(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kRelay, 64);
  const GeneratedProblem lcp = Generate(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kLCP, 64);
  ExpectChoice(relay, AutoCandidate::kPsor, no_bpp);
  ExpectChoice(lcp, AutoCandidate::kLemke, no_bpp);
  ExpectChoice(relay, AutoCandidate::kBpp);
  ExpectChoice(lcp, AutoCandidate::kBpp);
  AutoSolver solver;
  const AutoChoice& chain = solver.ChoiceFor(relay.problem);
  ASSERT_EQ(chain.count, 4);
  EXPECT_EQ(chain.order[0], AutoCandidate::kBpp);
  EXPECT_EQ(chain.order[1], AutoCandidate::kPsor);
  EXPECT_EQ(chain.order[2], AutoCandidate::kLemke);
  EXPECT_EQ(chain.order[3], AutoCandidate::kNewton);
}

// Past enum's rows: bpp up to bpp_max_size rows (free rows too), lemke above it.
TEST(AutoSolver, DenseGoesToBppUpToItsSizeThenLemke) {
  ExpectChoice(Generate(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kLCP, 64), AutoCandidate::kBpp);
  ExpectChoice(Generate(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kRelay, 64), AutoCandidate::kBpp);
  // Diagonally dominant but nonsymmetric: not SPD, so not psor.
  ExpectChoice(Generate(MatrixFamily::kDiagonallyDominant, BoundKind::kBox, 12), AutoCandidate::kBpp);
  ExpectChoice(Generate(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kMixed, 24), AutoCandidate::kBpp);
  AutoOptions small;
  small.bpp_max_size = 64;
  ExpectChoice(Generate(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kLCP, 65), AutoCandidate::kLemke, small);
  AutoOptions never;
  never.bpp_max_size = 0;
  AutoSolver solver(never);
  EXPECT_EQ(solver.ChoiceFor(Generate(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kLCP, 16).problem).chosen(),
            AutoCandidate::kLemke);
  EXPECT_EQ(AutoOptions{}.bpp_max_size, 256);
  std::string why;
  never.bpp_max_size = -1;
  EXPECT_FALSE(never.IsValid(&why));
  EXPECT_NE(why.find("bpp_max_size"), std::string::npos) << why;
}

// Siconos' lcp_CPS_2: an LCP that bpp ends singular on and lemke solves.
BoxMLCP LcpCps2() {
  DenseMatrix M(3, 3);
  M << 0, 2, -1,  //
      -1, 0, 1,   //
      2, -2, 0;
  const Vector q = (Vector(3) << -3, 6, -1).finished();
  return BoxMLCP(M, q, Vector::Zero(3), Vector::Constant(3, kInf), "lcp_CPS_2");
}

// bpp ends singular on a degenerate LCP that lemke solves (Cottle–Pang–Stone's example 4.4.7, Siconos' lcp_CPS_2:
// zero diagonal): the chain passes it on and lemke answers, with a residual recomputed here.
TEST(AutoSolver, BppFailureFallsBackToLemke) {
  const BoxMLCP problem = LcpCps2();
  BppSolver bpp;
  const SolveResult alone = bpp.Solve(problem);
  ASSERT_FALSE(alone.solved()) << "bpp solves lcp_CPS_2 now: pick another example of its failure";
  AutoOptions o;
  o.enum_max_choice_rows = 0;  // past enum, to reach bpp at n = 3
  AutoSolver solver(o);
  ASSERT_EQ(solver.ChoiceFor(problem).chosen(), AutoCandidate::kBpp);
  SolverOptions options;
  options.tolerance = kTol;
  EXPECT_EQ(solver.DelegateFor(problem, options), &solver.candidate(AutoCandidate::kBpp));
  const SolveResult r = solver.Solve(problem, options);
  ASSERT_TRUE(r.solved()) << ToString(r.status) << " " << r.message;
  EXPECT_EQ(Chosen(r), AutoCandidate::kLemke);
  EXPECT_EQ(r.GetDetail("fallbacks"), 1.0);
  EXPECT_LE(IndependentResidual(problem, r.z), kTol);
  // The fallback is remembered for the matrix: the next delegate is lemke, until the warm state is forgotten.
  EXPECT_EQ(solver.DelegateFor(problem, options), &solver.candidate(AutoCandidate::kLemke));
  EXPECT_EQ(solver.ForgetWarmState(), WarmStateReset::kForgotten);
  EXPECT_EQ(solver.DelegateFor(problem, options), &solver.candidate(AutoCandidate::kBpp));
}

// A session whose delegate (bpp) fails on its matrix pays that failure once: the chain answers (lemke) and the
// session asks auto for its delegate again, so later steps go to lemke directly, with no fallback. Forgetting the
// warm state (a cold repeat) makes bpp the delegate again.
TEST(AutoSolver, ASessionPaysItsDelegatesFailureOnce) {
  const BoxMLCP problem = LcpCps2();
  AutoOptions o;
  o.enum_max_choice_rows = 0;
  AutoSolver solver(o);
  SolverOptions options;
  options.tolerance = kTol;
  SessionOptions no_reuse;  // every step through the backend
  no_reuse.reuse_active_set = false;
  SolveSession session = solver.Prepare(problem, options, no_reuse);
  ASSERT_EQ(&session.backend(), &solver.candidate(AutoCandidate::kBpp));
  SolveResult r;
  session.Solve(problem.q(), &r);
  ASSERT_TRUE(r.solved()) << ToString(r.status) << " " << r.message;
  EXPECT_EQ(Chosen(r), AutoCandidate::kLemke);
  EXPECT_EQ(r.GetDetail("fallbacks"), 1.0);
  EXPECT_EQ(&session.backend(), &solver.candidate(AutoCandidate::kLemke));
  session.Solve(problem.q(), &r);
  ASSERT_TRUE(r.solved()) << ToString(r.status) << " " << r.message;
  EXPECT_EQ(r.solver, "lemke");  // the delegate's own answer: no chain, no fallback
  EXPECT_TRUE(std::isnan(r.GetDetail("fallbacks")));
  EXPECT_EQ(session.ForgetWarmState(), WarmStateReset::kForgotten);
  EXPECT_EQ(&session.backend(), &solver.candidate(AutoCandidate::kBpp));
}

// The session's hand-over after its delegate failed starts the chain after that delegate (NoteDelegateFailure):
// here bpp would solve the problem, so an answer from the next candidate shows bpp was not run again. The skip is
// one-shot, for the matrix it was noted on, and only for the delegate auto would call.
TEST(AutoSolver, ANotedDelegateFailureIsNotRunAgain) {
  const GeneratedProblem gen = Generate(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kLCP, 20);
  AutoSolver solver;
  SolverOptions options;
  options.tolerance = kTol;
  ASSERT_EQ(solver.DelegateFor(gen.problem, options), &solver.candidate(AutoCandidate::kBpp));
  SolveResult failed;
  failed.status = SolveStatus::kIterationLimit;
  failed.message = "max_single_pivots reached";
  // Another backend's failure is not the delegate's: nothing is skipped.
  SolveResult noted = failed;
  EXPECT_FALSE(solver.NoteDelegateFailure(gen.problem, solver.candidate(AutoCandidate::kLemke), &noted));
  SolveResult r;
  solver.Solve(gen.problem, options, &r);
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_EQ(Chosen(r), AutoCandidate::kBpp);

  noted = failed;
  EXPECT_FALSE(solver.NoteDelegateFailure(gen.problem, solver.candidate(AutoCandidate::kBpp), &noted));
  solver.Solve(gen.problem, options, &r);
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_NE(Chosen(r), AutoCandidate::kBpp);
  EXPECT_EQ(r.GetDetail("fallbacks"), 1.0);
  EXPECT_EQ(solver.DelegateFor(gen.problem, options), &solver.candidate(Chosen(r)));  // it answered: first now
  EXPECT_EQ(solver.ForgetWarmState(), WarmStateReset::kForgotten);

  // A proof (infeasible from an exact backend) or a time limit ends the chain: the delegate's answer is auto's,
  // labelled as Solve labels it, and the caller does not call Solve.
  failed.status = SolveStatus::kTimeLimit;
  noted = failed;
  EXPECT_TRUE(solver.NoteDelegateFailure(gen.problem, solver.candidate(AutoCandidate::kBpp), &noted));
  EXPECT_EQ(noted.status, SolveStatus::kTimeLimit);
  EXPECT_EQ(noted.message, failed.message);
  EXPECT_EQ(Chosen(noted), AutoCandidate::kBpp);
  EXPECT_EQ(noted.GetDetail("fallbacks"), 0.0);
  solver.Solve(gen.problem, options, &r);
  EXPECT_EQ(Chosen(r), AutoCandidate::kBpp);  // and nothing was left to skip
}

// A session on an infeasible problem whose delegate is exact (enum: its answer is a proof): one enum run per call,
// and the answer auto's Solve gives (before, the session handed the proof to auto's Solve, which ran enum again).
TEST(AutoSolver, ASessionReturnsTheDelegatesProofWithoutRunningItAgain) {
  // w = −z − 1 < 0 for every z ≥ 0: no solution.
  const DenseMatrix M = -DenseMatrix::Identity(2, 2);
  const Vector q = Vector::Constant(2, -1.0);
  const BoxMLCP problem = BoxMLCP::LCP(M, q);
  AutoSolver solver;
  SolverOptions options;
  options.tolerance = kTol;
  ASSERT_EQ(solver.DelegateFor(problem, options), &solver.candidate(AutoCandidate::kEnum));
  SolveResult direct;
  solver.Solve(problem, options, &direct);
  ASSERT_EQ(direct.status, SolveStatus::kInfeasible) << direct.message;

  SessionOptions no_reuse;  // every call through the backend
  no_reuse.reuse_active_set = false;
  SolveSession session = solver.Prepare(problem, options, no_reuse);
  SolveResult r;
  session.Solve(problem.q(), &r);
  EXPECT_EQ(r.status, direct.status);
  EXPECT_EQ(r.message, direct.message);
  EXPECT_EQ(r.iterations, direct.iterations);
  EXPECT_EQ(r.z, direct.z);
  EXPECT_EQ(Chosen(r), AutoCandidate::kEnum);
  EXPECT_EQ(r.GetDetail("fallbacks"), direct.GetDetail("fallbacks"));
  // That the session did not call auto's Solve after enum: NoteDelegateFailure took the proof as auto's answer.
  SolveResult proof = direct;
  EXPECT_TRUE(solver.NoteDelegateFailure(problem, solver.candidate(AutoCandidate::kEnum), &proof));
}

// Sparse M up to sparse_bpp_max_size rows: enum on a dense copy where it would take the problem, else bpp (its sparse
// LU per set); newton above it (UMFPACK), or with sparse_bpp_max_size 0.
TEST(AutoSolver, SmallSparseGoesToBppLargeSparseToNewton) {
  ExpectChoice(Generate(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kRelay, 200, true),
               AutoCandidate::kNewton);
  ExpectChoice(Generate(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kMixed, 3, true), AutoCandidate::kEnum);
  ExpectChoice(Generate(MatrixFamily::kDiagonallyDominant, BoundKind::kRelay, 6, true), AutoCandidate::kEnum);
  ExpectChoice(Generate(MatrixFamily::kDiagonallyDominant, BoundKind::kRelay, 8, true), AutoCandidate::kBpp);  // 3^8 sets
  ExpectChoice(Generate(MatrixFamily::kDiagonallyDominant, BoundKind::kRelay, 64, true), AutoCandidate::kBpp);
  AutoOptions no_bpp;
  no_bpp.sparse_bpp_max_size = 0;
  ExpectChoice(Generate(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kMixed, 3, true), AutoCandidate::kNewton,
               no_bpp);
}

// Rows without a choice (free, fixed) do not count towards enum's size: 40 rows of which 3 are bounded.
TEST(AutoSolver, FreeAndFixedRowsDoNotCountTowardsEnum) {
  const GeneratedProblem gen = Generate(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kLCP, 40);
  Vector l = Vector::Constant(40, -kInf), u = Vector::Constant(40, kInf);
  for (int i : {3, 17, 31}) l[i] = 0.0;
  l[5] = u[5] = 0.25;  // fixed
  Vector z_star = gen.z_star;
  z_star[5] = 0.25;
  // Planted: z* with the bounded rows at their lower bound (w > 0) or inside (w = 0); free rows w = 0.
  Vector w = Vector::Zero(40);
  z_star[3] = 0.0, w[3] = 0.7;
  z_star[17] = 1.5;
  z_star[31] = 0.0, w[31] = 0.2;
  w[5] = 3.0;  // a fixed row's w is unconstrained
  const DenseMatrix& M = gen.problem.dense_matrix();
  GeneratedProblem planted{BoxMLCP(M, w - M * z_star, l, u, "mostly-free"), z_star, gen.options};
  ExpectChoice(planted, AutoCandidate::kEnum);
}

TEST(AutoSolver, NonlinearMcpGoesToNewton) {
  const FunctionMCP mcp = BillupsMcp();  // solution 1 + √1.01
  AutoSolver solver;
  const SolveResult r = solver.Solve(mcp);
  ASSERT_TRUE(r.solved()) << ToString(r.status) << " " << r.message;
  EXPECT_EQ(Chosen(r), AutoCandidate::kNewton);
  EXPECT_NEAR(r.z[0], 1.0 + std::sqrt(1.01), 1e-9);
}

// ---------------------------------------------------------------- the MCP chain: newton → newton-min → ipopt


// Josephy's NCP from MCPLIB's start (1, 1, 1, 1) with a budget of one iteration: newton stops at its iteration limit
// (a failure that proves nothing), while ipopt's Newton refinement of its first iterate reaches the solution.
SolverOptions OneIterationFromMcplibStart() {
  SolverOptions o;
  o.warm_start = Vector::Ones(4);
  o.max_iterations = 1;
  return o;
}

// A stand-in for a registered MCP backend that always fails without proof, counting its calls.
class FailingMcpBackend final : public Solver {
 public:
  explicit FailingMcpBackend(int* calls) : calls_(calls) {}
  const SolverInfo& info() const override {
    static const SolverInfo kInfo{"newton-min", "always stalls (test double)", "none", true, false, false, false,
                                  /*mcp=*/true};
    return kInfo;
  }

 protected:
  void DoSolve(const BoxMLCP&, const SolverOptions&, SolveResult* result) override {
    result->status = SolveStatus::kStalled;
  }
  void DoSolveMCP(const MCP&, const SolverOptions&, SolveResult* result) override {
    ++*calls_;
    result->status = SolveStatus::kStalled;
    result->message = "test double stalls";
  }

 private:
  int* calls_;
};

// A lookup that knows ipopt (the real backend) and, when calls is given, a failing newton-min.
BackendLookup TestLookup(int* calls) {
  return [calls](std::string_view name) -> std::unique_ptr<Solver> {
    if (name == "ipopt") return std::make_unique<IpoptQpSolver>();
    if (name == "newton-min" && calls != nullptr) return std::make_unique<FailingMcpBackend>(calls);
    return nullptr;
  };
}

TEST(AutoSolverMcp, ChainSkipsNamesTheLookupDoesNotKnow) {
  AutoSolver without;
  const AutoChoice only_newton = without.McpChoice();
  ASSERT_EQ(only_newton.count, 1);
  EXPECT_EQ(only_newton.order[0], AutoCandidate::kNewton);
  AutoSolver with_ipopt(AutoOptions{}, TestLookup(nullptr));
  const AutoChoice two = with_ipopt.McpChoice();
  ASSERT_EQ(two.count, 2);
  EXPECT_EQ(two.order[1], AutoCandidate::kIpopt);
  int calls = 0;
  AutoSolver all(AutoOptions{}, TestLookup(&calls));
  const AutoChoice three = all.McpChoice();
  ASSERT_EQ(three.count, 3);
  EXPECT_EQ(three.order[0], AutoCandidate::kNewton);
  EXPECT_EQ(three.order[1], AutoCandidate::kNewtonMin);
  EXPECT_EQ(three.order[2], AutoCandidate::kIpopt);
}

TEST(AutoSolverMcp, AFailingFirstCandidateHandsOverToIpopt) {
  AutoSolver solver(AutoOptions{}, TestLookup(nullptr));
  const SolveResult r = solver.Solve(JosephyMcp(), OneIterationFromMcplibStart());
  ASSERT_TRUE(r.solved()) << ToString(r.status) << " " << r.message;
  EXPECT_EQ(Chosen(r), AutoCandidate::kIpopt);
  EXPECT_EQ(r.GetDetail("fallbacks"), 1.0);
  EXPECT_EQ(r.solver, "auto");
  EXPECT_LE((r.z - JosephySolution()).cwiseAbs().maxCoeff(), 1e-8);
}

TEST(AutoSolverMcp, EveryFailingCandidateIsTriedInOrder) {
  int calls = 0;
  AutoSolver solver(AutoOptions{}, TestLookup(&calls));
  const SolveResult r = solver.Solve(JosephyMcp(), OneIterationFromMcplibStart());
  ASSERT_TRUE(r.solved()) << ToString(r.status) << " " << r.message;
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(Chosen(r), AutoCandidate::kIpopt);
  EXPECT_EQ(r.GetDetail("fallbacks"), 2.0);
  EXPECT_LE((r.z - JosephySolution()).cwiseAbs().maxCoeff(), 1e-8);
}

TEST(AutoSolverMcp, FirstSuccessEndsTheChain) {
  int calls = 0;
  AutoSolver solver(AutoOptions{}, TestLookup(&calls));
  const SolveResult r = solver.Solve(BillupsMcp());  // newton with its safeguard solves it
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_EQ(Chosen(r), AutoCandidate::kNewton);
  EXPECT_EQ(r.GetDetail("fallbacks"), 0.0);
  EXPECT_EQ(calls, 0);
}

TEST(AutoSolverMcp, WithoutFallbackTheFirstFailureIsTheAnswer) {
  AutoOptions o;
  o.fallback = false;
  AutoSolver solver(o, TestLookup(nullptr));
  const SolveResult r = solver.Solve(JosephyMcp(), OneIterationFromMcplibStart());
  EXPECT_EQ(r.status, SolveStatus::kIterationLimit) << r.message;
  EXPECT_EQ(Chosen(r), AutoCandidate::kNewton);
  EXPECT_EQ(r.GetDetail("fallbacks"), 0.0);
}

TEST(AutoSolverMcp, AFinalFailureListsEveryCandidate) {
  // No solution: F(x) = −1/(1 + x²) < 0 on [0, ∞). Every candidate fails; none may claim infeasibility.
  const FunctionMCP none(
      Vector::Zero(1), Vector::Constant(1, kInf),
      [](const Vector& x, Vector* F) { (*F)[0] = -1.0 / (1.0 + x[0] * x[0]); },
      [](const Vector& x, DenseMatrix* J) {
        (*J)(0, 0) = 2.0 * x[0] / ((1.0 + x[0] * x[0]) * (1.0 + x[0] * x[0]));
      },
      "no-solution");
  int calls = 0;
  AutoSolver solver(AutoOptions{}, TestLookup(&calls));
  SolverOptions o;
  o.max_iterations = 100;
  const SolveResult r = solver.Solve(none, o);
  EXPECT_FALSE(r.solved());
  EXPECT_NE(r.status, SolveStatus::kInfeasible);
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(r.GetDetail("fallbacks"), 2.0);
  EXPECT_NE(r.message.find("newton-min"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("ipopt"), std::string::npos) << r.message;
}

// PSOR's sweeps grow with the condition number (docs/auto.md: 35 sweeps at 1e2, 3441 at 1e8 for this relay
// problem at m = 64), lemke's pivots do not: an ill-conditioned SPD matrix goes to lemke.
TEST(AutoSolver, IllConditionedSpdIsNotGivenToPsor) {
  AutoOptions no_bpp;
  no_bpp.bpp_max_size = 0;
  AutoSolver solver(no_bpp);
  EXPECT_EQ(solver.ChoiceFor(GenerateSpdWithCondition(64, 1e2, BoundKind::kRelay).problem).chosen(), AutoCandidate::kPsor);
  const GeneratedProblem ill = GenerateSpdWithCondition(64, 1e8, BoundKind::kRelay);
  EXPECT_EQ(solver.ChoiceFor(ill.problem).chosen(), AutoCandidate::kLemke);
  ExpectChoice(ill, AutoCandidate::kLemke, no_bpp);
}

// The fallback path: psor is chosen (psor_min_speedup 0 gives it an ill-conditioned SPD problem), fails within the
// iteration budget without proving anything, and lemke, next in the chain, solves it within the same budget. Later
// calls on the same matrix start with lemke, and DelegateFor says so.
TEST(AutoSolver, FallsBackWhenTheChoiceFailsWithoutProof) {
  AutoOptions o;
  o.enum_max_choice_rows = 0;
  o.psor_min_speedup = 0.0;  // psor on any SPD matrix
  o.bpp_max_size = 0;        // psor's fallback is then lemke
  AutoSolver solver(o);
  const GeneratedProblem gen = GenerateSpdWithCondition(12, 1e6, BoundKind::kLCP);
  SolverOptions options;
  options.tolerance = kTol;
  options.max_iterations = 100;  // sweeps for psor (far too few at this condition), pivots for lemke (enough)
  options.polish = false;        // the base's polish would finish psor's job from a good active set
  // and so would psor's own subspace step: plain sweeps here, so that psor fails
  std::string error;
  ASSERT_TRUE(solver.candidate(AutoCandidate::kPsor).SetOption("subspace_sweeps", "0", &error)) << error;
  ASSERT_EQ(solver.DelegateFor(gen.problem, options), &solver.candidate(AutoCandidate::kPsor));

  // What psor alone does with this budget: no answer, and no proof either.
  PsorOptions plain;
  plain.subspace_sweeps = 0;
  PsorSolver psor(plain);
  const SolveResult alone = psor.Solve(gen.problem, options);
  ASSERT_FALSE(alone.solved());
  ASSERT_NE(alone.status, SolveStatus::kInfeasible);

  const SolveResult r = solver.Solve(gen.problem, options);
  ASSERT_TRUE(r.solved()) << ToString(r.status) << " " << r.message;
  EXPECT_EQ(Chosen(r), AutoCandidate::kLemke);
  EXPECT_EQ(r.GetDetail("fallbacks"), 1.0);
  EXPECT_LE(IndependentResidual(gen.problem, r.z), kTol);
  EXPECT_LE((r.z - gen.z_star).cwiseAbs().maxCoeff(), 1e-4 * (1.0 + gen.z_star.cwiseAbs().maxCoeff()));

  // What the last call showed: lemke answers directly from now on.
  EXPECT_EQ(solver.DelegateFor(gen.problem, options), &solver.candidate(AutoCandidate::kLemke));
  const SolveResult again = solver.Solve(gen.problem, options);
  ASSERT_TRUE(again.solved());
  EXPECT_EQ(Chosen(again), AutoCandidate::kLemke);
  EXPECT_EQ(again.GetDetail("fallbacks"), 0.0);
  EXPECT_EQ(again.z, r.z);

  // That is warm state: forgotten, the chain starts at the rule's choice again and a repeat falls back as the first
  // solve did (a cold benchmark repeat does the whole work).
  EXPECT_EQ(solver.ForgetWarmState(), WarmStateReset::kForgotten);
  EXPECT_EQ(solver.DelegateFor(gen.problem, options), &solver.candidate(AutoCandidate::kPsor));
  const SolveResult cold = solver.Solve(gen.problem, options);
  ASSERT_TRUE(cold.solved());
  EXPECT_EQ(cold.GetDetail("fallbacks"), 1.0);
  EXPECT_EQ(cold.z, r.z);
  EXPECT_EQ(solver.ForgetWarmState(), WarmStateReset::kForgotten);
  EXPECT_EQ(solver.ForgetWarmState(), WarmStateReset::kNothingRemembered);  // nothing left since
}

// An SPD relay problem on which psor refuses when its min_diagonal is raised: M is block diagonal with blocks
// [[1, 2], [2, 10]] (SPD: determinant 6), so after row equilibration every other row has M_ii = 0.5. Planted z*
// strictly inside the box (w* = 0), so q = −M z*.
GeneratedProblem SmallDiagonalSpdRelay() {
  const int n = 10;
  DenseMatrix M = DenseMatrix::Zero(n, n);
  Vector z_star(n);
  for (int b = 0; b < n; b += 2) {
    M(b, b) = 1.0, M(b, b + 1) = M(b + 1, b) = 2.0, M(b + 1, b + 1) = 10.0;
    z_star[b] = 0.5, z_star[b + 1] = -0.25;
  }
  GeneratorOptions g;
  g.size = n;
  return {BoxMLCP::Relay(M, -(M * z_star), -1.0, 1.0, "small-diagonal-spd-relay"), z_star, g};
}

// psor refuses a row whose diagonal is below min_diagonal · max|M_jk| (of the row-equilibrated problem).
PsorOptions StrictPsor() {
  PsorOptions strict;
  strict.min_diagonal = 0.6;
  return strict;
}

// A refusal of the chosen backend (psor: kNotApplicable) passes the problem on too.
TEST(AutoSolver, FallsBackOnARefusal) {
  AutoOptions no_bpp;
  no_bpp.bpp_max_size = 0;
  AutoSolver solver(no_bpp);
  static_cast<PsorSolver&>(solver.candidate(AutoCandidate::kPsor)).set_options(StrictPsor());
  const GeneratedProblem gen = SmallDiagonalSpdRelay();
  ASSERT_EQ(solver.ChoiceFor(gen.problem).chosen(), AutoCandidate::kPsor);
  const SolveResult r = solver.Solve(gen.problem);
  ASSERT_TRUE(r.solved()) << ToString(r.status) << " " << r.message;
  EXPECT_EQ(Chosen(r), AutoCandidate::kLemke);
  EXPECT_EQ(r.GetDetail("fallbacks"), 1.0);
  EXPECT_LE((r.z - gen.z_star).cwiseAbs().maxCoeff(), 1e-12);
}

// A session prepared on auto calls auto's choice directly, and hands a call the choice did not solve to auto's own
// Solve, whose chain answers: here psor (the delegate) refuses every step and lemke answers each one.
TEST(AutoSolver, ASessionFallsBackThroughTheChain) {
  AutoOptions no_bpp;
  no_bpp.bpp_max_size = 0;
  AutoSolver solver(no_bpp);
  static_cast<PsorSolver&>(solver.candidate(AutoCandidate::kPsor)).set_options(StrictPsor());
  const GeneratedProblem gen = SmallDiagonalSpdRelay();
  SessionOptions no_reuse;  // every step through the backend, not the reused active set
  no_reuse.reuse_active_set = false;
  SolveSession session = solver.Prepare(gen.problem, SolverOptions{}, no_reuse);
  EXPECT_EQ(&session.backend(), &solver.candidate(AutoCandidate::kPsor));
  SolveResult r;
  for (int step = 0; step < 3; ++step) {
    const Vector q = gen.problem.q() * (1.0 + 0.01 * step);
    session.Solve(q, &r);
    ASSERT_TRUE(r.solved()) << "step " << step << ": " << ToString(r.status) << " " << r.message;
    // Step 0 falls back through auto's chain; then the session's delegate is the candidate that answered.
    if (step == 0) {
      EXPECT_EQ(Chosen(r), AutoCandidate::kLemke);
    } else {
      EXPECT_EQ(r.solver, "lemke") << "step " << step;
    }
    EXPECT_EQ(&session.backend(), &solver.candidate(AutoCandidate::kLemke)) << "step " << step;
    // z* scales with q here (q = −M z*, every row strictly inside its box for these q).
    EXPECT_LE((r.z - gen.z_star * (1.0 + 0.01 * step)).cwiseAbs().maxCoeff(), 1e-12) << "step " << step;
  }
}

// With fallback off, the first choice's answer is returned as it is.
TEST(AutoSolver, FallbackCanBeSwitchedOff) {
  AutoSolver solver;
  std::string error;
  ASSERT_TRUE(solver.SetOption("fallback", "false", &error)) << error;
  ASSERT_TRUE(solver.SetOption("bpp_max_size", "0", &error)) << error;  // psor first
  static_cast<PsorSolver&>(solver.candidate(AutoCandidate::kPsor)).set_options(StrictPsor());
  const SolveResult r = solver.Solve(SmallDiagonalSpdRelay().problem);
  EXPECT_EQ(r.status, SolveStatus::kNotApplicable) << r.message;
  EXPECT_EQ(Chosen(r), AutoCandidate::kPsor);
  EXPECT_EQ(r.GetDetail("fallbacks"), 0.0);
}

// LCP(M = [[-1]], q = [-1]): w = −z − 1 < 0 for every z ≥ 0, so there is no solution. enum (exact) proves it and
// auto reports it; when enum is not chosen, bpp and lemke fail without a proof (lemke ends on a ray) and newton
// fails, and auto does not claim infeasibility.
TEST(AutoSolver, InfeasibleOnlyFromAnExactBackend) {
  const BoxMLCP p = BoxMLCP::LCP(DenseMatrix::Constant(1, 1, -1.0), Vector::Constant(1, -1.0), "no-solution");
  AutoSolver solver;
  const SolveResult proved = solver.Solve(p);
  EXPECT_EQ(proved.status, SolveStatus::kInfeasible) << proved.message;
  EXPECT_EQ(Chosen(proved), AutoCandidate::kEnum);
  EXPECT_EQ(proved.GetDetail("fallbacks"), 0.0);
  EXPECT_TRUE(solver.candidate(AutoCandidate::kEnum).info().exact);

  AutoOptions no_enum;
  no_enum.enum_max_choice_rows = 0;
  AutoSolver without_enum(no_enum);
  const SolveResult r = without_enum.Solve(p);
  EXPECT_FALSE(r.solved());
  EXPECT_NE(r.status, SolveStatus::kInfeasible) << r.message;
  EXPECT_EQ(Chosen(r), AutoCandidate::kNewton);
  EXPECT_EQ(r.GetDetail("fallbacks"), 2.0);
  EXPECT_NE(r.message.find("bpp"), std::string::npos) << r.message;  // says what bpp, then lemke reported
  EXPECT_NE(r.message.find("lemke"), std::string::npos) << r.message;
}

// One-off solves through DelegateFor's backend give the answer auto gives (same backend, same algorithm; for bpp's
// problems the next candidate, and the same unique solution).
TEST(AutoSolver, DelegateAnswersLikeAuto) {
  for (const GeneratedProblem& gen :
       {Generate(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kRelay, 2),
        Generate(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kRelay, 64),
        Generate(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kLCP, 64)}) {
    AutoSolver solver;
    const SolveResult via_auto = solver.Solve(gen.problem);
    Solver* delegate = solver.DelegateFor(gen.problem, SolverOptions{});
    ASSERT_NE(delegate, nullptr);
    const SolveResult direct = delegate->Solve(gen.problem);
    ASSERT_TRUE(direct.solved()) << gen.problem.name();
    EXPECT_EQ(direct.solver, ToString(Chosen(via_auto)));
    EXPECT_EQ(via_auto.status, direct.status) << gen.problem.name();
    EXPECT_EQ(via_auto.iterations, direct.iterations) << gen.problem.name();
    EXPECT_LE((via_auto.z - direct.z).cwiseAbs().maxCoeff(), 1e-14 * (1.0 + direct.z.cwiseAbs().maxCoeff()))
        << gen.problem.name();
  }
}

// The decision is per matrix: a new matrix is classified afresh, and options changed through SetOption apply.
TEST(AutoSolver, ChoiceFollowsTheMatrixAndTheOptions) {
  AutoOptions no_bpp;
  no_bpp.bpp_max_size = 0;
  AutoSolver solver(no_bpp);
  const GeneratedProblem small = Generate(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kRelay, 4);
  const GeneratedProblem large = Generate(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kRelay, 64);
  EXPECT_EQ(solver.ChoiceFor(small.problem).chosen(), AutoCandidate::kEnum);
  EXPECT_EQ(solver.ChoiceFor(large.problem).chosen(), AutoCandidate::kPsor);
  EXPECT_EQ(solver.ChoiceFor(small.problem).chosen(), AutoCandidate::kEnum);
  std::string error;
  ASSERT_TRUE(solver.SetOption("enum_max_choice_rows", "0", &error)) << error;
  EXPECT_NE(solver.ChoiceFor(small.problem).chosen(), AutoCandidate::kEnum);
  ASSERT_TRUE(solver.SetOption("psor_min_speedup", "inf", &error)) << error;
  EXPECT_EQ(solver.ChoiceFor(large.problem).chosen(), AutoCandidate::kLemke);
  ASSERT_TRUE(solver.SetOption("bpp_max_size", "64", &error)) << error;
  EXPECT_EQ(solver.ChoiceFor(large.problem).chosen(), AutoCandidate::kBpp);
  ASSERT_TRUE(solver.SetOption("bpp_max_size", "0", &error)) << error;
  ASSERT_TRUE(solver.SetOption("psor_min_speedup", "0", &error)) << error;
  EXPECT_EQ(solver.ChoiceFor(large.problem).chosen(), AutoCandidate::kPsor);
  // The typed accessors decide the cached choice again just as SetOption does (BackendWithOptions).
  solver.mutable_options().enum_max_choice_rows = 8;
  EXPECT_EQ(solver.ChoiceFor(small.problem).chosen(), AutoCandidate::kEnum);
  AutoOptions no_enum;
  no_enum.enum_max_choice_rows = 0;
  solver.set_options(no_enum);
  EXPECT_NE(solver.ChoiceFor(small.problem).chosen(), AutoCandidate::kEnum);
}

TEST(AutoSolver, RejectsBadOptionsNamingTheField) {
  AutoSolver solver;
  std::string error;
  EXPECT_FALSE(solver.SetOption("enum_max_choice_rows", "21", &error));
  EXPECT_NE(error.find("enum_max_choice_rows"), std::string::npos) << error;
  EXPECT_FALSE(solver.SetOption("psor_min_speedup", "-1", &error));
  EXPECT_NE(error.find("psor_min_speedup"), std::string::npos) << error;
  EXPECT_FALSE(solver.SetOption("enum_max_active_sets", "-1", &error));
  EXPECT_NE(error.find("enum_max_active_sets"), std::string::npos) << error;
  EXPECT_FALSE(solver.SetOption("omega", "1.5", &error));  // psor's, not auto's
  AutoOptions bad;
  bad.psor_min_speedup = std::nan("");
  solver.set_options(bad);
  const BoxMLCP p = Generate(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kLCP, 2).problem;
  const SolveResult r = solver.Solve(p);
  EXPECT_EQ(r.status, SolveStatus::kInvalidOptions);
  EXPECT_NE(r.message.find("psor_min_speedup"), std::string::npos) << r.message;
  EXPECT_EQ(solver.DelegateFor(p, SolverOptions{}), nullptr);  // a session then reports them too
}

// Issue 34: the small-h P-matrix relay of condition 1e6 at m = 8 (families.h), where DART's PGS plus our polish was
// faster than auto. auto gives it to bpp (3⁸ active sets, past enum's limit), whose first set now comes from
// projected sweeps (a nonsymmetric box): two sets where the natural map at Π(0) took nine, the same answer, which is
// the planted one and lemke's.
TEST(AutoSolver, SmallHRelayIsSolvedByBppFromASweptFirstSet) {
  for (double h : {1e-2, 1e-8}) {
    const LibraryProblem p = SmallHPMatrixProblem(8, 6, h, 1);
    AutoSolver solver;
    const SolveResult r = solver.Solve(p.problem);
    ASSERT_TRUE(r.solved()) << r.message;
    EXPECT_EQ(ChosenCandidateOf(r), AutoCandidate::kBpp);
    EXPECT_EQ(r.GetDetail("swept_guess"), 1.0);
    EXPECT_LE(r.iterations, 2);
    LemkeSolver lemke;
    const SolveResult by_lemke = lemke.Solve(p.problem);
    ASSERT_TRUE(by_lemke.solved()) << by_lemke.message;
    EXPECT_LE((r.z - by_lemke.z).cwiseAbs().maxCoeff(), 1e-8);
    EXPECT_LE((r.z - p.solution).cwiseAbs().maxCoeff(), 1e-8);
    BppOptions unswept;
    unswept.guess_sweeps = 0;
    BppSolver from_zero(unswept);
    const SolveResult r0 = from_zero.Solve(p.problem);
    ASSERT_TRUE(r0.solved()) << r0.message;
    EXPECT_GT(r0.iterations, 4) << "the natural map at the projection of 0 should need many sets here";
    EXPECT_LE((r0.z - r.z).cwiseAbs().maxCoeff(), 1e-8);
  }
}

}  // namespace
}  // namespace smcbench

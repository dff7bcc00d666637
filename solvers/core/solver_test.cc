// Pins down what the Solver base guarantees for every backend: the merit-function rule, option checks,
// start points, statuses and their names.
#include "solvers/core/solver.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "solvers/core/active_set.h"
#include "solvers/core/verdict.h"

namespace smcbench {
namespace {

using ::testing::HasSubstr;

// A backend that returns a scripted z and status: lets us test what the base does with whatever a backend says.
class ScriptedSolver final : public Solver {
 public:
  struct Options {
    double factor = 1.0;
  };
  const SolverInfo& info() const override {
    static const SolverInfo kInfo{"scripted", "returns a scripted answer", "none"};
    return kInfo;
  }
  SolveStatus status_to_report = SolveStatus::kSolved;
  Vector z_to_report;
  Vector seen_start;
  Options options;
  bool note_polish_redundant = false;  // DoSolve calls NotePolishRedundant

 protected:
  void DoSolve(const BoxMLCP&, const SolverOptions&, SolveResult* result) override {
    seen_start = result->z;
    if (note_polish_redundant) NotePolishRedundant();
    if (z_to_report.size()) result->z = z_to_report;
    result->status = status_to_report;
    result->iterations = 7;
    result->SetDetail("answer", 42.0);
  }
  void BindOptions(OptionBinder* binder) override { binder->Add("factor", &options.factor, "a positive number"); }
  bool ValidateBackendOptions(std::string* why) const override {
    if (options.factor > 0) return true;
    *why = "factor must be > 0";
    return false;
  }
};

BoxMLCP SimpleLCP() {
  Vector q(2);
  q << -1.0, 2.0;  // solution z = (1, 0)
  return BoxMLCP::LCP(DenseMatrix::Identity(2, 2), q, "simple");
}

// The raw rule, with the polish off (it would turn this z into the solution: see PolishReplacesANearbyAnswer).
SolverOptions NoPolish() {
  SolverOptions o;
  o.polish = false;
  return o;
}

TEST(SolverBase, WrongClaimOfSuccessBecomesInaccurate) {
  ScriptedSolver solver;
  solver.z_to_report = Vector::Zero(2);  // not a solution: residual 1
  const SolveResult r = solver.Solve(SimpleLCP(), NoPolish());
  EXPECT_EQ(r.status, SolveStatus::kInaccurate);
  EXPECT_THAT(r.message, HasSubstr("natural residual"));
  EXPECT_DOUBLE_EQ(r.residual_abs, 1.0);
  EXPECT_DOUBLE_EQ(r.residual_rel, 1.0 / 3.0);
  EXPECT_EQ(r.solver, "scripted");
}

TEST(SolverBase, TrueSuccessIsKeptAndResidualRecomputed) {
  ScriptedSolver solver;
  solver.z_to_report = (Vector(2) << 1.0, 0.0).finished();
  const SolveResult r = solver.Solve(SimpleLCP());
  EXPECT_EQ(r.status, SolveStatus::kSolved);
  EXPECT_EQ(r.residual_abs, 0.0);
  EXPECT_EQ(r.w, (Vector(2) << 0.0, 2.0).finished());
  EXPECT_EQ(r.iterations, 7);
  EXPECT_EQ(r.GetDetail("answer"), 42.0);
  EXPECT_TRUE(std::isnan(r.GetDetail("missing")));
  EXPECT_GE(r.solve_seconds, 0.0);
}

TEST(SolverBase, NaNIterateIsNeverSolved) {
  ScriptedSolver solver;
  solver.z_to_report = Vector::Constant(2, std::nan(""));
  const SolveResult r = solver.Solve(SimpleLCP());
  EXPECT_EQ(r.status, SolveStatus::kInaccurate);
  EXPECT_EQ(r.residual_abs, kInf);
}

TEST(SolverBase, FailureStatusIsPassedThroughWithResidual) {
  ScriptedSolver solver;
  solver.status_to_report = SolveStatus::kIterationLimit;
  solver.z_to_report = (Vector(2) << 0.5, 0.0).finished();
  const SolveResult r = solver.Solve(SimpleLCP(), NoPolish());
  EXPECT_EQ(r.status, SolveStatus::kIterationLimit);
  EXPECT_DOUBLE_EQ(r.residual_abs, 0.5);
}

TEST(SolverBase, ColdStartIsProjectionOfZeroWarmStartIsPassed) {
  ScriptedSolver solver;
  Vector l(2), u(2);
  l << 0.5, -kInf;
  u << 1.0, -2.0;
  const BoxMLCP p(DenseMatrix::Identity(2, 2), Vector::Zero(2), l, u);
  solver.Solve(p);
  EXPECT_EQ(solver.seen_start, (Vector(2) << 0.5, -2.0).finished());
  SolverOptions options;
  options.warm_start = (Vector(2) << 0.75, -3.0).finished();
  solver.Solve(p, options);
  EXPECT_EQ(solver.seen_start, options.warm_start);
}

TEST(SolverBase, InvalidCommonOptionsAreAStatusNotACrash) {
  ScriptedSolver solver;
  SolverOptions options;
  options.tolerance = -1.0;
  SolveResult r = solver.Solve(SimpleLCP(), options);
  EXPECT_EQ(r.status, SolveStatus::kInvalidOptions);
  EXPECT_THAT(r.message, HasSubstr("tolerance"));
  options = {};
  options.tolerance = std::nan("");
  EXPECT_EQ(solver.Solve(SimpleLCP(), options).status, SolveStatus::kInvalidOptions);
  options = {};
  options.warm_start = Vector::Zero(3);
  r = solver.Solve(SimpleLCP(), options);
  EXPECT_EQ(r.status, SolveStatus::kInvalidOptions);
  EXPECT_THAT(r.message, HasSubstr("warm_start has size 3"));
  options.warm_start = (Vector(2) << 0.0, kInf).finished();
  r = solver.Solve(SimpleLCP(), options);
  EXPECT_THAT(r.message, HasSubstr("warm_start[1]"));
  options = {};
  options.time_limit_seconds = 0.0;
  EXPECT_EQ(solver.Solve(SimpleLCP(), options).status, SolveStatus::kInvalidOptions);
}

TEST(SolverBase, OptionsAreValidatedOnEverySolveNotOnlyTheFirst) {
  // The same options object reused across solves (as a time-stepper does) and then made invalid.
  ScriptedSolver solver;
  solver.z_to_report = (Vector(2) << 1.0, 0.0).finished();
  SolverOptions options;
  SolveResult r;
  const BoxMLCP p = SimpleLCP();
  solver.Solve(p, options, &r);
  EXPECT_TRUE(r.solved());
  options.tolerance = -1.0;
  solver.Solve(p, options, &r);
  EXPECT_EQ(r.status, SolveStatus::kInvalidOptions);
  EXPECT_THAT(r.message, HasSubstr("tolerance"));
  options.tolerance = 1e-10;
  solver.Solve(p, options, &r);
  EXPECT_TRUE(r.solved());
  solver.options.factor = -1.0;  // backend options changed directly between solves
  solver.Solve(p, options, &r);
  EXPECT_EQ(r.status, SolveStatus::kInvalidOptions);
  EXPECT_THAT(r.message, HasSubstr("factor must be > 0"));
  solver.options.factor = 1.0;
  options.warm_start = (Vector(2) << 0.0, std::nan("")).finished();
  solver.Solve(p, options, &r);
  EXPECT_EQ(r.status, SolveStatus::kInvalidOptions);
  EXPECT_THAT(r.message, HasSubstr("warm_start[1] is not finite"));
  EXPECT_EQ(r.z, Vector::Zero(2));
  options.warm_start = Vector::Zero(1);
  solver.Solve(p, options, &r);
  EXPECT_THAT(r.message, HasSubstr("warm_start has size 1 but the problem has 2"));
  // Both wrong: the invalid value is reported first, as IsValid orders it.
  options.warm_start = (Vector(1) << kInf).finished();
  solver.Solve(p, options, &r);
  EXPECT_THAT(r.message, HasSubstr("warm_start[0] is not finite"));
}

// A library's return code belongs to one answer: Reset (the start of every solve) clears it with the details.
TEST(SolveResultDetails, ResetClearsTheLibrarysReturnCode) {
  SolveResult r;
  r.backend_code = 2;
  r.SetDetail("siconos_info", 2.0);
  r.Reset();
  EXPECT_EQ(r.backend_code, std::nullopt);
  EXPECT_EQ(r.num_details, 0);
}

TEST(SolveResultDetails, NamesStayUniqueWhenReusedInAnotherOrder) {
  static const char kAlpha[] = "alpha";
  const std::string alpha_copy = "alpha";  // same text, another pointer
  SolveResult r;
  r.SetDetail(kAlpha, 1.0);
  r.SetDetail("beta", 2.0);
  r.Reset();
  r.SetDetail("beta", 3.0);  // slot 0 held "alpha": appended by text
  r.SetDetail(kAlpha, 4.0);
  r.SetDetail(alpha_copy.c_str(), 5.0);  // overwrites, never duplicates
  EXPECT_EQ(r.num_details, 2);
  EXPECT_EQ(r.GetDetail("alpha"), 5.0);
  EXPECT_EQ(r.GetDetail("beta"), 3.0);
  r.Reset();
  r.SetDetail("beta", 6.0);  // the same literals in the same order: reuses the slots
  r.SetDetail(kAlpha, 7.0);
  r.SetDetail(alpha_copy.c_str(), 8.0);
  EXPECT_EQ(r.num_details, 2);
  EXPECT_EQ(r.GetDetail("alpha"), 8.0);
  r.Reset();
  r.SetDetail(alpha_copy.c_str(), 9.0);  // a new pointer at slot 0, then the old literals
  r.SetDetail("beta", 10.0);
  r.SetDetail(kAlpha, 11.0);
  EXPECT_EQ(r.num_details, 2);
  EXPECT_EQ(r.GetDetail("alpha"), 11.0);
  EXPECT_EQ(r.GetDetail("beta"), 10.0);
}

TEST(SolveResultDetails, CodesAreReadAsTheirEnumAndNamedForPrinting) {
  SolveResult r;
  EXPECT_EQ(SessionPathOf(r), std::nullopt) << "no session, no path";
  r.SetDetail("sweeps", 3.0);
  kSessionPathDetail.Set(&r, SessionPath::kReusedActiveSet);
  ASSERT_EQ(r.num_details, 2);
  EXPECT_EQ(SessionPathOf(r), SessionPath::kReusedActiveSet);
  EXPECT_EQ(SolveResult::CodeText(r.details[1]), "reused_active_set");
  EXPECT_EQ(SolveResult::CodeText(r.details[0]), "") << "a measurement has no name";
  // Reused across solves: the same code again overwrites in place, and a number that is no SessionPath reads as none.
  r.Reset();
  r.SetDetail("sweeps", 4.0);
  kSessionPathDetail.Set(&r, SessionPath::kBackend);
  EXPECT_EQ(r.num_details, 2);
  EXPECT_EQ(SessionPathOf(r), SessionPath::kBackend);
  EXPECT_EQ(SolveResult::CodeText(r.details[1]), "backend");
  for (double stray : {2.0, -1.0, 0.5, std::nan("")}) {
    r.SetCodeDetail(kSessionPathDetail.name, 0, kSessionPathDetail.NameOf);
    r.details[1].value = stray;
    EXPECT_EQ(SessionPathOf(r), std::nullopt) << stray;
    EXPECT_EQ(SolveResult::CodeText(r.details[1]), "") << stray;
  }
  // A measurement written over a code's name drops the namer.
  r.SetDetail("path", 1.0);
  EXPECT_EQ(SolveResult::CodeText(r.details[1]), "");
}

TEST(SessionPathNames, RoundTrip) {
  for (const SessionPath path : {SessionPath::kBackend, SessionPath::kReusedActiveSet}) {
    EXPECT_EQ(SessionPathFromString(ToString(path)), path);
  }
  EXPECT_EQ(ToString(SessionPath::kReusedActiveSet), "reused_active_set");
  EXPECT_FALSE(SessionPathFromString("1").has_value());
  EXPECT_FALSE(SessionPathFromString("Backend").has_value());
}

TEST(SolverBase, TypedBackendOptionsFromText) {
  ScriptedSolver solver;
  std::string error;
  EXPECT_TRUE(solver.SetOption("factor", "2.5", &error));
  EXPECT_EQ(solver.options.factor, 2.5);
  EXPECT_FALSE(solver.SetOption("factr", "2.5", &error));
  EXPECT_THAT(error, HasSubstr("unknown option 'factr' (known: factor)"));
  EXPECT_FALSE(solver.SetOption("factor", "abc", &error));
  EXPECT_THAT(error, HasSubstr("expects a number"));
  EXPECT_FALSE(solver.SetOption("factor", "-1", &error));
  EXPECT_THAT(error, HasSubstr("factor must be > 0"));
  // A rejected value is not kept.
  EXPECT_EQ(solver.options.factor, 2.5);
  // An invalid value set directly in the typed struct is rejected at solve time: never silently used.
  solver.options.factor = -1;
  const SolveResult r = solver.Solve(SimpleLCP());
  EXPECT_EQ(r.status, SolveStatus::kInvalidOptions);
  EXPECT_THAT(solver.OptionsHelp(), HasSubstr("factor"));
}

TEST(SolverBase, DenseOnlyBackendSolvesADenseCopyOfASparseProblem) {
  ScriptedSolver solver;
  solver.z_to_report = (Vector(2) << 1.0, 0.0).finished();
  Vector q(2);
  q << -1.0, 2.0;
  const SparseMatrix M = DenseMatrix::Identity(2, 2).sparseView();
  const BoxMLCP p(M, q, Vector::Zero(2), Vector::Constant(2, kInf));
  const SolveResult r = solver.Solve(p);
  EXPECT_EQ(r.status, SolveStatus::kSolved);
  EXPECT_EQ(r.GetDetail("densified"), 1.0);
}

TEST(SolverBase, DenseOnlyBackendRefusesHugeSparseProblem) {
  ScriptedSolver solver;
  const int n = Solver::kMaxDensifiedSize + 1;
  SparseMatrix M(n, n);
  M.setIdentity();
  const BoxMLCP p(M, Vector::Zero(n), Vector::Zero(n), Vector::Constant(n, kInf));
  const SolveResult r = solver.Solve(p);
  EXPECT_EQ(r.status, SolveStatus::kNotApplicable);
  EXPECT_THAT(r.message, HasSubstr("too large to densify"));
}

TEST(SolverBase, NonMcpBackendRefusesMcp) {
  ScriptedSolver solver;
  const FunctionMCP mcp(
      Vector::Zero(1), Vector::Constant(1, kInf), [](const Vector& z, Vector* F) { *F = z; },
      [](const Vector&, DenseMatrix* J) { J->setIdentity(1, 1); });
  const SolveResult r = solver.Solve(mcp);
  EXPECT_EQ(r.status, SolveStatus::kNotApplicable);
  EXPECT_EQ(r.residual_abs, 0.0);  // z = Π(0) = 0 happens to solve it; the status still says "not applicable"
}

TEST(SolverBase, ResultIsReusedWithoutStaleState) {
  ScriptedSolver solver;
  SolveResult r;
  solver.z_to_report = Vector::Zero(2);
  solver.Solve(SimpleLCP(), NoPolish(), &r);
  EXPECT_FALSE(r.message.empty());
  solver.z_to_report = (Vector(2) << 1.0, 0.0).finished();
  solver.Solve(SimpleLCP(), SolverOptions{}, &r);
  EXPECT_TRUE(r.solved());
  EXPECT_TRUE(r.message.empty());
}

// ---- Nonlinear MCPs: the base's scale-free rule and JudgeMCP ----

// An MCP backend that returns a scripted z and status (optionally evaluating F first, as a real backend does).
class ScriptedMcpSolver final : public Solver {
 public:
  const SolverInfo& info() const override {
    static const SolverInfo kInfo{"scripted-mcp", "returns a scripted answer", "none", true, false, false, false,
                                  /*mcp=*/true};
    return kInfo;
  }
  SolveStatus status_to_report = SolveStatus::kSolved;
  Vector z_to_report;
  bool evaluate_f = false;

 protected:
  void DoSolve(const BoxMLCP&, const SolverOptions&, SolveResult* result) override {
    result->status = SolveStatus::kNotApplicable;
  }
  void DoSolveMCP(const MCP& problem, const SolverOptions&, SolveResult* result) override {
    if (evaluate_f) problem.Evaluate(result->z, &result->w);
    result->z = z_to_report;
    result->status = status_to_report;
  }
};

// A general-equilibrium failure reduced to one price: p ≥ 1e-8 (F is undefined at 0), F(p) = row·(1 − 1/p), the
// unique solution p* = 1. At Π(0) = 1e-8, |F| = 1e8·row, so a residual relative to 1 + ‖F(Π(0))‖∞ lets through
// answers off by ~1e-2; near p*, J = row/p² is modest.
FunctionMCP PriceMcp(double row = 1.0) {
  return FunctionMCP(
      Vector::Constant(1, 1e-8), Vector::Constant(1, kInf),
      [row](const Vector& p, Vector* F) { (*F)[0] = row * (1.0 - 1.0 / p[0]); },
      [row](const Vector& p, DenseMatrix* J) { (*J)(0, 0) = row / (p[0] * p[0]); }, "price");
}

TEST(McpVerdict, AWrongAnswerThatTheRelativeResidualPassesIsInaccurate) {
  ScriptedMcpSolver solver;
  solver.z_to_report = Vector::Constant(1, 1.0 + 1e-4);  // 1e-4 off the unique solution
  const SolveResult r = solver.Solve(PriceMcp());
  EXPECT_LE(r.residual_rel, 1e-10) << "relative to 1 + |F(1e-8)| = 1e8: blind to it";
  // F = 1 − 1/p ≈ 1e-4, d = 1/p²: the step F/d = p(p − 1) ≈ 1.0001e-4, over 1 + |p| ≈ 2.
  EXPECT_NEAR(r.residual_scaled, (1.0 + 1e-4) * 1e-4 / (2.0 + 1e-4), 1e-15);
  EXPECT_EQ(r.status, SolveStatus::kInaccurate);
  EXPECT_THAT(r.message, HasSubstr("scale-free residual"));
}

TEST(McpVerdict, ARightAnswerIsSolvedWithWEqualToF) {
  ScriptedMcpSolver solver;
  solver.z_to_report = Vector::Constant(1, 1.0);
  const SolveResult r = solver.Solve(PriceMcp(1e8));
  EXPECT_EQ(r.status, SolveStatus::kSolved) << r.message;
  EXPECT_EQ(r.residual_scaled, 0.0);
  EXPECT_EQ(r.w[0], 0.0);
}

// residual_rel is information: scaling F by 1e8 changes it, never the status; residual_scaled does not change.
TEST(McpVerdict, TheRuleIsInvariantUnderScalingFsRows) {
  for (double p : {1.0, 1.0 + 1e-12, 1.0 + 1e-6, 0.5}) {
    ScriptedMcpSolver solver;
    solver.z_to_report = Vector::Constant(1, p);
    const SolveResult a = solver.Solve(PriceMcp(1.0));
    for (double row : {1e8, 1e-8}) {
      const SolveResult b = solver.Solve(PriceMcp(row));
      EXPECT_EQ(a.status, b.status) << p << " " << row;
      EXPECT_NEAR(b.residual_scaled, a.residual_scaled, 1e-14 * a.residual_scaled) << p << " " << row;
    }
  }
}

TEST(McpVerdict, AMalformedOrThrowingJacobianIsANumericalFailureNotACrash) {
  const auto F = [](const Vector& z, Vector* f) { (*f)[0] = z[0] - 1.0; };
  const FunctionMCP wrong_size(
      Vector::Zero(1), Vector::Constant(1, kInf), F, [](const Vector&, DenseMatrix* J) { J->setIdentity(2, 2); });
  const FunctionMCP throws(Vector::Zero(1), Vector::Constant(1, kInf), F,
                           [](const Vector&, DenseMatrix*) -> void { throw std::runtime_error("no Jacobian here"); });
  ScriptedMcpSolver solver;
  solver.z_to_report = Vector::Constant(1, 1.0);  // the solution: only the Jacobian is wrong
  SolveResult r = solver.Solve(wrong_size);
  EXPECT_EQ(r.status, SolveStatus::kNumericalFailure);
  EXPECT_THAT(r.message, HasSubstr("Jacobian at z is 2x2, expected 1x1"));
  EXPECT_EQ(r.residual_scaled, kInf);
  r = solver.Solve(throws);
  EXPECT_EQ(r.status, SolveStatus::kNumericalFailure);
  EXPECT_THAT(r.message, HasSubstr("no Jacobian here"));
  // F throwing inside the backend ends the solve with a status too.
  const FunctionMCP f_throws(
      Vector::Zero(1), Vector::Constant(1, kInf), [](const Vector&, Vector*) { throw std::runtime_error("F broke"); },
      [](const Vector&, DenseMatrix* J) { J->setIdentity(1, 1); });
  solver.evaluate_f = true;
  r = solver.Solve(f_throws);
  EXPECT_EQ(r.status, SolveStatus::kNumericalFailure);
  EXPECT_THAT(r.message, HasSubstr("F broke"));
  // Bad input is an error naming the field, not a status (the Python binding's shape checks rely on it).
  const FunctionMCP bad_input(Vector::Zero(1), Vector::Constant(1, kInf), F, [](const Vector&, DenseMatrix*) -> void {
    throw InvalidInputError("J(z) returned a 2x2 matrix, expected 1x1");
  });
  EXPECT_THROW(solver.Solve(bad_input), InvalidInputError);
  // A backend that refused keeps its reason.
  ScriptedSolver not_mcp;
  r = not_mcp.Solve(wrong_size);
  EXPECT_EQ(r.status, SolveStatus::kNotApplicable);
}

// The verdicts of JudgeMCP on MCPs whose solutions are known by hand.
ReferenceSolution Reference(Certificate certificate, double z, double condition = 1.0) {
  ReferenceSolution r;
  r.certificate = certificate;
  r.z = Vector::Constant(1, z);
  r.condition = condition;
  return r;
}

TEST(JudgeMCP, SolvedAndWronglyClaimedFollowTheScaleFreeResidual) {
  const FunctionMCP mcp = PriceMcp(1e8);
  const std::vector<ReferenceSolution> unique = {Reference(Certificate::kUnique, 1.0)};
  Judgement j = JudgeMCP(mcp, ExpectedOutcome::kSolvable, unique, false, SolveStatus::kSolved,
                         Vector::Constant(1, 1.0 + 1e-12), 1e-10);
  EXPECT_EQ(j.verdict, Verdict::kSolved);
  EXPECT_NEAR(j.forward_error, 1e-12, 1e-15);
  EXPECT_DOUBLE_EQ(j.forward_allowance, ForwardErrorAllowance(unique[0], 1e-10));
  // The case a relative residual lets through: relative residual ≤ tol, scale-free residual 5e-5.
  j = JudgeMCP(mcp, ExpectedOutcome::kSolvable, unique, false, SolveStatus::kSolved, Vector::Constant(1, 1.0001),
               1e-10);
  EXPECT_LE(j.residual.rel, 1e-10);
  EXPECT_EQ(j.verdict, Verdict::kWronglyClaimed);
  // Solved on a problem without a solution; a z of the wrong size.
  j = JudgeMCP(mcp, ExpectedOutcome::kInfeasible, {}, false, SolveStatus::kSolved, Vector::Constant(1, 1.0), 1e-10);
  EXPECT_EQ(j.verdict, Verdict::kWronglyClaimed);
  j = JudgeMCP(mcp, ExpectedOutcome::kSolvable, {}, false, SolveStatus::kSolved, Vector::Ones(2), 1e-10);
  EXPECT_EQ(j.verdict, Verdict::kWronglyClaimed);
}

// z ≥ 0, F(z) = z(z − 1)² + 1e-12 > 0 on z ≥ 0: the only solution is z* = 0 (at its bound, F(0) > 0: no free rows,
// μ = 0). At z = 1, F = 1e-12 and F' = 0 (the row scale falls back to 1): every residual passes, 1 away from z*.
TEST(JudgeMCP, ASmallResidualFarFromTheUniqueSolutionIsInaccurate) {
  const FunctionMCP mcp(
      Vector::Zero(1), Vector::Constant(1, kInf),
      [](const Vector& z, Vector* F) { (*F)[0] = z[0] * (z[0] - 1.0) * (z[0] - 1.0) + 1e-12; },
      [](const Vector& z, DenseMatrix* J) { (*J)(0, 0) = (z[0] - 1.0) * (3.0 * z[0] - 1.0); }, "fake-root");
  const std::vector<ReferenceSolution> unique = {Reference(Certificate::kUnique, 0.0, 0.0)};
  Judgement j = JudgeMCP(mcp, ExpectedOutcome::kSolvable, unique, false, SolveStatus::kSolved, Vector::Ones(1), 1e-10);
  EXPECT_LE(j.residual.scaled, 1e-10);
  EXPECT_EQ(j.forward_error, 1.0);
  EXPECT_EQ(j.verdict, Verdict::kInaccurate);
  EXPECT_TRUE(IsWrong(j.verdict));
  j = JudgeMCP(mcp, ExpectedOutcome::kSolvable, unique, false, SolveStatus::kSolved, Vector::Zero(1), 1e-10);
  EXPECT_EQ(j.verdict, Verdict::kSolved);
  // Without a reference nothing proves it wrong: the residuals decide.
  j = JudgeMCP(mcp, ExpectedOutcome::kSolvable, {}, false, SolveStatus::kSolved, Vector::Ones(1), 1e-10);
  EXPECT_EQ(j.verdict, Verdict::kSolved);
  EXPECT_TRUE(std::isnan(j.forward_error));
}

TEST(JudgeMCP, RefusalsAndFailures) {
  const FunctionMCP solvable = PriceMcp();
  // z ≥ 0, F(z) = −1 − z²: F < 0 everywhere, so no z ≥ 0 is a solution.
  const FunctionMCP no_solution(
      Vector::Zero(1), Vector::Constant(1, kInf), [](const Vector& z, Vector* F) { (*F)[0] = -1.0 - z[0] * z[0]; },
      [](const Vector& z, DenseMatrix* J) { (*J)(0, 0) = -2.0 * z[0]; }, "none");
  const Vector z = Vector::Constant(1, 3.0);
  EXPECT_EQ(JudgeMCP(solvable, ExpectedOutcome::kSolvable, {}, false, SolveStatus::kInfeasible, z, 1e-10).verdict,
            Verdict::kWronglyRefused);
  // A verified reference proves solvability even when the expected outcome is unknown.
  EXPECT_EQ(JudgeMCP(solvable, ExpectedOutcome::kUnknown, {Reference(Certificate::kIsolated, 1.0)}, false,
                     SolveStatus::kInfeasible, z, 1e-10)
                .verdict,
            Verdict::kWronglyRefused);
  EXPECT_EQ(JudgeMCP(solvable, ExpectedOutcome::kSolvable, {}, false, SolveStatus::kIterationLimit, z, 1e-10).verdict,
            Verdict::kFailed);
  EXPECT_EQ(JudgeMCP(no_solution, ExpectedOutcome::kInfeasible, {}, false, SolveStatus::kInfeasible, z, 1e-10).verdict,
            Verdict::kCorrectlyRefused);
  EXPECT_EQ(JudgeMCP(no_solution, ExpectedOutcome::kInfeasible, {}, false, SolveStatus::kStalled, z, 1e-10).verdict,
            Verdict::kCorrectlyRefused);
}

// z ∈ [0, 3], F(z) = (z − 1)(z − 2): solutions 0 (F(0) = 2 > 0 at the lower bound), 1 and 2 (F = 0 inside).
TEST(JudgeMCP, SeveralSolutionsAcceptAnyListedOneAndJudgeAgainstTheNearest) {
  const FunctionMCP mcp(
      Vector::Zero(1), Vector::Constant(1, 3.0),
      [](const Vector& z, Vector* F) { (*F)[0] = (z[0] - 1.0) * (z[0] - 2.0); },
      [](const Vector& z, DenseMatrix* J) { (*J)(0, 0) = 2.0 * z[0] - 3.0; }, "three-solutions");
  const std::vector<ReferenceSolution> all = {Reference(Certificate::kNonUnique, 0.0, 0.0),
                                              Reference(Certificate::kNonUnique, 1.0),
                                              Reference(Certificate::kNonUnique, 2.0)};
  for (double z : {0.0, 1.0, 2.0}) {
    const Judgement j =
        JudgeMCP(mcp, ExpectedOutcome::kSolvable, all, true, SolveStatus::kSolved, Vector::Constant(1, z), 1e-10);
    EXPECT_EQ(j.verdict, Verdict::kSolved) << z;
    EXPECT_EQ(j.forward_error, 0.0) << z;
  }
  // A list that claims to be complete but misses z = 2: the answer 2 is 1 from the nearest listed solution.
  const std::vector<ReferenceSolution> missing(all.begin(), all.begin() + 2);
  Judgement j =
      JudgeMCP(mcp, ExpectedOutcome::kSolvable, missing, true, SolveStatus::kSolved, Vector::Constant(1, 2.0), 1e-10);
  EXPECT_EQ(j.forward_error, 1.0);
  EXPECT_EQ(j.verdict, Verdict::kInaccurate);
  // Not complete and none unique: no forward error is defined.
  j = JudgeMCP(mcp, ExpectedOutcome::kSolvable, missing, false, SolveStatus::kSolved, Vector::Constant(1, 2.0), 1e-10);
  EXPECT_TRUE(std::isnan(j.forward_error));
  EXPECT_EQ(j.verdict, Verdict::kSolved);
}

// The forward error and its allowance are in the variables' units: the price problem written in cents (y = 100 p,
// c = 100) gets the same verdicts, forward errors and allowances as in units.
TEST(JudgeMCP, ForwardErrorIsMeasuredInTheStatedUnits) {
  FunctionMCP cents(
      Vector::Constant(1, 1e-6), Vector::Constant(1, kInf),
      [](const Vector& y, Vector* F) { (*F)[0] = 1.0 - 100.0 / y[0]; },
      [](const Vector& y, DenseMatrix* J) { (*J)(0, 0) = 100.0 / (y[0] * y[0]); }, "price-in-cents");
  cents.set_variable_scale(Vector::Constant(1, 100.0));
  const FunctionMCP units = PriceMcp();
  for (double p : {1.0, 1.0 + 1e-11, 1.0 + 1e-9, 1.001}) {
    const Judgement a = JudgeMCP(units, ExpectedOutcome::kSolvable, {Reference(Certificate::kUnique, 1.0)}, false,
                                 SolveStatus::kSolved, Vector::Constant(1, p), 1e-10);
    const Judgement b = JudgeMCP(cents, ExpectedOutcome::kSolvable, {Reference(Certificate::kUnique, 100.0)}, false,
                                 SolveStatus::kSolved, Vector::Constant(1, 100.0 * p), 1e-10);
    EXPECT_EQ(a.verdict, b.verdict) << p;
    EXPECT_NEAR(a.forward_error, b.forward_error, 1e-13) << p;
    EXPECT_DOUBLE_EQ(a.forward_allowance, b.forward_allowance) << p;
    EXPECT_NEAR(a.residual.scaled, b.residual.scaled, 1e-13 * (1.0 + a.residual.scaled)) << p;
  }
}

TEST(SolveStatusNames, RoundTripAndStayStable) {
  for (int v = 0; v <= 13; ++v) {
    const auto status = static_cast<SolveStatus>(v);
    const auto name = ToString(status);
    ASSERT_NE(name, "unknown") << v;
    EXPECT_EQ(SolveStatusFromString(name), status);
  }
  // Scripts depend on these exact strings.
  EXPECT_EQ(ToString(SolveStatus::kSolved), "solved");
  EXPECT_EQ(ToString(SolveStatus::kRayTermination), "ray_termination");
  EXPECT_EQ(static_cast<int>(SolveStatus::kSizeLimit), 7);
  EXPECT_FALSE(SolveStatusFromString("nope").has_value());
}

}  // namespace
}  // namespace smcbench

namespace smcbench {
namespace {

TEST(SolverBase, MeasureTimeOffLeavesSolveSecondsZero) {
  ScriptedSolver solver;
  solver.z_to_report = (Vector(2) << 1.0, 0.0).finished();
  SolverOptions options;
  options.measure_time = false;
  const SolveResult r = solver.Solve(SimpleLCP(), options);
  EXPECT_TRUE(r.solved());
  EXPECT_EQ(r.solve_seconds, 0.0);
}

// A backend that evaluates the merit function itself (Solver::FixedSizeMerit), then optionally changes z or w
// afterwards: the base judges what is returned, never the backend's own value.
class MeritCallingSolver final : public Solver {
 public:
  const SolverInfo& info() const override {
    static const SolverInfo kInfo{"merit-calling", "evaluates the merit function itself", "none"};
    return kInfo;
  }
  Vector answer;
  enum class Then { kNothing, kChangeZ, kScribbleOnW } then = Then::kNothing;
  Residual seen;

 protected:
  void DoSolve(const BoxMLCP& problem, const SolverOptions&, SolveResult* result) override {
    result->z = answer;
    seen = FixedSizeMerit<2>(problem, result);
    if (then == Then::kChangeZ) result->z[0] += 0.5;
    if (then == Then::kScribbleOnW) result->w.setConstant(123.0);
    result->status = SolveStatus::kSolved;
  }
};

TEST(SolverBase, FixedSizeMeritNeverStandsInForTheBasesMerit) {
  MeritCallingSolver solver;
  solver.answer = (Vector(2) << 1.0, 0.0).finished();  // SimpleLCP's solution
  SolveResult r = solver.Solve(SimpleLCP(), NoPolish());
  EXPECT_EQ(r.status, SolveStatus::kSolved);
  EXPECT_EQ(r.residual_abs, solver.seen.abs);
  EXPECT_EQ(r.residual_abs, 0.0);
  EXPECT_EQ(r.w, (Vector(2) << 0.0, 2.0).finished());

  solver.then = MeritCallingSolver::Then::kChangeZ;  // z = (1.5, 0): w = (0.5, 2), residual 0.5
  r = solver.Solve(SimpleLCP(), NoPolish());
  EXPECT_EQ(solver.seen.abs, 0.0);
  EXPECT_DOUBLE_EQ(r.residual_abs, 0.5);
  EXPECT_EQ(r.w, (Vector(2) << 0.5, 2.0).finished());
  EXPECT_EQ(r.status, SolveStatus::kInaccurate);

  solver.then = MeritCallingSolver::Then::kScribbleOnW;
  r = solver.Solve(SimpleLCP(), NoPolish());
  EXPECT_EQ(r.w, (Vector(2) << 0.0, 2.0).finished()) << "w recomputed, not the backend's scribble";
  EXPECT_EQ(r.status, SolveStatus::kSolved);
}

// A session whose every call runs the backend (no warm active-set path).
SessionOptions BackendOnly() {
  SessionOptions o;
  o.reuse_active_set = false;
  return o;
}

// Solver::Prepare / SolveSession (session.h): what is checked once, what is still checked per call, and the warm
// active-set path.
TEST(Session, RefusesWhatSolveWouldRefuseWithTheSameMessage) {
  ScriptedSolver solver;
  solver.z_to_report = (Vector(2) << 1.0, 0.0).finished();
  const BoxMLCP p = SimpleLCP();
  SolverOptions bad;
  bad.tolerance = -1.0;
  SolveResult by_solve, by_session;
  solver.Solve(p, bad, &by_solve);
  SolveSession session = solver.Prepare(p, bad);
  session.Solve(p.q(), &by_session);
  EXPECT_EQ(by_session.status, SolveStatus::kInvalidOptions);
  EXPECT_EQ(by_session.message, by_solve.message);
  solver.options.factor = -1.0;  // the backend's own options, changed directly: Solve sees it
  solver.Solve(p, SolverOptions{}, &by_solve);
  SolveSession other = solver.Prepare(p);
  other.Solve(p.q(), &by_session);
  EXPECT_EQ(by_session.status, SolveStatus::kInvalidOptions);
  EXPECT_EQ(by_session.message, by_solve.message);
  EXPECT_THAT(by_session.message, HasSubstr("factor"));
}

TEST(Session, NonFiniteWarmStartIsStillRefusedPerCall) {
  ScriptedSolver solver;
  solver.z_to_report = (Vector(2) << 1.0, 0.0).finished();
  const BoxMLCP p = SimpleLCP();
  SolveSession session = solver.Prepare(p, SolverOptions{}, BackendOnly());
  SolveResult r;
  Vector warm = Vector::Zero(2);
  session.Solve(p.q(), &r, &warm);
  EXPECT_EQ(r.status, SolveStatus::kSolved);
  EXPECT_EQ(r.solver, "scripted");
  EXPECT_EQ(r.GetDetail("answer"), 42.0);
  EXPECT_EQ(SessionPathOf(r), SessionPath::kBackend);
  warm[1] = std::nan("");
  session.Solve(p.q(), &r, &warm);
  EXPECT_EQ(r.status, SolveStatus::kInvalidOptions);
  EXPECT_THAT(r.message, HasSubstr("warm_start"));
  EXPECT_EQ(r.z, Vector::Zero(2));
  EXPECT_DOUBLE_EQ(r.residual_abs, 1.0) << "the merit function at the returned z, as Solve reports it";
}

TEST(Session, BackendOptionsChangedAfterPrepareAreCheckedOnTheNextCall) {
  ScriptedSolver solver;
  solver.z_to_report = (Vector(2) << 1.0, 0.0).finished();
  const BoxMLCP p = SimpleLCP();
  SolveSession session = solver.Prepare(p, SolverOptions{}, BackendOnly());
  SolveResult r;
  session.Solve(p.q(), &r);
  ASSERT_EQ(r.status, SolveStatus::kSolved);
  std::string error;
  ASSERT_TRUE(solver.SetOption("factor", "2", &error)) << error;
  solver.options.factor = -3.0;  // after SetOption: the generation changed, so the session checks again
  session.Solve(p.q(), &r);
  EXPECT_EQ(r.status, SolveStatus::kInvalidOptions);
  EXPECT_THAT(r.message, HasSubstr("factor"));
  solver.options.factor = 1.0;
  ASSERT_TRUE(solver.SetOption("factor", "1", &error)) << error;
  session.Solve(p.q(), &r);
  EXPECT_EQ(r.status, SolveStatus::kSolved);
}

TEST(Session, BadQIsAnErrorNamingQ) {
  ScriptedSolver solver;
  const BoxMLCP p = SimpleLCP();
  SolveSession session = solver.Prepare(p);
  SolveResult r;
  EXPECT_THROW(session.Solve(Vector::Zero(3), &r), InvalidInputError);
  Vector nan_q = p.q();
  nan_q[0] = std::nan("");
  try {
    session.Solve(nan_q, &r);
    FAIL() << "NaN in q accepted";
  } catch (const InvalidInputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("q"));
  }
}

// The warm path on a 2×2 box problem whose solution is known by hand. M = [[2, 1], [1, 2]], l = −1, u = 1.
// q = (−1, −1): both rows free, z = M⁻¹(1, 1) = (1/3, 1/3). q = (−1.3, −0.5): same active set, z = (0.7, −0.1).
// q = (−9, 0): row 0 hits u (z0 = 1), row 1 free: 2 z1 + 1 = 0, z1 = −1/2 — another active set.
TEST(Session, ReusesTheActiveSetWhileItHoldsAndSaysSo) {
  DenseMatrix M(2, 2);
  M << 2.0, 1.0, 1.0, 2.0;
  const Vector ones = Vector::Ones(2);
  const BoxMLCP p(M, (Vector(2) << -1.0, -1.0).finished(), -ones, ones, "box");
  ScriptedSolver solver;
  solver.z_to_report = (Vector(2) << 1.0 / 3.0, 1.0 / 3.0).finished();
  SolverOptions options;
  options.polish = false;
  SolveSession session = solver.Prepare(p, options);
  SolveResult r;
  session.Solve(p.q(), &r);
  ASSERT_EQ(r.status, SolveStatus::kSolved);
  EXPECT_EQ(SessionPathOf(r), SessionPath::kBackend);
  EXPECT_EQ(r.iterations, 7);

  solver.z_to_report = Vector::Zero(2);  // the backend would now be wrong: only the warm path can answer
  session.Solve((Vector(2) << -1.3, -0.5).finished(), &r);
  ASSERT_EQ(r.status, SolveStatus::kSolved);
  EXPECT_EQ(SessionPathOf(r), SessionPath::kReusedActiveSet);
  EXPECT_EQ(r.iterations, 0);
  EXPECT_NEAR(r.z[0], 0.7, 1e-15);
  EXPECT_NEAR(r.z[1], -0.1, 1e-15);
  EXPECT_EQ(r.solver, "scripted");
  EXPECT_LE(r.residual_scaled, 1e-15);
  EXPECT_EQ(session.reused(), 1);

  // The stored set gives z0 = (2·9 − 0)/3 = 6 > u: the warm path declines and the backend answers.
  solver.z_to_report = (Vector(2) << 1.0, -0.5).finished();
  session.Solve((Vector(2) << -9.0, 0.0).finished(), &r);
  ASSERT_EQ(r.status, SolveStatus::kSolved);
  EXPECT_EQ(SessionPathOf(r), SessionPath::kBackend);
  // ... and its active set is the one tried next: q = (−9, 0.2) → z = (1, −0.6).
  solver.z_to_report = Vector::Zero(2);
  session.Solve((Vector(2) << -9.0, 0.2).finished(), &r);
  ASSERT_EQ(r.status, SolveStatus::kSolved);
  EXPECT_EQ(SessionPathOf(r), SessionPath::kReusedActiveSet);
  EXPECT_EQ(r.z[0], 1.0);
  EXPECT_NEAR(r.z[1], -0.6, 1e-15);
  EXPECT_EQ(session.calls(), 4);
}

// ForgetWarmState drops the remembered active set: the next call goes to the backend, as the first did.
TEST(Session, ForgetWarmStateSendsTheNextCallToTheBackend) {
  DenseMatrix M(2, 2);
  M << 2.0, 1.0, 1.0, 2.0;
  const Vector ones = Vector::Ones(2);
  const BoxMLCP p(M, (Vector(2) << -1.0, -1.0).finished(), -ones, ones, "box");
  ScriptedSolver solver;
  solver.z_to_report = (Vector(2) << 1.0 / 3.0, 1.0 / 3.0).finished();
  SolverOptions options;
  options.polish = false;
  SolveSession session = solver.Prepare(p, options);
  EXPECT_EQ(session.ForgetWarmState(), WarmStateReset::kNothingRemembered);  // nothing solved yet
  SolveResult r;
  session.Solve(p.q(), &r);
  session.Solve(p.q(), &r);
  ASSERT_EQ(SessionPathOf(r), SessionPath::kReusedActiveSet);
  EXPECT_EQ(session.ForgetWarmState(), WarmStateReset::kForgotten);
  session.Solve(p.q(), &r);
  EXPECT_EQ(SessionPathOf(r), SessionPath::kBackend);
  EXPECT_EQ(r.iterations, 7);
  EXPECT_EQ(session.reused(), 1);
  // Without reuse a session remembers nothing, and a plain backend neither (Solver::ForgetWarmState's default).
  SessionOptions no_reuse;
  no_reuse.reuse_active_set = false;
  SolveSession plain = solver.Prepare(p, options, no_reuse);
  plain.Solve(p.q(), &r);
  EXPECT_EQ(plain.ForgetWarmState(), WarmStateReset::kNothingRemembered);
  EXPECT_EQ(solver.ForgetWarmState(), WarmStateReset::kNothingRemembered);
  EXPECT_EQ(ToString(WarmStateReset::kCannotForget), "cannot_forget");
}

TEST(Session, ReuseOffAlwaysCallsTheBackend) {
  ScriptedSolver solver;
  solver.z_to_report = (Vector(2) << 1.0, 0.0).finished();
  const BoxMLCP p = SimpleLCP();
  SolveSession session = solver.Prepare(p, SolverOptions{}, BackendOnly());
  SolveResult r;
  for (int k = 0; k < 3; ++k) {
    session.Solve(p.q(), &r);
    EXPECT_EQ(SessionPathOf(r), SessionPath::kBackend);
    EXPECT_EQ(r.iterations, 7);
  }
  EXPECT_EQ(session.reused(), 0);
}

// A backend that takes sparse M natively (as newton does), answering z = (1, 0).
class SparseScriptedSolver final : public Solver {
 public:
  const SolverInfo& info() const override {
    static const SolverInfo kInfo{"sparse-scripted", "returns (1, 0)", "none", /*dense=*/true, /*sparse=*/true};
    return kInfo;
  }

 protected:
  void DoSolve(const BoxMLCP& problem, const SolverOptions&, SolveResult* result) override {
    EXPECT_TRUE(problem.is_sparse());
    result->z = (Vector(2) << 1.0, 0.0).finished();
    result->status = SolveStatus::kSolved;
    result->iterations = 1;
  }
};

// A small sparse problem never takes the fixed-size dense path (which reads M's dense storage: a sparse problem
// has none — `smcbench bench` crashed on the paper suite's sparse copies solved by newton), and never the reused
// active set (dense only): every call goes to the backend, and answers as Solve does.
TEST(Session, SmallSparseProblemGoesToTheBackendThroughTheGeneralPath) {
  SparseScriptedSolver solver;
  Vector q(2);
  q << -1.0, 2.0;
  const SparseMatrix M = DenseMatrix::Identity(2, 2).sparseView();
  const BoxMLCP p(M, q, Vector::Zero(2), Vector::Constant(2, kInf));
  for (bool reuse : {true, false}) {
    SessionOptions session_options;
    session_options.reuse_active_set = reuse;
    SolveSession session = solver.Prepare(p, SolverOptions{}, session_options);
    SolveResult r;
    for (int k = 0; k < 3; ++k) {
      session.Solve(q, &r);
      EXPECT_EQ(r.status, SolveStatus::kSolved) << r.message;
      EXPECT_EQ(r.z, (Vector(2) << 1.0, 0.0).finished());
      EXPECT_EQ(SessionPathOf(r), SessionPath::kBackend);
    }
    EXPECT_EQ(session.reused(), 0);
  }
}

// A block too close to singular is not stored: the backend answers (its own safeguards handle it).
TEST(Session, NearlySingularFreeBlockIsNotReused) {
  DenseMatrix M(2, 2);
  M << 1.0, 1.0, 1.0, 1.0 + 1e-15;
  const Vector ones = Vector::Ones(2);
  ActiveSetFactors factors;
  factors.Resize(2);
  const signed char both_free[2] = {0, 0};
  EXPECT_FALSE(factors.Factor(M, both_free));
  EXPECT_FALSE(factors.valid());
  M(1, 1) = 3.0;
  EXPECT_TRUE(factors.Factor(M, both_free));
}

// --- The scale-free verdict and the exact polish (docs/verdict.md). -------------------------------------------

// A backend that records the problem it is given.
class RecordingSolver final : public Solver {
 public:
  const SolverInfo& info() const override {
    static const SolverInfo kInfo{"recording", "records the problem it is given", "none"};
    return kInfo;
  }
  DenseMatrix seen_M;
  Vector seen_q;
  Vector answer;

 protected:
  void DoSolve(const BoxMLCP& problem, const SolverOptions&, SolveResult* result) override {
    seen_M = problem.dense_matrix();
    seen_q = problem.q();
    result->z = answer;
    result->status = SolveStatus::kSolved;
  }
};

// W = h G, G nonsymmetric with a positive definite symmetric part; s* = (1, 0.25) has row 0 at its upper bound
// (w_0 = −h·0.5 < 0) and row 1 interior (w_1 = 0): q = w − W s*.
BoxMLCP SmallHRelay(double h, Vector* solution) {
  DenseMatrix G(2, 2);
  G << 2.0, 1.0, -1.0, 2.0;
  *solution = (Vector(2) << 1.0, 0.25).finished();
  const Vector w = (Vector(2) << -0.5 * h, 0.0).finished();
  const DenseMatrix W = h * G;
  return BoxMLCP::Relay(W, w - W * *solution);
}

TEST(ScaledResidual, RowScalesAreRowMaximaAndAZeroRowTakesTheMatrixScale) {
  DenseMatrix M(3, 3);
  M << 1e6, -3e6, 0.0, 0.0, 0.0, 0.0, 2e-5, 0.0, -1e-5;
  const BoxMLCP p = BoxMLCP::LCP(M, Vector::Ones(3));
  EXPECT_EQ(p.row_scale(), (Vector(3) << 3e6, 3e6, 2e-5).finished());
  const BoxMLCP zero = BoxMLCP::LCP(DenseMatrix::Zero(2, 2), Vector::Ones(2));
  EXPECT_EQ(zero.row_scale(), Vector::Ones(2));
  // The equilibrated problem has every row's largest entry exactly 1.
  EXPECT_EQ(p.Equilibrated().row_scale(), Vector::Ones(3));
}

TEST(ScaledResidual, SeesAnErrorInZThatTheRelativeResidualCannotAtSmallH) {
  Vector s_star;
  const BoxMLCP p = SmallHRelay(1e-8, &s_star);
  ScriptedSolver solver;
  solver.z_to_report = s_star;
  solver.z_to_report[1] += 1e-4;  // wrong in the interior row by 1e-4: W moves w by only 2e-12
  const SolveResult r = solver.Solve(p, NoPolish());
  EXPECT_LE(r.residual_rel, 1e-10) << "the unscaled residual is blind to it";
  EXPECT_NEAR(r.residual_scaled, 1e-4 / 2.0, 1e-12) << "|w_1/d_1| = 2e-4 h / 2h in units of z, over 1 + |z|inf = 2";
  EXPECT_EQ(r.status, SolveStatus::kInaccurate);
  EXPECT_THAT(r.message, HasSubstr("row-equilibrated"));
}

TEST(ScaledResidual, IsInvariantUnderRowScalingAndUnderScalingMAndQTogether) {
  Vector s_star;
  const BoxMLCP p = SmallHRelay(1e-3, &s_star);
  Vector z = s_star;
  z[1] += 1e-6;
  Vector w;
  const double reference = p.NaturalResidual(z, &w).scaled;
  for (const auto& rows : {std::pair{1e6, 1e-5}, std::pair{1e-150, 1e-150}, std::pair{1e150, 1e150}}) {
    const Vector r = (Vector(2) << rows.first, rows.second).finished();
    const BoxMLCP scaled(r.asDiagonal() * p.dense_matrix(), r.asDiagonal() * p.q(), p.l(), p.u());
    EXPECT_NEAR(scaled.NaturalResidual(z, &w).scaled, reference, 1e-15 * (1.0 + reference)) << rows.first;
  }
}

TEST(Equilibration, BackendsAreGivenTheRowEquilibratedProblem) {
  RecordingSolver solver;
  DenseMatrix M(2, 2);
  M << 4.0, -8.0, 1e-6, 5e-7;
  const BoxMLCP p = BoxMLCP::LCP(M, (Vector(2) << 2.0, -3e-6).finished());
  solver.answer = Vector::Zero(2);
  solver.Solve(p, NoPolish());
  DenseMatrix expected(2, 2);
  expected << 0.5, -1.0, 1.0, 0.5;
  EXPECT_EQ(solver.seen_M, expected);
  EXPECT_EQ(solver.seen_q, (Vector(2) << 0.25, -3.0).finished());
  // A second solve with a new q: the equilibrated copy is kept (one per M) and its q refreshed.
  BoxMLCP again = p;
  again.set_q((Vector(2) << -4.0, 1e-6).finished());
  solver.Solve(again, NoPolish());
  EXPECT_EQ(solver.seen_q, (Vector(2) << -0.5, 1.0).finished());
}

TEST(Polish, ReplacesANearbyAnswerWithTheExactOne) {
  Vector s_star;
  const BoxMLCP p = SmallHRelay(1e-8, &s_star);
  ScriptedSolver solver;
  solver.z_to_report = s_star;
  solver.z_to_report[1] += 1e-4;
  const SolveResult r = solver.Solve(p);
  EXPECT_EQ(r.status, SolveStatus::kSolved);
  EXPECT_EQ(r.GetDetail("polished"), 1.0);
  EXPECT_NEAR(r.z[1], 0.25, 1e-15);
  EXPECT_EQ(r.z[0], 1.0);
  EXPECT_LE(r.residual_scaled, 1e-15);
}

// A backend that says its answer is the exact solve of the set the polish would read (NotePolishRedundant) is not
// polished when that answer passes; one that does not pass is polished as before, and the note lasts one solve.
TEST(Polish, ANotedRedundantPolishIsSkippedOnlyForAPassingAnswer) {
  Vector s_star;
  const BoxMLCP p = SmallHRelay(1e-8, &s_star);
  ScriptedSolver solver;
  solver.note_polish_redundant = true;
  solver.z_to_report = s_star;
  solver.z_to_report[1] += 1e-13;  // passes (scaled residual ~1e-13), not exact
  SolveResult r = solver.Solve(p);
  EXPECT_EQ(r.status, SolveStatus::kSolved);
  EXPECT_TRUE(std::isnan(r.GetDetail("polished")));
  EXPECT_EQ(r.z, solver.z_to_report) << "the backend's own answer is returned";
  EXPECT_GT(r.residual_scaled, 0.0);
  solver.z_to_report[1] = s_star[1] + 1e-4;  // fails: the polish runs whatever the backend said
  r = solver.Solve(p);
  EXPECT_EQ(r.status, SolveStatus::kSolved);
  EXPECT_EQ(r.GetDetail("polished"), 1.0);
  EXPECT_NEAR(r.z[1], 0.25, 1e-15);
  solver.note_polish_redundant = false;  // the note of an earlier solve does not carry over
  solver.z_to_report[1] = s_star[1] + 1e-13;
  r = solver.Solve(p);
  EXPECT_EQ(r.GetDetail("polished"), 1.0);
}

TEST(Polish, AVerifiedAnswerOutranksTheBackendsFailureStatus) {
  ScriptedSolver solver;
  solver.status_to_report = SolveStatus::kIterationLimit;
  solver.z_to_report = (Vector(2) << 0.9, 0.0).finished();  // SimpleLCP: row 0 free, row 1 at its bound
  const SolveResult r = solver.Solve(SimpleLCP());
  EXPECT_EQ(r.status, SolveStatus::kSolved);
  EXPECT_TRUE(r.message.empty());
  EXPECT_EQ(r.z, (Vector(2) << 1.0, 0.0).finished());
}

TEST(Polish, NeverLeavesTheBoxNorMakesAnUnsolvableProblemLookSolved) {
  // z ≥ 0, w = −z − 1 < 0: no solution. The reduced system's answer z = −1 lies outside the box.
  const BoxMLCP p = BoxMLCP::LCP(DenseMatrix::Constant(1, 1, -1.0), Vector::Constant(1, -1.0));
  ScriptedSolver solver;
  solver.z_to_report = Vector::Zero(1);
  const SolveResult r = solver.Solve(p);
  EXPECT_EQ(r.status, SolveStatus::kInaccurate);
  EXPECT_EQ(r.z[0], 0.0) << "the free row's value −1 leaves the box; at its bound it is the backend's own point";
}

TEST(Polish, NeverSolvesOnBehalfOfABackendThatFailedOrRefused) {
  for (SolveStatus status : {SolveStatus::kNumericalFailure, SolveStatus::kRayTermination, SolveStatus::kInfeasible}) {
    ScriptedSolver solver;
    solver.status_to_report = status;
    solver.z_to_report = (Vector(2) << 0.9, 0.0).finished();  // close to SimpleLCP's solution
    const SolveResult r = solver.Solve(SimpleLCP());
    EXPECT_EQ(r.status, status) << ToString(status);
    EXPECT_EQ(r.z, solver.z_to_report) << ToString(status);
  }
}

TEST(Polish, AnExactIterateAtAnIterationLimitIsSolved) {
  ScriptedSolver solver;
  solver.status_to_report = SolveStatus::kIterationLimit;
  solver.z_to_report = (Vector(2) << 1.0, 0.0).finished();  // residual exactly 0: nothing to polish
  EXPECT_EQ(solver.Solve(SimpleLCP()).status, SolveStatus::kSolved);
}

TEST(Polish, ADegenerateRowCalledFreeIsMovedToItsBound) {
  // LCP M = I, q = (−1, 1e-17): z* = (1, 0), row 1 at its bound with w = 1e-17 (nearly degenerate). The answer
  // (1 + 1e-9, 2e-17) makes the natural map call row 1 free; its exact value −1e-17 leaves the box, so the polish
  // moves it to the bound and solves again.
  const BoxMLCP p = BoxMLCP::LCP(DenseMatrix::Identity(2, 2), (Vector(2) << -1.0, 1e-17).finished());
  ScriptedSolver solver;
  solver.z_to_report = (Vector(2) << 1.0 + 1e-9, 2e-17).finished();
  const SolveResult r = solver.Solve(p);
  EXPECT_EQ(r.status, SolveStatus::kSolved);
  EXPECT_EQ(r.z, (Vector(2) << 1.0, 0.0).finished());
  EXPECT_EQ(r.GetDetail("polished"), 1.0);
}

TEST(Polish, OffLeavesTheBackendsAnswerAlone) {
  ScriptedSolver solver;
  solver.z_to_report = (Vector(2) << 0.9, 0.0).finished();
  const SolveResult r = solver.Solve(SimpleLCP(), NoPolish());
  EXPECT_EQ(r.z, solver.z_to_report);
  EXPECT_TRUE(std::isnan(r.GetDetail("polished")));
}

}  // namespace
}  // namespace smcbench

namespace smcbench {
namespace {
using ::testing::HasSubstr;
enum class Colour { kRed, kGreen };

TEST(OptionBinder, NamedValuesAcceptOnlyTheirNamesAndPrintTheFirstName) {
  Colour colour = Colour::kRed;
  OptionBinder binder;
  binder.Add("colour", &colour,
             {{"red", static_cast<int>(Colour::kRed)}, {"green", static_cast<int>(Colour::kGreen)},
              {"g", static_cast<int>(Colour::kGreen)}},
             "a colour");
  std::string error;
  ASSERT_TRUE(binder.Set("colour", "g", &error)) << error;
  EXPECT_EQ(colour, Colour::kGreen);
  EXPECT_EQ(binder.ValueText("colour"), "green") << "the first name listed for the value";
  EXPECT_FALSE(binder.Set("colour", "1", &error));
  EXPECT_EQ(error, "option 'colour' expects one of red, green, g, got '1'");
  EXPECT_EQ(colour, Colour::kGreen);
  EXPECT_THAT(binder.Help(), HasSubstr("colour = green (one of red green g)"));
}
}  // namespace
}  // namespace smcbench

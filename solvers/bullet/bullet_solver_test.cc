// bullet-dantzig, bullet-pgs, bullet-lemke (bullet_solver.cc) judged by our verdict on problems with known solutions,
// and the peer's flag kept as a detail, never trusted: Dantzig's failure on a nonsymmetric P-matrix relay and PGS's
// unconditional "success" far from the solution.
#include <gtest/gtest.h>

#include "solvers/peer/peer_backends_test_util.h"

namespace smcbench {
namespace {

using peer_checks::Detail;
using peer_checks::Generate;

TEST(BulletBackends, SolveSmallSpdLcpsRelaysAndBoxes) {
  SolverOptions options;
  options.tolerance = 1e-8;
  options.polish = false;  // the peer's own answer is judged, not our polish of it
  for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay, BoundKind::kBox}) {
    for (std::uint64_t seed : {1u, 2u, 3u}) {
      const GeneratedProblem gen = Generate(MatrixFamily::kSymmetricPositiveDefinite, bounds, 8, seed);
      peer_checks::ExpectSolves("bullet-dantzig", gen, options);
      peer_checks::ExpectSolves("bullet-lemke", gen, options);
      SolverOptions many_sweeps = options;
      many_sweeps.max_iterations = 20000;  // PGS's rate on these (cond ≈ 100) needs thousands of sweeps
      peer_checks::ExpectSolves("bullet-pgs", gen, many_sweeps);
    }
  }
}

TEST(BulletBackends, DantzigKeepsFreeRowsAndLemkeRefusesInfiniteBounds) {
  SolverOptions options;
  options.tolerance = 1e-8;
  options.polish = false;  // the peer's own answer is judged, not our polish of it
  const GeneratedProblem gen = Generate(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kMixed, 10, 4);
  peer_checks::ExpectSolves("bullet-dantzig", gen, options);
  const SolveResult lemke = CreateSolver("bullet-lemke")->Solve(gen.problem, options);
  EXPECT_EQ(lemke.status, SolveStatus::kNotApplicable) << lemke.message;
  EXPECT_NE(lemke.message.find("finite"), std::string::npos) << lemke.message;
}

TEST(BulletBackends, TheProbeAndTheInProcessCallGiveTheSameAnswer) {
  const GeneratedProblem gen = Generate(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kRelay, 12, 5);
  for (const char* name : {"bullet-dantzig", "bullet-pgs", "bullet-lemke"}) {
    peer_checks::ExpectSameAnswerInWorkerAndInProcess(name, gen.problem, SolverOptions{});
  }
}

// Isolation: a solve that outlasts its time limit runs in the worker (the probe), which is killed: a status, and
// the next solve gets a fresh worker.
TEST(BulletBackends, ASolveOverItsTimeLimitIsKilledAndReportedAsTimeLimit) {
  const GeneratedProblem gen = Generate(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kRelay, 300, 1);
  SolverOptions endless;
  endless.max_iterations = 1000000000;  // 10^9 sweeps of 300^2: hours
  endless.time_limit_seconds = 0.3;
  const auto solver = CreateSolver("bullet-pgs");
  const SolveResult r = solver->Solve(gen.problem, endless);
  EXPECT_EQ(r.status, SolveStatus::kTimeLimit) << r.message;
  EXPECT_NE(r.message.find("killed"), std::string::npos) << r.message;
  const SolveResult next = solver->Solve(gen.problem, SolverOptions{});
  EXPECT_EQ(Detail(next, "peer_success"), 1.0);  // answered by a fresh worker (Bullet's PGS always says true)
  EXPECT_EQ(next.backend_code, std::optional<int>(0));  // its flag as a code, 0 = success
  EXPECT_EQ(r.backend_code, std::nullopt);  // killed: Bullet never answered
}

// Dantzig assumes symmetry (LDL^T updates); on nonsymmetric P-matrix relays Bullet's
// returns false (on each of these ten) and leaves x at the start. Whatever its flag says, our verdict decides.
TEST(BulletBackends, DantzigOnANonsymmetricPMatrixRelayIsNotSolvedWhateverItsFlagSays) {
  SolverOptions raw;
  raw.polish = false;  // the peer's own answer, not our polish of it
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const GeneratedProblem gen = Generate(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kRelay, 20, seed);
    SCOPED_TRACE(gen.problem.name());
    const SolveResult r = CreateSolver("bullet-dantzig")->Solve(gen.problem, raw);
    EXPECT_FALSE(r.solved());
    EXPECT_EQ(Detail(r, "peer_success"), 0.0);
    EXPECT_EQ(r.backend_code, std::optional<int>(1));  // false as a code
    EXPECT_EQ(r.status, SolveStatus::kNumericalFailure) << r.message;
    EXPECT_GT(r.residual_rel, 0.1);
    // The same problem is solved by Bullet's Lemke (which does not assume symmetry).
    EXPECT_TRUE(CreateSolver("bullet-lemke")->Solve(gen.problem, raw).solved());
  }
}

// A success flag that says nothing: btSolveProjectedGaussSeidel always returns true. After its default 10 sweeps on a
// nonsymmetric P-matrix relay the natural residual is large; the detail keeps its claim, our verdict says failed.
TEST(BulletBackends, PgsClaimsSuccessFarFromTheSolutionAndOurVerdictSaysInaccurate) {
  SolverOptions raw;
  raw.polish = false;
  const GeneratedProblem gen = Generate(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kRelay, 20, 1);
  const SolveResult r = CreateSolver("bullet-pgs")->Solve(gen.problem, raw);
  EXPECT_EQ(Detail(r, "peer_success"), 1.0);
  EXPECT_EQ(r.status, SolveStatus::kInaccurate) << r.message;
  EXPECT_GT(r.residual_rel, 1e-3);
  EXPECT_EQ(r.iterations, 10);  // Bullet's default budget (btContactSolverInfo::m_numIterations)
}

}  // namespace
}  // namespace smcbench

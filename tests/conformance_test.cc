// One conformance suite run over every registered backend: seeded problems with a known solution (SPD,
// nonsymmetric P-matrix, diagonally dominant; LCP, relay, box and mixed bounds with infinite entries;
// degenerate rows). The test recomputes the merit function itself and never trusts a backend's status alone.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <string>

#include "problems/generators/random_problems.h"
#include "solvers/registry/registry.h"
#include "solvers/siconos/external_backends.h"

namespace smcbench {
namespace {

constexpr double kTol = 1e-10;

// The independent check: natural residual recomputed here from M, q, l, u.
double IndependentResidual(const BoxMLCP& p, const Vector& z) {
  const DenseMatrix M = p.ToDense();
  const Vector w = M * z + p.q();
  double r = 0;
  for (int i = 0; i < p.size(); ++i) {
    const double proj = std::min(std::max(z[i] - w[i], p.l()[i]), p.u()[i]);
    r = std::max(r, std::abs(z[i] - proj));
  }
  return r / (1.0 + p.q().cwiseAbs().maxCoeff());
}

struct Family {
  MatrixFamily matrix;
  BoundKind bounds;
  double degenerate;
};

// Which backends must solve which matrix class. Everything else may fail — with an honest status.
bool MustSolve(const std::string& solver, const Family& f, int n) {
  if (solver == "enum") return n <= 10;  // its default size limit is above this; keeps the suite fast
  if (solver == "psor") return f.matrix != MatrixFamily::kNonsymmetricPMatrix;  // PSOR needs SPD or H-matrix
  return true;  // lemke, newton, ipopt: every family here (PD / P-matrices)
}

class Conformance : public ::testing::TestWithParam<std::string> {};

TEST_P(Conformance, SolvesGeneratedProblemsWithKnownSolution) {
  const std::string name = GetParam();
  auto solver = CreateSolver(name);
  auto reference = CreateSolver("enum");
  const Family families[] = {
      {MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kLCP, 0.0},
      {MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kRelay, 0.0},
      {MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kMixed, 0.0},
      {MatrixFamily::kNonsymmetricPMatrix, BoundKind::kLCP, 0.0},
      {MatrixFamily::kNonsymmetricPMatrix, BoundKind::kBox, 0.0},
      {MatrixFamily::kNonsymmetricPMatrix, BoundKind::kMixed, 0.0},
      {MatrixFamily::kDiagonallyDominant, BoundKind::kRelay, 0.0},
      {MatrixFamily::kDiagonallyDominant, BoundKind::kMixed, 0.0},
      // Degenerate: z* at a bound with w* = 0 on a third of the rows.
      {MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kLCP, 0.34},
      {MatrixFamily::kNonsymmetricPMatrix, BoundKind::kRelay, 0.34},
      {MatrixFamily::kDiagonallyDominant, BoundKind::kBox, 0.5},
  };
  int checked = 0;
  for (const Family& f : families) {
    for (int n : {1, 2, 3, 5, 8, 10, 30}) {
      for (std::uint64_t seed : {1u, 2u}) {
        GeneratorOptions g;
        g.family = f.matrix;
        g.bounds = f.bounds;
        g.degenerate_fraction = f.degenerate;
        g.size = n;
        g.seed = seed;
        const GeneratedProblem gen = GenerateProblem(g);
        const BoxMLCP& p = gen.problem;
        SolverOptions options;
        options.tolerance = kTol;
        options.time_limit_seconds = 20;
        const SolveResult r = solver->Solve(p, options);
        const std::string where = name + " on " + p.name();
        // The invariant for every backend and every problem: "solved" is true.
        if (r.solved()) {
          EXPECT_LE(IndependentResidual(p, r.z), kTol) << where;
          ++checked;
        }
        if (MustSolve(name, f, n)) {
          EXPECT_TRUE(r.solved()) << where << ": " << ToString(r.status) << " " << r.message << " (residual "
                                  << r.residual_rel << ")";
        }
        // P-matrices (and PD matrices) have a unique solution: it must be z*, and the enumerative one.
        if (r.solved()) {
          const double scale = 1.0 + gen.z_star.cwiseAbs().maxCoeff();
          EXPECT_LE((r.z - gen.z_star).cwiseAbs().maxCoeff(), 1e-6 * scale) << where;
          if (n <= 10 && name != "enum") {
            const SolveResult e = reference->Solve(p, options);
            ASSERT_TRUE(e.solved()) << "enum on " << p.name();
            EXPECT_LE((r.z - e.z).cwiseAbs().maxCoeff(), 1e-6 * scale) << where << " vs enum";
          }
        }
      }
    }
  }
  EXPECT_GT(checked, 0) << name << " solved nothing";
}

// A session without the warm active-set path (the time-stepper's path, the backend's own algorithm) is Solve
// without the per-call re-checks: over a sequence of one-step problems (q replaced, warm start = the previous
// answer) two instances of the backend, one driven by each, must return the same bits: status, z, w, residuals,
// iterations, details (the session adds only "path").
TEST_P(Conformance, SessionGivesTheBitsOfSolve) {
  const std::string name = GetParam();
  auto plain = CreateSolver(name);
  auto prepared = CreateSolver(name);
  int compared = 0;
  for (BoundKind bounds : {BoundKind::kRelay, BoundKind::kLCP, BoundKind::kBox}) {
    for (int n : {1, 2, 3, 4, 6}) {
      GeneratorOptions g;
      g.family = MatrixFamily::kSymmetricPositiveDefinite;
      g.bounds = bounds;
      g.size = n;
      g.seed = 7;
      BoxMLCP p = GenerateProblem(g).problem;
      const Vector q0 = p.q();
      SolverOptions options;
      options.tolerance = kTol;
      SessionOptions no_reuse;
      no_reuse.reuse_active_set = false;
      SolveSession session = prepared->Prepare(p, options, no_reuse);
      // A meta-backend's session calls its choice directly: compare with that backend's own Solve.
      if (prepared->DelegateFor(p, options) != nullptr) plain = CreateSolver(session.backend().info().name);
      SolveResult a, b;
      Vector warm_a, warm_b;
      for (int k = 0; k < 12; ++k) {
        // A slowly turning right side, as along a trajectory.
        Vector q = q0;
        for (int i = 0; i < n; ++i) q[i] *= std::cos(0.4 * k + i);
        p.set_q(q);
        options.warm_start = warm_a;
        plain->Solve(p, options, &a);
        session.Solve(q, &b, &warm_b);
        const std::string where = name + " on " + p.name() + ", step " + std::to_string(k);
        ASSERT_EQ(a.status, b.status) << where;
        EXPECT_EQ(a.message, b.message) << where;
        EXPECT_EQ(a.solver, b.solver) << where;
        EXPECT_EQ(a.z, b.z) << where;
        EXPECT_EQ(a.w, b.w) << where;
        EXPECT_EQ(a.residual_abs, b.residual_abs) << where;
        EXPECT_EQ(a.residual_rel, b.residual_rel) << where;
        EXPECT_EQ(a.residual_scaled, b.residual_scaled) << where;
        EXPECT_EQ(a.iterations, b.iterations) << where;
        EXPECT_EQ(b.GetDetail("path"), static_cast<double>(SessionPath::kBackend)) << where;
        ASSERT_EQ(a.num_details + 1, b.num_details) << where;
        for (int d = 0; d < a.num_details; ++d) {
          EXPECT_STREQ(a.details[d].name, b.details[d].name) << where;
          EXPECT_EQ(a.details[d].value, b.details[d].value) << where << " " << a.details[d].name;
        }
        if (a.solved()) {
          warm_a = a.z;
          warm_b = b.z;
        }
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 3 * 5 * 12);
}

// With the warm active-set path on (the default), every answer still satisfies the verdict and agrees with the
// backend's own answer to rounding, and along a slowly moving q most calls are answered by the reused set.
TEST_P(Conformance, SessionReusedActiveSetAgreesWithTheBackend) {
  const std::string name = GetParam();
  auto plain = CreateSolver(name);
  auto prepared = CreateSolver(name);
  int reused = 0, calls = 0;
  for (BoundKind bounds : {BoundKind::kRelay, BoundKind::kLCP, BoundKind::kBox}) {
    for (int n : {1, 2, 4, 8}) {
      GeneratorOptions g;
      g.family = MatrixFamily::kSymmetricPositiveDefinite;
      g.bounds = bounds;
      g.size = n;
      g.seed = 11;
      BoxMLCP p = GenerateProblem(g).problem;
      const Vector q0 = p.q();
      SolverOptions options;
      options.tolerance = kTol;
      SolveSession session = prepared->Prepare(p, options);
      SolveResult a, b;
      for (int k = 0; k < 40; ++k) {
        Vector q = q0;
        for (int i = 0; i < n; ++i) q[i] *= 1.0 + 0.3 * std::sin(0.05 * k + i);
        p.set_q(q);
        plain->Solve(p, options, &a);
        session.Solve(q, &b);
        const std::string where = name + " on " + p.name() + ", step " + std::to_string(k);
        ++calls;
        if (!a.solved()) continue;
        ASSERT_TRUE(b.solved()) << where << ": " << b.message;
        EXPECT_LE(b.residual_rel, kTol) << where;
        EXPECT_LE(b.residual_scaled, kTol) << where;
        EXPECT_LE((a.z - b.z).lpNorm<Eigen::Infinity>(), 1e-9 * (1.0 + a.z.lpNorm<Eigen::Infinity>())) << where;
        if (b.GetDetail("path") == static_cast<double>(SessionPath::kReusedActiveSet)) {
          EXPECT_EQ(b.iterations, 0) << where;
          ++reused;
        }
      }
    }
  }
  EXPECT_GT(reused, calls / 2) << name << ": the reused active set answered " << reused << " of " << calls;
}

// smcbench's own backends: external adapters (siconos-*) take only the shapes their library expresses and are
// tested in solvers/siconos/.
std::vector<std::string> AllSolvers() {
  std::vector<std::string> names;
  for (auto n : SolverNames()) {
    if (!IsExternalBackend(n)) names.emplace_back(n);
  }
  return names;
}

INSTANTIATE_TEST_SUITE_P(EveryBackend, Conformance, ::testing::ValuesIn(AllSolvers()),
                         [](const auto& info) { return info.param; });

TEST(Registry, CreatesEveryListedBackendAndRejectsUnknownNames) {
  std::set<std::string> seen;
  for (auto name : SolverNames()) {
    auto solver = CreateSolver(name);
    ASSERT_NE(solver, nullptr);
    EXPECT_EQ(solver->info().name, name);
    EXPECT_FALSE(solver->info().reference.empty()) << name;
    EXPECT_FALSE(solver->info().algorithm.empty()) << name;
    seen.emplace(name);
  }
  std::set<std::string> own;
  for (const auto& name : seen) {
    if (!IsExternalBackend(name)) own.insert(name);
  }
  // The five benchmarked backends, the `auto` meta-backend, and the certifier "reference" once it is registered.
  own.erase("reference");
  EXPECT_EQ(own, (std::set<std::string>{"lemke", "psor", "newton", "enum", "ipopt", "auto"}));
  try {
    CreateSolver("simplex");
    FAIL() << "no error";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("known: lemke"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace smcbench

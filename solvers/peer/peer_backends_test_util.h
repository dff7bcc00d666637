// Why: bullet-* and dart-* are the same kind of adapter (peer_solver.h), so their tests share these checks, each
// judged by our verdict with a known solution (generated problems: z* first, q derived; unique for a P-matrix).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "solvers/generators/random_problems.h"
#include "solvers/core/solver.h"
#include "solvers/registry/registry.h"
#include "solvers/isolation/child_process.h"

namespace smcbench::peer_checks {

inline GeneratedProblem Generate(MatrixFamily family, BoundKind bounds, int size, std::uint64_t seed) {
  GeneratorOptions g;
  g.size = size;
  g.family = family;
  g.bounds = bounds;
  g.seed = seed;
  return GenerateProblem(g);
}

// A detail's value, −1 if absent (GetDetail's NaN would compare unequal to everything).
inline double Detail(const SolveResult& r, const char* name) {
  const double v = r.GetDetail(name);
  return std::isnan(v) ? -1.0 : v;
}

// The backend solves the problem by our verdict, finds the unique solution and its own flag says success.
inline void ExpectSolves(const std::string& backend, const GeneratedProblem& gen, const SolverOptions& options) {
  SCOPED_TRACE(backend + " on " + gen.problem.name());
  const SolveResult r = CreateSolver(backend)->Solve(gen.problem, options);
  ASSERT_TRUE(r.solved()) << ToString(r.status) << ": " << r.message;
  EXPECT_LE(r.residual_rel, options.tolerance);
  EXPECT_LE((r.z - gen.z_star).cwiseAbs().maxCoeff(), 1e-6 * (1.0 + gen.z_star.cwiseAbs().maxCoeff()));
  EXPECT_EQ(Detail(r, "peer_success"), 1.0);
  EXPECT_EQ(r.backend_code, std::optional<int>(0));
  EXPECT_EQ(Detail(r, "standard_size") > 0, true);
}

// The first solve of a problem runs in the worker (the probe), the second in process, with the same answer bit for
// bit; isolate=always and isolate=never agree with them too.
inline void ExpectSameAnswerInWorkerAndInProcess(const std::string& backend, const BoxMLCP& problem,
                                                  const SolverOptions& options) {
  SCOPED_TRACE(backend);
  const auto solver = CreateSolver(backend);
  const SolveResult probe = solver->Solve(problem, options);
  const SolveResult again = solver->Solve(problem, options);
  EXPECT_EQ(AnswerProcessOf(probe), AnswerProcess::kWorker);
  EXPECT_EQ(AnswerProcessOf(again), AnswerProcess::kThisProcess);
  EXPECT_EQ(probe.status, again.status);
  EXPECT_EQ(probe.z, again.z);
  EXPECT_EQ(Detail(probe, "peer_success"), Detail(again, "peer_success"));
  EXPECT_EQ(probe.backend_code, again.backend_code);
  for (const char* isolate : {"always", "never"}) {
    const auto other = CreateSolver(backend);
    std::string error;
    ASSERT_TRUE(other->SetOption("isolate", isolate, &error)) << error;
    const SolveResult r = other->Solve(problem, options);
    const AnswerProcess expected = std::string(isolate) == "never" ? AnswerProcess::kThisProcess : AnswerProcess::kWorker;
    EXPECT_EQ(AnswerProcessOf(r), expected);
    EXPECT_EQ(r.status, probe.status) << isolate;
    EXPECT_EQ(r.z, probe.z) << isolate;
  }
}

}  // namespace smcbench::peer_checks

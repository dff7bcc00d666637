// auto on every classic MCP from every published start (docs/auto.md, "Nonlinear MCPs"): solved, the answer checked
// here (the scale-free residual recomputed from z, and agreement with a published or proved solution, or with an
// independent backend's answer from the same start where none is listed); and the globalization that makes newton
// alone solve them (the crash phase and the non-monotone watchdog), each seen to act where it is needed.
#include "problems/mcp/classic_mcps.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "problems/mcp/builtin_entry.h"
#include "solvers/newton/semismooth_newton_solver.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

// The verdict's measure, recomputed from z alone.
double ScaledResidual(const MCP& p, const Vector& z) {
  Vector F(p.size()), d;
  p.Evaluate(z, &F);
  DenseMatrix J;
  p.JacobianDense(z, &J);
  McpRowScales(J, p.variable_scale(), &d);
  return McpScaledResidual(z, F, p.l(), p.u(), d, p.variable_scale());
}

// max_i |a_i − b_i| / (1 + max_i |b_i|).
double Distance(const Vector& a, const Vector& b) {
  return (a - b).cwiseAbs().maxCoeff() / (1.0 + b.cwiseAbs().maxCoeff());
}

BuiltinMcpEntry Entry(const std::string& id) {
  BuiltinMcpEntry entry;
  EXPECT_TRUE(MakeClassicMcp(id, &entry)) << id;
  return entry;
}

TEST(ClassicMcpsAuto, EveryClassicProblemFromEveryPublishedStartIsSolvedAndChecked) {
  const std::unique_ptr<Solver> automatic = CreateSolver("auto");
  const std::unique_ptr<Solver> ipopt = CreateSolver("ipopt");  // a different method: the independent answer
  for (const std::string& id : ClassicMcpIds()) {
    const BuiltinMcpEntry entry = Entry(id);
    const McpLibraryProblem& p = entry.problem;
    for (size_t s = 0; s < p.starts.size(); ++s) {
      const std::string where = id + " from " + p.start_labels[s];
      SolverOptions o;
      o.warm_start = p.starts[s];
      const SolveResult r = automatic->Solve(*p.problem, o);
      ASSERT_TRUE(r.solved()) << where << ": " << r.message;
      EXPECT_LE(ScaledResidual(*p.problem, r.z), 1e-10) << where;
      EXPECT_TRUE((r.z.array() >= p.problem->l().array()).all() && (r.z.array() <= p.problem->u().array()).all())
          << where;
      if (!entry.known_solutions.empty()) {
        // nash5's published solution has 5 digits; the others are exact.
        const double allowed = id == "mcp/classic/nash5" ? 1e-4 : 1e-8;
        double nearest = kInf;
        for (const Vector& known : entry.known_solutions) nearest = std::min(nearest, Distance(r.z, known));
        EXPECT_LE(nearest, allowed) << where;
      } else {
        const SolveResult other = ipopt->Solve(*p.problem, o);
        ASSERT_TRUE(other.solved()) << where << " (ipopt): " << other.message;
        EXPECT_LE(Distance(r.z, other.z), 1e-8) << where;
      }
    }
  }
}

SolveResult SolveWithNewton(const std::string& id, int start, const std::vector<std::string>& settings = {}) {
  const BuiltinMcpEntry entry = Entry(id);
  SemismoothNewtonSolver newton;
  for (const std::string& s : settings) {
    std::string error;
    EXPECT_TRUE(newton.SetOption(s.substr(0, s.find('=')), s.substr(s.find('=') + 1), &error)) << error;
  }
  SolverOptions o;
  o.warm_start = entry.problem.starts[start];
  return newton.Solve(*entry.problem.problem, o);
}

// Mathiesen's economy from its cold point Π(0) (prices at their floor 1e-8): ∇F's rows there are ~1e16, so Psi in
// the start's row scales is ~1e-16 and keeps falling while the verdict's residual grows to 0.5; the monotone search
// then crawls until the budget. Refreshing the row scales where they went stale solves it.
TEST(ClassicMcpsNewton, RowScaleRefreshSolvesMathiesensEconomyFromTheColdPoint) {
  const SolveResult stale = SolveWithNewton("mcp/classic/mathiesen", 1,
                                            {"row_scale_refresh=false", "crash_steps=0", "mcp_nonmonotone_memory=1"});
  EXPECT_FALSE(stale.solved());
  const SolveResult r = SolveWithNewton("mcp/classic/mathiesen", 1);
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_GE(r.GetDetail("row_rescalings"), 1.0);
  Vector expected(4);
  expected << 3, 6, 1, 5;
  EXPECT_LE(Distance(r.z, expected), 1e-9);
}

// Josephy's NCP from MCPLIB's start 7 (0, 1, 0, 1): the monotone search crawls along a valley of Psi (67 iterations
// measured); the non-monotone memory accepts steps that raise Psi for a while and is done in about a dozen.
TEST(ClassicMcpsNewton, NonMonotoneSearchTakesTheStepsTheMonotoneOneRefuses) {
  const SolveResult monotone = SolveWithNewton("mcp/classic/josephy", 6, {"mcp_nonmonotone_memory=1"});
  ASSERT_TRUE(monotone.solved()) << monotone.message;
  EXPECT_EQ(monotone.GetDetail("nonmonotone_steps"), 0.0);
  const SolveResult r = SolveWithNewton("mcp/classic/josephy", 6);
  ASSERT_TRUE(r.solved()) << r.message;
  EXPECT_GE(r.GetDetail("nonmonotone_steps"), 1.0);
  EXPECT_LT(2 * r.iterations, monotone.iterations);
}

// The crash phase: from Kojima–Shindo's start 4 (1, 0, 1, 0) the natural map's active set is the solution's, and
// one min-map Newton step lands on (1, 0, 3, 0), one of its two solutions; so does x = 0.4 on (x − 1)(x − 2), x ≥ 0
// (x − F(x) = −0.56 < 0 puts x at its bound, and F(0) = 2 > 0: the solution 0).
TEST(ClassicMcpsNewton, OneCrashStepSolvesAProblemWhoseStartShowsTheActiveSet) {
  const SolveResult k = SolveWithNewton("mcp/classic/kojshin", 3);
  ASSERT_TRUE(k.solved()) << k.message;
  EXPECT_EQ(k.iterations, 1);
  EXPECT_EQ(k.GetDetail("crash_steps"), 1.0);
  Vector solution(4);
  solution << 1, 0, 3, 0;
  EXPECT_LE(Distance(k.z, solution), 1e-12);
  const SolveResult without = SolveWithNewton("mcp/classic/kojshin", 3, {"crash_steps=0"});
  ASSERT_TRUE(without.solved()) << without.message;
  EXPECT_GT(without.iterations, 1);
  const SolveResult t = SolveWithNewton("mcp/hard/three-solutions", 0);
  ASSERT_TRUE(t.solved()) << t.message;
  EXPECT_EQ(t.GetDetail("crash_steps"), 1.0);
  EXPECT_EQ(t.z[0], 0.0);
}

// The proximal restart with the MCP's shorter stagnation window (5) and smaller first λ (0.3 ‖∇G‖): from
// Kojima–Shindo's start 6 and Josephy's start 3 the search sits in a basin of the merit function that holds no
// solution; the box's window (10) and λ (1) leave it after 71 and 83 iterations (4 proximal rounds each), the
// MCP's after 25 and 26. Both reach a published solution.
TEST(ClassicMcpsNewton, ShorterStagnationWindowAndSmallerProximalStepLeaveAMeritBasinSooner) {
  for (const auto& [id, start] : {std::pair<std::string, int>{"mcp/classic/kojshin", 5}, {"mcp/classic/josephy", 2}}) {
    const SolveResult box = SolveWithNewton(id, start, {"mcp_stagnation_window=10", "mcp_proximal_lambda=1"});
    ASSERT_TRUE(box.solved()) << id << ": " << box.message;
    const SolveResult r = SolveWithNewton(id, start);
    ASSERT_TRUE(r.solved()) << id << ": " << r.message;
    EXPECT_GE(r.GetDetail("proximal_rounds"), 1.0) << id;
    EXPECT_LT(2 * r.iterations, box.iterations) << id;
    const BuiltinMcpEntry entry = Entry(id);
    double nearest = kInf;
    for (const Vector& known : entry.known_solutions) nearest = std::min(nearest, Distance(r.z, known));
    EXPECT_LE(nearest, 1e-8) << id;
  }
}

}  // namespace
}  // namespace smcbench

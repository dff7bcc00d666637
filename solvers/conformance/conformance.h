// The conformance checks every smcbench backend passes, as a library function: our tests call it on each of our
// backends, and the author of an out-of-tree backend calls it on theirs (examples/custom-backend). It never trusts
// a backend's status alone: the merit function is recomputed here from M, q, l, u.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "solvers/generators/random_problems.h"
#include "solvers/registry/registry.h"

namespace smcbench {

// One generated problem of the known-solution check: a P-matrix family, its bounds, the fraction of degenerate
// rows (z* at a bound with w* = 0) and the size. Its solution z* is unique.
struct ConformanceCase {
  MatrixFamily family = MatrixFamily::kSymmetricPositiveDefinite;
  BoundKind bounds = BoundKind::kLCP;
  double degenerate_fraction = 0.0;
  int size = 1;
};

struct ConformanceOptions {
  double tolerance = 1e-10;            // SolverOptions::tolerance of every solve
  double time_limit_seconds = 20;      // per solve
  int max_size = 30;                   // cases larger than this are skipped (sizes 1, 2, 3, 5, 8, 10, 30)
  // Which cases the backend must solve; a case it need not solve may end in any honest status, but a "solved"
  // answer is still checked. Empty: every case must be solved (every family is a P-matrix, so a complete method
  // solves them all). E.g. projected Gauss–Seidel/Jacobi converge only for SPD or diagonally dominant M.
  std::function<bool(const ConformanceCase&)> must_solve;
  // For a backend with info().mcp: every planted MCP of the mcp-known-solution check must be solved (they are
  // strongly monotone, so each has exactly one solution). False: any honest status, but "solved" is still checked.
  bool mcp_must_solve = true;
};

// One failed check: which check, on which problem, and what was wrong.
struct ConformanceFailure {
  std::string check;    // "known-solution", "session-bits", "session-reuse", "mcp-known-solution", ..."
  std::string problem;  // the generated problem's name (and step, for the session checks)
  std::string message;
};

struct ConformanceReport {
  std::vector<ConformanceFailure> failures;
  int solves = 0;          // solves run by the backend under test (plain and session)
  int solved_checked = 0;  // "solved" answers whose residual and z* were checked independently
  int mcp_solves = 0;          // nonlinear MCP solves (the mcp-* checks), counted apart from the box-MLCP ones
  int mcp_solved_checked = 0;  // "solved" MCP answers judged by JudgeMCP against the planted solution
  bool passed() const { return failures.empty(); }
};

// Runs the three checks of tests/conformance_test.cc on backends made by create (each check needs fresh and
// paired instances, hence a factory):
//  - known-solution: seeded problems with a planted unique solution z* (SPD, nonsymmetric P-matrix, diagonally
//    dominant; LCP, relay, box and mixed bounds with infinite entries; degenerate rows). Every "solved" answer has
//    an independently recomputed natural residual ≤ tolerance and equals z* (and the enumerative backend's answer)
//    to 1e-6·(1 + ‖z*‖∞); options.must_solve says which cases must be solved.
//  - session-bits: a session without the warm active-set path returns the very bits of Solve (status, message, z,
//    w, residuals, iterations, details) along a sequence of one-step problems.
//  - session-reuse: with the warm active-set path on, every answer agrees with the backend's own to rounding,
//    and the reused active set answers most calls along a slowly moving q.
// and on nonlinear MCPs (Solver::Solve(const MCP&)):
//  - mcp-known-solution (a backend with info().mcp): seeded strongly monotone MCPs F(z) = A z + κ∘z³ + b with a
//    planted solution (LCP, box, free and upper-bounded rows; n = 1 … 10). On return w = F(z), and every "solved"
//    answer is solved by JudgeMCP (scale-free residual, forward error against z*); options.mcp_must_solve.
//  - mcp-malformed-jacobian (info().mcp): a Jacobian of the wrong size, or one that throws, gives a non-solved
//    status with a message, never an exception or a crash.
//  - mcp-not-applicable (a backend without info().mcp): every MCP is answered not_applicable.
// Throws InvalidInputError if create is empty or returns null; a backend that throws is reported as a failure.
ConformanceReport CheckConformance(const SolverFactory& create, const ConformanceOptions& options = {});
// The same for a registered backend (ours, an external adapter, or one added with RegisterSolver).
ConformanceReport CheckConformance(std::string_view registered_name, const ConformanceOptions& options = {});

// One line per failure ("check: problem: message"), or "passed (N solves, M solved answers checked)" (and, for a
// backend that solves MCPs, how many MCP answers were checked).
std::string ToString(const ConformanceReport& report);

}  // namespace smcbench

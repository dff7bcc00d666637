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

// The cold-repeat check: a cold repeat of a problem does no less work than its first solve, so that what a benchmark
// times as cold is never answered from what an earlier solve left behind (Solver::ForgetWarmState). Meant for every
// registered backend, external adapters included (tests/conformance_test.cc runs it so).
struct ColdRepeatOptions {
  double tolerance = 1e-10;        // SolverOptions::tolerance of every solve
  double time_limit_seconds = 20;  // per solve
  int repeats = 7;                 // cold repeats per problem on one instance, ForgetWarmState before each
  int fresh_instances = 3;         // instances whose first solve of the problem gives the reference time
  // The repeats' median time may not fall below the least of those first solves divided by this. Generous, since a
  // first solve meets colder caches; a cache hit is far below it (Siconos' mlcp_direct_FB: microseconds against
  // milliseconds).
  double time_factor = 5.0;
  // The time test applies only when the least of those first solves takes at least this long: below it, clock reads,
  // cache misses and a fresh instance's first touch of its memory (20–45 µs measured on solves whose repeats take
  // 1–6 µs: bullet-dantzig, dart-*, relays of 6 and 20 rows) are of the order of the solve itself, and the iteration
  // test alone decides.
  double min_timed_seconds = 1e-4;
};

struct ColdRepeatReport {
  std::vector<ConformanceFailure> failures;  // check "cold-repeat"
  int solves = 0;
  int problems_checked = 0;  // problems the backend took (first solve not refused): its repeats were compared
  int problems_timed = 0;    // of them, those where the time test applied (ColdRepeatOptions::min_timed_seconds)
  // False in an AddressSanitizer build: no fresh instances are solved and nothing is timed (see CheckColdRepeat).
  bool time_test_on = true;
  bool passed() const { return failures.empty(); }
};

// On seeded problems (nonsymmetric P-matrix relays of 6 and 20 rows, SPD LCPs of 8 and 20 rows, a 10-row
// nonsymmetric P-matrix problem with free, one-sided and box rows), each one the backend does not refuse
// (not_applicable, size_limit, invalid_options):
//  - iterations: on one instance with its default options, a first solve, then `repeats` solves each after
//    ForgetWarmState: every repeat has the first solve's status, at least its iterations, and (solved) its z to
//    1e-8·(1 + ‖z‖∞). Run again on an instance whose external library runs in process (option isolate=never,
//    where the backend has it), as the timing below does.
//  - time: the median of those in-process repeats is at least the least of the first solves of the problem by
//    `fresh_instances` other instances divided by time_factor (a loaded machine only adds time to a measurement).
//    Each of them (in process too: an external adapter's first solve would otherwise run in its isolation worker)
//    has solved another problem of the same shape before, so that what an instance pays once is not counted as the
//    problem's cold cost. Not in an AddressSanitizer build: there a first solve's allocations (a fallback's
//    workspace, say) cost hundreds of microseconds and the time measures the sanitizer (the release build decides).
// Throws InvalidInputError if create is empty or returns null; a backend that throws is reported as a failure.
ColdRepeatReport CheckColdRepeat(const SolverFactory& create, const ColdRepeatOptions& options = {});
ColdRepeatReport CheckColdRepeat(std::string_view registered_name, const ColdRepeatOptions& options = {});

// One line per failure, or "passed (N solves, P problems compared, T timed)".
std::string ToString(const ColdRepeatReport& report);

}  // namespace smcbench

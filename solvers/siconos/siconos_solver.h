// Siconos Numerics (INRIA; Debian 12 libsiconos-numerics-dev 4.4) solvers as smcbench backends named
// "siconos-<solver>", so that every suite and report can put the reference library next to our backends and
// judge both by the same merit function. See solvers/siconos/README.md for each adapter.
//
// Three families, by the problem shape Siconos accepts (the rewriting is standard_form.h, exact both ways):
//   siconos-relay-*  RelayProblem(M, q, lb, ub): every row needs finite bounds (fixed rows are eliminated).
//                    lemke (relay_lexicolemke), pgs (relay_pgs), enum (relay_enum), avi (relay_avi_caoferris:
//                    Cao & Ferris' pivotal AVI method, the relay solver Siconos recommends).
//   siconos-lcp-*    LinearComplementarityProblem on the box → LCP rewriting (no free rows allowed):
//                    lemke (lcp_lexicolemke), newton-fb (lcp_newton_FB), newton-min (lcp_newton_minFB).
//   siconos-mlcp-*   MixedLinearComplementarityProblem (free rows as equalities, the rest as the LCP above):
//                    enum (mlcp_enum), lemke (mlcp_lcp_lemke: Schur complement on the equality block, then
//                    Lemke), fb (mlcp_FB), direct-enum / direct-fb (mlcp_direct_*: try the last few active sets
//                    first, fall back to enum / FB).
// And one method that is no backend of its own: avi_caoferris_stage3 on the LCP that siconos-avi-caoferris
// (siconos_avi_solver.h) builds at a vertex of an AVI's polytope.
// Anything a family cannot express is kNotApplicable with the reason.
//
// Trust. Siconos reports success on wrong answers in known cases (its dense LCP driver "solves" every 1×1 LCP as
// z = −q/M, info 0, even for M ≤ 0: a negative z, or z = inf for M = 0; NaN passes its error test, since
// NaN > tol is false). So: a non-finite z is kNumericalFailure whatever Siconos said; info ≠ 0 is never
// kSolved; info = 0 is only a claim, which the base class checks with our merit function (kInaccurate if it
// fails). Siconos' own code is recorded as detail "siconos_info".
//
// Isolation (option isolate, IsolationPolicy; default kFirst). Siconos aborts or hangs on some inputs, so a call
// can run in this backend's own worker process (child_process.h): a crash becomes kNumericalFailure naming the
// signal, a solve that outlasts the time limit (options.time_limit_seconds, else default_time_limit) is killed and
// reported as kTimeLimit, console output is discarded. That costs a socket round trip per solve, far more than a small
// solve itself (solvers/siconos/README.md, "Isolation", has the measured cost), so by default only a problem's first
// solve (the probe) runs there; once a probe came back normally (any status, but no crash, no signal, no deadline),
// later solves of exactly the same bytes (request, options that reach Siconos, M, q, bounds, start point) run in this
// process, with the same answer bit for bit.
// Detail "in_process" says which process answered (AnswerProcessOf). In process there is no time limit and no
// protection (a problem whose probe failed is never run here, a call whose time limit is shorter than its probe
// took goes to the worker); the C streams stdout/stderr point to /dev/null during the call (no system
// call), descriptors 1 and 2 are redirected too only if the probe saw Siconos write there (or, for kNever, unless
// quiet is off); Siconos' file-static MLCP state (the "direct" solvers' active-set cache) is handed between
// instances (SiconosSession). In-process instances must not run concurrently on different threads.
// remembered_problems / remembered_megabytes bound the memory of probed problems (probed_problems.h).
//
// Options mapped from ours: tolerance → Siconos' dparam[TOL] = max(tol·t/((1 + ‖q_s‖₂)·√N), 10·N·ε) with
// t = min(1 + ‖q‖∞, 1, min_i d_i), d the row scales (Siconos tests a 2-norm relative to its own rewritten q_s, we
// test the ∞-norm relative to 1 + ‖q‖∞ and the row-equilibrated residual relative to 1 + ‖z‖∞; N = size of the
// rewritten problem: Siconos' test then implies both within our threshold; the floor keeps it reachable), max_iterations > 0 → iparam[MAX_ITER] (else Siconos' default),
// verbosity ≥ 2 → Siconos verbose and its output kept. Warm starts reach the methods that use a start point
// (pgs, newton-*, fb). iterations = Siconos' iparam[ITER_DONE]. The relay and LCP drivers end with an accuracy
// check (filterOn) whose verdict replaces the algorithm's info; the adapter replays it exactly as the 4.4 drivers
// do (checked against them on 10,500 runs), so detail siconos_info is what Siconos returns and
// siconos_algorithm_info (when different) what the algorithm said: "Lemke found a basis that Siconos' check
// rejects" is kInaccurate, not a ray.
#pragma once

#include <array>
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>

#include "solvers/core/backend_options.h"
#include "solvers/core/solver.h"
#include "solvers/isolation/child_process.h"
#include "solvers/isolation/probed_problems.h"
#include "solvers/siconos/standard_form.h"

namespace smcbench {

enum class SiconosMethod : int {
  kRelayLemke = 0,
  kRelayPgs = 1,
  kRelayEnum = 2,
  kRelayAvi = 3,
  kLcpLemke = 4,
  kLcpNewtonFb = 5,
  kLcpNewtonMin = 6,
  kMlcpEnum = 7,
  kMlcpLemke = 8,
  kMlcpFb = 9,
  kMlcpDirectEnum = 10,
  kMlcpDirectFb = 11,
  // avi_caoferris_stage3, the pivoting of Cao–Ferris' AVI method on the LCP-like problem built at a vertex of P.
  // Not a registered backend: siconos-avi-caoferris (siconos_avi_solver.h) builds that problem and calls it
  // through an instance of this class, for the isolation and the probe policy.
  kAviCaoFerrisStage3 = 12,
};
inline constexpr int kNumSiconosMethods = 13;


struct SiconosOptions {
  // Where Siconos runs: see IsolationPolicy and the header comment.
  IsolationPolicy isolate = IsolationPolicy::kFirst;
  // kFirst: how many probed problems are remembered (the most recent ones), and how much memory their copies may
  // take (a problem is M, q, bounds and start point of the rewritten form: 8·(N² + 4N) bytes). A problem that is
  // not remembered, or no longer, is probed again. 0 problems: every solve is a probe (like kAlways).
  int remembered_problems = 32;
  double remembered_megabytes = 64.0;
  // Seconds a solve in the worker may take when SolverOptions::time_limit_seconds is infinite (> 0).
  double default_time_limit = 60.0;
  // Enumerative methods: largest number of complementarity variables they may enumerate (2^k candidate
  // bases; a relay row counts 2, Siconos enumerates the doubled LCP). Larger problems get kSizeLimit.
  int max_enumerated = 16;
  // Largest rewritten problem (unknowns N; a relay row counts 2 in the LCP and MLCP forms) sent to Siconos, whose
  // methods here are dense, O(N^2) memory per copy and O(N^3) time. Larger problems get kSizeLimit.
  int max_size = 2048;
  // Pass problems on which Siconos is known to crash (siconos-mlcp-lemke without equality or without
  // complementarity rows) instead of refusing them with kNotApplicable. For demonstrating the isolation.
  bool allow_known_crashes = false;
  // In process: redirect stdout/stderr to /dev/null around a Siconos call (some of its messages are unconditional
  // printf). Costs a few system calls per solve, so kFirst does it only for a problem whose probe saw
  // Siconos print; kNever, which has no probe, does it on every call. false: never (the bare call, output
  // through). Verbosity ≥ 2 keeps Siconos' output in every mode.
  bool quiet = true;

  bool IsValid(std::string* why) const;
};

class SiconosSession;  // Siconos' problem and option structs (siconos_solver.cc), kept out of this header

class SiconosSolver final : public BackendWithOptions<SiconosOptions> {
 public:
  explicit SiconosSolver(SiconosMethod method);
  SiconosSolver(SiconosMethod method, const SiconosOptions& options);
  ~SiconosSolver() override;

  const SolverInfo& info() const override;
  SiconosMethod method() const { return method_; }
  // Process id of the running worker, or −1 (none yet, or killed after a timeout or crash).
  int worker_pid() const { return worker_.running() ? static_cast<int>(worker_.pid()) : -1; }

  // Siconos' own solver id (SICONOS_RELAY_LEMKE, ...) for a method.
  static int SiconosId(SiconosMethod method);

  // mlcp_direct_* (siconos-mlcp-direct-*): drops their active-set cache, in this process and in the worker, and
  // initialises Siconos for the last problem again (mlcp_driver_reset, mlcp_driver_init) here rather than in the
  // next solve. The other methods keep nothing learned between solves.
  WarmStateReset ForgetWarmState() override;

  // kAviCaoFerrisStage3 only: the first `rows` rows of the LCP given to Solve are the vertex's (their u basic, the
  // rows Lemke's covering vector covers: stage 3's size_x and A = {1, ..., rows}); any other LCP row is an inactive
  // constraint of the AVI. Without it (0) that method refuses every problem.
  void set_covering_rows(int rows) { covering_rows_ = rows; }

 protected:
  void DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) override;
  void BindOptions(OptionBinder* binder) override;
  bool ValidateBackendOptions(std::string* why) const override;

 private:
  struct Outcome;
  // The exact bytes sent to Siconos for the request in *outcome (ProbedProblems' key).
  std::array<ProbedProblems::Part, 6> RequestParts(const Outcome& outcome) const;
  // DoSolve's phases 2 and 3 (the .cc file); the refusals and the classification of the answer need no state.
  void PrepareRequest(const BoxMLCP& problem, const SolverOptions& options, Outcome* outcome, SolveResult* result);
  bool RunWherePolicySays(const SolverOptions& options, std::chrono::steady_clock::time_point start,
                          Outcome* outcome, SolveResult* result);
  bool RunIsolated(bool keep_output, double limit_seconds, std::chrono::steady_clock::time_point deadline,
                   Outcome* outcome, SolveResult* result);
  // silence: what to silence around the call (ProbedProblems::Console).
  void RunInProcess(ProbedProblems::Console silence, Outcome* outcome);
  // ForgetWarmState's message to the worker; a worker that does not confirm within default_time_limit is stopped.
  void ForgetInWorker();

  SiconosMethod method_;
  int covering_rows_ = 0;  // kAviCaoFerrisStage3: set_covering_rows
  StandardForm form_;
  Vector x_;  // unknowns of the rewritten problem: start point in, Siconos' answer out
  std::unique_ptr<Outcome> last_;  // the request made from form_ (always the two of one problem) and its answer
  bool last_came_back_ = false;    // that request's call returned normally (in process, or the worker answered)
  // A direct method's call came back, here or in the worker, since the last ForgetWarmState: a cache to drop there.
  bool cache_in_process_ = false;
  bool cache_in_worker_ = false;
  std::unique_ptr<SiconosSession> session_;  // in-process Siconos state, created on first in-process solve
  ChildProcess worker_;
  bool worker_keeps_output_ = false;
  ProbedProblems probed_;  // isolate = kFirst: the problems whose probe came back normally
  int dev_null_ = -1;            // /dev/null, opened on the first in-process solve that silences descriptors
  std::FILE* stdio_sink_ = nullptr;  // /dev/null as a C stream, opened on the first that silences stdio only
};

}  // namespace smcbench

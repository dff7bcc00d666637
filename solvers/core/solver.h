// The one interface every backend implements. Solve() does all shared work once (Drake style): option and
// capability checks, cold/warm start, row equilibration, timing, the exact polish, the merit function and the
// rule that "solved" requires it; a backend implements only its algorithm in DoSolve().
#pragma once

#include <chrono>
#include <cstdint>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "solvers/core/options.h"
#include "solvers/core/problem.h"
#include "solvers/core/result.h"
#include "solvers/core/session.h"

namespace smcbench {

namespace internal {
// A backend's storage for the polish of run-time sizes and the MCP merit function (internal headers polish.h and
// mcp_merit.h, not installed): defined in solver.cc.
struct SolverWorkspace;
}  // namespace internal

// What `smcbench list` prints about a backend.
struct SolverInfo {
  std::string_view name;        // registry name, e.g. "lemke"
  std::string_view algorithm;   // one line: what it does
  std::string_view reference;   // the paper or book the algorithm follows
  bool dense = true;            // accepts dense M
  bool sparse = false;          // accepts sparse M natively
  bool symmetric_only = false;  // needs symmetric M (else kNotApplicable)
  bool exact = false;           // finite termination (pivoting / enumeration) rather than iterative
  bool mcp = false;             // also solves nonlinear MCPs
  int default_size_limit = 0;   // refuses larger problems with kSizeLimit; 0 = none
  // DoSolve receives the row-equilibrated problem (BoxMLCP::Equilibrated), so the backend's pivot tolerances,
  // stopping and sign tests are in units of z. External codes (siconos-*) get the problem as the user wrote it.
  bool equilibrate = true;
  // A meta-backend (auto) whose DoSolve hands the problem to another backend's Solve, which already did the shared
  // work (equilibration, polish, merit function, the rule for "solved"): the base does not do it a second time.
  bool delegates = false;
  // An adapter to another library (siconos-*): timed and studied as that library runs, so a solve session never
  // answers for it from a reused active set (its own warm behaviour, e.g. a direct solver's cache, is what counts).
  bool external = false;
  // Capabilities that tests and benchmarks select backends by ("every backend that can X"), so that a new backend is
  // covered by registering it. Repeated solves of one size, plain or in a session, allocate nothing after a warm-up
  // (tests/allocation_test.cc pins it); an external library's internals are not ours to promise.
  bool allocation_free = !external;
  // Expected to solve every box-MLCP whose M is a P-matrix (within its size limit): the conformance suite requires
  // it. False for splitting methods (psor), which converge for symmetric positive definite and H-matrices only.
  bool solves_every_p_matrix = true;
  // Above this many rows one solve takes seconds (a dense interior point's factorizations): benchmarks of growing
  // size stop there, though the backend accepts larger problems. 0 = none.
  int practical_size_limit = 0;
  // Solves box-MLCPs. False for an MCP-only adapter (siconos-mcp-*), which answers every box-MLCP not_applicable:
  // bench runs it on the MCP suites only, and box tables do not list it.
  bool box = true;
};

// Not thread-safe: a Solver owns its workspace. Use one instance per thread.
class Solver {
 public:
  // A dense-only backend given a sparse problem up to this size solves a dense copy (detail "densified" = 1).
  static constexpr int kMaxDensifiedSize = 4096;

  Solver();
  // A backend owns its workspaces: not copyable.
  Solver(const Solver&) = delete;
  Solver& operator=(const Solver&) = delete;
  virtual ~Solver();
  virtual const SolverInfo& info() const = 0;

  // Solves problem into *result, reusing its storage. Never throws for a valid problem: every outcome,
  // including invalid options, is a status with a message. Guarantees on return: result->w = F(z),
  // result->residual_* is the merit function at z, and status == kSolved ⇒ residual_rel ≤ tolerance and
  // residual_scaled ≤ tolerance. With options.polish, the exact polish (polish.h) ran on the backend's answer.
  // For an MCP the rule is the scale-free residual alone: residual_scaled = McpScaledResidual with the row scales
  // of the Jacobian at z (one more Jacobian evaluation per solve), status == kSolved ⇒ residual_scaled ≤ tolerance;
  // residual_rel = residual_abs / (1 + ‖F(Π(0))‖∞) is information only, since a scale read at an arbitrary point
  // such as Π(0) changes with the scaling of F's rows (docs/verdict.md, "Nonlinear MCPs"). An F or Jacobian that
  // throws std::runtime_error or std::logic_error, or a Jacobian of the wrong size, is kNumericalFailure with a
  // message; InvalidInputError and exceptions of other types (a Python callback's own) reach the caller unchanged.
  void Solve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result);
  void Solve(const MCP& problem, const SolverOptions& options, SolveResult* result);
  // Convenience forms that allocate a fresh result.
  SolveResult Solve(const BoxMLCP& problem, const SolverOptions& options = {});
  SolveResult Solve(const MCP& problem, const SolverOptions& options = {});

  // Prepare once, solve many (session.h): checks the options and this backend's capability once, keeps copies of
  // the problem and the options; session.Solve(q) then does the per-call part only, and tries the previous answer's
  // active set first. The session points to this backend, which must outlive it.
  SolveSession Prepare(const BoxMLCP& problem, const SolverOptions& options = {},
                       const SessionOptions& session = {});

  // A meta-backend (`auto`) that hands a problem to another backend returns that backend here (owned by this one,
  // valid while it lives); a solve session and the time-steppers then call it directly, so the choice costs
  // nothing per step. nullptr (every real backend): this backend solves the problem itself.
  virtual Solver* DelegateFor(const BoxMLCP& /*problem*/, const SolverOptions& /*options*/) { return nullptr; }

  // A caller that solved through DelegateFor's backend tells the meta-backend that it did not solve `problem`,
  // with its answer in `result`. True: that answer is the meta-backend's own (its Solve would return it as it is,
  // e.g. an exact backend's proof of infeasibility), and *result now holds it as that Solve would; the caller is done.
  // False: the caller hands the problem to this one's Solve, which goes on after the delegate instead of running it
  // again. Default: false, nothing to skip.
  virtual bool NoteDelegateFailure(const BoxMLCP& /*problem*/, const Solver& /*delegate*/,
                                   SolveResult* /*result*/) {
    return false;
  }

  // The next solve starts as if it were the first: no cache, no remembered active set, no candidate chosen by an
  // earlier answer. What depends on the problem's M alone and is prepared once (the equilibrated copy, enum's block
  // factors, auto's classification, an external library's initialisation for the last problem) may stay: that is
  // set-up, not warm state. A backend that keeps anything learned from earlier answers overrides this; work that
  // is a separate call (Siconos' MLCP driver reset and init) runs here, so a caller timing cold solves keeps it
  // out of the timed region (bench/replay/replay.h, TimeSolves). Default: nothing is kept.
  virtual WarmStateReset ForgetWarmState() { return WarmStateReset::kNothingRemembered; }

  // Typed backend options set from text ("omega", "1.5"); false with *error on unknown name or bad value,
  // in which case the option keeps its previous value.
  bool SetOption(std::string_view name, std::string_view value, std::string* error);
  std::string OptionsHelp();
  // Changes whenever the backend's options may have changed (SetOption, OptionsChanged): sessions re-check then.
  std::uint64_t option_generation() const { return option_generation_; }

 protected:
  // Called with result->z holding the starting point (warm start or Π(0)), sizes checked, options valid.
  // Must set status (and message when not solved), z and iterations. The base computes the residual.
  virtual void DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) = 0;
  // Default: kNotApplicable.
  virtual void DoSolveMCP(const MCP& problem, const SolverOptions& options, SolveResult* result);
  // Binds the backend's typed options for SetOption/OptionsHelp.
  virtual void BindOptions(OptionBinder* binder);
  // Checks the backend's typed options; false with *why when invalid.
  virtual bool ValidateBackendOptions(std::string* why) const;

  // DoSolve's answer is the exact solution of the very active set the polish would read off it (the same rows
  // free, the same bounds; ClassifyRowsForPolish), its free block freshly factored: the polish would factor that
  // block once more for the same point. The base then skips it for this solve when the answer passes the tolerance
  // (so the verdict is the one the polish would give: a polished point is kept only if not worse); otherwise it
  // polishes as usual. Cleared at the start and end of every solve.
  void NotePolishRedundant() { polish_redundant_ = true; }

  // A backend whose options can change other than through SetOption (a mutable_options() accessor, a setter)
  // calls this from there, so prepared sessions validate them again.
  void OptionsChanged() { ++option_generation_; }
  // For iterative backends: true once the options' time limit has passed (cheap when there is none).
  bool TimeLimitReached() const;
  // max_iterations if positive, else fallback.
  static int IterationBudget(const SolverOptions& options, int fallback) {
    return options.max_iterations > 0 ? options.max_iterations : fallback;
  }
  // For a dense backend with N = problem.size() ≤ BoxMLCP::kSmallSize rows whose acceptance test is the merit
  // function itself: the merit function of the problem it was given at result->z, with result->w = M z + q.
  template <int N>
  Residual FixedSizeMerit(const BoxMLCP& problem, SolveResult* result) {
    static_assert(N >= 1 && N <= BoxMLCP::kSmallSize);
    return problem.template NaturalResidualFixed<N>(result->z, &result->w);
  }

 private:
  friend class SolveSession;
  // N > 0: n = N known at compile time (dense problems up to BoxMLCP::kSmallSize), 0: read at run time.
  template <int N>
  void SolveBox(const BoxMLCP& problem, const SolverOptions& options, const SolverInfo& solver_info,
                SolveResult* result);
  // Solve for a backend with info().delegates (auto): its DoSolve hands the problem to another backend's Solve.
  void SolveDelegated(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result);
  template <int N, bool kCheckOptions>
  bool BeginSolve(int n, const Vector& l, const Vector& u, const SolverOptions& options, std::string_view name,
               SolveResult* result);
  // The problem DoSolve receives: the equilibrated copy (made once per matrix_id, its q refreshed per call), or
  // the problem itself for a backend with info().equilibrate false.
  const BoxMLCP& EquilibratedFor(const BoxMLCP& problem);
  // The same for a dense problem of N rows (0: read at run time): the cached copy's q refreshed inline, the loop
  // unrolled; a new matrix goes to EquilibratedFor.
  template <int N>
  const BoxMLCP& EquilibratedFixed(const BoxMLCP& problem) {
    if constexpr (N > 0) {
      if (equilibrated_source_ == problem.matrix_id()) {
        equilibrated_->template AssignEquilibratedQ<N>(problem);
        return *equilibrated_;
      }
    }
    return EquilibratedFor(problem);
  }
  template <int N>
  void Conclude(const BoxMLCP& problem, const SolverOptions& options, std::chrono::steady_clock::time_point start,
                SolveResult* result);
  // The exact polish of result->z (polish.h) on the equilibrated problem; kept when its scaled residual is not
  // larger and its relative one not pushed above the tolerance. Updates *r and, for a backend that stopped short
  // (iteration, time limit, stalled), the status when the polished point passes.
  template <int N>
  void Polish(const BoxMLCP& problem, double tolerance, Residual* r, SolveResult* result);
  // Every check of Solve that cannot change while a session's problem and options stay the same: the options
  // (SolverOptions::IsValid, the backend's), dense storage or a backend that takes sparse M, symmetry when
  // required. False: Solve reports the refusal, so the session sends its calls there.
  bool ChecksPass(const BoxMLCP& problem, const SolverOptions& options) const;
  // A session's per-call part for dense n = N ≤ BoxMLCP::kSmallSize once ChecksPass held: the warm start's size
  // and finiteness, DoSolve, timing, the polish, the merit function and the rule that "solved" requires it.
  template <int N>
  void SolveValidated(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result);
  // BeginSolve's failure path: re-checks in the documented order and sets kInvalidOptions with the message.
  bool RejectOptions(int n, const SolverOptions& options, SolveResult* result);
  // Arms TimeLimitReached for this solve (cheap when there is no limit).
  void StartDeadline(double time_limit_seconds) {
    has_deadline_ = time_limit_seconds < kInf;
    if (has_deadline_) {
      deadline_ = std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                         std::chrono::duration<double>(time_limit_seconds));
    }
  }
  // start == time_point{} means "not timed" (options.measure_time off).
  void Finish(double tolerance, std::chrono::steady_clock::time_point start, SolveResult* result);
  // After DoSolveMCP: the MCP's merit function at result->z (F there into result->w, the Jacobian there into the
  // workspace; skipped for a delegating backend, whose delegate's Solve computed it), the MCP rule for
  // "solved", then the end every solve shares. A failure to evaluate is a status (internal::McpMerit).
  void ConcludeMcp(const MCP& problem, const SolverOptions& options, bool recompute,
                   std::chrono::steady_clock::time_point start, SolveResult* result);

  // EquilibratedFor's copy and the matrix_id of the problem it was made from (0: none).
  std::optional<BoxMLCP> equilibrated_;
  std::uint64_t equilibrated_source_ = 0;
  Vector polish_z_, polish_w_;  // the polished candidate, kept to avoid allocating per solve
  // Made on the first solve that needs it (the polish of a dense problem larger than BoxMLCP::kSmallSize, an MCP's
  // merit function), then reused, so repeated solves of one size do not allocate.
  std::unique_ptr<internal::SolverWorkspace> workspace_;
  std::uint64_t option_generation_ = 1;
  std::chrono::steady_clock::time_point deadline_{};
  bool has_deadline_ = false;
  bool polish_redundant_ = false;  // NotePolishRedundant during this solve
};

}  // namespace smcbench

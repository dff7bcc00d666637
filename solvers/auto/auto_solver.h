// The default backend: picks, per problem, the fastest of our backends that is exact or reliable for the problem's
// class, hands the problem to it, and tries the next candidate when the choice fails without proving anything.
// docs/auto.md gives the rule and the measurements behind each threshold.
//
// The rule (per M, l, u, i.e. per BoxMLCP::matrix_id(); the decision is cached, so a time-stepper pays it once):
//   sparse M                                        → up to sparse_bpp_max_size rows enum (on a dense copy) where
//                                                     it would take the dense problem, else bpp; then newton
//                                                     (UMFPACK), then lemke on a dense copy (n ≤ 4096)
//   dense, lower triangular with a positive
//     diagonal, from 5 rows                         → psor (one sweep is the forward substitution), then lemke,
//                                                     then newton
//   dense, upper triangular with a positive
//     diagonal, from 5 rows                         → psor with the backward sweep (one sweep is the back
//                                                     substitution), then lemke, then newton
//   dense, at most enum_max_choice_rows rows with a
//     choice of state (l < u, not free: enum's own
//     size measure) and enum_max_active_sets sets   → enum, then lemke, then newton
//   any other dense M with at most bpp_max_size
//     rows, unless M is skew-dominant (‖M − Mᵀ‖_F >
//     4‖M + Mᵀ‖_F) with skew_lemke_min_size rows
//     or more                                          → bpp (at most max(4, n/4) single pivots), then as below
//   dense, symmetric positive definite (a Cholesky
//     factorization of M succeeds), and psor predicted
//     faster than lemke from M's condition estimate
//     and the row counts (psor_min_speedup)         → psor, then lemke, then newton
//   any other dense M                               → lemke, then newton
//   nonlinear MCP                                   → newton, then newton-min, then ipopt
// The MCP candidates after newton are created by registry name through the BackendLookup the registry hands auto
// (auto cannot link the registry, which lists auto itself); a name the lookup does not know is skipped, so the
// chain is whatever subset of newton → newton-min → ipopt is built in.
// A candidate's answer ends the chain when it is solved, when it is a proof (kInfeasible from an exact backend),
// when the caller's time limit ran out (kTimeLimit: the budget is spent) or when the options were refused (every
// candidate would refuse them). Any other status (iteration limit, stall, ray, singular, numerical failure, a
// refusal such as kNotApplicable) passes the problem on. kInfeasible from a backend that is not exact is never
// reported as such: it becomes kNumericalFailure. When a later candidate solved the problem, later calls on the
// same matrix start with it ("what the last call showed"); DelegateFor returns that same backend. A session hands a
// call its delegate did not solve to auto's chain and then asks DelegateFor again, so a candidate that fails on a
// matrix (bpp ends singular on some degenerate problems lemke solves) fails once per session, not on every step;
// that hand-over starts the chain after the delegate (NoteDelegateFailure), which is not run twice.
// That is warm state: ForgetWarmState drops it, so a cold repeat runs the whole chain again.
//
// The backward-sweep psor is auto's second PsorSolver: the psor candidate's options (as set through candidate() or
// `--set psor.X=...`), copied when they change, with sweep = backward; it answers as candidate psor.
// Details: "chosen" = the AutoCandidate of the backend whose answer is returned (read it with ChosenCandidateOf),
// "fallbacks" = how many candidates failed before it; the chosen backend's own details are kept. The result's
// solver name is "auto".
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "solvers/core/backend_options.h"
#include "solvers/core/solver.h"

namespace smcbench {

class PsorSolver;

// The backends auto chooses from, in a fixed order: detail "chosen" stores this value, so values are never
// renumbered (new candidates are appended).
enum class AutoCandidate : int {
  kEnum = 0,
  kPsor = 1,
  kLemke = 2,
  kNewton = 3,
  kNewtonMin = 4,  // MCPs only, when registered
  kIpopt = 5,      // MCPs only
  kBpp = 6,
};
inline constexpr int kAutoCandidateCount = 7;

// Registry name of candidate `index` ("enum", "psor", "lemke", "newton", "newton-min", "ipopt"); "" outside
// [0, kAutoCandidateCount).
std::string_view AutoCandidateName(int index);
// The inverse: the candidate index of a registry name, −1 for a name that is not a candidate.
int AutoCandidateIndex(std::string_view name);
// The candidate's registry name: the text of detail "chosen" in JSON and Python.
std::string_view ToString(AutoCandidate candidate);
std::optional<AutoCandidate> AutoCandidateFromString(std::string_view name);

// Detail "chosen": the candidate whose answer auto returns (set by LabelAutoAnswer).
inline constexpr CodeDetail<AutoCandidate, kAutoCandidateCount> kAutoChosenDetail{"chosen"};
// The candidate that answered, for a result labelled as auto's; nullopt for any other backend's result.
inline std::optional<AutoCandidate> ChosenCandidateOf(const SolveResult& result) {
  return result.solver == "auto" ? kAutoChosenDetail.Get(result) : std::nullopt;
}

// Labels an answer as auto's own Solve labels it: solver "auto", detail "chosen" = the candidate that answered,
// "fallbacks" = how many candidates failed before it. Auto's Solve uses it, and so does a caller whose session or
// time-stepper called auto's choice directly (DelegateFor) and reports the answer as auto's.
// Inline: it ends every solve of auto's, whose paper problems take a few hundred instructions.
inline void LabelAutoAnswer(AutoCandidate chosen, int fallbacks, SolveResult* result) {
  result->solver = "auto";
  kAutoChosenDetail.Set(result, chosen);
  result->SetDetail("fallbacks", static_cast<double>(fallbacks));
}

// A fresh backend with default options for a registry name, or nullptr for a name that is not registered.
using BackendLookup = std::function<std::unique_ptr<Solver>(std::string_view name)>;

struct AutoOptions {
  // Dense problems with at most this many rows with a choice of state go to enum (exact; its search grows as
  // 2^k or 3^k in this number k, the guided first phase makes it fastest at small k). At most enum's size_limit.
  int enum_max_choice_rows = 8;
  // ... and at most this many active sets (2 per one-sided row, 3 per finite box: 3⁶ = 6 box rows, 9 one-sided):
  // past it, enum's worst case shows on strongly nonsymmetric M (a relay of 8 rows: 45.8 µs where bpp takes 1.2 µs)
  // while bpp is within 1.12x of enum on every class at 8 rows (docs/auto.md, "Every class").
  double enum_max_active_sets = 729;
  // Dense symmetric positive definite M goes to psor when lemke's predicted time is at least this many times
  // psor's. The prediction (docs/auto.md) uses M's reciprocal condition estimate from its Cholesky factor: PSOR's
  // sweeps grow with the condition number, lemke's pivots do not. 0: psor on every SPD M; inf: never.
  double psor_min_speedup = 1.0;
  // Dense problems with more rows with a choice than enum takes and at most this many rows go to bpp first (block
  // principal pivoting on the n rows, where lemke doubles the finite boxes), then to the candidates below. bpp ends
  // singular on some MLCPs with free rows and some degenerate LCPs, cheaply, and the next candidate answers. The
  // size is the largest at which bpp was measured faster than psor and lemke (docs/auto.md); 0: never.
  int bpp_max_size = 256;
  // Skew-dominant M (‖M − Mᵀ‖_F > 4‖M + Mᵀ‖_F: the unsymmetric part outweighs the symmetric one) with at least
  // this many rows skips bpp: there bpp's block phase does not settle and its single pivots run for hundreds of
  // sets where lemke needs tens of pivots (auto_rule_measure handover: bpp capped, then lemke, 1.1-4.4x lemke alone
  // at m = 64-128; uncapped 9-48x), while at 16 rows bpp is within 0.6-1.2x of lemke. 0: never skip.
  int skew_lemke_min_size = 32;
  // Sparse M with at most this many rows goes to enum (on a dense copy, when it has enum's few rows with a choice)
  // or bpp (a sparse LU per active set) before newton: the families' coupled sliding surfaces (sparse, m = 16 and 64)
  // took newton 10-117 µs and bpp 4-13 µs (9x at 64), and at 4-8 rows enum took 0.7-1.6 µs where bpp took 2.8-11 µs
  // (auto_rule_measure classes, docs/auto.md). 0: sparse M always to newton first.
  int sparse_bpp_max_size = 64;
  // Pass the problem to the next candidate when the chosen one fails without a proof.
  bool fallback = true;

  // True if every field is usable; otherwise *why names the field and the accepted range.
  bool IsValid(std::string* why) const;
};

// The candidates auto tries on one problem, in order.
struct AutoChoice {
  std::array<AutoCandidate, kAutoCandidateCount> order{};
  int count = 0;
  // Where the chain starts: 0, or the candidate that answered after a fallback on this matrix.
  int first = 0;
  // psor runs as auto's backward-sweep instance on this matrix (upper triangular M: one sweep is the back
  // substitution), else as the psor candidate itself.
  bool psor_backward = false;

  AutoCandidate chosen() const { return order[first]; }
};

class AutoSolver final : public BackendWithOptions<AutoOptions> {
 public:
  AutoSolver();
  explicit AutoSolver(const AutoOptions& options);
  // lookup creates the candidates auto does not build itself (newton-min, ipopt: the MCP chain), on first use.
  AutoSolver(const AutoOptions& options, BackendLookup lookup);
  ~AutoSolver() override;
  AutoSolver(const AutoSolver&) = delete;
  AutoSolver& operator=(const AutoSolver&) = delete;

  const SolverInfo& info() const override;

  // The backend auto would hand this problem to first (owned by this AutoSolver), without solving; nullptr while
  // auto's own options are invalid (Solve then reports them).
  Solver* DelegateFor(const BoxMLCP& problem, const SolverOptions& options) override;
  // The session's call of that delegate did not solve the problem. When the chain ends there (a status it does not
  // pass on, or no candidate after it), *result becomes auto's answer as Solve would give it (true); otherwise the
  // next Solve of this matrix goes on with the candidate after it (its message names the delegate's failure;
  // fallbacks counts it), instead of running the delegate again (false).
  bool NoteDelegateFailure(const BoxMLCP& problem, const Solver& delegate, SolveResult* result) override;
  // Forgets the candidate a fallback made the first choice for the current matrix (the chain starts at the rule's
  // choice again; the classification itself depends on M alone and stays), and whatever each created candidate
  // keeps (their ForgetWarmState).
  WarmStateReset ForgetWarmState() override;
  // The candidates auto tries on this problem, in order (cached per matrix_id; may cost a Cholesky of M once).
  // Inline: the cached case is three comparisons on every solve.
  const AutoChoice& ChoiceFor(const BoxMLCP& problem) {
    // The rule reads auto's options and enum's size limits.
    if (choice_matrix_id_ == problem.matrix_id() && choice_generation_ == option_generation() &&
        choice_enum_generation_ == candidates_[static_cast<int>(AutoCandidate::kEnum)]->option_generation()) {
      return choice_;
    }
    return Reclassify(problem);
  }
  // The instance auto uses for one candidate (its options can be changed there). The box candidates always exist;
  // newton-min and ipopt only when the lookup knows them (created here on first use), else candidate() throws
  // std::logic_error and FindCandidate returns nullptr.
  // Inline: the box chain asks for its candidates on every solve, and the paper's solves are tens of nanoseconds.
  Solver& candidate(AutoCandidate c) {
    Solver* solver = candidates_[static_cast<int>(c)].get();
    return solver != nullptr ? *solver : CreateCandidate(c);
  }
  const Solver& candidate(AutoCandidate c) const;
  Solver* FindCandidate(AutoCandidate c);
  // The instance that runs entry `at` of a choice: candidate(order[at]), except psor on a choice with
  // psor_backward, which runs as the backward-sweep instance. Inline: on every solve.
  Solver& Backend(const AutoChoice& choice, int at) {
    const AutoCandidate c = choice.order[at];
    return choice.psor_backward && c == AutoCandidate::kPsor ? BackwardPsor() : candidate(c);
  }
  // The backward-sweep psor, with the psor candidate's current options but sweep = backward (created on first
  // use, its options copied again when the candidate's change).
  Solver& BackwardPsor();
  // The MCP chain on this build, in order (newton, then newton-min and ipopt where the lookup knows them).
  AutoChoice McpChoice();

 protected:
  void DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) override;
  void DoSolveMCP(const MCP& problem, const SolverOptions& options, SolveResult* result) override;
  void BindOptions(OptionBinder* binder) override;
  bool ValidateBackendOptions(std::string* why) const override;

 private:
  // The rule above, for a problem not seen before.
  AutoChoice Classify(const BoxMLCP& problem) const;
  // DoSolve past the first candidate's answer (have_answer: result holds it) or after a session's failed delegate
  // (NoteDelegateFailure): the rest of the chain, the messages and the label. Out of line, so the common case (the
  // choice answers) sets up nothing.
  [[gnu::noinline]] void SolveChain(const BoxMLCP& problem, const SolverOptions& given, bool have_answer,
                                    SolveResult* result);
  // The end of every box solve, on the answer of the candidate it stopped at: "infeasible" from a backend that is
  // not exact becomes a numerical failure (it is not a proof).
  static void RefuseInexactInfeasible(const Solver& answered, SolveResult* result);
  // ChoiceFor's slow half: classifies the problem and caches the choice.
  const AutoChoice& Reclassify(const BoxMLCP& problem);
  // The options the candidate gets: the caller's, with measure_time off (the base times auto's call; the
  // candidate's own two clock reads would only add to it).
  const SolverOptions& UntimedOptions(const SolverOptions& options);
  // candidate()'s first use of a looked-up candidate: creates it, or throws std::logic_error when not registered.
  Solver& CreateCandidate(AutoCandidate c);

  std::array<std::unique_ptr<Solver>, kAutoCandidateCount> candidates_;
  // BackwardPsor's instance (nullptr until first used) and the psor candidate's option generation it copied.
  std::unique_ptr<PsorSolver> backward_psor_;
  std::uint64_t backward_psor_generation_ = 0;
  BackendLookup lookup_;
  // Candidates the lookup was asked for (created or not), so an unknown name is looked up once.
  std::array<bool, kAutoCandidateCount> looked_up_{};
  // ChoiceFor's cache: the last matrix seen (0: none) and the option generations (auto's, enum's) it was decided
  // under.
  std::uint64_t choice_matrix_id_ = 0;
  std::uint64_t choice_generation_ = 0;
  std::uint64_t choice_enum_generation_ = 0;
  AutoChoice choice_;
  // NoteDelegateFailure's one-shot skip: the next Solve of matrix skip_matrix_id_ starts at choice_.first + 1, its
  // trail beginning with skip_trail_ (0: no skip pending).
  std::uint64_t skip_matrix_id_ = 0;
  std::string skip_trail_;
  // UntimedOptions' copy, kept to avoid allocating per solve.
  SolverOptions delegate_options_;
};

}  // namespace smcbench

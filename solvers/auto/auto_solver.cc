#include "solvers/auto/auto_solver.h"

#include <Eigen/Cholesky>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "solvers/core/matrix_class.h"
#include "solvers/enumerative/enumerative_solver.h"
#include "solvers/lemke/lemke_solver.h"
#include "solvers/newton/semismooth_newton_solver.h"
#include "solvers/pivoting/bpp_solver.h"
#include "solvers/psor/psor_solver.h"

namespace smcbench {

namespace {

constexpr std::string_view kCandidateNames[kAutoCandidateCount] = {"enum",       "psor",  "lemke", "newton",
                                                                   "newton-min", "ipopt", "bpp"};

// Whether the chain goes on after a candidate returned `status`: not after an answer, a proof (kInfeasible from
// an exact backend), the caller's spent time budget, or options every candidate would refuse.
bool PassOn(SolveStatus status, bool exact) {
  switch (status) {
    case SolveStatus::kSolved:
    case SolveStatus::kTimeLimit:
    case SolveStatus::kInvalidOptions:
      return false;
    case SolveStatus::kInfeasible:
      return !exact;
    default:
      return true;
  }
}

// Rows with a choice of state (enum's size measure: free rows l = −∞, u = +∞ and fixed rows l = u have none), the
// number of active sets a full enumeration may need (2 states per half-bounded row, 3 per finite box), and the size
// of lemke's LCP (one variable per row with a choice, plus the upper-bound multiplier of each finite box row).
struct RowCounts {
  int choice = 0;
  double active_sets = 1.0;
  int lemke_size = 0;
};
RowCounts CountRows(const BoxMLCP& problem) {
  RowCounts c;
  for (int i = 0; i < problem.size(); ++i) {
    const double l = problem.l()[i], u = problem.u()[i];
    const bool lower = std::isfinite(l), upper = std::isfinite(u);
    if (!(l < u) || (!lower && !upper)) continue;
    ++c.choice;
    c.active_sets *= lower && upper ? 3.0 : 2.0;
    c.lemke_size += lower && upper ? 2 : 1;
  }
  return c;
}

// Predicted time of lemke over that of psor on SPD M (docs/auto.md, measured at m = 16 … 256, condition 1e2 … 1e8):
// psor takes about 3·√(1/rcond) sweeps of m² entry updates (rcond: the reciprocal 1-norm condition estimate of M),
// lemke about p/2 pivots of p² updates on its LCP of size p; the cost of an update of each (the two constants
// below) was measured on the reference machine (docs/auto.md, "Why these thresholds").
double LemkeOverPsor(int m, int lemke_size, double rcond) {
  const double m2 = static_cast<double>(m) * m, p = lemke_size;
  return (0.5 * p * p * p * 0.2) / (3.0 * std::sqrt(1.0 / rcond) * m2 * 0.16);
}

// The reciprocal condition estimate of M if it is symmetric positive definite (a Cholesky attempt: m³/3 flops,
// once per matrix), else 0. Symmetry is matrix_class.h's test; the Cholesky stays here without a margin because
// the rule needs its condition estimate, which a tiny λ_min already makes small.
double SpdReciprocalCondition(const BoxMLCP& problem) {
  if (!problem.IsSymmetric()) return 0.0;
  const Eigen::LLT<DenseMatrix> cholesky(problem.dense_matrix());
  return cholesky.info() == Eigen::Success ? cholesky.rcond() : 0.0;
}

// ‖M − Mᵀ‖_F > kSkewDominanceRatio·‖M + Mᵀ‖_F: the unsymmetric part of M outweighs its symmetric part (m² work,
// once per matrix). The generators' strongly nonsymmetric P-matrices (unit-entry skew part) are at 4-8 from 16 rows
// on, their nonsymmetric P-matrices (skew part of the symmetric part's 2-norm) near 1, where bpp is the fastest.
constexpr double kSkewDominanceRatio = 4.0;

bool SkewDominant(const DenseMatrix& M) {
  return SymmetricAndSkewPartNorms(M).SkewOutweighsSymmetric(kSkewDominanceRatio);
}

// Which triangle of M holds its off-diagonal nonzeros, when that is one triangle and the diagonal is positive.
enum class Triangular { kNo, kLower, kUpper };

// M triangular (every entry on one side of the diagonal exactly 0) with a positive diagonal: then the box-MLCP has
// one solution, found by substitution, z_i = Π_[l_i,u_i](−(q_i + Σ_{j≠i} M_ij z_j) / M_ii) with the z_j known so far,
// which is what one projected Gauss–Seidel sweep computes: in row order for lower triangular M (the forward
// substitution), in reverse row order for upper triangular M (the back substitution); psor's second sweep confirms
// it. Murty's family is the case (lemke takes 2ⁿ pivots there from the standard start, bpp one set per row). The
// scan, column by column, stops once it has seen a nonzero on both sides, so a matrix that is not triangular pays a
// few reads. A diagonal M is kLower (the forward sweep, psor's default).
Triangular TriangularWithPositiveDiagonal(const DenseMatrix& M) {
  const Eigen::Index n = M.rows();
  bool above = false, below = false;
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::Index i = 0; i < j && !above; ++i) above = M(i, j) != 0.0;
    for (Eigen::Index i = j + 1; i < n && !below; ++i) below = M(i, j) != 0.0;
    if (above && below) return Triangular::kNo;
  }
  if (!(M.diagonal().array() > 0.0).all()) return Triangular::kNo;
  return above ? Triangular::kUpper : Triangular::kLower;
}

}  // namespace

std::string_view AutoCandidateName(int index) {
  return index >= 0 && index < kAutoCandidateCount ? kCandidateNames[index] : std::string_view();
}

int AutoCandidateIndex(std::string_view name) {
  for (int i = 0; i < kAutoCandidateCount; ++i) {
    if (kCandidateNames[i] == name) return i;
  }
  return -1;
}

std::string_view ToString(AutoCandidate candidate) { return AutoCandidateName(static_cast<int>(candidate)); }

std::optional<AutoCandidate> AutoCandidateFromString(std::string_view name) {
  const int index = AutoCandidateIndex(name);
  return index >= 0 ? std::optional(static_cast<AutoCandidate>(index)) : std::nullopt;
}

namespace {
// AutoOptions::IsValid's failure path, out of line: the messages' strings set up in the function that runs on every
// Solve cost the valid case its frame (30 instructions a call).
[[gnu::noinline, gnu::cold]] bool ExplainInvalid(const AutoOptions& o, std::string* why) {
  const int enum_limit = EnumerativeOptions{}.size_limit;
  if (o.enum_max_choice_rows < 0 || o.enum_max_choice_rows > enum_limit) {
    *why = "enum_max_choice_rows must be in [0, " + std::to_string(enum_limit) + "] (enum's size_limit), got " +
           std::to_string(o.enum_max_choice_rows);
  } else if (!(o.enum_max_active_sets >= 0.0)) {
    *why = "enum_max_active_sets must be >= 0 (0: never enum), got " + std::to_string(o.enum_max_active_sets);
  } else if (o.bpp_max_size < 0) {
    *why = "bpp_max_size must be >= 0 (0: never bpp), got " + std::to_string(o.bpp_max_size);
  } else if (o.sparse_bpp_max_size < 0) {
    *why = "sparse_bpp_max_size must be >= 0 (0: never bpp on sparse M), got " +
           std::to_string(o.sparse_bpp_max_size);
  } else if (o.skew_lemke_min_size < 0) {
    *why = "skew_lemke_min_size must be >= 0 (0: never skip bpp), got " + std::to_string(o.skew_lemke_min_size);
  } else {
    *why = "psor_min_speedup must be >= 0 (0: psor on every SPD M, inf: never), got " +
           std::to_string(o.psor_min_speedup);
  }
  return false;
}
}  // namespace

bool AutoOptions::IsValid(std::string* why) const {
  const bool ok = enum_max_choice_rows >= 0 && enum_max_choice_rows <= EnumerativeOptions{}.size_limit &&
                  enum_max_active_sets >= 0.0 && bpp_max_size >= 0 && skew_lemke_min_size >= 0 && sparse_bpp_max_size >= 0 &&
                  psor_min_speedup >= 0.0;
  return ok || ExplainInvalid(*this, why);
}

AutoSolver::AutoSolver() : AutoSolver(AutoOptions{}) {}

AutoSolver::AutoSolver(const AutoOptions& options) : AutoSolver(options, BackendLookup()) {}

AutoSolver::AutoSolver(const AutoOptions& options, BackendLookup lookup)
    : BackendWithOptions(options), lookup_(std::move(lookup)) {
  candidates_[static_cast<int>(AutoCandidate::kEnum)] = std::make_unique<EnumerativeSolver>();
  candidates_[static_cast<int>(AutoCandidate::kPsor)] = std::make_unique<PsorSolver>();
  candidates_[static_cast<int>(AutoCandidate::kLemke)] = std::make_unique<LemkeSolver>();
  candidates_[static_cast<int>(AutoCandidate::kNewton)] = std::make_unique<SemismoothNewtonSolver>();
  // bpp's single-pivot phase is cut at max(4, n/4) pivots, then the next candidate answers (docs/auto.md,
  // auto_rule_measure handover): a cap never reached on the classes bpp solves in its block phase.
  BppOptions bpp;
  bpp.single_pivots_per_row = 0.25;
  candidates_[static_cast<int>(AutoCandidate::kBpp)] = std::make_unique<BppSolver>(bpp);
  for (const AutoCandidate own : {AutoCandidate::kEnum, AutoCandidate::kPsor, AutoCandidate::kLemke,
                                  AutoCandidate::kNewton, AutoCandidate::kBpp}) {
    looked_up_[static_cast<int>(own)] = true;
  }
}

Solver* AutoSolver::FindCandidate(AutoCandidate c) {
  const int i = static_cast<int>(c);
  if (!looked_up_[i]) {
    looked_up_[i] = true;
    if (lookup_) candidates_[i] = lookup_(kCandidateNames[i]);
  }
  return candidates_[i].get();
}

Solver& AutoSolver::CreateCandidate(AutoCandidate c) {
  Solver* solver = FindCandidate(c);
  if (solver == nullptr) {
    throw std::logic_error("auto: candidate '" + std::string(AutoCandidateName(static_cast<int>(c))) +
                           "' is not registered in this build");
  }
  return *solver;
}

const Solver& AutoSolver::candidate(AutoCandidate c) const {
  const Solver* solver = candidates_[static_cast<int>(c)].get();
  if (solver == nullptr) {
    throw std::logic_error("auto: candidate '" + std::string(AutoCandidateName(static_cast<int>(c))) +
                           "' is not created (non-const candidate() or FindCandidate creates it)");
  }
  return *solver;
}

Solver& AutoSolver::BackwardPsor() {
  const auto& configured = static_cast<const PsorSolver&>(candidate(AutoCandidate::kPsor));
  if (backward_psor_ == nullptr || backward_psor_generation_ != configured.option_generation()) {
    PsorOptions options = configured.options();
    options.sweep = PsorOptions::kBackwardSweep;
    if (backward_psor_ == nullptr) {
      backward_psor_ = std::make_unique<PsorSolver>(options);
    } else {
      backward_psor_->set_options(options);
    }
    backward_psor_generation_ = configured.option_generation();
  }
  return *backward_psor_;
}

AutoChoice AutoSolver::McpChoice() {
  AutoChoice c;
  for (const AutoCandidate candidate : {AutoCandidate::kNewton, AutoCandidate::kNewtonMin, AutoCandidate::kIpopt}) {
    Solver* solver = FindCandidate(candidate);
    if (solver != nullptr && solver->info().mcp) c.order[c.count++] = candidate;
  }
  return c;
}

AutoSolver::~AutoSolver() = default;

const SolverInfo& AutoSolver::info() const {
  static const SolverInfo kInfo{
      "auto",
      "picks per problem the fastest backend that is exact or reliable for its class: psor (dense triangular; "
      "the backward sweep on upper triangular M), enum (dense, few rows with a choice), bpp (dense, up to 256 "
      "rows), psor (dense SPD, well conditioned), lemke (other dense), newton (sparse, nonlinear MCP); on a "
      "failure that proves nothing it tries the next (psor, lemke, newton; MCPs: newton-min, ipopt); a session "
      "gets the first candidate after bpp; details chosen, fallbacks",
      "docs/auto.md (the rule and the measurements behind it); the chosen backend's own reference",
      /*dense=*/true,
      /*sparse=*/true,
      /*symmetric_only=*/false,
      /*exact=*/false,
      /*mcp=*/true,
      /*default_size_limit=*/0,
      // The chosen backend equilibrates the problem itself; doing it here too would only cost a copy per call.
      /*equilibrate=*/false,
      // ... and its Solve polishes, computes the merit function and applies the rule: the base skips them here.
      /*delegates=*/true};
  return kInfo;
}

void AutoSolver::BindOptions(OptionBinder* binder) {
  binder->Add("enum_max_choice_rows", &options_.enum_max_choice_rows,
              "dense problems with at most this many rows with a choice of state (l < u, not free) go to enum");
  binder->Add("enum_max_active_sets", &options_.enum_max_active_sets,
              "... and at most this many active sets (2 per one-sided row, 3 per finite box)");
  binder->Add("psor_min_speedup", &options_.psor_min_speedup,
              "dense SPD M goes to psor when lemke's predicted time is at least this many times psor's (0: always)");
  binder->Add("bpp_max_size", &options_.bpp_max_size,
              "dense problems past enum's rows with at most this many rows go to bpp first (0: never)");
  binder->Add("sparse_bpp_max_size", &options_.sparse_bpp_max_size,
              "sparse problems with at most this many rows go to bpp (its SparseLU path) before newton (0: never)");
  binder->Add("skew_lemke_min_size", &options_.skew_lemke_min_size,
              "skew-dominant M (||M - M'|| > 4 ||M + M'||, Frobenius) with at least this many rows skips bpp (0: never)");
  binder->Add("fallback", &options_.fallback, "try the next candidate when the chosen one fails without a proof");
}

bool AutoSolver::ValidateBackendOptions(std::string* why) const { return options_.IsValid(why); }

AutoChoice AutoSolver::Classify(const BoxMLCP& problem) const {
  AutoChoice c;
  const auto add = [&c](AutoCandidate candidate) { c.order[c.count++] = candidate; };
  const RowCounts rows = CountRows(problem);
  const auto& enum_options = static_cast<const EnumerativeSolver&>(candidate(AutoCandidate::kEnum)).options();
  const bool enum_fits = rows.choice <= options_.enum_max_choice_rows && rows.choice <= enum_options.size_limit &&
                         rows.active_sets <= options_.enum_max_active_sets &&
                         rows.active_sets <= enum_options.max_candidates;
  if (problem.is_sparse()) {
    // A small sparse problem is solved on a dense copy (enum) or by bpp's sparse LU per set; larger ones by newton.
    if (problem.size() <= options_.sparse_bpp_max_size) add(enum_fits ? AutoCandidate::kEnum : AutoCandidate::kBpp);
    add(AutoCandidate::kNewton);
    if (problem.size() <= kMaxDensifiedSize) add(AutoCandidate::kLemke);
    return c;
  }
  // From 5 rows: up to 4 enum's fixed-size kernel answers as fast (the paper's one-step problems and the
  // time-steppers' diagonal M stay there).
  const Triangular triangular =
      problem.size() > 4 ? TriangularWithPositiveDiagonal(problem.dense_matrix()) : Triangular::kNo;
  if (triangular != Triangular::kNo) {
    add(AutoCandidate::kPsor);
    c.psor_backward = triangular == Triangular::kUpper;
  } else if (enum_fits) {
    add(AutoCandidate::kEnum);
  } else {
    const bool skew = options_.skew_lemke_min_size > 0 && problem.size() >= options_.skew_lemke_min_size &&
                      SkewDominant(problem.dense_matrix());
    if (problem.size() <= options_.bpp_max_size && !skew) add(AutoCandidate::kBpp);
    const double rcond = rows.lemke_size > 0 ? SpdReciprocalCondition(problem) : 0.0;
    if (rcond > 0.0 && LemkeOverPsor(problem.size(), rows.lemke_size, rcond) >= options_.psor_min_speedup) {
      add(AutoCandidate::kPsor);
    }
  }
  add(AutoCandidate::kLemke);
  add(AutoCandidate::kNewton);
  return c;
}

const AutoChoice& AutoSolver::Reclassify(const BoxMLCP& problem) {
  const std::uint64_t enum_generation = candidate(AutoCandidate::kEnum).option_generation();
  choice_matrix_id_ = 0;  // a throw below (out of memory in the Cholesky) must not leave a stale choice
  choice_ = Classify(problem);
  choice_matrix_id_ = problem.matrix_id();
  choice_generation_ = option_generation();
  choice_enum_generation_ = enum_generation;
  return choice_;
}

Solver* AutoSolver::DelegateFor(const BoxMLCP& problem, const SolverOptions&) {
  // Invalid options of auto's own: no delegate, so the caller's solves come here and report them.
  std::string why;
  if (!options_.IsValid(&why)) return nullptr;
  const AutoChoice& choice = ChoiceFor(problem);
  return &Backend(choice, choice.first);
}

WarmStateReset AutoSolver::ForgetWarmState() {
  WarmStateReset reset = WarmStateReset::kNothingRemembered;
  skip_matrix_id_ = 0;
  if (choice_.first != 0) {
    choice_.first = 0;
    reset = WarmStateReset::kForgotten;
  }
  for (const std::unique_ptr<Solver>& c : candidates_) {
    if (c != nullptr) reset = LeastCold(reset, c->ForgetWarmState());
  }
  if (backward_psor_ != nullptr) reset = LeastCold(reset, backward_psor_->ForgetWarmState());
  return reset;
}

const SolverOptions& AutoSolver::UntimedOptions(const SolverOptions& options) {
  if (!options.measure_time) return options;
  delegate_options_ = options;  // no allocation while the warm start keeps its size
  delegate_options_.measure_time = false;
  return delegate_options_;
}

bool AutoSolver::NoteDelegateFailure(const BoxMLCP& problem, const Solver& delegate, SolveResult* result) {
  skip_matrix_id_ = 0;
  if (DelegateFor(problem, {}) != &delegate) return false;
  const AutoChoice& choice = ChoiceFor(problem);
  const bool refused = result->status == SolveStatus::kInvalidOptions;  // Solve refuses them with its own message
  if (!refused && (!options_.fallback || choice.first + 1 >= choice.count ||
                   !PassOn(result->status, delegate.info().exact))) {
    // Solve would run the delegate again and stop there (SolveChain with no candidate passed): its answer, labelled.
    RefuseInexactInfeasible(delegate, result);
    LabelAutoAnswer(choice.order[choice.first], 0, result);
    return true;
  }
  skip_matrix_id_ = problem.matrix_id();
  skip_trail_ = std::string(delegate.info().name) + " " + std::string(ToString(result->status)) +
                (result->message.empty() ? "" : " (" + result->message + ")");
  return false;
}

void AutoSolver::RefuseInexactInfeasible(const Solver& answered, SolveResult* result) {
  if (result->status == SolveStatus::kInfeasible && !answered.info().exact) {
    result->status = SolveStatus::kNumericalFailure;
    result->message = std::string(answered.info().name) + " reported infeasible, which is not a proof (it is not "
                      "exact): " + result->message;
  }
}

void AutoSolver::DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) {
  const AutoChoice& choice = ChoiceFor(problem);
  const SolverOptions& given = UntimedOptions(options);
  if (skip_matrix_id_ != 0) return SolveChain(problem, given, /*answered=*/false, result);
  // The common case first, with nothing else to set up: the choice answers.
  const AutoCandidate first = choice.order[choice.first];
  Backend(choice, choice.first).Solve(problem, given, result);
  if (result->status == SolveStatus::kSolved) return LabelAutoAnswer(first, 0, result);
  SolveChain(problem, given, /*answered=*/true, result);
}

void AutoSolver::SolveChain(const BoxMLCP& problem, const SolverOptions& given, bool have_answer,
                            SolveResult* result) {
  const AutoChoice& choice = choice_;
  const int last = options_.fallback ? choice.count - 1 : choice.first;
  int at = choice.first;
  std::string trail;  // the failed candidates, for the message (written only on the fallback path)
  if (skip_matrix_id_ != 0) {
    // The session ran the first candidate already (NoteDelegateFailure): go on after it.
    if (skip_matrix_id_ == problem.matrix_id() && at < last) {
      ++at;
      trail = std::move(skip_trail_);
    }
    skip_matrix_id_ = 0;
  }
  for (;;) {
    Solver& backend = Backend(choice, at);
    if (!have_answer) backend.Solve(problem, given, result);
    have_answer = false;
    if (at == last || !PassOn(result->status, backend.info().exact)) break;
    trail += std::string(trail.empty() ? "" : "; ") + std::string(backend.info().name) + " " +
             std::string(ToString(result->status)) + (result->message.empty() ? "" : " (" + result->message + ")");
    ++at;
  }
  const int fallbacks = at - choice.first;
  const Solver& answered = Backend(choice_, at);
  RefuseInexactInfeasible(answered, result);
  if (!trail.empty()) {
    if (result->solved()) {
      choice_.first = at;  // later calls on this matrix start with the candidate that answered
    } else {
      result->message = "after " + trail + ": " + std::string(answered.info().name) + " " +
                        std::string(ToString(result->status)) + (result->message.empty() ? "" : " (" +
                        result->message + ")");
    }
  }
  LabelAutoAnswer(choice.order[at], fallbacks, result);
}

// The box chain's rule for passing on, over the MCP chain (no backend there is exact: nothing it says is a proof).
void AutoSolver::DoSolveMCP(const MCP& problem, const SolverOptions& options, SolveResult* result) {
  const AutoChoice choice = McpChoice();
  const SolverOptions& given = UntimedOptions(options);
  const int last = options_.fallback ? choice.count - 1 : 0;
  int at = 0;
  std::string trail;
  for (;;) {
    Solver& backend = candidate(choice.order[at]);
    backend.Solve(problem, given, result);
    if (at == last || !PassOn(result->status, /*exact=*/false)) break;
    trail += std::string(trail.empty() ? "" : "; ") + std::string(backend.info().name) + " " +
             std::string(ToString(result->status)) + (result->message.empty() ? "" : " (" + result->message + ")");
    ++at;
  }
  const Solver& answered = candidate(choice.order[at]);
  if (result->status == SolveStatus::kInfeasible) {
    result->status = SolveStatus::kNumericalFailure;
    result->message = std::string(answered.info().name) + " reported infeasible, which is not a proof for a "
                      "nonlinear MCP: " + result->message;
  }
  if (!trail.empty() && !result->solved()) {
    result->message = "after " + trail + ": " + std::string(answered.info().name) + " " +
                      std::string(ToString(result->status)) + (result->message.empty() ? "" : " (" +
                      result->message + ")");
  }
  LabelAutoAnswer(choice.order[at], at, result);
}

}  // namespace smcbench

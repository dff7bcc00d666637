// The Siconos Numerics adapters (see siconos_solver.h): the registry entries, the in-process Siconos call
// (SiconosSession, also what the worker process runs) and the worker protocol.
#include "solvers/siconos/siconos_solver.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

// Siconos Numerics C API (include directories: /usr/include/siconos and /usr/include/siconos/numerics).
#include "LCP_Solvers.h"
#include "LinearComplementarityProblem.h"
#include "MLCP_Solvers.h"
#include "MixedLinearComplementarityProblem.h"
#include "NonSmoothDrivers.h"
#include "NumericsMatrix.h"
#include "NumericsVerbose.h"
#include "RelayProblem.h"
#include "Relay_Solvers.h"
#include "SolverOptions.h"
#include "AVI_cst.h"
#include "avi_caoferris.h"
#include "lcp_cst.h"
#include "mlcp_cst.h"
#include "relay_cst.h"
#include "solvers/siconos/external_backends.h"
#include "solvers/siconos/siconos_avi_solver.h"
#include "solvers/siconos/siconos_mcp_solver.h"
#include "solvers/isolation/swapped_stdio.h"
#include "solvers/isolation/worker_call.h"

namespace smcbench {
// Method table and wire format, shared by the backend and its worker (named, not anonymous: SiconosSession and
// SiconosSolver::Outcome use them).
namespace siconos_detail {

// kAviStage3: an LCP whose first rows are covered (avi_caoferris_stage3), given in the LCP form.
enum class Family { kRelay, kLcp, kMlcp, kAviStage3 };
// What an info ≠ 0 means depends on the algorithm behind the method (for direct-* methods: their fallback).
enum class Algorithm { kLemke, kPgs, kEnum, kAvi, kNewton };

struct Spec {
  SiconosMethod method;
  int siconos_id;
  Family family;
  Algorithm algorithm;
  bool direct;  // keeps an active-set cache between solves (mlcp_direct_*)
  SolverInfo info;
};

[[maybe_unused]] constexpr std::string_view kSiconosRef =
    "Siconos Numerics 4.4 (INRIA, Acary et al.; Debian libsiconos-numerics-dev)";

const Spec& SpecOf(SiconosMethod method) {
  static const Spec kSpecs[kNumSiconosMethods] = {
      {SiconosMethod::kRelayLemke, SICONOS_RELAY_LEMKE, Family::kRelay, Algorithm::kLemke, false,
       {"siconos-relay-lemke",
        "Siconos relay_lexicolemke: Siconos' own relay -> LCP doubling (2n unknowns), then lexicographic Lemke; "
        "needs finite bounds on every row",
        "Siconos Numerics 4.4 relay_lexicolemke; Cottle, Pang & Stone 1992, The Linear Complementarity Problem, "
        "ch. 4",
        true, false, false, true, false, 0, /*equilibrate=*/false, /*delegates=*/false, /*external=*/true}},
      {SiconosMethod::kRelayPgs, SICONOS_RELAY_PGS, Family::kRelay, Algorithm::kPgs, false,
       {"siconos-relay-pgs",
        "Siconos relay_pgs: projected Gauss-Seidel sweeps on the box problem; needs finite bounds on every row",
        "Siconos Numerics 4.4 relay_pgs; Cottle, Pang & Stone 1992, sec. 5.2", true, false, false, false, false,
        0, /*equilibrate=*/false, /*delegates=*/false, /*external=*/true}},
      {SiconosMethod::kRelayEnum, SICONOS_RELAY_ENUM, Family::kRelay, Algorithm::kEnum, false,
       {"siconos-relay-enum",
        "Siconos relay_enum: relay -> LCP (2n unknowns), enumeration of complementary bases; needs finite bounds",
        "Siconos Numerics 4.4 relay_enum / lcp_enum; Murty 1988, Linear Complementarity, ch. 1", true, false,
        false, true, false, 8, /*equilibrate=*/false, /*delegates=*/false, /*external=*/true}},
      {SiconosMethod::kRelayAvi, SICONOS_RELAY_AVI_CAOFERRIS, Family::kRelay, Algorithm::kAvi, false,
       {"siconos-relay-avi",
        "Siconos relay_avi_caoferris (its default relay solver): the relay as an affine variational inequality "
        "over the box, solved by Cao & Ferris' pivotal method; needs finite bounds",
        "Siconos Numerics 4.4 relay_avi_caoferris; Cao & Ferris 1996, A pivotal method for affine variational "
        "inequalities, Math. Oper. Res. 21(1)",
        true, false, false, true, false, 0, /*equilibrate=*/false, /*delegates=*/false, /*external=*/true}},
      {SiconosMethod::kLcpLemke, SICONOS_LCP_LEMKE, Family::kLcp, Algorithm::kLemke, false,
       {"siconos-lcp-lemke",
        "Siconos lcp_lexicolemke on the box -> LCP rewriting (shifted / negated one-sided rows, doubled box "
        "rows); no free rows",
        "Siconos Numerics 4.4 lcp_lexicolemke; Cottle, Pang & Stone 1992, ch. 4", true, false, false, true, false,
        0, /*equilibrate=*/false, /*delegates=*/false, /*external=*/true}},
      {SiconosMethod::kLcpNewtonFb, SICONOS_LCP_NEWTON_FB_FBLSA, Family::kLcp, Algorithm::kNewton, false,
       {"siconos-lcp-newton-fb",
        "Siconos lcp_newton_FB: nonsmooth Newton on the Fischer-Burmeister reformulation with a line search on "
        "its merit function, on the box -> LCP rewriting; no free rows",
        "Siconos Numerics 4.4 lcp_newton_FB; De Luca, Facchinei & Kanzow 1996, Math. Program. 75; Facchinei & "
        "Pang 2003, ch. 9",
        true, false, false, false, false, 0, /*equilibrate=*/false, /*delegates=*/false, /*external=*/true}},
      {SiconosMethod::kLcpNewtonMin, SICONOS_LCP_NEWTON_MIN_FBLSA, Family::kLcp, Algorithm::kNewton, false,
       {"siconos-lcp-newton-min",
        "Siconos lcp_newton_minFB: nonsmooth Newton on the min reformulation, line search on the "
        "Fischer-Burmeister merit function, on the box -> LCP rewriting; no free rows",
        "Siconos Numerics 4.4 lcp_newton_minFB; Facchinei & Pang 2003, Finite-Dimensional Variational "
        "Inequalities and Complementarity Problems, ch. 9",
        true, false, false, false, false, 0, /*equilibrate=*/false, /*delegates=*/false, /*external=*/true}},
      {SiconosMethod::kMlcpEnum, SICONOS_MLCP_ENUM, Family::kMlcp, Algorithm::kEnum, false,
       {"siconos-mlcp-enum",
        "Siconos mlcp_enum: enumeration of the complementarity configurations of the standard MLCP (free rows "
        "as equalities, the rest as the box -> LCP rewriting)",
        "Siconos Numerics 4.4 mlcp_enum; Murty 1988, ch. 1", true, false, false, true, false, 16, /*equilibrate=*/false, /*delegates=*/false, /*external=*/true}},
      {SiconosMethod::kMlcpLemke, SICONOS_MLCP_LCP_LEMKE, Family::kMlcp, Algorithm::kLemke, false,
       {"siconos-mlcp-lemke",
        "Siconos mlcp_lcp_lemke: eliminates the equality block by its Schur complement (needs it invertible), "
        "then lexicographic Lemke; needs at least one free and one sign-constrained row",
        "Siconos Numerics 4.4 mlcp_lcp_lemke; Cottle, Pang & Stone 1992, sec. 1.5 and ch. 4", true, false,
        false, true, false, 0, /*equilibrate=*/false, /*delegates=*/false, /*external=*/true}},
      {SiconosMethod::kMlcpFb, SICONOS_MLCP_FB, Family::kMlcp, Algorithm::kNewton, false,
       {"siconos-mlcp-fb",
        "Siconos mlcp_FB: nonsmooth Newton with line search on the Fischer-Burmeister reformulation of the "
        "standard MLCP",
        "Siconos Numerics 4.4 mlcp_FB (NonSmoothNewton); De Luca, Facchinei & Kanzow 1996", true, false, false,
        false, false, 0, /*equilibrate=*/false, /*delegates=*/false, /*external=*/true}},
      {SiconosMethod::kMlcpDirectEnum, SICONOS_MLCP_DIRECT_ENUM, Family::kMlcp, Algorithm::kEnum, true,
       {"siconos-mlcp-direct-enum",
        "Siconos mlcp_direct_enum: solves with the last active sets that worked (up to 3, cached per worker "
        "process) and falls back to mlcp_enum",
        "Siconos Numerics 4.4 mlcp_direct_enum; Murty 1988, ch. 1", true, false, false, true, false, 16, /*equilibrate=*/false, /*delegates=*/false, /*external=*/true}},
      {SiconosMethod::kMlcpDirectFb, SICONOS_MLCP_DIRECT_FB, Family::kMlcp, Algorithm::kNewton, true,
       {"siconos-mlcp-direct-fb",
        "Siconos mlcp_direct_FB: solves with the last active sets that worked (up to 3, cached per worker "
        "process) and falls back to mlcp_FB",
        "Siconos Numerics 4.4 mlcp_direct_FB; De Luca, Facchinei & Kanzow 1996", true, false, false, false,
        false, 0, /*equilibrate=*/false, /*delegates=*/false, /*external=*/true}},
      {SiconosMethod::kAviCaoFerrisStage3, SICONOS_AVI_CAOFERRIS, Family::kAviStage3, Algorithm::kLemke, false,
       {"siconos-avi-caoferris",
        "Siconos avi_caoferris_stage3: Lemke's method with the covering vector on the vertex's rows, on the "
        "LCP-like problem of Cao & Ferris built at a vertex of P",
        "Siconos Numerics 4.4 avi_caoferris_stage3; Cao & Ferris 1996, Math. Oper. Res. 21(1)", true, false, false,
        true, false, 0, /*equilibrate=*/false, /*delegates=*/false, /*external=*/true}},
  };
  return kSpecs[static_cast<int>(method)];
}

// Fixed-size messages between the backend and its worker; the arrays follow them on the socket.
constexpr std::int32_t kMagic = 0x53494331;  // "SIC1"
// A Request with this magic (nothing follows it) asks the worker to start its next solve cold
// (SiconosSession::StartColdAgain); it answers with a Response carrying the same magic.
constexpr std::int32_t kForgetMagic = 0x53494346;  // "SICF"
constexpr int kMaxWireSize = 1 << 15;        // largest N the worker accepts

struct Request {
  std::int32_t magic = kMagic;
  std::int32_t method = 0;
  std::int32_t size = 0;           // N, unknowns of the rewritten problem
  std::int32_t num_equalities = 0;  // MLCP: free rows first
  std::int32_t max_iterations = 0;  // ≤ 0: Siconos' default
  std::int32_t verbose = 0;
  std::int32_t keep_cache = 1;  // direct-* may keep their active sets from earlier solves
  std::int32_t has_bounds = 0;  // relay: lower and upper bounds follow q
  std::int32_t covering_rows = 0;  // AVI stage 3: the vertex's rows, first (SiconosSolver::set_covering_rows)
  std::int32_t unused = 0;         // keeps the struct free of padding
  double tolerance = 1e-10;
};
// Hashed and compared bytewise (ProbedProblems): no padding bytes, whose values would be arbitrary.
static_assert(sizeof(Request) == 10 * sizeof(std::int32_t) + sizeof(double), "Request has padding");

struct Response {
  std::int32_t magic = kMagic;
  std::int32_t info = -1;            // what Siconos' driver returns (after its accuracy check, if it makes one)
  std::int32_t algorithm_info = -1;  // what the algorithm itself returned, before that check
  std::int32_t iterations = 0;
  std::int32_t budget = 0;  // iteration budget Siconos used
  std::int32_t console = 0;  // worker only: ProbedProblems::Console, what Siconos printed during this solve
  double error = NAN;  // Siconos' own error measure, if it set one
};

// Silences this process's stdout/stderr for the lifetime of the object (in-process calls only; the worker's
// output goes to /dev/null for good). dev_null is an open descriptor of /dev/null, or −1 to do nothing. The
// current stdout/stderr are duplicated per call, so a redirection made by the caller in the meantime (a test
// capturing stdout) is restored as it was. No allocation.
class QuietStdio {
 public:
  explicit QuietStdio(int dev_null) {
    if (dev_null < 0) return;
    std::fflush(stdout);
    std::fflush(stderr);
    saved_out_ = dup(STDOUT_FILENO);
    saved_err_ = dup(STDERR_FILENO);
    dup2(dev_null, STDOUT_FILENO);
    dup2(dev_null, STDERR_FILENO);
  }
  ~QuietStdio() {
    if (saved_out_ < 0) return;
    std::fflush(stdout);
    std::fflush(stderr);
    dup2(saved_out_, STDOUT_FILENO);
    dup2(saved_err_, STDERR_FILENO);
    close(saved_out_);
    close(saved_err_);
  }
  QuietStdio(const QuietStdio&) = delete;
  QuietStdio& operator=(const QuietStdio&) = delete;

 private:
  int saved_out_ = -1;
  int saved_err_ = -1;
};

bool AllFinite(const Vector& v) {
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) return false;
  }
  return true;
}

}  // namespace siconos_detail

using namespace siconos_detail;  // NOLINT: this file's own helpers

class SiconosSession;
namespace {
// Siconos' MLCP solvers keep their state in file-static variables (mlcp_direct.c: the direct solvers' active-set
// cache and pointers into the options' work arrays; mlcp_enum.c likewise), so at most one SiconosSession of a
// process can have an MLCP solver initialised. This names it, so that another session first releases it (its next
// solve re-initialises, a direct solver from an empty cache) instead of leaving it pointing into memory Siconos
// has moved on from. Global because Siconos' state is; in-process solves never run concurrently
// (siconos_solver.h). A worker process forgets the holder it inherited (ServeSiconos).
SiconosSession* mlcp_state_holder = nullptr;
}  // namespace

// Siconos' structs for one method, reused across solves of one size. In the worker this is the whole state.
class SiconosSession {
 public:
  SiconosSession() = default;
  ~SiconosSession() { Release(); }
  SiconosSession(const SiconosSession&) = delete;
  SiconosSession& operator=(const SiconosSession&) = delete;

  // Solves the rewritten problem: M is N×N column-major, lb/ub only for relay methods; x is the start point on
  // entry and Siconos' answer on return.
  Response Solve(const Request& r, const double* M, const double* q, const double* lb, const double* ub,
                 double* x);
  // For a direct method (mlcp_direct_*): drops its active-set cache and initialises Siconos' MLCP state for this
  // problem now (mlcp_driver_reset, then mlcp_driver_init), so that the next Solve of it starts from an empty cache
  // without paying the initialisation inside the solve, as a time-stepper's first step does. Other methods keep
  // nothing learned between solves: nothing to do.
  void StartCold(const Request& r, const double* M, const double* q);
  // The same for the problem last solved here (the worker's answer to kForgetMagic); nothing when there is none.
  void StartColdAgain();
  // Releases every Siconos struct of this session: the next Solve starts from nothing.
  void Release();

 private:
  // fresh: initialise even when the previous solve's state could be kept.
  void PrepareMlcp(const Request& r, const Spec& spec, const double* M, const double* q, bool fresh);

  int method_ = -1;
  int size_ = -1;
  int num_equalities_ = -1;
  int default_budget_ = 0;
  bool driver_checks_ = false;  // Siconos' default filterOn for this solver (relay and LCP drivers)
  ::SolverOptions* options_ = nullptr;  // Siconos' options (not smcbench::SolverOptions)
  NumericsMatrix* matrix_ = nullptr;
  bool mlcp_initialised_ = false;
  Request last_request_{};  // of the last Solve or StartCold (while method_ ≥ 0)
  MixedLinearComplementarityProblem mlcp_{};
  std::vector<double> q_, lb_, ub_, w_, last_M_;
  std::vector<double> A_, B_, C_, D_, a_, b_;  // the MLCP's ABCD storage (mlcp_lcp_lemke reads it)
  std::vector<double> stage3_u_, stage3_s_, stage3_d_;  // AVI stage 3: its u and s out, its covering vector in
  std::vector<unsigned> stage3_rows_;                   // AVI stage 3: A = {1, ..., covering rows}
};

void SiconosSession::Release() {
  if (mlcp_initialised_) mlcp_driver_reset(&mlcp_, options_);
  mlcp_initialised_ = false;
  if (mlcp_state_holder == this) mlcp_state_holder = nullptr;
  if (options_) solver_options_delete(options_);
  options_ = nullptr;
  if (matrix_) NM_free(matrix_);
  matrix_ = nullptr;
  method_ = -1;
  size_ = -1;
  num_equalities_ = -1;
}

void SiconosSession::PrepareMlcp(const Request& r, const Spec& spec, const double* M, const double* q,
                                 bool fresh) {
  const int N = r.size, n = r.num_equalities, m = N - n;
  // The direct solvers' cache describes M: it survives only while M (and the split) stays the same.
  const bool same_matrix = last_M_.size() == static_cast<std::size_t>(N) * N &&
                           std::memcmp(last_M_.data(), M, sizeof(double) * N * N) == 0;
  const bool reuse = !fresh && spec.direct && r.keep_cache && mlcp_initialised_ && mlcp_state_holder == this &&
                     method_ == r.method && size_ == N && num_equalities_ == n && same_matrix;
  if (!reuse) {
    if (mlcp_state_holder != nullptr && mlcp_state_holder != this) mlcp_state_holder->Release();
    Release();
    options_ = solver_options_create(spec.siconos_id);
    default_budget_ = options_->iparam[SICONOS_IPARAM_MAX_ITER];
    matrix_ = NM_create(NM_DENSE, N, N);
    if (M != last_M_.data()) last_M_.assign(M, M + static_cast<std::size_t>(N) * N);
    method_ = r.method;
    size_ = N;
    num_equalities_ = n;
  }
  std::memcpy(matrix_->matrix0, M, sizeof(double) * N * N);
  if (q != q_.data()) q_.assign(q, q + N);
  A_.resize(static_cast<std::size_t>(n) * n);
  B_.resize(static_cast<std::size_t>(m) * m);
  C_.resize(static_cast<std::size_t>(n) * m);
  D_.resize(static_cast<std::size_t>(m) * n);
  a_.assign(q, q + n);
  b_.assign(q + n, q + N);
  for (int j = 0; j < N; ++j) {
    for (int i = 0; i < N; ++i) {
      const double v = M[static_cast<std::size_t>(j) * N + i];
      if (i < n && j < n) A_[static_cast<std::size_t>(j) * n + i] = v;
      else if (i < n) C_[static_cast<std::size_t>(j - n) * n + i] = v;
      else if (j < n) D_[static_cast<std::size_t>(j) * m + (i - n)] = v;
      else B_[static_cast<std::size_t>(j - n) * m + (i - n)] = v;
    }
  }
  mlcp_ = MixedLinearComplementarityProblem{};
  mlcp_.isStorageType1 = 1;
  mlcp_.isStorageType2 = 1;
  mlcp_.n = n;
  mlcp_.m = m;
  mlcp_.M = matrix_;
  mlcp_.q = q_.data();
  mlcp_.A = A_.data();
  mlcp_.B = B_.data();
  mlcp_.C = C_.data();
  mlcp_.D = D_.data();
  mlcp_.a = a_.data();
  mlcp_.b = b_.data();
  int budget = r.max_iterations > 0 ? r.max_iterations : default_budget_;
  if (spec.algorithm == Algorithm::kEnum && r.max_iterations <= 0) {
    // Enumeration's budget counts configurations; without one of ours, let it finish the full search (its
    // default, 10^4 for mlcp_direct_enum, would end an m = 16 search a sixth of the way and report info 1).
    budget = std::max(budget, m >= 30 ? std::numeric_limits<int>::max() : (1 << m));
  }
  options_->iparam[SICONOS_IPARAM_MAX_ITER] = budget;
  options_->dparam[SICONOS_DPARAM_TOL] = r.tolerance;
  if (!reuse) {
    mlcp_driver_init(&mlcp_, options_);
    mlcp_initialised_ = true;
    mlcp_state_holder = this;
  }
}

void SiconosSession::StartCold(const Request& r, const double* M, const double* q) {
  const Spec& spec = SpecOf(static_cast<SiconosMethod>(r.method));
  if (spec.family != Family::kMlcp || !spec.direct || !r.keep_cache) return;
  numerics_set_verbose(r.verbose);
  PrepareMlcp(r, spec, M, q, /*fresh=*/true);
  last_request_ = r;
}

void SiconosSession::StartColdAgain() {
  if (method_ < 0 || method_ != last_request_.method) return;  // nothing solved, or released since
  StartCold(last_request_, last_M_.data(), q_.data());
}

Response SiconosSession::Solve(const Request& r, const double* M, const double* q, const double* lb,
                               const double* ub, double* x) {
  const Spec& spec = SpecOf(static_cast<SiconosMethod>(r.method));
  const int N = r.size;
  numerics_set_verbose(r.verbose);
  w_.assign(N, 0.0);
  last_request_ = r;
  Response out;
  if (spec.family == Family::kMlcp) {
    PrepareMlcp(r, spec, M, q, /*fresh=*/false);
  } else {
    if (method_ != r.method || size_ != N) {
      Release();
      options_ = solver_options_create(spec.siconos_id);
      default_budget_ = options_->iparam[SICONOS_IPARAM_MAX_ITER];
      driver_checks_ = options_->filterOn;
      // The driver's final accuracy check (filterOn) overwrites the algorithm's info, so a Lemke run that found
      // its basis and one that ended on a ray look alike. It is replayed below, exactly as the 4.4 drivers do it,
      // to report both verdicts.
      options_->filterOn = false;
      matrix_ = NM_create(NM_DENSE, N, N);
      method_ = r.method;
      size_ = N;
      num_equalities_ = 0;
    }
    std::memcpy(matrix_->matrix0, M, sizeof(double) * N * N);
    q_.assign(q, q + N);
    // Enumeration has no iteration budget of its own: leave its iparam[0] alone unless asked.
    if (r.max_iterations > 0 || spec.algorithm != Algorithm::kEnum) {
      options_->iparam[SICONOS_IPARAM_MAX_ITER] = r.max_iterations > 0 ? r.max_iterations : default_budget_;
    }
    options_->dparam[SICONOS_DPARAM_TOL] = r.tolerance;
  }
  options_->iparam[SICONOS_IPARAM_ITER_DONE] = 0;
  options_->dparam[SICONOS_DPARAM_RESIDU] = NAN;
  switch (spec.family) {
    case Family::kRelay: {
      lb_.assign(lb, lb + N);
      ub_.assign(ub, ub + N);
      RelayProblem problem{};
      problem.size = N;
      problem.M = matrix_;
      problem.q = q_.data();
      problem.lb = lb_.data();
      problem.ub = ub_.data();
      out.algorithm_info = out.info = relay_driver(&problem, x, w_.data(), options_);
      // relay_driver: info = relay_compute_error(...) whatever the solver said.
      if (driver_checks_) {
        out.info = relay_compute_error(&problem, x, w_.data(), r.tolerance, &options_->dparam[SICONOS_DPARAM_RESIDU]);
      }
      break;
    }
    case Family::kLcp: {
      LinearComplementarityProblem problem{};
      problem.size = N;
      problem.M = matrix_;
      problem.q = q_.data();
      out.algorithm_info = out.info = linearComplementarity_driver(&problem, x, w_.data(), options_);
      // lcp_driver_DenseMatrix: returns early (no check) for q ≥ 0 and for n = 1; otherwise the check's verdict
      // replaces info only when the solver reported success (info ≤ 0).
      const bool shortcut = N == 1 || std::all_of(q_.begin(), q_.end(), [](double v) { return v >= 0.0; });
      if (driver_checks_ && !shortcut) {
        const int check =
            lcp_compute_error(&problem, x, w_.data(), r.tolerance, &options_->dparam[SICONOS_DPARAM_RESIDU]);
        if (out.info <= 0) out.info = check;
      }
      break;
    }
    case Family::kMlcp:  // mlcp_driver makes no final check of its own
      out.algorithm_info = out.info = mlcp_driver(&mlcp_, x, w_.data(), options_);
      break;
    case Family::kAviStage3: {
      // The LCP's rows are (u_A, s_I) and its unknowns (u_I, s_A): stage 3 returns u and s per constraint, in the
      // order of the rows, and the LCP's z is (u of the inactive rows, s of the covered ones). Its covering vector
      // is passed negated (stage 3 copies it into the tableau's column as is).
      const int covered = r.covering_rows;
      LinearComplementarityProblem problem{};
      problem.size = N;
      problem.M = matrix_;
      problem.q = q_.data();
      stage3_u_.assign(N, 0.0);
      stage3_s_.assign(N, 0.0);
      stage3_d_.assign(N, 0.0);
      stage3_rows_.resize(static_cast<std::size_t>(covered));
      for (int i = 0; i < covered; ++i) {
        stage3_d_[static_cast<std::size_t>(i)] = -1.0;
        stage3_rows_[static_cast<std::size_t>(i)] = static_cast<unsigned>(i + 1);
      }
      out.algorithm_info = out.info =
          avi_caoferris_stage3(&problem, stage3_u_.data(), stage3_s_.data(), stage3_d_.data(),
                               static_cast<unsigned>(covered), stage3_rows_.data(), options_);
      for (int i = covered; i < N; ++i) x[i - covered] = stage3_u_[static_cast<std::size_t>(i)];
      for (int i = 0; i < covered; ++i) x[N - covered + i] = stage3_s_[static_cast<std::size_t>(i)];
      break;
    }
  }
  out.iterations = options_->iparam[SICONOS_IPARAM_ITER_DONE];
  out.budget = options_->iparam[SICONOS_IPARAM_MAX_ITER];
  out.error = options_->dparam[SICONOS_DPARAM_RESIDU];
  if (spec.family == Family::kMlcp && !(spec.direct && r.keep_cache)) {
    // Non-caching MLCP solvers keep pointers to this problem in file-static variables: drop them now.
    mlcp_driver_reset(&mlcp_, options_);
    mlcp_initialised_ = false;
    Release();
  }
  return out;
}

namespace {

// The worker's console capture (ServeSiconos): the C streams write to one memory file, descriptors 1 and 2 to
// another, so that each answer can say whether and how Siconos printed during the solve.
struct ConsoleCapture {
  FILE* stdio = nullptr;  // what stdout and stderr point to
  bool active = false;    // false: not capturing (output kept, or a system call failed): reads as kDescriptors
};

ConsoleCapture CaptureConsole(bool keep_output) {
  ConsoleCapture capture;
  if (keep_output) return capture;
  const int raw = memfd_create("siconos-descriptor-output", MFD_CLOEXEC);
  const int buffered = memfd_create("siconos-stdio-output", MFD_CLOEXEC);
  const bool redirected = raw >= 0 && dup2(raw, STDOUT_FILENO) >= 0 && dup2(raw, STDERR_FILENO) >= 0;
  if (raw >= 0) close(raw);
  capture.stdio = redirected && buffered >= 0 ? fdopen(buffered, "w") : nullptr;
  if (capture.stdio == nullptr) {
    if (buffered >= 0) close(buffered);
    return capture;
  }
  stdout = capture.stdio;
  stderr = capture.stdio;
  capture.active = true;
  return capture;
}

// What Siconos printed since the last call; both memory files are emptied for the next solve.
ProbedProblems::Console TakeConsole(const ConsoleCapture& capture) {
  using Console = ProbedProblems::Console;
  if (!capture.active) return Console::kDescriptors;
  std::fflush(capture.stdio);
  const long via_stdio = std::ftell(capture.stdio);
  const off_t via_descriptors = lseek(STDOUT_FILENO, 0, SEEK_CUR);
  if (via_stdio != 0 && ftruncate(fileno(capture.stdio), 0) == 0) std::rewind(capture.stdio);
  if (via_descriptors != 0 && ftruncate(STDOUT_FILENO, 0) == 0) lseek(STDOUT_FILENO, 0, SEEK_SET);
  if (via_descriptors != 0) return Console::kDescriptors;
  return via_stdio != 0 ? Console::kStdio : Console::kSilent;
}

// The worker's main loop: read a request, solve it, answer; ends when the backend closes the socket. context
// points to the backend's keep_output flag (a copy of it: this is a forked process).
void ServeSiconos(int fd, void* context) {
  mlcp_state_holder = nullptr;  // the parent's, copied by the fork: no Siconos state of this process
  const ConsoleCapture capture = CaptureConsole(*static_cast<const bool*>(context));
  SiconosSession session;
  std::vector<double> payload;  // M (N×N), q, [lb, ub,] x: one block, read with one call
  for (;;) {
    Request r;
    ChildProcess::WaitReadable(fd, std::chrono::microseconds(100));
    if (!ChildProcess::ReadAll(fd, &r, sizeof r)) return;
    if (r.magic == kForgetMagic) {
      session.StartColdAgain();
      TakeConsole(capture);  // what the initialisation printed belongs to no solve
      Response ack;
      ack.magic = kForgetMagic;
      if (!ChildProcess::WriteAll(fd, &ack, sizeof ack)) return;
      continue;
    }
    if (r.magic != kMagic) return;
    if (r.size <= 0 || r.size > kMaxWireSize || r.method < 0 || r.method >= kNumSiconosMethods) return;
    if (r.covering_rows < 0 || r.covering_rows > r.size) return;
    const std::size_t N = static_cast<std::size_t>(r.size);
    payload.resize(N * N + (r.has_bounds ? 4 : 2) * N);
    if (!ChildProcess::ReadAll(fd, payload.data(), sizeof(double) * payload.size())) return;
    const double* M = payload.data();
    const double* q = M + N * N;
    const double* lb = r.has_bounds ? q + N : nullptr;
    const double* ub = r.has_bounds ? q + 2 * N : nullptr;
    double* x = payload.data() + payload.size() - N;
    Response out = session.Solve(r, M, q, lb, ub, x);
    out.console = static_cast<std::int32_t>(TakeConsole(capture));
    if (!ChildProcess::WriteAll(fd, {{&out, sizeof out}, {x, sizeof(double) * N}})) return;
  }
}

}  // namespace

struct SiconosSolver::Outcome {
  Request request;
  Response response;
};

bool SiconosOptions::IsValid(std::string* why) const {
  if (!(default_time_limit > 0.0)) {
    *why = "default_time_limit must be positive (seconds), got " + std::to_string(default_time_limit);
    return false;
  }
  if (max_enumerated < 1 || max_enumerated > 30) {
    *why = "max_enumerated must be in [1, 30], got " + std::to_string(max_enumerated);
    return false;
  }
  if (max_size < 1 || max_size > kMaxWireSize) {
    *why = "max_size must be in [1, " + std::to_string(kMaxWireSize) + "], got " + std::to_string(max_size);
    return false;
  }
  if (remembered_problems < 0) {
    *why = "remembered_problems must be >= 0, got " + std::to_string(remembered_problems);
    return false;
  }
  if (!(remembered_megabytes >= 0.0 && remembered_megabytes <= 1e6)) {
    *why = "remembered_megabytes must be in [0, 1e6], got " + std::to_string(remembered_megabytes);
    return false;
  }
  return true;
}

SiconosSolver::SiconosSolver(SiconosMethod method) : SiconosSolver(method, SiconosOptions{}) {}

SiconosSolver::SiconosSolver(SiconosMethod method, const SiconosOptions& options)
    : BackendWithOptions(options), method_(method), last_(std::make_unique<Outcome>()) {}

SiconosSolver::~SiconosSolver() {
  if (dev_null_ >= 0) close(dev_null_);
  if (stdio_sink_ != nullptr) std::fclose(stdio_sink_);
}

const SolverInfo& SiconosSolver::info() const { return SpecOf(method_).info; }

int SiconosSolver::SiconosId(SiconosMethod method) { return SpecOf(method).siconos_id; }

void SiconosSolver::BindOptions(OptionBinder* binder) {
  binder->Add("isolate", &options_.isolate,
              {{"first", static_cast<int>(IsolationPolicy::kFirst)},
               {"always", static_cast<int>(IsolationPolicy::kAlways)},
               {"never", static_cast<int>(IsolationPolicy::kNever)}},
              {"never", "always"},  // the option's old boolean spelling: 0 isolated no solve, 1 every solve
              "where Siconos runs: first (default: a problem's first solve in this backend's worker process, "
              "later solves of the same problem in process once it came back), always (in the worker: "
              "crash/hang containment per solve, +7 us), never (in process, no protection)");
  binder->Add("default_time_limit", &options_.default_time_limit,
              "seconds a solve in the worker may take when no time limit is given; then the worker is killed");
  binder->Add("remembered_problems", &options_.remembered_problems,
              "isolate=first: how many probed problems are remembered (the latest); others are probed again");
  binder->Add("remembered_megabytes", &options_.remembered_megabytes,
              "isolate=first: memory for the copies of the remembered problems (8(N^2+4N) bytes each)");
  binder->Add("max_enumerated", &options_.max_enumerated,
              "enum methods: largest number of complementarity variables (2^k bases; a relay row counts 2)");
  binder->Add("max_size", &options_.max_size,
              "largest rewritten problem (unknowns; relay rows count 2 in LCP/MLCP form) sent to Siconos");
  binder->Add("quiet", &options_.quiet,
              "in process: silence Siconos' console around each call (the C streams always, free; descriptors "
              "1 and 2 too, ~1 us, only if the probe saw output there, or always with isolate=never); 0 = bare call");
  binder->Add("allow_known_crashes", &options_.allow_known_crashes,
              "pass problems on which Siconos is known to crash instead of refusing them (isolation demo)");
}

bool SiconosSolver::ValidateBackendOptions(std::string* why) const {
  return options_.IsValid(why);
}

namespace {

// Complementarity variables of the rewritten problem: a relay row counts 2 (its two one-sided rows), and so does a
// box row of the mixed form; free rows are equalities.
int ComplementarityCount(const Spec& spec, const StandardForm::RowCounts& rows) {
  return spec.family == Family::kRelay ? 2 * rows.box : rows.lower + rows.upper + 2 * rows.box;
}

// Phase 1: the problems this method cannot express, or that are over the size options, or on which Siconos is
// known to crash. True (status and message set) when refused.
bool Refused(SiconosMethod method, const Spec& spec, const StandardForm::RowCounts& rows, const SiconosOptions& o,
             SolveResult* result) {
  if (spec.family == Family::kRelay && rows.unbounded() > 0) {
    result->status = SolveStatus::kNotApplicable;
    result->message = "Siconos' relay solvers need finite bounds on every row; this problem has " +
                      std::to_string(rows.free) + " free, " + std::to_string(rows.lower) + " lower-bounded and " +
                      std::to_string(rows.upper) + " upper-bounded rows (siconos-lcp-* / siconos-mlcp-* take them)";
    return true;
  }
  if (spec.family == Family::kLcp && rows.free > 0) {
    result->status = SolveStatus::kNotApplicable;
    result->message = "an LCP has no free rows and this problem has " + std::to_string(rows.free) +
                      " (l = -inf, u = +inf); siconos-mlcp-* keep them as equalities";
    return true;
  }
  const int complementarity = ComplementarityCount(spec, rows);
  if (method == SiconosMethod::kMlcpLemke && !o.allow_known_crashes && (rows.free == 0 || complementarity == 0)) {
    result->status = SolveStatus::kNotApplicable;
    result->message = rows.free == 0
                          ? "Siconos' mlcp_lcp_lemke aborts (DGETRF on an empty equality block) on an MLCP without "
                            "free rows; siconos-lcp-lemke solves this problem"
                          : "Siconos' mlcp_lcp_lemke aborts (NM_gemm assertion) on an MLCP without "
                            "complementarity rows";
    return true;
  }
  const int standard_size = spec.family == Family::kRelay ? rows.box : rows.free + complementarity;
  if (standard_size > o.max_size) {
    result->status = SolveStatus::kSizeLimit;
    result->message = "the rewritten problem has " + std::to_string(standard_size) +
                      " unknowns, above max_size = " + std::to_string(o.max_size) +
                      " (Siconos' dense methods: O(N^2) memory, O(N^3) time)";
    return true;
  }
  if (spec.algorithm == Algorithm::kEnum && complementarity > o.max_enumerated) {
    result->status = SolveStatus::kSizeLimit;
    result->message = "enumeration over " + std::to_string(complementarity) +
                      " complementarity variables exceeds max_enumerated = " + std::to_string(o.max_enumerated);
    return true;
  }
  return false;
}

// Siconos' tolerance for our test. Ours is ‖r‖∞ ≤ tol·(1 + ‖q‖∞) on the box-MLCP and, row-equilibrated,
// |r_i(D⁻¹)| ≤ tol·(1 + ‖z‖∞), which ‖r‖∞ ≤ tol·min(1, min_i d_i) implies (|z_i − Π(z_i − t w_i)| grows with t, and
// at most linearly: a row with d_i < 1 can grow by 1/d_i); so the target is ‖r‖∞ ≤ tol·min(1 + ‖q‖∞, 1, min_i d_i).
// Siconos' test is ‖r_s‖₂ ≤ tol_s·(‖q_s‖₂ or 1 + ‖q_s‖₂) on the rewritten problem. This tol_s makes Siconos' test
// imply ‖r_s‖∞ ≤ that target whichever normalisation the driver uses, so a Siconos "success" is not routinely a
// hair above our tolerance; the floor 10·N·ε keeps it reachable in floating point (else Siconos' final check would
// reject every answer of a badly scaled problem).
double SiconosTolerance(const BoxMLCP& problem, const StandardForm& form, double tolerance) {
  const int N = form.size();
  const double target = std::min(problem.residual_scale(), std::min(1.0, problem.row_scale().minCoeff()));
  return std::max(tolerance * target / ((1.0 + form.q().norm()) * std::sqrt(static_cast<double>(N))),
                  10.0 * N * std::numeric_limits<double>::epsilon());
}

// Phase 4: our status from Siconos' answer. Siconos' verdict (info, after its driver's check) decides "solved or
// not"; the algorithm's own code (algorithm_info) says which failure it was. Neither ever upgrades a result, and the
// base class checks every "solved". finite: the answer has no NaN/Inf; tolerance: what was sent to Siconos.
void ClassifyAnswer(SiconosMethod method, const Spec& spec, const Response& out, bool finite, double tolerance,
              int complementarity, const SolverOptions& options, SolveResult* result) {
  const int algo = out.algorithm_info;
  const bool at_budget = out.budget > 0 && out.iterations >= out.budget;
  const auto code = [&] {  // built on failure paths only: a solved call allocates nothing
    return "(info " + std::to_string(out.info) +
           (algo != out.info ? ", algorithm info " + std::to_string(algo) : std::string()) + ")";
  };
  if (!finite) {
    result->status = SolveStatus::kNumericalFailure;
    result->message = "Siconos returned a non-finite solution " + code();
  } else if (out.info == 0) {
    result->status = SolveStatus::kSolved;
  } else if (algo == 0) {
    // The algorithm ended as if successful and Siconos' own final check rejected the answer.
    result->status = SolveStatus::kInaccurate;
    char text[160];
    std::snprintf(text, sizeof text, "the Siconos solver finished but Siconos' accuracy check rejected its answer "
                  "(error %.3g > %.3g) ", out.error, tolerance);
    result->message = text + code();
  } else if (method == SiconosMethod::kMlcpLemke && algo == 1 && out.iterations == 0) {
    // Lemke counts its first pivot as iteration 1: info 1 before any pivot is mlcp_to_lcp giving up.
    result->status = SolveStatus::kSingular;
    result->message =
        "Siconos' mlcp_lcp_lemke could not eliminate the equality rows (LU of their block failed) " + code();
  } else if (spec.algorithm == Algorithm::kLemke && algo == 1) {
    result->status = at_budget ? SolveStatus::kIterationLimit : SolveStatus::kRayTermination;
    result->message = at_budget
                          ? "Siconos' Lemke used its budget of " + std::to_string(out.budget) + " pivots " + code()
                          : "Siconos' Lemke ended on a secondary ray after " + std::to_string(out.iterations) +
                                " pivots " + code() + "; Siconos gives no certificate, so this is not a proof that "
                                "no solution exists";
  } else if (spec.algorithm == Algorithm::kEnum && algo == 1) {
    // Siconos enumerates 2^m configurations unless our budget stops it earlier. Finding none is not a proof:
    // Siconos gives no certificate, and its tests on each configuration are in floating point without a margin
    // (on M = [0], q = [0], a free row, where every z solves, mlcp_enum returns info 1). So a complete
    // enumeration that found nothing is a numerical failure, never kInfeasible.
    const bool complete = options.max_iterations <= 0 || complementarity >= 31 ||
                          options.max_iterations >= (1 << complementarity);
    result->status = complete ? SolveStatus::kNumericalFailure : SolveStatus::kIterationLimit;
    result->message = complete ? "Siconos' enumeration found no complementary solution " + code() +
                                     "; Siconos gives no certificate, so this is not a proof that no solution exists"
                               : "Siconos' enumeration stopped at its budget of " +
                                     std::to_string(options.max_iterations) + " configurations " + code();
  } else if (spec.algorithm == Algorithm::kPgs && algo == 2) {
    result->status = SolveStatus::kNotApplicable;
    result->message = "Siconos' PGS needs nonzero diagonal entries " + code();
  } else if (algo == 1 && at_budget) {
    result->status = SolveStatus::kIterationLimit;
    result->message = "Siconos used its budget of " + std::to_string(out.budget) + " iterations " + code();
  } else if (spec.algorithm == Algorithm::kNewton && algo == 2) {
    result->status = SolveStatus::kSingular;
    result->message = "Siconos' Newton direction failed in LAPACK " + code();
  } else if (algo == 1) {
    result->status = SolveStatus::kStalled;
    result->message = "Siconos stopped after " + std::to_string(out.iterations) +
                      " iterations without meeting its tolerance " + code();
  } else {
    result->status = SolveStatus::kNumericalFailure;
    result->message = "Siconos failed " + code();
  }
}

}  // namespace

// The phases in order: refuse what the method cannot take (1), rewrite the problem and fill the request (2), run
// Siconos where the isolation policy says (3), read its answer back and classify it (4).
void SiconosSolver::DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) {
  const std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  const Spec& spec = SpecOf(method_);
  result->SetDetail("siconos_id", spec.siconos_id);
  const StandardForm::RowCounts rows = StandardForm::Count(problem.l(), problem.u());
  if (rows.fixed == problem.size()) {  // every row fixed: z = l is the solution, nothing to ask Siconos
    result->z = problem.l();
    result->iterations = 0;
    result->status = SolveStatus::kSolved;
    return;
  }
  if (spec.family == Family::kAviStage3 &&
      (covering_rows_ < 1 || covering_rows_ > problem.size() || rows.lower != problem.size())) {
    result->status = SolveStatus::kNotApplicable;
    result->message = "Siconos' avi_caoferris_stage3 takes the LCP that siconos-avi-caoferris builds at a vertex "
                      "(its covered rows set, every row z >= 0)";
    return;
  }
  if (Refused(method_, spec, rows, options_, result)) return;
  Outcome& outcome = *last_;
  outcome = Outcome{};
  PrepareRequest(problem, options, &outcome, result);
  last_came_back_ = false;
  if (!RunWherePolicySays(options, start, &outcome, result)) {
    form_.ToBox(problem, x_, &result->z);  // the start point: Siconos' answer never arrived
    return;
  }
  last_came_back_ = true;
  if (spec.direct) (AnswerProcessOf(*result) == AnswerProcess::kThisProcess ? cache_in_process_ : cache_in_worker_) = true;
  const Response& out = outcome.response;
  form_.ToBox(problem, x_, &result->z);
  result->iterations = out.iterations;
  result->SetDetail("siconos_info", out.info);
  result->backend_code = out.info;
  if (out.algorithm_info != out.info) result->SetDetail("siconos_algorithm_info", out.algorithm_info);
  if (std::isfinite(out.error)) result->SetDetail("siconos_error", out.error);
  ClassifyAnswer(method_, spec, out, AllFinite(x_), outcome.request.tolerance, ComplementarityCount(spec, rows),
                 options, result);
}

// Phase 2: the standard form Siconos takes (x_ holds the start), and the request: method, sizes, budget, tolerance.
void SiconosSolver::PrepareRequest(const BoxMLCP& problem, const SolverOptions& options, Outcome* outcome,
                                   SolveResult* result) {
  const Spec& spec = SpecOf(method_);
  form_.Build(problem, spec.family == Family::kRelay ? StandardForm::Kind::kBox : StandardForm::Kind::kMixed);
  const int N = form_.size();
  result->SetDetail("standard_size", N);
  form_.FromBox(problem, result->z, &x_);
  Request& r = outcome->request;
  r.method = static_cast<std::int32_t>(method_);
  r.size = N;
  r.num_equalities = form_.num_equalities();
  r.max_iterations = options.max_iterations;
  r.verbose = options.verbosity >= 2 ? 1 : 0;
  r.has_bounds = spec.family == Family::kRelay ? 1 : 0;
  r.covering_rows = spec.family == Family::kAviStage3 ? covering_rows_ : 0;
  r.tolerance = SiconosTolerance(problem, form_, options.tolerance);
}

// Phase 3. Where this call runs (siconos_solver.h, "Isolation"): in process when the policy says never, or says
// first and these exact bytes have come back from a probe before; else in the worker, a probe when the policy is
// first. A problem whose probe took longer than this call's time limit stays in the worker, where the limit is
// enforced. False (status set) when no answer came back: a crash, a signal or the deadline.
bool SiconosSolver::RunWherePolicySays(const SolverOptions& options, std::chrono::steady_clock::time_point start,
                                       Outcome* outcome, SolveResult* result) {
  using Clock = std::chrono::steady_clock;
  const IsolationPolicy isolation = options_.isolate;
  const double limit =
      std::isfinite(options.time_limit_seconds) ? options.time_limit_seconds : options_.default_time_limit;
  const ProbedProblems::Outcome* probed = nullptr;
  if (isolation == IsolationPolicy::kFirst) {
    probed_.set_limits(options_.remembered_problems,
                       static_cast<std::size_t>(options_.remembered_megabytes * 1024.0 * 1024.0));
    probed = probed_.Find(RequestParts(*outcome));
  }
  const auto [in_process, probe] = DecideWhereToRun(isolation, probed, limit);
  kAnswerProcessDetail.Set(result, in_process ? AnswerProcess::kThisProcess : AnswerProcess::kWorker);
  if (in_process) {
    // What to silence: the C streams always (free of system calls, and what Siconos prints may depend on its state,
    // e.g. a direct solver's cache that is warm in the worker and cold here), the descriptors too when the probe
    // saw output there or there was no probe (kNever).
    using Console = ProbedProblems::Console;
    const Console silence = !options_.quiet || options.verbosity >= 2                       ? Console::kSilent
                            : probed != nullptr && probed->console != Console::kDescriptors ? Console::kStdio
                                                                                            : Console::kDescriptors;
    RunInProcess(silence, outcome);
    return true;
  }
  const Clock::time_point deadline =
      start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(limit));
  if (probe) probed_.Stage(RequestParts(*outcome));  // before x_ is overwritten
  if (!RunIsolated(options.verbosity >= 2, limit, deadline, outcome, result)) {
    probed_.Discard();  // this problem never runs in process
    return false;
  }
  if (probe) {
    const int console = outcome->response.console;
    probed_.Commit({console == 0   ? ProbedProblems::Console::kSilent
                    : console == 1 ? ProbedProblems::Console::kStdio
                                   : ProbedProblems::Console::kDescriptors,
                    std::chrono::duration<double>(Clock::now() - start).count()});
  }
  return true;
}

// The in-process state is re-initialised here for the last problem (or released when that problem never came back
// or never runs in process), the worker's by a message; both outside any solve a caller times.
WarmStateReset SiconosSolver::ForgetWarmState() {
  if (!cache_in_process_ && !cache_in_worker_) return WarmStateReset::kNothingRemembered;
  if (cache_in_worker_ && worker_.running()) ForgetInWorker();
  cache_in_process_ = cache_in_worker_ = false;
  // In process even when the last call ran in the worker: a probe's next solve of the problem runs here.
  if (session_ != nullptr || options_.isolate != IsolationPolicy::kAlways) {
    if (session_ == nullptr) session_ = std::make_unique<SiconosSession>();
    if (last_came_back_ && options_.isolate != IsolationPolicy::kAlways) {
      if (options_.quiet && stdio_sink_ == nullptr) stdio_sink_ = std::fopen("/dev/null", "we");
      const SwappedStdio swapped(options_.quiet ? stdio_sink_ : nullptr);
      session_->StartCold(last_->request, form_.M().data(), form_.q().data());
    } else {
      session_->Release();
    }
  }
  return WarmStateReset::kForgotten;
}

void SiconosSolver::ForgetInWorker() {
  using Clock = std::chrono::steady_clock;
  using Io = ChildProcess::Io;
  Request forget;
  forget.magic = kForgetMagic;
  Response ack;
  const Clock::time_point deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(
                         std::chrono::duration<double>(options_.default_time_limit));
  if (worker_.Write(&forget, sizeof forget) == Io::kOk && worker_.Read(&ack, sizeof ack, deadline) == Io::kOk &&
      ack.magic == kForgetMagic) {
    return;
  }
  worker_.Stop();  // a worker that did not confirm keeps no cache once it is gone
}

std::array<ProbedProblems::Part, 6> SiconosSolver::RequestParts(const Outcome& outcome) const {
  const Request& r = outcome.request;
  const std::size_t N = static_cast<std::size_t>(r.size);
  const std::size_t bounds = r.has_bounds ? sizeof(double) * N : 0;  // relay only
  return {{{&r, sizeof r},
           {form_.M().data(), sizeof(double) * N * N},
           {form_.q().data(), sizeof(double) * N},
           {form_.lower().data(), bounds},
           {form_.upper().data(), bounds},
           {x_.data(), sizeof(double) * N}}};
}

void SiconosSolver::RunInProcess(ProbedProblems::Console silence, Outcome* outcome) {
  using Console = ProbedProblems::Console;
  if (!session_) session_ = std::make_unique<SiconosSession>();
  if (silence == Console::kDescriptors && dev_null_ < 0) dev_null_ = open("/dev/null", O_WRONLY | O_CLOEXEC);
  if (silence == Console::kStdio && stdio_sink_ == nullptr) stdio_sink_ = std::fopen("/dev/null", "we");
  const QuietStdio quiet(silence == Console::kDescriptors ? dev_null_ : -1);
  const SwappedStdio swapped(silence == Console::kStdio ? stdio_sink_ : nullptr);
  const bool relay = outcome->request.has_bounds != 0;
  outcome->response = session_->Solve(outcome->request, form_.M().data(), form_.q().data(),
                                      relay ? form_.lower().data() : nullptr,
                                      relay ? form_.upper().data() : nullptr, x_.data());
}

bool SiconosSolver::RunIsolated(bool keep_output, double limit_seconds,
                                std::chrono::steady_clock::time_point deadline, Outcome* outcome,
                                SolveResult* result) {
  static constexpr WorkerCallNames kNames{"Siconos", "the Siconos worker process", "siconos_signal"};
  if (worker_.running() && worker_keeps_output_ != keep_output) worker_.Stop();
  const auto start_worker = [this, keep_output](std::string* error) {
    worker_keeps_output_ = keep_output;  // the worker reads it through the context pointer, at its start
    return worker_.Start(&ServeSiconos, &worker_keeps_output_, keep_output, error);
  };
  return CallWorker(&worker_, start_worker, RequestParts(*outcome), {&outcome->response, sizeof outcome->response},
                    {x_.data(), sizeof(double) * static_cast<std::size_t>(outcome->request.size)},
                    [outcome] { return outcome->response.magic == kMagic; }, limit_seconds, deadline, kNames, result);
}

namespace {

template <SiconosMethod kMethod>
std::unique_ptr<Solver> MakeSiconos() {
  return std::make_unique<SiconosSolver>(kMethod);
}

std::unique_ptr<Solver> MakeSiconosAvi() { return std::make_unique<SiconosAviSolver>(); }

}  // namespace

void AppendExternalBackends(std::vector<ExternalBackend>* backends) {
  using M = SiconosMethod;
  const ExternalBackend list[] = {
      {SpecOf(M::kRelayAvi).info.name, &MakeSiconos<M::kRelayAvi>},
      {SpecOf(M::kRelayLemke).info.name, &MakeSiconos<M::kRelayLemke>},
      {SpecOf(M::kRelayPgs).info.name, &MakeSiconos<M::kRelayPgs>},
      {SpecOf(M::kRelayEnum).info.name, &MakeSiconos<M::kRelayEnum>},
      {SpecOf(M::kLcpLemke).info.name, &MakeSiconos<M::kLcpLemke>},
      {SpecOf(M::kLcpNewtonFb).info.name, &MakeSiconos<M::kLcpNewtonFb>},
      {SpecOf(M::kLcpNewtonMin).info.name, &MakeSiconos<M::kLcpNewtonMin>},
      {SpecOf(M::kMlcpEnum).info.name, &MakeSiconos<M::kMlcpEnum>},
      {SpecOf(M::kMlcpLemke).info.name, &MakeSiconos<M::kMlcpLemke>},
      {SpecOf(M::kMlcpFb).info.name, &MakeSiconos<M::kMlcpFb>},
      {SpecOf(M::kMlcpDirectEnum).info.name, &MakeSiconos<M::kMlcpDirectEnum>},
      {SpecOf(M::kMlcpDirectFb).info.name, &MakeSiconos<M::kMlcpDirectFb>},
      // Cao–Ferris on P (a box as {l <= z <= u}); also a DirectAviBackend, so SolveAvi hands it the AVI itself.
      {SpecOf(M::kAviCaoFerrisStage3).info.name, &MakeSiconosAvi},
  };
  backends->insert(backends->end(), std::begin(list), std::end(list));
  AppendSiconosMcpBackends(backends);
}

}  // namespace smcbench

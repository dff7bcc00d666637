// The shared half of the bullet-* and dart-* adapters (peer_solver.h): rewrite, isolation policy, worker protocol,
// classification of the library's answer.
#include "solvers/peer/peer_solver.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "solvers/isolation/swapped_stdio.h"
#include "solvers/isolation/worker_call.h"

namespace smcbench {
namespace {

constexpr std::int32_t kMagic = 0x50454552;
constexpr int kMaxWireSize = 1 << 15;  // largest N the worker accepts
static_assert(sizeof(PeerBoxSolver::Request) == 4 * sizeof(std::int32_t), "Request has padding");

bool AllFinite(const Vector& v) {
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) return false;
  }
  return true;
}

}  // namespace

// The worker's main loop: read a request, run the library on it, answer; ends when the backend closes the socket.
// context is the backend (this process's copy of it, made by the fork).
void ServePeer(int fd, void* context) { static_cast<PeerBoxSolver*>(context)->Serve(fd); }

void PeerBoxSolver::Serve(int fd) {
  std::vector<double> payload;  // A (N×N row-major), b, lo, hi, x: one block, read with one call
  for (;;) {
    Request r;
    ChildProcess::WaitReadable(fd, std::chrono::microseconds(100));
    if (!ChildProcess::ReadAll(fd, &r, sizeof r) || r.magic != kMagic) return;
    if (r.size <= 0 || r.size > kMaxWireSize || r.nub < 0 || r.nub > r.size) return;
    const std::size_t N = static_cast<std::size_t>(r.size);
    payload.resize(N * N + 4 * N);
    if (!ChildProcess::ReadAll(fd, payload.data(), sizeof(double) * payload.size())) return;
    double* A = payload.data();
    double* b = A + N * N;
    double* x = b + 3 * N;
    Reply out = Run(r, A, b, b + N, b + 2 * N, x);
    out.magic = kMagic;
    if (!ChildProcess::WriteAll(fd, {{&out, sizeof out}, {x, sizeof(double) * N}})) return;
  }
}

bool PeerOptions::IsValid(std::string* why) const {
  if (!(default_time_limit > 0.0)) {
    *why = "default_time_limit must be positive (seconds), got " + std::to_string(default_time_limit);
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

PeerBoxSolver::PeerBoxSolver(Shape shape, const PeerOptions& options) : BackendWithOptions(options), shape_(shape) {}

PeerBoxSolver::~PeerBoxSolver() {
  if (stdio_sink_ != nullptr) std::fclose(stdio_sink_);
}

void PeerBoxSolver::BindOptions(OptionBinder* binder) {
  binder->Add("isolate", &options_.isolate,
              {{"first", static_cast<int>(IsolationPolicy::kFirst)},
               {"always", static_cast<int>(IsolationPolicy::kAlways)},
               {"never", static_cast<int>(IsolationPolicy::kNever)}},
              "where the library runs: first (default: a problem's first solve in this backend's worker process, "
              "later solves of the same problem in process once it came back), always (in the worker), never (in "
              "process, no protection)");
  binder->Add("default_time_limit", &options_.default_time_limit,
              "seconds a solve in the worker may take when no time limit is given; then the worker is killed");
  binder->Add("remembered_problems", &options_.remembered_problems,
              "isolate=first: how many probed problems are remembered (the latest); others are probed again");
  binder->Add("remembered_megabytes", &options_.remembered_megabytes,
              "isolate=first: memory for the copies of the remembered problems (8(N^2+4N) bytes each)");
  binder->Add("max_size", &options_.max_size, "largest peer problem (rows after the rewrite) sent to the library");
}

bool PeerBoxSolver::ValidateBackendOptions(std::string* why) const { return options_.IsValid(why); }

// The phases: rewrite into the peer's shape (or refuse), run where the policy says, map back and classify.
void PeerBoxSolver::DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) {
  const std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  const StandardForm::RowCounts rows = StandardForm::Count(problem.l(), problem.u());
  if (rows.fixed == problem.size()) {  // every row fixed: z = l, nothing to ask the library
    result->z = problem.l();
    result->iterations = 0;
    result->status = SolveStatus::kSolved;
    return;
  }
  int N = 0;
  if (shape_ == Shape::kBox) {
    ToPeerBoxForm(problem, &form_);
    N = form_.size();
    request_.nub = form_.nub;
  } else {
    if (rows.free > 0) {
      result->status = SolveStatus::kNotApplicable;
      result->message = "this library solves LCPs (x >= 0), which have no free rows, and this problem has " +
                        std::to_string(rows.free) + " (l = -inf, u = +inf)";
      return;
    }
    lcp_form_.Build(problem, StandardForm::Kind::kMixed);
    N = lcp_form_.size();
    request_.nub = 0;
  }
  result->SetDetail("standard_size", N);
  if (N > options_.max_size) {
    result->status = SolveStatus::kSizeLimit;
    result->message = "the rewritten problem has " + std::to_string(N) + " rows, above max_size = " +
                      std::to_string(options_.max_size) + " (dense library solvers: O(N^2) memory)";
    return;
  }
  const std::size_t n = static_cast<std::size_t>(N);
  A_.resize(n * n);
  b_.resize(n);
  lo_.resize(n);
  hi_.resize(n);
  const DenseMatrix& A = shape_ == Shape::kBox ? form_.A : lcp_form_.M();
  for (int i = 0; i < N; ++i) {
    for (int j = 0; j < N; ++j) A_[static_cast<std::size_t>(i) * n + j] = A(i, j);
  }
  if (shape_ == Shape::kBox) {
    std::copy(form_.b.data(), form_.b.data() + N, b_.begin());
    std::copy(form_.lo.data(), form_.lo.data() + N, lo_.begin());
    std::copy(form_.hi.data(), form_.hi.data() + N, hi_.begin());
    ToPeerPoint(form_, result->z, &x_);
  } else {
    for (int i = 0; i < N; ++i) b_[i] = -lcp_form_.q()[i];  // A x = b + w with w = M_std x + q_std
    std::fill(lo_.begin(), lo_.end(), 0.0);
    std::fill(hi_.begin(), hi_.end(), std::numeric_limits<double>::infinity());
    lcp_form_.FromBox(problem, result->z, &x_);
  }
  request_.size = N;
  request_.iterations = options.max_iterations > 0 ? options.max_iterations : DefaultIterations();
  std::string why;
  if (Refuses(request_, lo_.data(), hi_.data(), &why)) {
    result->status = SolveStatus::kNotApplicable;
    result->message = why;
    return;
  }
  const bool answered = RunWherePolicySays(options, start, result);
  if (shape_ == Shape::kBox) {
    FromPeerPoint(form_, x_, &result->z);
  } else {
    lcp_form_.ToBox(problem, x_, &result->z);
  }
  if (!answered) return;  // status set: a crash, a signal or the deadline (z: the start point)
  result->iterations = reply_.iterations >= 0 ? reply_.iterations : 0;
  result->SetDetail("peer_success", reply_.success != 0 ? 1.0 : 0.0);
  result->backend_code = reply_.success != 0 ? 0 : 1;
  if (HasCode()) result->SetDetail("peer_code", reply_.code);
  if (!AllFinite(x_)) {
    result->status = SolveStatus::kNumericalFailure;
    result->message = std::string("the library returned a non-finite solution (its flag: ") +
                      (reply_.success != 0 ? "success)" : "failure)");
  } else if (reply_.success != 0) {
    result->status = SolveStatus::kSolved;  // a claim: the base checks it with our merit function
  } else {
    DescribeFailure(reply_, result);
  }
}

std::array<ProbedProblems::Part, 6> PeerBoxSolver::RequestParts() const {
  const std::size_t N = static_cast<std::size_t>(request_.size);
  return {{{&request_, sizeof request_},
           {A_.data(), sizeof(double) * N * N},
           {b_.data(), sizeof(double) * N},
           {lo_.data(), sizeof(double) * N},
           {hi_.data(), sizeof(double) * N},
           {x_.data(), sizeof(double) * N}}};
}

// In process when the policy says never, or says first and these exact bytes came back from a probe within this
// call's time limit; else in the worker (a probe when the policy is first). False (status set) without an answer.
bool PeerBoxSolver::RunWherePolicySays(const SolverOptions& options, std::chrono::steady_clock::time_point start,
                                       SolveResult* result) {
  using Clock = std::chrono::steady_clock;
  const IsolationPolicy isolation = options_.isolate;
  const double limit =
      std::isfinite(options.time_limit_seconds) ? options.time_limit_seconds : options_.default_time_limit;
  const ProbedProblems::Outcome* probed = nullptr;
  if (isolation == IsolationPolicy::kFirst) {
    probed_.set_limits(options_.remembered_problems,
                       static_cast<std::size_t>(options_.remembered_megabytes * 1024.0 * 1024.0));
    probed = probed_.Find(RequestParts());
  }
  const auto [in_process, probe] = DecideWhereToRun(isolation, probed, limit);
  kAnswerProcessDetail.Set(result, in_process ? AnswerProcess::kThisProcess : AnswerProcess::kWorker);
  if (in_process) {
    RunInProcess();
    return true;
  }
  const Clock::time_point deadline =
      start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(limit));
  if (probe) probed_.Stage(RequestParts());  // before x_ is overwritten
  if (!RunIsolated(limit, deadline, result)) {
    probed_.Discard();  // this problem never runs in process
    return false;
  }
  if (probe) {
    probed_.Commit({ProbedProblems::Console::kStdio, std::chrono::duration<double>(Clock::now() - start).count()});
  }
  return true;
}

void PeerBoxSolver::RunInProcess() {
  if (stdio_sink_ == nullptr) stdio_sink_ = std::fopen("/dev/null", "we");
  const SwappedStdio quiet(stdio_sink_);
  // The library may overwrite its inputs: it gets copies, and the request's bytes stay as the probe saw them.
  work_A_ = A_;
  work_b_ = b_;
  work_lo_ = lo_;
  work_hi_ = hi_;
  reply_ = Run(request_, work_A_.data(), work_b_.data(), work_lo_.data(), work_hi_.data(), x_.data());
}

bool PeerBoxSolver::RunIsolated(double limit_seconds, std::chrono::steady_clock::time_point deadline,
                                SolveResult* result) {
  static constexpr WorkerCallNames kNames{"the library", "the worker process", "peer_signal"};
  const auto start_worker = [this](std::string* error) {
    return worker_.Start(&ServePeer, this, /*keep_output=*/false, error);
  };
  return CallWorker(&worker_, start_worker, RequestParts(), {&reply_, sizeof reply_},
                    {x_.data(), sizeof(double) * static_cast<std::size_t>(request_.size)},
                    [this] { return reply_.magic == kMagic; }, limit_seconds, deadline, kNames, result);
}

}  // namespace smcbench

// The shared half of the physics-engine box-LCP adapters (bullet-*, dart-*): rewrite our box-MLCP into the peer's
// convention (peer_box_form.h, or the LCP rewriting of standard_form.h for a peer without bounds), run the library's
// solve where the isolation policy says, map the answer back and record the library's own flag. A backend states
// only how it calls its library (Run) and what its failure codes mean (DescribeFailure). See docs/peers.md.
//
// Trust. The library's own success flag is detail "peer_success" (1/0) and never more than a claim: a true flag is
// kSolved only if our merit function agrees (else the base reports kInaccurate); a non-finite answer is
// kNumericalFailure whatever the flag says. Library codes beyond a bool are detail "peer_code".
//
// Isolation (option isolate), as the Siconos adapters do it (siconos_solver.h): a problem's first solve runs in this
// backend's worker process (child_process.h), so a crash is kNumericalFailure naming the signal and a hang is
// killed at the time limit (kTimeLimit); once the probe came back, later solves of exactly the same bytes run in
// process (probed_problems.h). Detail "in_process" says which process answered (AnswerProcessOf). In process, the
// C streams point to /dev/null during the call (the libraries print on some failures). In-process instances must
// not run concurrently on different threads.
//
// The problem goes to the library as the user wrote it (SolverInfo::equilibrate = false), in double precision.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "solvers/core/backend_options.h"
#include "solvers/peer/peer_box_form.h"
#include "solvers/isolation/child_process.h"
#include "solvers/isolation/probed_problems.h"
#include "solvers/siconos/standard_form.h"

namespace smcbench {

struct PeerOptions {
  IsolationPolicy isolate = IsolationPolicy::kFirst;
  // kFirst: how many probed problems are remembered, and how much memory their copies may take (8·(N² + 4N) bytes).
  int remembered_problems = 32;
  double remembered_megabytes = 64.0;
  // Seconds a solve in the worker may take when SolverOptions::time_limit_seconds is infinite (> 0).
  double default_time_limit = 60.0;
  // Largest peer problem (rows after the rewrite) sent to the library: its solvers are dense, O(N²) memory.
  int max_size = 2048;

  bool IsValid(std::string* why) const;
};

class PeerBoxSolver : public BackendWithOptions<PeerOptions> {
 public:
  // How the library takes a problem: a box-LCP (peer_box_form.h), or an LCP w = A x − b ≥ 0, x ≥ 0 (lo = 0,
  // hi = +∞, nub = 0) from the box → LCP rewriting of standard_form.h, for a library without bounds (no free rows).
  enum class Shape { kBox, kLcp };

  // What crosses to the library (fixed size, no padding: hashed bytewise by the probe memory).
  struct Request {
    std::int32_t magic = 0x50454552;  // "PEER"
    std::int32_t size = 0;            // N, rows of the peer problem
    std::int32_t nub = 0;
    std::int32_t iterations = 0;      // the library's iteration or pivot budget (its default unless max_iterations)
  };
  // What comes back (then x).
  struct Reply {
    std::int32_t magic = 0x50454552;
    std::int32_t success = 0;      // the library's own flag
    std::int32_t code = 0;         // a library code beyond the flag (DART's Lemke), else 0
    std::int32_t iterations = -1;  // as the library counts them, −1 if it does not say
  };

  explicit PeerBoxSolver(Shape shape, const PeerOptions& options = {});
  ~PeerBoxSolver() override;

  // Process id of the running worker, or −1.
  int worker_pid() const { return worker_.running() ? static_cast<int>(worker_.pid()) : -1; }

 protected:
  // The library's solve. A is N×N row-major (stride N), b, lo, hi, x of length N; all may be overwritten (ODE's
  // dSolveLCP does), x holds the start on entry and the answer on return. Runs in process or in the worker.
  virtual Reply Run(const Request& request, double* A, double* b, double* lo, double* hi, double* x) = 0;
  // The library's default budget (Request::iterations) when SolverOptions::max_iterations ≤ 0.
  virtual int DefaultIterations() const = 0;
  // Problems the library cannot take (e.g. infinite bounds for a bounded Lemke): true with *why.
  virtual bool Refuses(const Request& /*request*/, const double* /*lo*/, const double* /*hi*/,
                       std::string* /*why*/) const {
    return false;
  }
  // Status and message for a reply whose flag is false (the answer is finite).
  virtual void DescribeFailure(const Reply& reply, SolveResult* result) const = 0;
  // Whether the library reports a code beyond its flag (detail "peer_code").
  virtual bool HasCode() const { return false; }

  void DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) final;
  void BindOptions(OptionBinder* binder) override;
  bool ValidateBackendOptions(std::string* why) const override;

 private:
  friend void ServePeer(int fd, void* context);
  std::array<ProbedProblems::Part, 6> RequestParts() const;
  bool RunWherePolicySays(const SolverOptions& options, std::chrono::steady_clock::time_point start,
                          SolveResult* result);
  bool RunIsolated(double limit_seconds, std::chrono::steady_clock::time_point deadline, SolveResult* result);
  void RunInProcess();
  void Serve(int fd);

  Shape shape_;
  PeerBoxForm form_;
  StandardForm lcp_form_;
  Request request_;
  Reply reply_;
  // The peer problem as sent (row-major A), the start / answer x, and the copies the library may overwrite.
  std::vector<double> A_, b_, lo_, hi_;
  Vector x_;
  std::vector<double> work_A_, work_b_, work_lo_, work_hi_;
  Vector z_start_;
  ChildProcess worker_;
  ProbedProblems probed_;
  std::FILE* stdio_sink_ = nullptr;  // /dev/null, opened at the first in-process solve
};

}  // namespace smcbench

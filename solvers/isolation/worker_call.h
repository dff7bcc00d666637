// One solve in an external adapter's isolation worker, with the supervision every adapter needs: one home for what
// the Siconos and the Bullet/DART adapters did each in their own copy (start the worker, send the request, wait for
// the reply until the deadline, tell a hang from a crash).
#pragma once

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <string>

#include "solvers/core/result.h"
#include "solvers/isolation/child_process.h"
#include "solvers/isolation/probed_problems.h"

namespace smcbench {

// How the messages of a failed worker call name the parties, and the detail that carries a fatal signal.
struct WorkerCallNames {
  const char* library;        // who did not return in time: "the library", "Siconos"
  const char* worker;         // whose process died: "the worker process", "the Siconos worker process"
  const char* signal_detail;  // SolveResult detail with the signal number: "peer_signal", "siconos_signal"
};

// A buffer the reply is read into.
struct ReplyBuffer {
  void* data;
  std::size_t bytes;
};

// Where a solve runs under an isolation policy (child_process.h): in this process when the policy says never, or
// says first and these exact bytes came back from a probe within this call's time limit; else in the worker, as a
// probe when the policy is first and the problem has not been probed.
struct IsolationDecision {
  bool in_process = false;
  bool probe = false;
};
inline IsolationDecision DecideWhereToRun(IsolationPolicy policy, const ProbedProblems::Outcome* probed,
                                          double limit_seconds) {
  IsolationDecision d;
  d.probe = policy == IsolationPolicy::kFirst && probed == nullptr;
  d.in_process = policy == IsolationPolicy::kNever || (probed != nullptr && probed->seconds <= limit_seconds);
  return d;
}

// Sends the request to the worker and reads the reply (head, then the answer) by the deadline. The worker is
// started by start_worker(std::string* error) -> bool when it is not running; a worker found dead before it read
// the request (it died while idle) is replaced once. True when both reads came back and reply_ok() accepts the
// head (its magic number). Otherwise false with result's status and message set: kTimeLimit when the reply missed
// the deadline (the worker is killed), kNumericalFailure when the worker could not start or died during the solve
// (how, and the signal in names.signal_detail). The request and reply buffers are the caller's; nothing allocates
// on the success path.
template <std::size_t kParts, typename StartWorker, typename ReplyOk>
bool CallWorker(ChildProcess* worker, StartWorker&& start_worker, const std::array<ProbedProblems::Part, kParts>& request,
                ReplyBuffer head, ReplyBuffer answer, ReplyOk&& reply_ok, double limit_seconds,
                ChildProcess::Clock::time_point deadline, const WorkerCallNames& names, SolveResult* result) {
  using Io = ChildProcess::Io;
  std::array<ChildProcess::Buffer, kParts> buffers;
  for (std::size_t k = 0; k < kParts; ++k) buffers[k] = {request[k].data, request[k].bytes};
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (!worker->running()) {
      std::string error;
      if (!start_worker(&error)) {
        result->status = SolveStatus::kNumericalFailure;
        result->message = std::string("could not start ") + names.worker + ": " + error;
        return false;
      }
    }
    Io io = worker->Write(buffers.data(), buffers.size());
    if (io == Io::kClosed && attempt == 0) {  // the worker died while idle: start a fresh one, once
      int signal = 0;
      worker->Reap(&signal);
      continue;
    }
    if (io == Io::kOk) io = worker->Read(head.data, head.bytes, deadline);
    if (io == Io::kOk) io = worker->Read(answer.data, answer.bytes, deadline);
    if (io == Io::kOk && reply_ok()) return true;
    if (io == Io::kTimeout) {
      worker->Stop();
      result->status = SolveStatus::kTimeLimit;
      char text[160];
      std::snprintf(text, sizeof text, "%s did not return within the time limit (%.3g s); its worker process was killed",
                    names.library, limit_seconds);
      result->message = text;
      return false;
    }
    int signal = 0;
    const std::string how = worker->Reap(&signal);
    result->status = SolveStatus::kNumericalFailure;
    result->message = std::string(names.worker) + " died during the solve: " + how;
    if (signal != 0) result->SetDetail(names.signal_detail, signal);
    return false;
  }
  result->status = SolveStatus::kNumericalFailure;
  result->message = std::string(names.worker) + " keeps dying before it reads a request";
  return false;
}

}  // namespace smcbench

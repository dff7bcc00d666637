// A worker process forked from this one that serves requests over a socket, so that third-party code which
// crashes, aborts or hangs costs one solve a status instead of taking the whole benchmark run down with it.
//
// The worker is started once (fork, no exec: it shares this process's code and its state at the time of the
// fork) and then serves any number of requests, so per-solve cost is a socket round trip (a few µs), not a
// fork, and third-party state that persists between calls (Siconos' "direct" MLCP solvers keep their active-set
// cache in file-static variables) lives in this worker only, away from other backends. In the worker:
// stdout/stderr go to /dev/null (unless asked to keep them), every inherited descriptor other than the socket
// is closed, the worker dies with its parent (PR_SET_PDEATHSIG), and it leaves with _exit (no atexit handlers,
// no GoogleTest or sanitizer teardown of the parent's state).
//
// Parent-side reads take a deadline; a worker that misses it is killed with SIGKILL. Both sides poll briefly
// before sleeping (set_spin, WaitReadable), which keeps a tight loop of small solves at a few µs per round
// trip instead of a scheduler wake-up each way. Writes use MSG_NOSIGNAL, so a dead worker is an error code,
// never a SIGPIPE in this process. Repeated calls allocate nothing.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <cstddef>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include "solvers/core/result.h"

namespace smcbench {

// Where an external adapter (siconos-*, bullet-*, dart-*) runs the other library's code (its `isolate` option).
enum class IsolationPolicy {
  kNever,   // always in this process: fastest, no crash or hang protection
  kFirst,   // a problem's first solve in the worker (the probe); once it came back normally, in this process
  kAlways,  // every solve in the worker
};
// "never", "first", "always".
std::string_view ToString(IsolationPolicy isolation);

// Where an external adapter's answer was computed: SolveResult detail "in_process" (read it with AnswerProcessOf).
enum class AnswerProcess : int {
  kWorker = 0,       // the isolation worker: a probe, isolate=always, or a problem whose probe failed
  kThisProcess = 1,  // this process
};
// "worker", "this_process" (the detail's text in JSON and Python).
std::string_view ToString(AnswerProcess where);
std::optional<AnswerProcess> AnswerProcessFromString(std::string_view name);
inline constexpr CodeDetail<AnswerProcess, 2> kAnswerProcessDetail{"in_process"};
// nullopt for a result no external adapter answered (our backends, or a problem refused before the library ran).
inline std::optional<AnswerProcess> AnswerProcessOf(const SolveResult& result) {
  return kAnswerProcessDetail.Get(result);
}

class ChildProcess {
 public:
  using Clock = std::chrono::steady_clock;
  // Runs in the worker with its end of the socket; the worker _exits when it returns.
  using ServeFunction = void (*)(int fd, void* context);

  enum class Io { kOk, kTimeout, kClosed };

  ChildProcess() = default;
  ~ChildProcess();  // kills and reaps a running worker
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  // Forks a worker running serve(fd, context). keep_output leaves its stdout/stderr alone. False with *error
  // (naming the failing system call) if the socket or the fork failed.
  bool Start(ServeFunction serve, void* context, bool keep_output, std::string* error);
  bool running() const { return pid_ > 0; }
  pid_t pid() const { return pid_; }

  // Parent side: sends / receives exactly `bytes` bytes. Write blocks until the worker has read them (it reads
  // every request completely before working on it); Read waits at most until `deadline`.
  Io Write(const void* data, std::size_t bytes);
  // Sends several buffers as one message (one system call when the socket buffer takes them).
  struct Buffer {
    const void* data;
    std::size_t bytes;
  };
  Io Write(std::initializer_list<Buffer> buffers);
  Io Write(const Buffer* buffers, std::size_t count);  // the same for an array (at most 8 non-empty buffers)
  Io Read(void* data, std::size_t bytes, Clock::time_point deadline);

  // Kills the worker (SIGKILL), reaps it and says how it ended ("killed by signal 9 (Killed)"). The next Start()
  // forks a fresh one. Safe to call when no worker runs (returns "not running").
  std::string Stop();
  // After Read/Write returned kClosed: reaps the worker, which has exited or died by itself, and describes how
  // ("killed by signal 11 (Segmentation fault)", "exited with code 1"). *signal receives the signal number or 0.
  std::string Reap(int* signal);

  // Before sleeping in poll(), Read keeps trying for this long (default 50 µs): a short solve's answer is then
  // picked up at once instead of after a scheduler wake-up (tens of µs on an idle virtual CPU). 0 disables it.
  void set_spin(std::chrono::microseconds spin) { spin_ = spin; }

  // Worker side helpers (blocking, restart on EINTR): false on end of stream or error.
  static bool ReadAll(int fd, void* data, std::size_t bytes);
  static bool WriteAll(int fd, const void* data, std::size_t bytes);
  static bool WriteAll(int fd, std::initializer_list<Buffer> buffers);
  static bool WriteAll(int fd, const Buffer* buffers, std::size_t count);
  // Worker side: waits until fd has data (or end of stream), trying without sleeping for `spin` first, so that
  // the next request of a tight loop of solves is served without a wake-up delay.
  static void WaitReadable(int fd, std::chrono::microseconds spin);

 private:
  static std::string Describe(int wait_status, int* signal);

  pid_t pid_ = -1;
  int fd_ = -1;  // parent's end of the socket pair
  std::chrono::microseconds spin_{50};
};

}  // namespace smcbench

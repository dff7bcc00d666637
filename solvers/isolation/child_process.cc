// Forked worker process with a socket, a read deadline and a kill switch (see child_process.h).
#include "solvers/isolation/child_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/uio.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <thread>

namespace smcbench {

std::string_view ToString(IsolationPolicy isolation) {
  switch (isolation) {
    case IsolationPolicy::kNever:
      return "never";
    case IsolationPolicy::kFirst:
      return "first";
    case IsolationPolicy::kAlways:
      return "always";
  }
  return "?";
}

std::string_view ToString(AnswerProcess where) {
  switch (where) {
    case AnswerProcess::kWorker:
      return "worker";
    case AnswerProcess::kThisProcess:
      return "this_process";
  }
  return "unknown";
}

std::optional<AnswerProcess> AnswerProcessFromString(std::string_view name) {
  for (const AnswerProcess where : {AnswerProcess::kWorker, AnswerProcess::kThisProcess}) {
    if (ToString(where) == name) return where;
  }
  return std::nullopt;
}

namespace {

// The worker's end of the socket is moved here; every descriptor above it is closed.
constexpr int kWorkerFd = 3;

std::string SystemError(const char* call) { return std::string(call) + " failed: " + std::strerror(errno); }

}  // namespace

ChildProcess::~ChildProcess() {
  if (running()) Stop();
}

bool ChildProcess::Start(ServeFunction serve, void* context, bool keep_output, std::string* error) {
  if (running()) Stop();
  int sv[2];
  if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0) {
    *error = SystemError("socketpair");
    return false;
  }
  // Unflushed stdio buffers would otherwise be written twice, once by each process.
  std::fflush(nullptr);
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) {
    *error = SystemError("fork");
    close(sv[0]);
    close(sv[1]);
    return false;
  }
  if (pid == 0) {
    // Worker. Dies with the parent, even if the parent is killed without running its destructors.
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(1);
    if (!keep_output) {
      const int null = open("/dev/null", O_WRONLY);
      if (null >= 0) {
        dup2(null, STDOUT_FILENO);
        dup2(null, STDERR_FILENO);
        if (null > STDERR_FILENO) close(null);
      }
    }
    if (sv[1] != kWorkerFd && dup2(sv[1], kWorkerFd) != kWorkerFd) _exit(1);
    // Other workers' sockets, files of the parent: none of them is this worker's business, and holding another
    // worker's socket open would hide that worker's end of stream.
    closefrom(kWorkerFd + 1);
    serve(kWorkerFd, context);
    std::fflush(nullptr);
    _exit(0);
  }
  close(sv[1]);
  pid_ = pid;
  fd_ = sv[0];
  return true;
}

ChildProcess::Io ChildProcess::Write(const void* data, std::size_t bytes) {
  if (!running()) return Io::kClosed;
  return WriteAll(fd_, data, bytes) ? Io::kOk : Io::kClosed;
}

ChildProcess::Io ChildProcess::Write(std::initializer_list<Buffer> buffers) {
  return Write(buffers.begin(), buffers.size());
}

ChildProcess::Io ChildProcess::Write(const Buffer* buffers, std::size_t count) {
  if (!running()) return Io::kClosed;
  return WriteAll(fd_, buffers, count) ? Io::kOk : Io::kClosed;
}

ChildProcess::Io ChildProcess::Read(void* data, std::size_t bytes, Clock::time_point deadline) {
  if (!running()) return Io::kClosed;
  auto* p = static_cast<char*>(data);
  const Clock::time_point spin_end = Clock::now() + spin_;
  while (bytes > 0) {
    if (Clock::now() < spin_end) {  // answer expected soon: try without sleeping
      const ssize_t got = recv(fd_, p, bytes, MSG_DONTWAIT);
      if (got > 0) {
        p += got;
        bytes -= static_cast<std::size_t>(got);
        continue;
      }
      if (got == 0) return Io::kClosed;
      if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) return Io::kClosed;
      continue;
    }
    int timeout_ms = -1;
    if (deadline != Clock::time_point::max()) {
      const double left = std::chrono::duration<double, std::milli>(deadline - Clock::now()).count();
      if (left <= 0.0) return Io::kTimeout;
      timeout_ms = static_cast<int>(std::min(std::ceil(left), 1e9));
    }
    pollfd pfd{fd_, POLLIN, 0};
    const int ready = poll(&pfd, 1, timeout_ms);
    if (ready < 0) {
      if (errno == EINTR) continue;
      return Io::kClosed;
    }
    if (ready == 0) continue;  // re-check the deadline
    const ssize_t got = recv(fd_, p, bytes, MSG_DONTWAIT);
    if (got > 0) {
      p += got;
      bytes -= static_cast<std::size_t>(got);
    } else if (got == 0) {
      return Io::kClosed;
    } else if (errno != EINTR && errno != EAGAIN && errno != EWOULDBLOCK) {
      return Io::kClosed;
    }
  }
  return Io::kOk;
}

std::string ChildProcess::Stop() {
  if (!running()) return "not running";
  kill(pid_, SIGKILL);
  int status = 0;
  while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  close(fd_);
  pid_ = -1;
  fd_ = -1;
  int ignored = 0;
  return Describe(status, &ignored);
}

std::string ChildProcess::Reap(int* signal) {
  *signal = 0;
  if (!running()) return "not running";
  // End of stream means the worker is exiting; give it a moment, then make sure.
  int status = 0;
  pid_t done = 0;
  for (int i = 0; i < 200 && done == 0; ++i) {
    done = waitpid(pid_, &status, WNOHANG);
    if (done == 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    if (done < 0 && errno == EINTR) done = 0;
  }
  if (done == 0) {
    kill(pid_, SIGKILL);
    while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
  }
  close(fd_);
  pid_ = -1;
  fd_ = -1;
  return Describe(status, signal);
}

std::string ChildProcess::Describe(int wait_status, int* signal) {
  *signal = 0;
  if (WIFEXITED(wait_status)) return "exited with code " + std::to_string(WEXITSTATUS(wait_status));
  if (WIFSIGNALED(wait_status)) {
    *signal = WTERMSIG(wait_status);
    const char* abbrev = sigabbrev_np(*signal);
    const char* text = sigdescr_np(*signal);
    return "killed by signal " + std::to_string(*signal) + " (SIG" + (abbrev ? abbrev : "?") + ", " +
           (text ? text : "unknown") + ")";
  }
  return "ended with wait status " + std::to_string(wait_status);
}

bool ChildProcess::ReadAll(int fd, void* data, std::size_t bytes) {
  auto* p = static_cast<char*>(data);
  while (bytes > 0) {
    const ssize_t got = recv(fd, p, bytes, 0);
    if (got > 0) {
      p += got;
      bytes -= static_cast<std::size_t>(got);
    } else if (got == 0 || errno != EINTR) {
      return false;
    }
  }
  return true;
}

void ChildProcess::WaitReadable(int fd, std::chrono::microseconds spin) {
  const Clock::time_point spin_end = Clock::now() + spin;
  char byte;
  while (Clock::now() < spin_end) {
    const ssize_t got = recv(fd, &byte, 1, MSG_PEEK | MSG_DONTWAIT);
    if (got >= 0 || (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) return;  // data, end or error
  }
  pollfd pfd{fd, POLLIN, 0};
  while (poll(&pfd, 1, -1) < 0 && errno == EINTR) {
  }
}

bool ChildProcess::WriteAll(int fd, std::initializer_list<Buffer> buffers) {
  return WriteAll(fd, buffers.begin(), buffers.size());
}

bool ChildProcess::WriteAll(int fd, const Buffer* buffers, std::size_t buffer_count) {
  constexpr std::size_t kMaxParts = 8;
  iovec parts[kMaxParts];
  std::size_t count = 0;
  for (std::size_t k = 0; k < buffer_count; ++k) {
    const Buffer& b = buffers[k];
    if (b.bytes == 0) continue;
    if (count == kMaxParts) return false;
    parts[count++] = iovec{const_cast<void*>(b.data), b.bytes};
  }
  std::size_t first = 0;
  while (first < count) {
    msghdr message{};
    message.msg_iov = parts + first;
    message.msg_iovlen = count - first;
    ssize_t sent = sendmsg(fd, &message, MSG_NOSIGNAL);
    if (sent < 0 && errno == EINTR) continue;
    if (sent <= 0) return false;
    // Skip what went out; a partly sent part continues from where it stopped.
    while (first < count && static_cast<std::size_t>(sent) >= parts[first].iov_len) {
      sent -= static_cast<ssize_t>(parts[first].iov_len);
      ++first;
    }
    if (first < count) {
      parts[first].iov_base = static_cast<char*>(parts[first].iov_base) + sent;
      parts[first].iov_len -= static_cast<std::size_t>(sent);
    }
  }
  return true;
}

bool ChildProcess::WriteAll(int fd, const void* data, std::size_t bytes) {
  const auto* p = static_cast<const char*>(data);
  while (bytes > 0) {
    const ssize_t sent = send(fd, p, bytes, MSG_NOSIGNAL);
    if (sent > 0) {
      p += sent;
      bytes -= static_cast<std::size_t>(sent);
    } else if (sent == 0 || errno != EINTR) {
      return false;
    }
  }
  return true;
}

}  // namespace smcbench

// The worker process behind isolated external backends: request/response, crash and hang containment,
// silenced output, no inherited descriptors, no worker left behind.
#include "solvers/isolation/child_process.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <thread>

namespace smcbench {
namespace {

using Clock = ChildProcess::Clock;

// Requests are one int: ≥ 0 echo twice the value; −1 abort(); −2 hang; −3 report whether stdout is /dev/null;
// −4 report how many descriptors above 3 are open.
void Serve(int fd, void*) {
  for (;;) {
    int request = 0;
    if (!ChildProcess::ReadAll(fd, &request, sizeof request)) return;
    int reply = 0;
    if (request >= 0) {
      reply = 2 * request;
    } else if (request == -1) {
      std::abort();
    } else if (request == -2) {
      for (;;) pause();
    } else if (request == -3) {
      struct stat out {}, null {};
      reply = fstat(STDOUT_FILENO, &out) == 0 && stat("/dev/null", &null) == 0 && out.st_rdev == null.st_rdev;
      std::printf("this line must not reach the test's output\n");
    } else if (request == -4) {
      for (int d = 4; d < 1024; ++d) reply += fcntl(d, F_GETFD) != -1;
    }
    if (!ChildProcess::WriteAll(fd, &reply, sizeof reply)) return;
  }
}

int Ask(ChildProcess* worker, int request, ChildProcess::Io* io, double seconds = 10.0) {
  int reply = -1;
  *io = worker->Write(&request, sizeof request);
  if (*io != ChildProcess::Io::kOk) return reply;
  const auto limit = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  *io = worker->Read(&reply, sizeof reply, Clock::now() + limit);
  return reply;
}

TEST(ChildProcess, ServesManyRequestsFromOneWorker) {
  ChildProcess worker;
  std::string error;
  ASSERT_TRUE(worker.Start(&Serve, nullptr, false, &error)) << error;
  const pid_t pid = worker.pid();
  EXPECT_NE(pid, getpid());
  for (int k = 0; k < 100; ++k) {
    ChildProcess::Io io;
    EXPECT_EQ(Ask(&worker, k, &io), 2 * k);
    EXPECT_EQ(io, ChildProcess::Io::kOk);
  }
  EXPECT_EQ(worker.pid(), pid);
}

TEST(ChildProcess, CrashIsReportedWithItsSignal) {
  ChildProcess worker;
  std::string error;
  ASSERT_TRUE(worker.Start(&Serve, nullptr, false, &error)) << error;
  ChildProcess::Io io;
  Ask(&worker, -1, &io);
  EXPECT_EQ(io, ChildProcess::Io::kClosed);
  int signal = 0;
  const std::string how = worker.Reap(&signal);
  EXPECT_EQ(signal, SIGABRT) << how;
  EXPECT_NE(how.find("SIGABRT"), std::string::npos) << how;
  EXPECT_FALSE(worker.running());
  // A fresh worker can be started after a crash.
  ASSERT_TRUE(worker.Start(&Serve, nullptr, false, &error)) << error;
  EXPECT_EQ(Ask(&worker, 21, &io), 42);
}

TEST(ChildProcess, HangMissesTheDeadlineAndIsKilled) {
  ChildProcess worker;
  std::string error;
  ASSERT_TRUE(worker.Start(&Serve, nullptr, false, &error)) << error;
  const pid_t pid = worker.pid();
  const auto start = Clock::now();
  ChildProcess::Io io;
  Ask(&worker, -2, &io, 0.2);
  const double waited = std::chrono::duration<double>(Clock::now() - start).count();
  EXPECT_EQ(io, ChildProcess::Io::kTimeout);
  EXPECT_GE(waited, 0.19);
  EXPECT_LT(waited, 5.0);
  const std::string how = worker.Stop();
  EXPECT_NE(how.find("SIGKILL"), std::string::npos) << how;
  EXPECT_EQ(kill(pid, 0), -1);  // reaped: the pid no longer exists
  EXPECT_EQ(errno, ESRCH);
}

TEST(ChildProcess, OutputGoesToDevNullUnlessKept) {
  ChildProcess worker;
  std::string error;
  ASSERT_TRUE(worker.Start(&Serve, nullptr, false, &error)) << error;
  ChildProcess::Io io;
  EXPECT_EQ(Ask(&worker, -3, &io), 1);
  ASSERT_TRUE(worker.Start(&Serve, nullptr, true, &error)) << error;  // replaces the first worker
  struct stat out {}, null {};
  const bool test_stdout_is_null =
      fstat(STDOUT_FILENO, &out) == 0 && stat("/dev/null", &null) == 0 && out.st_rdev == null.st_rdev;
  EXPECT_EQ(Ask(&worker, -3, &io), test_stdout_is_null ? 1 : 0);
}

TEST(ChildProcess, WorkersDoNotInheritEachOthersSockets) {
  ChildProcess a, b;
  std::string error;
  ASSERT_TRUE(a.Start(&Serve, nullptr, false, &error)) << error;
  ASSERT_TRUE(b.Start(&Serve, nullptr, false, &error)) << error;
  ChildProcess::Io io;
  EXPECT_EQ(Ask(&b, -4, &io), 0);  // b's only descriptors: 0, 1, 2 and its socket (3)
}

TEST(ChildProcess, DestructorLeavesNoWorkerBehind) {
  pid_t pid = -1;
  {
    ChildProcess worker;
    std::string error;
    ASSERT_TRUE(worker.Start(&Serve, nullptr, false, &error)) << error;
    pid = worker.pid();
    ChildProcess::Io io;
    EXPECT_EQ(Ask(&worker, 1, &io), 2);
  }
  EXPECT_EQ(kill(pid, 0), -1);
  EXPECT_EQ(errno, ESRCH);
}

TEST(ChildProcess, IoWithoutWorkerIsClosed) {
  ChildProcess worker;
  int v = 0;
  EXPECT_EQ(worker.Write(&v, sizeof v), ChildProcess::Io::kClosed);
  EXPECT_EQ(worker.Read(&v, sizeof v, Clock::now()), ChildProcess::Io::kClosed);
  EXPECT_EQ(worker.Stop(), "not running");
}

}  // namespace
}  // namespace smcbench

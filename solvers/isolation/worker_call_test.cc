// CallWorker, the supervision shared by the external adapters: an answer comes back, a hang is cut at the deadline
// and its worker killed, a crash is a status naming the signal, a worker that died while idle is replaced, a reply
// the caller rejects is not an answer; DecideWhereToRun follows the isolation policy.
#include "solvers/isolation/worker_call.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <cstdlib>
#include <thread>

namespace smcbench {
namespace {

using ::testing::HasSubstr;
using Clock = ChildProcess::Clock;

constexpr int kMagic = 0x54455354;  // "TEST"

struct Request {
  int magic = kMagic;
  int value = 0;  // ≥ 0: answer 2·value; −1 abort(); −2 hang; −3 a reply with the wrong magic number
};
struct Head {
  int magic = 0;
  int code = 0;
};

void Serve(int fd, void*) {
  for (;;) {
    Request r;
    if (!ChildProcess::ReadAll(fd, &r, sizeof r)) return;
    if (r.value == -1) std::abort();
    if (r.value == -2) std::this_thread::sleep_for(std::chrono::hours(1));
    const Head head{r.value == -3 ? 0 : kMagic, 7};
    const double answer = 2.0 * r.value;
    if (!ChildProcess::WriteAll(fd, {{&head, sizeof head}, {&answer, sizeof answer}})) return;
  }
}

constexpr WorkerCallNames kNames{"TheLib", "the test worker", "test_signal"};

// One call with request value; *answer receives the reply.
bool Call(ChildProcess* worker, int value, double seconds, SolveResult* result, double* answer, int* starts) {
  Request r;
  r.value = value;
  Head head;
  const std::array<ProbedProblems::Part, 1> parts{{{&r, sizeof r}}};
  const auto start = [&](std::string* error) {
    ++*starts;
    return worker->Start(&Serve, nullptr, /*keep_output=*/false, error);
  };
  const Clock::time_point deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  return CallWorker(worker, start, parts, {&head, sizeof head}, {answer, sizeof *answer},
                    [&] { return head.magic == kMagic; }, seconds, deadline, kNames, result);
}

TEST(CallWorker, AnswersHangsCrashesAndRejectedReplies) {
  ChildProcess worker;
  SolveResult result;
  double answer = 0.0;
  int starts = 0;
  ASSERT_TRUE(Call(&worker, 21, 10.0, &result, &answer, &starts)) << result.message;
  EXPECT_EQ(answer, 42.0);
  EXPECT_EQ(starts, 1);
  ASSERT_TRUE(Call(&worker, 5, 10.0, &result, &answer, &starts));
  EXPECT_EQ(answer, 10.0);
  EXPECT_EQ(starts, 1) << "the worker serves many requests";

  // A hang: cut at the deadline, the worker killed, a fresh one for the next call.
  SolveResult hang;
  EXPECT_FALSE(Call(&worker, -2, 0.2, &hang, &answer, &starts));
  EXPECT_EQ(hang.status, SolveStatus::kTimeLimit);
  EXPECT_THAT(hang.message, HasSubstr("TheLib did not return within the time limit (0.2 s)"));
  EXPECT_FALSE(worker.running());
  ASSERT_TRUE(Call(&worker, 1, 10.0, &result, &answer, &starts));
  EXPECT_EQ(starts, 2);

  // A crash during the solve: a status naming how it died, the signal as the named detail.
  SolveResult crash;
  EXPECT_FALSE(Call(&worker, -1, 10.0, &crash, &answer, &starts));
  EXPECT_EQ(crash.status, SolveStatus::kNumericalFailure);
  EXPECT_THAT(crash.message, HasSubstr("the test worker died during the solve: killed by signal 6"));
  EXPECT_EQ(crash.GetDetail("test_signal"), SIGABRT);

  // A worker that died while idle is replaced once, and the call answers.
  ASSERT_TRUE(Call(&worker, 2, 10.0, &result, &answer, &starts));
  const int before = starts;
  ASSERT_EQ(kill(worker.pid(), SIGKILL), 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  SolveResult replaced;
  ASSERT_TRUE(Call(&worker, 4, 10.0, &replaced, &answer, &starts)) << replaced.message;
  EXPECT_EQ(answer, 8.0);
  EXPECT_EQ(starts, before + 1);

  // A reply the caller rejects (wrong magic number) is no answer: the worker is stopped and it is a failure.
  SolveResult rejected;
  EXPECT_FALSE(Call(&worker, -3, 10.0, &rejected, &answer, &starts));
  EXPECT_EQ(rejected.status, SolveStatus::kNumericalFailure);
  EXPECT_THAT(rejected.message, HasSubstr("the test worker died during the solve"));
  EXPECT_FALSE(worker.running());
}

TEST(CallWorker, AWorkerThatCannotStartIsAStatus) {
  ChildProcess worker;
  SolveResult result;
  Request r;
  Head head;
  double answer = 0.0;
  const std::array<ProbedProblems::Part, 1> parts{{{&r, sizeof r}}};
  const auto cannot = [](std::string* error) {
    *error = "fork: Resource temporarily unavailable";
    return false;
  };
  EXPECT_FALSE(CallWorker(&worker, cannot, parts, {&head, sizeof head}, {&answer, sizeof answer},
                          [] { return true; }, 1.0, Clock::now() + std::chrono::seconds(1), kNames, &result));
  EXPECT_EQ(result.status, SolveStatus::kNumericalFailure);
  EXPECT_EQ(result.message, "could not start the test worker: fork: Resource temporarily unavailable");
}

TEST(DecideWhereToRun, FollowsThePolicyAndTheProbe) {
  const ProbedProblems::Outcome quick{ProbedProblems::Console::kSilent, 0.5};
  // never: in process, no probe; always: in the worker, no probe.
  EXPECT_TRUE(DecideWhereToRun(IsolationPolicy::kNever, nullptr, 1.0).in_process);
  EXPECT_FALSE(DecideWhereToRun(IsolationPolicy::kNever, nullptr, 1.0).probe);
  EXPECT_FALSE(DecideWhereToRun(IsolationPolicy::kAlways, nullptr, 1.0).in_process);
  EXPECT_FALSE(DecideWhereToRun(IsolationPolicy::kAlways, nullptr, 1.0).probe);
  // first: an unprobed problem is probed in the worker; a probed one runs here if its probe fit this limit.
  EXPECT_TRUE(DecideWhereToRun(IsolationPolicy::kFirst, nullptr, 1.0).probe);
  EXPECT_FALSE(DecideWhereToRun(IsolationPolicy::kFirst, nullptr, 1.0).in_process);
  EXPECT_TRUE(DecideWhereToRun(IsolationPolicy::kFirst, &quick, 1.0).in_process);
  EXPECT_FALSE(DecideWhereToRun(IsolationPolicy::kFirst, &quick, 1.0).probe);
  EXPECT_FALSE(DecideWhereToRun(IsolationPolicy::kFirst, &quick, 0.1).in_process) << "its probe took longer";
}

}  // namespace
}  // namespace smcbench

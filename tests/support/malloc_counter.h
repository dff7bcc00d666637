// Counts heap allocations at the malloc level (so Eigen's aligned_malloc, std::vector and operator new are all
// seen) by interposing glibc's malloc family in the test executable, records the largest single request, and keeps
// the live heap bytes and their peak (free is interposed too). Used to pin "hot paths do not allocate", "a hostile
// size field is refused before allocating" and "a run's memory does not grow with its length".
#pragma once

namespace smcbench::test_support {

// False under AddressSanitizer (it owns malloc): tests must then GTEST_SKIP.
bool CanCountMallocs();

// Number of malloc/calloc/realloc/aligned allocations made while fn runs on this thread's program.
template <typename Fn>
long CountMallocs(Fn&& fn);

void StartCountingMallocs();
long StopCountingMallocs();
// The largest single request (bytes) since the last StartCountingMallocs, while counting was on.
unsigned long LargestMallocRequest();
// Calls of the global operator new (new, new[]) since the last StartCountingMallocs, while counting was on: the
// allocations of C++ code, without the mallocs of C libraries (UMFPACK factorizes with its own malloc).
long OperatorNewCalls();

// Calls of the global operator new while fn runs (0 when allocations cannot be observed).
template <typename Fn>
long CountOperatorNew(Fn&& fn) {
  StartCountingMallocs();
  fn();
  StopCountingMallocs();
  return OperatorNewCalls();
}

// Live heap bytes: the usable size (malloc_usable_size) of every block malloc & co. returned that free has not
// released, tracked always (not only while counting). ResetHeapPeak starts a measurement; HeapPeakAboveReset is
// the most the live bytes rose above their level at the reset since then (0 when they cannot be observed).
void ResetHeapPeak();
long HeapPeakAboveReset();

// Largest single allocation while fn runs (0 when allocations cannot be observed).
template <typename Fn>
unsigned long LargestMalloc(Fn&& fn) {
  StartCountingMallocs();
  fn();
  StopCountingMallocs();
  return LargestMallocRequest();
}

template <typename Fn>
long CountMallocs(Fn&& fn) {
  StartCountingMallocs();
  fn();
  return StopCountingMallocs();
}

}  // namespace smcbench::test_support

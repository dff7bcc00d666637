// The interposed allocator behind malloc_counter.h: counts, largest request, operator new calls, live heap peak.
#include "tests/support/malloc_counter.h"

#include <malloc.h>

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>

#if defined(__SANITIZE_ADDRESS__)
#define SMCBENCH_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SMCBENCH_SANITIZED 1
#endif
#endif

namespace {
std::atomic<bool> g_counting{false};
std::atomic<long> g_count{0};
std::atomic<std::size_t> g_largest{0};
std::atomic<long> g_news{0};
std::atomic<long> g_live{0};
std::atomic<long> g_peak{0};
long g_live_at_reset = 0;
[[maybe_unused]] inline void Count(std::size_t size) {  // unused in sanitized builds (the allocator is ASan's)
  if (!g_counting.load(std::memory_order_relaxed)) return;
  g_count.fetch_add(1, std::memory_order_relaxed);
  std::size_t seen = g_largest.load(std::memory_order_relaxed);
  while (size > seen && !g_largest.compare_exchange_weak(seen, size, std::memory_order_relaxed)) {
  }
}
// The live-heap bookkeeping of every block returned and released (unused in sanitized builds).
[[maybe_unused]] inline void AddLive(void* p) {
  if (!p) return;
  const auto size = static_cast<long>(malloc_usable_size(p));
  const long now = g_live.fetch_add(size, std::memory_order_relaxed) + size;
  long seen = g_peak.load(std::memory_order_relaxed);
  while (now > seen && !g_peak.compare_exchange_weak(seen, now, std::memory_order_relaxed)) {
  }
}
[[maybe_unused]] inline void RemoveLive(void* p) {
  if (p) g_live.fetch_sub(static_cast<long>(malloc_usable_size(p)), std::memory_order_relaxed);
}
}  // namespace

#ifndef SMCBENCH_SANITIZED
// glibc exports its allocator under __libc_* names: defining malloc & co. in the executable interposes them.
extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t n, std::size_t size);
void* __libc_realloc(void* p, std::size_t size);
void* __libc_memalign(std::size_t alignment, std::size_t size);
void __libc_free(void* p);

void* malloc(std::size_t size) noexcept {
  Count(size);
  void* p = __libc_malloc(size);
  AddLive(p);
  return p;
}
void free(void* p) noexcept {
  RemoveLive(p);
  __libc_free(p);
}
void* calloc(std::size_t n, std::size_t size) noexcept {
  Count(n * size);
  void* p = __libc_calloc(n, size);
  AddLive(p);
  return p;
}
void* realloc(void* p, std::size_t size) noexcept {
  Count(size);
  // The old block is released (or moved) either way, except when the call fails, which leaves it in place.
  RemoveLive(p);
  void* q = __libc_realloc(p, size);
  AddLive(q ? q : (size ? p : nullptr));
  return q;
}
void* aligned_alloc(std::size_t alignment, std::size_t size) noexcept {
  Count(size);
  void* p = __libc_memalign(alignment, size);
  AddLive(p);
  return p;
}
void* memalign(std::size_t alignment, std::size_t size) noexcept {
  Count(size);
  void* p = __libc_memalign(alignment, size);
  AddLive(p);
  return p;
}
int posix_memalign(void** out, std::size_t alignment, std::size_t size) noexcept {
  Count(size);
  *out = __libc_memalign(alignment, size);
  AddLive(*out);
  return *out ? 0 : 12 /* ENOMEM */;
}
}

// Replaceable global operator new (the throwing forms; the others call these): counted on top of the malloc it
// makes, so that "our code did not allocate" can be told apart from a library's own mallocs (UMFPACK).
// GCC pairs the inlined replacement new/delete with malloc/free and warns; they are matched by construction.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t size) {
  if (g_counting.load(std::memory_order_relaxed)) g_news.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return ::operator new(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
#endif

namespace smcbench::test_support {

bool CanCountMallocs() {
#ifdef SMCBENCH_SANITIZED
  return false;
#else
  return true;
#endif
}

void StartCountingMallocs() {
  g_count = 0;
  g_news = 0;
  g_largest = 0;
  g_counting = true;
}

long StopCountingMallocs() {
  g_counting = false;
  return g_count.load();
}

unsigned long LargestMallocRequest() { return g_largest.load(); }

long OperatorNewCalls() { return g_news.load(); }

void ResetHeapPeak() {
  g_live_at_reset = g_live.load();
  g_peak = g_live_at_reset;
}

long HeapPeakAboveReset() { return g_peak.load() - g_live_at_reset; }

}  // namespace smcbench::test_support

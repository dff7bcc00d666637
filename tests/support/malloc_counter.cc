#include "tests/support/malloc_counter.h"

#include <atomic>
#include <cstddef>

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
[[maybe_unused]] inline void Count(std::size_t size) {  // unused in sanitized builds (the allocator is ASan's)
  if (!g_counting.load(std::memory_order_relaxed)) return;
  g_count.fetch_add(1, std::memory_order_relaxed);
  std::size_t seen = g_largest.load(std::memory_order_relaxed);
  while (size > seen && !g_largest.compare_exchange_weak(seen, size, std::memory_order_relaxed)) {
  }
}
}  // namespace

#ifndef SMCBENCH_SANITIZED
// glibc exports its allocator under __libc_* names: defining malloc & co. in the executable interposes them.
extern "C" {
void* __libc_malloc(std::size_t size);
void* __libc_calloc(std::size_t n, std::size_t size);
void* __libc_realloc(void* p, std::size_t size);
void* __libc_memalign(std::size_t alignment, std::size_t size);

void* malloc(std::size_t size) noexcept {
  Count(size);
  return __libc_malloc(size);
}
void* calloc(std::size_t n, std::size_t size) noexcept {
  Count(n * size);
  return __libc_calloc(n, size);
}
void* realloc(void* p, std::size_t size) noexcept {
  Count(size);
  return __libc_realloc(p, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size) noexcept {
  Count(size);
  return __libc_memalign(alignment, size);
}
void* memalign(std::size_t alignment, std::size_t size) noexcept {
  Count(size);
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** out, std::size_t alignment, std::size_t size) noexcept {
  Count(size);
  *out = __libc_memalign(alignment, size);
  return *out ? 0 : 12 /* ENOMEM */;
}
}
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
  g_largest = 0;
  g_counting = true;
}

long StopCountingMallocs() {
  g_counting = false;
  return g_count.load();
}

unsigned long LargestMallocRequest() { return g_largest.load(); }

}  // namespace smcbench::test_support

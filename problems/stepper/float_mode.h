// Opt-in flush of subnormal numbers for a time-stepping run: a state that decays to the origin passes through the
// subnormal range (|x| < 2.2e-308), where every operation costs 10–100× more. SubnormalPolicy::kFlushToZero
// (linear_stepper.h) turns it on for one Run(); the default, kZeroState, zeroes the subnormal state components
// instead, which is portable and, measured, faster (docs/benchmarks.md, "Long runs and subnormal numbers").
#pragma once

#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#define SMCBENCH_HAS_MXCSR 1
#endif

namespace smcbench {

// Sets flush-to-zero and denormals-are-zero (x86 MXCSR, this thread only) while it lives, when `on`; restores the
// previous mode on destruction. A no-op on other architectures (supported() is false there).
class ScopedFlushSubnormals {
 public:
  explicit ScopedFlushSubnormals(bool on) : on_(on && supported()) {
#ifdef SMCBENCH_HAS_MXCSR
    if (on_) {
      saved_ = _mm_getcsr();
      _mm_setcsr(saved_ | kFlushToZero | kDenormalsAreZero);
    }
#endif
  }
  ~ScopedFlushSubnormals() {
#ifdef SMCBENCH_HAS_MXCSR
    if (on_) _mm_setcsr(saved_);
#endif
  }
  ScopedFlushSubnormals(const ScopedFlushSubnormals&) = delete;
  ScopedFlushSubnormals& operator=(const ScopedFlushSubnormals&) = delete;

  static constexpr bool supported() {
#ifdef SMCBENCH_HAS_MXCSR
    return true;
#else
    return false;
#endif
  }

 private:
  static constexpr unsigned kFlushToZero = 0x8000, kDenormalsAreZero = 0x0040;
  bool on_;
  unsigned saved_ = 0;
};

}  // namespace smcbench

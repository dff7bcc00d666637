// The project's reproducible random numbers: std::mt19937_64 (fully specified by the standard) read through our
// own bit manipulation, never a std::*_distribution (their algorithms differ between standard libraries), so the
// same seed gives the same problems on every platform. Used by the generators and the suites.
#pragma once

#include <algorithm>
#include <cstdint>
#include <random>

namespace smcbench {

class SeededRandom {
 public:
  explicit SeededRandom(std::uint64_t seed) : engine_(seed) {}
  // Uniform in [0, 1): the top 53 bits scaled by 2⁻⁵³ (exact).
  double Uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  double Uniform(double a, double b) { return a + (b - a) * Uniform(); }
  // Uniform integer in [0, k) for small k (bias < k·2⁻⁵³, irrelevant here).
  int Index(int k) { return std::min(k - 1, static_cast<int>(Uniform() * k)); }
  bool Coin() { return Index(2) == 1; }

 private:
  std::mt19937_64 engine_;
};

}  // namespace smcbench

// The elementary functions the built-in MCPs use, for double (the standard library) and for __float128 (written
// here from their series, correct to a few units of quad rounding: libquadmath is not a dependency), so that an MCP
// written once as a template on the scalar type evaluates in both.
#pragma once

#include <cmath>
#include <limits>

#include "solvers/core/extended_precision_mcp.h"

namespace smcbench::mcp_math {

inline double Sqrt(double x) { return std::sqrt(x); }
inline double Exp(double x) { return std::exp(x); }
inline double Log(double x) { return std::log(x); }
inline double Pow(double x, double a) { return std::pow(x, a); }
inline double Atan(double x) { return std::atan(x); }
inline double Abs(double x) { return std::abs(x); }

inline Quad Abs(Quad x) { return x < 0 ? -x : x; }
inline bool IsNan(Quad x) { return x != x; }
inline Quad QuadNaN() { return static_cast<Quad>(std::numeric_limits<double>::quiet_NaN()); }

// Two Newton steps from the double root double the 53 correct bits twice (> 113).
inline Quad Sqrt(Quad x) {
  if (IsNan(x) || x < 0) return QuadNaN();
  if (x == 0) return 0;
  const double xd = static_cast<double>(x);
  if (!std::isfinite(xd)) return x;
  Quad r = std::sqrt(xd);
  for (int i = 0; i < 3; ++i) r = (r + x / r) / 2;
  return r;
}

// log 2 = 2 atanh(1/3) = 2 Σ 3^−(2k+1)/(2k+1): each term a factor 9 smaller, 36 terms reach 2⁻¹¹³.
inline Quad Ln2() {
  Quad sum = 0, power = Quad(1) / 3;
  for (int k = 0; k < 40; ++k, power /= 9) sum += power / (2 * k + 1);
  return 2 * sum;
}

// 2^e exactly (|e| < 1000).
inline Quad PowerOfTwo(int e) { return static_cast<Quad>(std::ldexp(1.0, e)); }

// x = k log 2 + r with |r| ≤ log 2 / 2, r quartered (each squaring back doubles the relative error, so few),
// Taylor to 2⁻¹¹³ (|r/4| ≤ 0.087: 30 terms), then squared twice.
inline Quad Exp(Quad x) {
  if (IsNan(x)) return x;
  if (x > 11000) return static_cast<Quad>(std::numeric_limits<double>::infinity());
  if (x < -11000) return 0;
  const Quad ln2 = Ln2();
  const double kd = std::nearbyint(static_cast<double>(x / ln2));
  const int k = static_cast<int>(kd);
  const Quad r = (x - kd * ln2) / 4;
  Quad sum = 1, term = 1;
  for (int n = 1; n < 34; ++n) {
    term = term * r / n;
    sum += term;
  }
  for (int i = 0; i < 2; ++i) sum *= sum;
  // 2^k in two factors keeps each within the double exponent range used by PowerOfTwo.
  return sum * PowerOfTwo(k / 2) * PowerOfTwo(k - k / 2);
}

// x = m 2^e with m ∈ [1/√2, √2), log m = 2 atanh((m − 1)/(m + 1)) by its series (|s| ≤ 0.172).
inline Quad Log(Quad x) {
  if (IsNan(x) || x < 0) return QuadNaN();
  if (x == 0) return -static_cast<Quad>(std::numeric_limits<double>::infinity());
  int e = 0;
  std::frexp(static_cast<double>(x), &e);
  Quad m = x * PowerOfTwo(-e);  // in [1/2, 1) up to the rounding of the double conversion
  if (m < Quad(0.70710678118654752)) {
    m *= 2;
    --e;
  }
  const Quad s = (m - 1) / (m + 1), s2 = s * s;
  Quad sum = 0, power = s;
  for (int k = 0; k < 40; ++k, power *= s2) sum += power / (2 * k + 1);
  return 2 * sum + e * Ln2();
}

// x^a for x > 0 (0 for x = 0 < a, NaN for x < 0).
inline Quad Pow(Quad x, Quad a) {
  if (IsNan(x) || IsNan(a) || x < 0) return QuadNaN();
  if (x == 0) return a > 0 ? Quad(0) : QuadNaN();
  return Exp(a * Log(x));
}

// atan x = 2 atan(x / (1 + √(1 + x²))) applied 4 times (|x| then ≤ tan(π/32) ≈ 0.1), then the odd series.
inline Quad Atan(Quad x) {
  if (IsNan(x)) return x;
  int halvings = 0;
  while (halvings < 4) {
    x = x / (1 + Sqrt(1 + x * x));
    ++halvings;
  }
  const Quad x2 = x * x;
  Quad sum = 0, power = x;
  for (int k = 0; k < 40; ++k, power *= -x2) sum += power / (2 * k + 1);
  return sum * PowerOfTwo(halvings);
}

}  // namespace smcbench::mcp_math

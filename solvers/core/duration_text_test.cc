// DurationText: the unit ladder and its rounding edges, written out by hand.
#include "solvers/core/duration_text.h"

#include <gtest/gtest.h>

namespace smcbench {
namespace {

TEST(DurationText, UnitLadderWithThreeSignificantDigits) {
  EXPECT_EQ(DurationText(0.0), "0 ns");
  EXPECT_EQ(DurationText(850e-9), "850 ns");
  EXPECT_EQ(DurationText(999.4e-9), "999 ns");
  EXPECT_EQ(DurationText(999.6e-9), "1 µs");  // rounds up across the unit, never "1000 ns"
  EXPECT_EQ(DurationText(12.34e-6), "12.3 µs");
  EXPECT_EQ(DurationText(999.7e-6), "1 ms");
  EXPECT_EQ(DurationText(4.567e-3), "4.57 ms");
  EXPECT_EQ(DurationText(1.234), "1.23 s");
  EXPECT_EQ(DurationText(1234.0), "1.23e+03 s");
}

TEST(DurationText, NotMeasuredAndNonFinite) {
  EXPECT_EQ(DurationText(-1.0), "-");
  EXPECT_EQ(DurationText(std::nan("")), "nan");
  EXPECT_EQ(DurationText(HUGE_VAL), "inf");
}

}  // namespace
}  // namespace smcbench

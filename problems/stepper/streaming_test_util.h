// Test helper for StepperOptions::sink: reassembles the streamed blocks into a recorded Trajectory, checking that
// rows arrive in order, each once, so that a streamed run can be compared bit for bit with the recorded one.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>

#include "problems/stepper/trajectory.h"

namespace smcbench::stepper_test {

class CollectingSink final : public TrajectorySink {
 public:
  void OnRows(const TrajectoryBlock& block) override {
    ++blocks;
    largest_block = std::max(largest_block, block.rows);
    if (block.first_row != rows.steps_taken + (rows.recorded ? 1 : 0)) in_order = false;
    if (!rows.recorded) {
      rows.recorded = true;
      rows.n = block.n;
      rows.m = block.m;
      rows.steps_taken = -1;
    }
    const auto old = static_cast<Eigen::Index>(rows.t.size());
    const auto add = static_cast<Eigen::Index>(block.rows);
    rows.x.conservativeResize(block.n, old + add);
    rows.s.conservativeResize(block.m, old + add);
    rows.y.conservativeResize(block.m, old + add);
    rows.has_input = block.has_input();
    rows.u.conservativeResize(block.u.rows(), old + add);
    for (Eigen::Index j = 0; j < add; ++j) {
      rows.t.push_back(block.t[static_cast<std::size_t>(j)]);
      rows.x.col(old + j) = block.x.col(j);
      rows.s.col(old + j) = block.s.col(j);
      rows.y.col(old + j) = block.y.col(j);
      if (rows.has_input) rows.u.col(old + j) = block.u.col(j);
      rows.iterations.push_back(block.iterations[static_cast<std::size_t>(j)]);
      rows.residual.push_back(block.residual[static_cast<std::size_t>(j)]);
      rows.status.push_back(block.status[static_cast<std::size_t>(j)]);
    }
    rows.steps_taken += block.rows;
  }

  Trajectory rows;  // recorded = true once a block came; steps_taken = the last row
  int blocks = 0;
  std::int64_t largest_block = 0;
  bool in_order = true;
};

inline bool SameBits(const DenseMatrix& a, const DenseMatrix& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

// Every row of the recorded run equals the streamed one bit for bit, statuses included.
inline void ExpectSameRows(const Trajectory& recorded, const CollectingSink& streamed) {
  EXPECT_TRUE(streamed.in_order);
  const Trajectory& s = streamed.rows;
  ASSERT_TRUE(s.recorded);
  ASSERT_EQ(s.steps_taken, recorded.steps_taken);
  EXPECT_EQ(std::memcmp(s.t.data(), recorded.t.data(), sizeof(double) * s.t.size()), 0);
  EXPECT_TRUE(SameBits(s.x, recorded.x));
  EXPECT_TRUE(SameBits(s.s, recorded.s));
  EXPECT_TRUE(SameBits(s.y, recorded.y));
  EXPECT_EQ(s.iterations, recorded.iterations);
  EXPECT_EQ(std::memcmp(s.residual.data(), recorded.residual.data(), sizeof(double) * s.residual.size()), 0);
  EXPECT_EQ(s.status, recorded.status);
}

}  // namespace smcbench::stepper_test

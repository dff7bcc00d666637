// What a time-stepper run produces: the discrete trajectory (t_k, x_k, s_k, y_k) and, per step, what the
// backend reported; plus the CSV writer of issue 3 (`t,x1..xn,s1..sm,y1..ym,iterations,residual`).
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "solvers/core/status.h"
#include "solvers/core/types.h"

namespace smcbench {

// Row/column k (k = 0..steps_taken) holds t_k, x_k, the s_k that produced x_k (s_0 = 0: no step produced x_0)
// and y_k = C x_k + D. The per-step arrays describe the one-step problem that produced x_k; entry 0 is empty
// (0 iterations, residual 0, kNotRun), and so is every step of an explicit-sign scheme (no problem is solved).
struct Trajectory {
  int n = 0;
  int m = 0;
  double h = 0.0;
  double t0 = 0.0;
  std::string description;           // the discretization, e.g. "theta=1, implicit sign"
  std::int64_t num_steps = 0;        // N requested
  std::int64_t steps_taken = 0;      // steps done; < num_steps only if the run stopped on a failure

  // Full history, filled only when the run records (StepperOptions::record); else empty.
  bool recorded = false;
  std::vector<double> t;             // steps_taken + 1
  DenseMatrix x;                     // n × (steps_taken + 1)
  DenseMatrix s;                     // m × (steps_taken + 1)
  DenseMatrix y;                     // m × (steps_taken + 1)
  std::vector<int> iterations;       // backend iterations of the step producing x_k
  std::vector<double> residual;      // its relative natural residual (what options.tolerance judges)
  std::vector<SolveStatus> status;   // its status

  // Always filled, recorded or not.
  Vector x_final, s_final, y_final;  // x_N, s_N, y_N (of the last step taken)
  double max_residual = 0.0;         // max relative natural residual over all solved one-step problems
  std::int64_t total_iterations = 0;
  int max_iterations = 0;
  std::int64_t failed_steps = 0;     // steps whose one-step problem was not kSolved (or whose state overflowed)
  std::int64_t first_failed_step = -1;  // k of the first failed step (the step producing x_k), -1 if none
  SolveStatus first_failure_status = SolveStatus::kNotRun;
  double first_failure_residual = 0.0;
  std::string first_failure_message;
  bool stopped_early = false;        // true when the run stopped at first_failed_step

  bool ok() const { return failed_steps == 0 && steps_taken == num_steps; }
  // Writes recorded row k (storage already sized by the stepper). Templated so fixed-size kernels write their
  // fixed-size vectors without a conversion.
  template <typename X, typename S, typename Y>
  void SetRow(std::int64_t k, double t_k, const X& x_k, const S& s_k, const Y& y_k, int iterations_k,
              double residual_k, SolveStatus status_k) {
    const auto c = static_cast<Eigen::Index>(k);
    t[c] = t_k;
    x.col(c) = x_k;
    s.col(c) = s_k;
    y.col(c) = y_k;
    iterations[c] = iterations_k;
    residual[c] = residual_k;
    status[c] = status_k;
  }
  double time(std::int64_t k) const { return t0 + static_cast<double>(k) * h; }
};

// Header `t,x1..xn,s1..sm,y1..ym,iterations,residual`, then one row per recorded step, numbers in shortest
// round-trip form. Throws InvalidInputError if the trajectory was not recorded or the stream fails.
void WriteTrajectoryCsv(const Trajectory& trajectory, std::ostream& out);
void WriteTrajectoryCsvFile(const Trajectory& trajectory, const std::string& path);

}  // namespace smcbench

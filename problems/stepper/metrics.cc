#include "problems/stepper/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "solvers/core/problem.h"

namespace smcbench {
namespace {

void RequireRecorded(const Trajectory& trajectory, const char* owner) {
  if (!trajectory.recorded) {
    throw InvalidInputError(std::string(owner) + ": the trajectory was not recorded (StepperOptions::record = false)");
  }
}

int Sign(double v, double dead_zone) { return v > dead_zone ? 1 : (v < -dead_zone ? -1 : 0); }

// Sign changes and total variation of s_i over rows [first, last] (pairs (j−1, j) with first < j ≤ last).
void SignStatistics(const DenseMatrix& s, int i, Eigen::Index first, Eigen::Index last, double dead_zone,
                    std::int64_t* changes, double* variation) {
  *changes = 0;
  *variation = 0.0;
  if (first > last) return;
  int last_sign = Sign(s(i, first), dead_zone);
  for (Eigen::Index j = first + 1; j <= last; ++j) {
    *variation += std::abs(s(i, j) - s(i, j - 1));
    const int sign = Sign(s(i, j), dead_zone);
    if (sign == 0) continue;
    if (last_sign != 0 && sign != last_sign) ++*changes;
    last_sign = sign;
  }
}

}  // namespace

TrajectoryMetrics ComputeMetrics(const Trajectory& trajectory, double tol, double sign_dead_zone) {
  RequireRecorded(trajectory, "ComputeMetrics");
  if (!(tol >= 0.0)) throw InvalidInputError("ComputeMetrics: tol must be >= 0");
  if (!(sign_dead_zone >= 0.0)) throw InvalidInputError("ComputeMetrics: sign_dead_zone must be >= 0");
  const Trajectory& tr = trajectory;
  const Eigen::Index last = static_cast<Eigen::Index>(tr.steps_taken);
  TrajectoryMetrics out;
  out.tolerance = tol;
  out.sign_dead_zone = sign_dead_zone;
  out.max_residual = tr.max_residual;
  out.total_iterations = tr.total_iterations;
  out.max_iterations = tr.max_iterations;
  out.failed_steps = tr.failed_steps;
  out.surfaces.resize(tr.m);
  bool all_reached = true;
  std::int64_t reaching_all = 0;
  for (int i = 0; i < tr.m; ++i) {
    SurfaceMetrics& sm = out.surfaces[i];
    // Scan backwards for the last violation; NaN counts as a violation.
    Eigen::Index j = last;
    while (j >= 0 && std::abs(tr.y(i, j)) <= tol) --j;
    if (j == last) {
      sm.reaching_step = -1;
      all_reached = false;
    } else {
      sm.reaching_step = j + 1;
      reaching_all = std::max(reaching_all, sm.reaching_step);
      for (Eigen::Index r = j + 1; r <= last; ++r) sm.max_abs_y_after = std::max(sm.max_abs_y_after, std::abs(tr.y(i, r)));
      SignStatistics(tr.s, i, std::max<Eigen::Index>(j + 1, 1), last, sign_dead_zone, &sm.sign_changes_after,
                     &sm.total_variation_after);
    }
    SignStatistics(tr.s, i, 1, last, sign_dead_zone, &sm.sign_changes_total, &sm.total_variation_total);
  }
  out.reaching_step = all_reached ? reaching_all : -1;
  return out;
}

// ------------------------------------------------------------------------------------------------------------
// MetricsAccumulator: ComputeMetrics forwards. Per surface and row j, with v the last violating row so far:
//   j violates (|y| > tol or NaN): v = j; the "after" statistics restart (max |y|, changes, variation = 0).
//   else: max |y| after includes |y_j|; and for j ≥ 1 (row 0 holds no step's s), SignStatistics over rows
//   [max(v + 1, 1), j]: the first of those rows sets the last sign, each later one adds |s_j − s_{j−1}| and
//   counts a sign change exactly as the backward scan does.
// The totals are SignStatistics over rows [1, j]. At the end, reached ⇔ the last row does not violate.

MetricsAccumulator::MetricsAccumulator(int m, double tol, double sign_dead_zone)
    : tol_(tol), dead_zone_(sign_dead_zone) {
  if (!(tol >= 0.0)) throw InvalidInputError("MetricsAccumulator: tol must be >= 0");
  if (!(sign_dead_zone >= 0.0)) throw InvalidInputError("MetricsAccumulator: sign_dead_zone must be >= 0");
  if (m < 0) throw InvalidInputError("MetricsAccumulator: m must be >= 0");
  surfaces_.resize(static_cast<std::size_t>(m));
}

void MetricsAccumulator::OnRows(const TrajectoryBlock& block) {
  const int m = static_cast<int>(surfaces_.size());
  if (block.m != m) {
    throw InvalidInputError("MetricsAccumulator: a block with m = " + std::to_string(block.m) + " for " +
                            std::to_string(m) + " surface(s)");
  }
  if (block.rows <= 0) return;
  // Surface by surface, its state in locals (registers) over the block's rows: this runs once per step of
  // `simulate --summary`, whose budget is a few nanoseconds.
  const double tol = tol_, dead_zone = dead_zone_;
  for (int i = 0; i < m; ++i) {
    Surface sf = surfaces_[static_cast<std::size_t>(i)];
    const double* s_row = block.s.data() + i;
    const double* y_row = block.y.data() + i;
    std::int64_t j = block.first_row;
    for (std::int64_t c = 0; c < block.rows; ++c, ++j, s_row += m, y_row += m) {
      const double s = *s_row;
      const double abs_y = std::abs(*y_row);
      const int sign = Sign(s, dead_zone);
      if (j >= 2) {
        // Totals over rows [1, j] (row 1 only sets the first sign, below).
        sf.variation_total += std::abs(s - sf.previous_s);
        if (sign != 0) {
          if (sf.last_sign_total != 0 && sign != sf.last_sign_total) ++sf.changes_total;
          sf.last_sign_total = sign;
        }
      } else if (j == 1) {
        sf.last_sign_total = sign;
      }
      if (!(abs_y <= tol)) {  // a violation (NaN included): the "after" statistics restart
        sf.last_violation = j;
        sf.max_abs_y_after = 0.0;
        sf.changes_after = 0;
        sf.variation_after = 0.0;
        sf.last_sign_after = 0;
      } else {
        sf.max_abs_y_after = std::max(sf.max_abs_y_after, abs_y);
        const std::int64_t first = std::max<std::int64_t>(sf.last_violation + 1, 1);
        if (j > first) {
          sf.variation_after += std::abs(s - sf.previous_s);
          if (sign != 0) {
            if (sf.last_sign_after != 0 && sign != sf.last_sign_after) ++sf.changes_after;
            sf.last_sign_after = sign;
          }
        } else if (j == first) {
          sf.last_sign_after = sign;
        }
      }
      sf.previous_s = s;
    }
    surfaces_[static_cast<std::size_t>(i)] = sf;
  }
  last_row_ = block.first_row + block.rows - 1;
}

TrajectoryMetrics MetricsAccumulator::Result(const Trajectory& run) const {
  TrajectoryMetrics out;
  out.tolerance = tol_;
  out.sign_dead_zone = dead_zone_;
  out.max_residual = run.max_residual;
  out.total_iterations = run.total_iterations;
  out.max_iterations = run.max_iterations;
  out.failed_steps = run.failed_steps;
  out.surfaces.resize(surfaces_.size());
  bool all_reached = true;
  std::int64_t reaching_all = 0;
  for (std::size_t i = 0; i < surfaces_.size(); ++i) {
    const Surface& sf = surfaces_[i];
    SurfaceMetrics& sm = out.surfaces[i];
    sm.sign_changes_total = sf.changes_total;
    sm.total_variation_total = sf.variation_total;
    if (last_row_ < 0 || sf.last_violation == last_row_) {
      sm.reaching_step = -1;
      all_reached = false;
    } else {
      sm.reaching_step = sf.last_violation + 1;
      reaching_all = std::max(reaching_all, sm.reaching_step);
      sm.max_abs_y_after = sf.max_abs_y_after;
      sm.sign_changes_after = sf.changes_after;
      sm.total_variation_after = sf.variation_after;
    }
  }
  out.reaching_step = all_reached ? reaching_all : -1;
  return out;
}

namespace {

ErrorNorms Norms(const std::vector<double>& e, double h) {
  ErrorNorms n;
  double sum_sq = 0.0;
  for (double v : e) {
    n.l1 += v;
    sum_sq += v * v;
    n.max = std::max(n.max, v);
  }
  n.l1 *= h;
  n.l2 = std::sqrt(h * sum_sq);
  return n;
}

}  // namespace

SolutionErrors ComputeErrors(const Trajectory& trajectory, const ExactSolution& exact) {
  RequireRecorded(trajectory, "ComputeErrors");
  const Trajectory& tr = trajectory;
  const Eigen::Index last = static_cast<Eigen::Index>(tr.steps_taken);
  // Norms over rows first..last of the largest error of one series (x from row 0; s from row 1: s_0 is no value).
  const auto series_errors = [&](const auto& reference_at, const DenseMatrix& values, Eigen::Index first) {
    Vector ref(values.rows());
    std::vector<double> e;
    for (Eigen::Index k = first; k <= last; ++k) {
      reference_at(tr.t[k], ref);
      e.push_back((values.col(k) - ref).cwiseAbs().maxCoeff());
    }
    return Norms(e, tr.h);
  };
  SolutionErrors out;
  if (exact.x) out.x = series_errors(exact.x, tr.x, 0);
  if (exact.s) out.s = series_errors(exact.s, tr.s, 1);
  return out;
}

ErrorsAccumulator::ErrorsAccumulator(int n, int m, double h, ExactSolution exact)
    : exact_(std::move(exact)), h_(h), x_ref_(n), s_ref_(m) {}

void ErrorsAccumulator::OnRows(const TrajectoryBlock& block) {
  for (std::int64_t c = 0; c < block.rows; ++c) {
    const auto col = static_cast<Eigen::Index>(c);
    if (exact_.x) {
      exact_.x(block.t[c], x_ref_);
      x_.Add((block.x.col(col) - x_ref_).cwiseAbs().maxCoeff());
    }
    if (exact_.s && block.row(c) >= 1) {
      exact_.s(block.t[c], s_ref_);
      s_.Add((block.s.col(col) - s_ref_).cwiseAbs().maxCoeff());
    }
  }
}

SolutionErrors ErrorsAccumulator::Result() const {
  const auto norms = [&](const Sums& sums) {
    ErrorNorms n;
    n.l1 = sums.sum * h_;
    n.l2 = std::sqrt(h_ * sums.sum_sq);
    n.max = sums.max;
    return n;
  };
  SolutionErrors out;
  if (exact_.x) out.x = norms(x_);
  if (exact_.s) out.s = norms(s_);
  return out;
}

void ReferenceErrorsAccumulator::Add(const double* s, const double* y, const double* s_ref, const double* y_ref,
                                     int m) {
  const auto worst = [](double current, double difference) {
    return std::isnan(difference) ? kInf : std::max(current, difference);
  };
  for (int i = 0; i < m; ++i) {
    errors_.s_error_max = worst(errors_.s_error_max, std::abs(s[i] - s_ref[i]));
    errors_.y_error_max = worst(errors_.y_error_max, std::abs(y[i] - y_ref[i]));
  }
  ++errors_.steps_compared;
}

ReferenceErrors CompareWithReference(const Trajectory& run, const Trajectory& reference) {
  RequireRecorded(run, "CompareWithReference (run)");
  RequireRecorded(reference, "CompareWithReference (reference)");
  if (run.n != reference.n || run.m != reference.m || run.h != reference.h) {
    throw InvalidInputError("CompareWithReference: the runs differ in n, m or h (n " + std::to_string(run.n) + "/" +
                            std::to_string(reference.n) + ", m " + std::to_string(run.m) + "/" +
                            std::to_string(reference.m) + ")");
  }
  // The reference is trusted up to its first failed step only (that step's s was not certified).
  std::int64_t last = std::min(run.steps_taken, reference.steps_taken);
  if (reference.first_failed_step >= 1) last = std::min(last, reference.first_failed_step - 1);
  ReferenceErrors out;
  out.steps_compared = std::max<std::int64_t>(last, 0);
  const auto worst = [](double current, double difference) {
    return std::isnan(difference) ? kInf : std::max(current, difference);
  };
  for (Eigen::Index k = 1; k <= static_cast<Eigen::Index>(last); ++k) {
    for (int i = 0; i < run.m; ++i) {
      out.s_error_max = worst(out.s_error_max, std::abs(run.s(i, k) - reference.s(i, k)));
      out.y_error_max = worst(out.y_error_max, std::abs(run.y(i, k) - reference.y(i, k)));
    }
  }
  return out;
}

// ------------------------------------------------------------------------------------------------------------
// ChatteringAccumulator

ChatteringAccumulator::ChatteringAccumulator(int m, double tol, double sign_dead_zone)
    : tol_(tol), dead_zone_(sign_dead_zone), m_(m) {
  if (!(tol >= 0.0)) throw InvalidInputError("ChatteringAccumulator: tol must be >= 0");
  if (!(sign_dead_zone >= 0.0)) throw InvalidInputError("ChatteringAccumulator: sign_dead_zone must be >= 0");
  if (m < 1) throw InvalidInputError("ChatteringAccumulator: m must be >= 1, got " + std::to_string(m));
  on_surface_.assign(static_cast<std::size_t>(m), 0);
  previous_y_.assign(static_cast<std::size_t>(m), 0.0);
  last_sign_.assign(static_cast<std::size_t>(m), 0);
  previous_u_.assign(static_cast<std::size_t>(m), std::numeric_limits<double>::quiet_NaN());
}

void ChatteringAccumulator::OnRows(const TrajectoryBlock& block) {
  ChatteringMetrics& r = result_;
  r.has_input = block.has_input();
  const auto m = static_cast<std::size_t>(m_);
  for (std::int64_t j = 0; j < block.rows; ++j) {
    const auto c = static_cast<Eigen::Index>(j);
    const std::int64_t row = block.row(j);
    // Reaching: every σ_i on its surface at some row so far.
    if (r.from_step < 0) {
      bool all = true;
      for (std::size_t i = 0; i < m; ++i) {
        const double y = block.y(static_cast<Eigen::Index>(i), c);
        const bool crossed = have_previous_row_ && ((y > 0.0 && previous_y_[i] < 0.0) || (y < 0.0 && previous_y_[i] > 0.0));
        if (std::abs(y) <= tol_ || crossed) on_surface_[i] = 1;
        previous_y_[i] = y;
        all = all && on_surface_[i];
      }
      have_previous_row_ = true;
      if (all) r.from_step = row;
    }
    // The input's magnitude over the whole run.
    bool u_known = r.has_input;
    for (std::size_t i = 0; u_known && i < m; ++i) u_known = !std::isnan(block.u(static_cast<Eigen::Index>(i), c));
    if (u_known) {
      for (std::size_t i = 0; i < m; ++i) r.u_max_abs = std::max(r.u_max_abs, std::abs(block.u(static_cast<Eigen::Index>(i), c)));
    }
    if (r.from_step < 0) continue;
    // After reaching.
    ++r.rows;
    double y_norm = 0.0;
    for (std::size_t i = 0; i < m; ++i) y_norm = std::max(y_norm, std::abs(block.y(static_cast<Eigen::Index>(i), c)));
    r.sigma_band = std::isnan(y_norm) ? kInf : std::max(r.sigma_band, y_norm);
    for (std::size_t i = 0; i < m && row >= 1; ++i) {
      const int sign = Sign(block.s(static_cast<Eigen::Index>(i), c), dead_zone_);
      if (sign == 0) continue;
      if (row > r.from_step && last_sign_[i] != 0 && sign != last_sign_[i]) ++r.switching_sign_changes;
      last_sign_[i] = sign;
    }
    if (!u_known) {
      previous_u_[0] = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    if (!std::isnan(previous_u_[0])) {
      double jump_sum = 0.0, jump_max = 0.0;
      for (std::size_t i = 0; i < m; ++i) {
        const double jump = std::abs(block.u(static_cast<Eigen::Index>(i), c) - previous_u_[i]);
        jump_sum += jump;
        jump_max = std::max(jump_max, jump);
      }
      r.u_total_variation += jump_sum;
      r.u_max_jump = std::max(r.u_max_jump, jump_max);
    }
    for (std::size_t i = 0; i < m; ++i) previous_u_[i] = block.u(static_cast<Eigen::Index>(i), c);
  }
}

ChatteringMetrics ComputeChattering(const Trajectory& trajectory, double tol, double sign_dead_zone) {
  RequireRecorded(trajectory, "ComputeChattering");
  ChatteringAccumulator accumulator(trajectory.m, tol, sign_dead_zone);
  FeedRecorded(trajectory, &accumulator);
  ChatteringMetrics result = accumulator.Result();
  result.has_input = trajectory.has_input;
  return result;
}

}  // namespace smcbench

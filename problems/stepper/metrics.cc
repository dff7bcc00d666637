#include "problems/stepper/metrics.h"

#include <algorithm>
#include <cmath>

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
  SolutionErrors out;
  std::vector<double> e;
  if (exact.x) {
    Vector ref(tr.n);
    e.clear();
    for (Eigen::Index k = 0; k <= last; ++k) {
      exact.x(tr.t[k], ref);
      e.push_back((tr.x.col(k) - ref).cwiseAbs().maxCoeff());
    }
    out.x = Norms(e, tr.h);
  }
  if (exact.s) {
    Vector ref(tr.m);
    e.clear();
    for (Eigen::Index k = 1; k <= last; ++k) {
      exact.s(tr.t[k], ref);
      e.push_back((tr.s.col(k) - ref).cwiseAbs().maxCoeff());
    }
    out.s = Norms(e, tr.h);
  }
  return out;
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

}  // namespace smcbench

// The states of a ZOH plant between its controller's samples (sampled_plant.h): exponentials once, then mat-vecs.
#include "problems/stepper/sampled_plant.h"

#include <cmath>
#include <limits>
#include <string>

#include "problems/stepper/discretization_detail.h"
#include "problems/stepper/validation.h"
#include "solvers/core/number_text.h"

namespace smcbench {

using stepper_detail::Fail;

namespace {
constexpr const char* kOwner = "plant_substeps";
// More points per sample than any plot or CSV could use; bounds the exponentials made once per run.
constexpr int kMaxSubsteps = 1'000'000;
}  // namespace

std::vector<PlantSubstep> DiscretizeBetweenSamples(const ZohSmcSystem& system, double h, int substeps) {
  if (substeps < 1 || substeps > kMaxSubsteps) {
    Fail(kOwner, "must be an integer in [1, " + std::to_string(kMaxSubsteps) + "], got " + std::to_string(substeps));
  }
  stepper_detail::CheckStep(kOwner, h);
  system.Validate();
  std::vector<PlantSubstep> points(static_cast<std::size_t>(substeps - 1));
  for (int j = 1; j < substeps; ++j) {
    PlantSubstep& point = points[static_cast<std::size_t>(j - 1)];
    // j h / s rather than j (h / s): the last point is then the nearest double below h for every s.
    point.tau = static_cast<double>(j) * h / static_cast<double>(substeps);
    auto [exp_F, psi_G] = stepper_detail::ExpAndIntegral(system.F, system.G, point.tau);
    point.exp_F = std::move(exp_F);
    point.psi_G = std::move(psi_G);
    if (!system.disturbance.empty()) {
      point.disturbance = stepper_detail::DiscretizeDisturbance(system.F, system.disturbance, point.tau);
    }
    const DisturbanceResponse& d = point.disturbance;
    if (!point.exp_F.allFinite() || !point.psi_G.allFinite() ||
        (d.present() && (!d.constant.allFinite() || !d.cos_part.allFinite() || !d.sin_part.allFinite()))) {
      Fail(kOwner, "the plant's exponential at tau = " + NumberText(point.tau) + " is not finite (h*||F|| too large)");
    }
  }
  return points;
}

SampledPlantSink::SampledPlantSink(const ZohSmcSystem& system, double h, int substeps, TrajectorySink* downstream)
    : substeps_(DiscretizeBetweenSamples(system, h, substeps)),
      C_(system.C),
      D_(system.D.size() ? system.D : Vector::Zero(system.m())),
      relation_offset_(system.relation_offset) {
  if (downstream == nullptr) Fail("SampledPlantSink", "downstream sink is null");
  const int n = system.n(), m = system.m();
  stream_.Start(n, m, downstream, /*has_input=*/true);
  held_x_.resize(n);
  held_s_.resize(m);
  held_y_.resize(m);
  held_u_.resize(m);
  point_x_.resize(n);
  point_y_.resize(m);
  point_e_.resize(m);
}

void SampledPlantSink::OnRows(const TrajectoryBlock& block) {
  if (!block.has_input()) {
    Fail("SampledPlantSink", "the run's rows carry no input u (only a ZOH run has a plant between samples)");
  }
  if (block.n != held_x_.size() || block.m != held_s_.size()) {
    Fail("SampledPlantSink", "rows of n = " + std::to_string(block.n) + ", m = " + std::to_string(block.m) +
                                 " for a plant of n = " + std::to_string(held_x_.size()) +
                                 ", m = " + std::to_string(held_s_.size()));
  }
  for (std::int64_t j = 0; j < block.rows; ++j) {
    const auto c = static_cast<Eigen::Index>(j);
    if (held_) EmitHeld(block.s.col(c).data());
    held_ = true;
    held_t_ = block.t[static_cast<std::size_t>(j)];
    held_x_ = block.x.col(c);
    held_s_ = block.s.col(c);
    held_y_ = block.y.col(c);
    held_u_ = block.u.col(c);
    held_iterations_ = block.iterations[static_cast<std::size_t>(j)];
    held_residual_ = block.residual[static_cast<std::size_t>(j)];
    held_status_ = block.status[static_cast<std::size_t>(j)];
  }
}

void SampledPlantSink::Finish() {
  if (held_) EmitHeld(nullptr);
  held_ = false;
  stream_.Flush();
  next_row_ = 0;  // ready for another run
}

// The held row k, then (when its input was applied and s_{k+1} is known) the points between t_k and t_{k+1}.
void SampledPlantSink::EmitHeld(const double* next_s) {
  const int n = static_cast<int>(held_x_.size()), m = static_cast<int>(held_s_.size());
  stream_.Add(next_row_++, held_t_, held_x_, held_s_, held_y_, held_iterations_, held_residual_, held_status_, n, m);
  stream_.SetLastInput(held_u_, m);
  if (next_s == nullptr || !held_u_.allFinite()) return;
  const Eigen::Map<const Vector> s_next(next_s, m);
  for (const PlantSubstep& point : substeps_) {
    point_x_.noalias() = point.exp_F * held_x_;
    point_x_.noalias() += point.psi_G * held_u_;
    point.disturbance.Add(held_t_, point_x_);
    point_y_ = D_;
    point_y_.noalias() += C_ * point_x_;
    if (relation_offset_) {  // the surface at the point itself, as y_k has e(t_k)
      relation_offset_(held_t_ + point.tau, point_e_);
      point_y_ += point_e_;
    }
    stream_.Add(next_row_++, held_t_ + point.tau, point_x_, s_next, point_y_, 0, 0.0, SolveStatus::kNotRun, n, m);
    stream_.SetLastInput(held_u_, m);
  }
}

}  // namespace smcbench

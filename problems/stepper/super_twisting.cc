#include "problems/stepper/super_twisting.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "solvers/core/number_text.h"

namespace smcbench {
namespace {


double Sign(double v) { return v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0); }

[[noreturn]] void Fail(const std::string& what) { throw InvalidInputError("SuperTwistingSystem: " + what); }

void RequireFinite(double v, const std::string& field) {
  if (!std::isfinite(v)) Fail(field + " is not finite (" + NumberText(v) + ")");
}

}  // namespace

double ScalarDisturbance::Value(double t) const {
  double d = constant;
  for (const Sinusoid& s : sinusoids) d += s.amplitude * std::sin(s.omega * t + s.phase);
  return d;
}

double ScalarDisturbance::Integral(double t0, double t1) const {
  double integral = constant * (t1 - t0);
  for (const Sinusoid& s : sinusoids) {
    if (s.omega == 0.0) {
      integral += s.amplitude * std::sin(s.phase) * (t1 - t0);
    } else {
      integral += s.amplitude / s.omega * (std::cos(s.omega * t0 + s.phase) - std::cos(s.omega * t1 + s.phase));
    }
  }
  return integral;
}

double ScalarDisturbance::Lipschitz() const {
  double L = 0.0;
  for (const Sinusoid& s : sinusoids) L += std::abs(s.amplitude * s.omega);
  return L;
}

void SuperTwistingSystem::Validate() const {
  RequireFinite(k1, "k1");
  RequireFinite(k2, "k2");
  if (!(k1 >= 0.0)) Fail("k1 must be >= 0, got " + NumberText(k1));
  if (!(k2 > 0.0)) Fail("k2 must be > 0, got " + NumberText(k2));
  RequireFinite(disturbance.constant, "disturbance.constant");
  for (std::size_t j = 0; j < disturbance.sinusoids.size(); ++j) {
    const std::string f = "disturbance.sinusoids[" + std::to_string(j) + "]";
    RequireFinite(disturbance.sinusoids[j].amplitude, f + ".amplitude");
    RequireFinite(disturbance.sinusoids[j].omega, f + ".omega");
    RequireFinite(disturbance.sinusoids[j].phase, f + ".phase");
  }
}

SuperTwistingStepSolution SolveSuperTwistingStep(double w, double a, double b) {
  const double magnitude = std::abs(w);
  if (magnitude <= b) return {0.0, w / b, true};
  const double excess = magnitude - b;
  const double r = 2.0 * excess / (a + std::sqrt(a * a + 4.0 * excess));
  return {Sign(w) * r * r, Sign(w), false};
}

SuperTwistingStepMcp::SuperTwistingStepMcp(double a, double b)
    : MCP((Vector(2) << -kInf, -1.0).finished(), (Vector(2) << kInf, 1.0).finished(), "super-twisting step"),
      a_(a),
      b_(b) {
  if (!(a >= 0.0) || !std::isfinite(a)) throw InvalidInputError("SuperTwistingStepMcp: a = h k1 must be finite and >= 0");
  if (!(b > 0.0) || !std::isfinite(b)) throw InvalidInputError("SuperTwistingStepMcp: b = h^2 k2 must be finite and > 0");
}

void SuperTwistingStepMcp::Evaluate(const Vector& z, Vector* F) const {
  const double r = z[0];
  (*F)[0] = r * std::abs(r) + a_ * r + b_ * z[1] - w_;
  (*F)[1] = -r;
}

void SuperTwistingStepMcp::JacobianDense(const Vector& z, DenseMatrix* J) const {
  (*J)(0, 0) = 2.0 * std::abs(z[0]) + a_;
  (*J)(0, 1) = b_;
  (*J)(1, 0) = -1.0;
  (*J)(1, 1) = 0.0;
}

void RunSuperTwisting(const SuperTwistingSystem& system, SignTreatment sign, double h, const Vector& x0,
                      std::int64_t num_steps, Solver* solver, const SuperTwistingOptions& options, Trajectory* out) {
  system.Validate();
  if (!(h > 0.0) || !std::isfinite(h)) throw InvalidInputError("super-twisting: h must be positive and finite");
  if (x0.size() != 2) {
    throw InvalidInputError("super-twisting: x0 = (sigma, v) has 2 entries, got " + std::to_string(x0.size()));
  }
  if (!x0.allFinite()) throw InvalidInputError("super-twisting: x0 is not finite");
  if (num_steps < 0) throw InvalidInputError("super-twisting: num_steps must be >= 0");
  std::string why;
  if (!options.stepper.IsValid(&why)) throw InvalidInputError("super-twisting: stepper options: " + why);
  const bool implicit = sign == SignTreatment::kImplicit;
  const bool use_mcp = implicit && options.solution == SuperTwistingSolution::kMcp;
  if (use_mcp && solver == nullptr) throw InvalidInputError("super-twisting: the MCP route needs a backend");
  if (use_mcp && !solver->info().mcp) {
    throw InvalidInputError("super-twisting: the MCP route needs a backend that solves MCPs; '" +
                            std::string(solver->info().name) + "' does not");
  }

  const double k1 = system.k1, k2 = system.k2;
  const double a = h * k1, b = h * h * k2;
  const std::string description = implicit ? (use_mcp ? "super-twisting, implicit, one-step MCP"
                                                      : "super-twisting, implicit, closed form")
                                           : "super-twisting, explicit Euler";
  const StepperOptions& so = options.stepper;
  out->Reset(2, 1, h, so.t0, description, num_steps, so.record, true);

  // MCP route only: the problem, its options and result, sized once.
  std::optional<SuperTwistingStepMcp> mcp;
  SolverOptions solver_options = so.solver;
  solver_options.measure_time = false;
  SolveResult result;
  if (use_mcp) {
    mcp.emplace(a, b);
    solver_options.warm_start = Vector::Zero(2);
  }

  Vector x = x0, s = Vector::Zero(1), y(1), u(1);
  y[0] = x[0];
  TrajectoryStream stream;
  stream.Start(2, 1, so.sink, true);
  if (so.record) out->SetRow(0, so.t0, x, s, y, 0, 0.0, SolveStatus::kNotRun);
  if (stream.active()) stream.Add(0, so.t0, x, s, y, 0, 0.0, SolveStatus::kNotRun, 2, 1);

  double max_residual = 0.0;
  std::int64_t total_iterations = 0;
  int max_iterations = 0;
  std::int64_t k = 0;
  while (k < num_steps) {
    const double t_k = so.t0 + static_cast<double>(k) * h;
    const double t_next = so.t0 + static_cast<double>(k + 1) * h;
    const double sigma = x[0], v = x[1];
    double selection = 0.0, control = 0.0, v_next = 0.0, sigma_next = 0.0, residual = 0.0;
    int iterations = 0;
    SolveStatus status = SolveStatus::kSolved;
    if (!implicit) {
      selection = Sign(sigma);
      control = -k1 * std::sqrt(std::abs(sigma)) * selection + v;
      v_next = v - h * k2 * selection;
      sigma_next = sigma + h * control + system.disturbance.Integral(t_k, t_next);
      status = SolveStatus::kNotRun;
    } else {
      const double w = sigma + h * v;
      double predicted = 0.0;
      bool sliding = false;
      if (use_mcp) {
        mcp->SetStep(w);
        if (!so.warm_start) solver_options.warm_start.setZero();
        solver->Solve(*mcp, solver_options, &result);
        const double r = result.z[0];
        predicted = r * std::abs(r);
        selection = std::clamp(result.z[1], -1.0, 1.0);
        iterations = result.iterations;
        residual = result.residual_rel;
        status = result.status;
        if (so.warm_start) solver_options.warm_start = result.z;
      } else {
        const SuperTwistingStepSolution step = SolveSuperTwistingStep(w, a, b);
        predicted = step.sigma;
        selection = step.selection;
        sliding = step.sliding;
        // The generalized equation's own residual at the closed form (rounding only), relative to 1 + |w|.
        const double root = Sign(predicted) * std::sqrt(std::abs(predicted));
        residual = std::abs(predicted + a * root + b * selection - w) / (1.0 + std::abs(w));
      }
      // v_k − h k₂ s with s = w/b = (σ_k + h v_k)/(h² k₂) is −σ_k/h: in the sliding set, that form (exactly 0 once
      // σ_k is) rather than the subtraction, whose rounding residue would only shrink geometrically.
      v_next = sliding ? 0.0 - sigma / h : v - h * k2 * selection;
      control = (predicted - sigma) / h;
      sigma_next = predicted + system.disturbance.Integral(t_k, t_next);
    }
    x[0] = sigma_next;
    x[1] = v_next;
    s[0] = selection;
    y[0] = sigma_next;
    u[0] = control;
    ++k;
    total_iterations += iterations;
    max_iterations = std::max(max_iterations, iterations);
    max_residual = std::isnan(residual) ? kInf : std::max(max_residual, residual);
    if (!x.allFinite()) status = x.hasNaN() ? SolveStatus::kNumericalFailure : SolveStatus::kDiverged;
    if (so.record) {
      out->SetRow(k, t_next, x, s, y, iterations, residual, status);
      out->u(0, static_cast<Eigen::Index>(k - 1)) = control;
    }
    if (stream.active()) {
      stream.SetLastInput(u, 1);
      stream.Add(k, t_next, x, s, y, iterations, residual, status, 2, 1);
    }
    const bool failed = implicit ? status != SolveStatus::kSolved
                                 : (status == SolveStatus::kNumericalFailure || status == SolveStatus::kDiverged);
    if (failed) {
      ++out->failed_steps;
      if (out->first_failed_step < 0) {
        out->first_failed_step = k;
        out->first_failure_status = status;
        out->first_failure_residual = residual;
        out->first_failure_message = x.allFinite() ? result.message : "the state is not finite";
      }
      if (so.on_failure == FailurePolicy::kStop || !x.allFinite()) {
        out->stopped_early = true;
        break;
      }
    }
  }
  stream.Flush();
  out->max_residual = max_residual;
  out->total_iterations = total_iterations;
  out->max_iterations = max_iterations;
  out->Truncate(k);
  out->x_final = x;
  out->s_final = s;
  out->y_final = y;
}

SuperTwistingPrecisionAccumulator::SuperTwistingPrecisionAccumulator(double band, std::int64_t num_steps, double h)
    : h_(h) {
  result_.band = band;
  result_.tail_from = num_steps - num_steps / 2;
}

void SuperTwistingPrecisionAccumulator::Add(std::int64_t k, double sigma) {
  if (!(std::abs(sigma) <= result_.band)) last_outside_ = k;
  if (k >= result_.tail_from) {
    result_.max_abs_sigma_tail = std::max(result_.max_abs_sigma_tail, std::abs(sigma));
    if (any_row_ && k > result_.tail_from) {
      result_.max_abs_sigma_dot_tail = std::max(result_.max_abs_sigma_dot_tail, std::abs(sigma - previous_) / h_);
    }
  }
  previous_ = sigma;
  any_row_ = true;
  last_row_ = k;
}

void SuperTwistingPrecisionAccumulator::OnRows(const TrajectoryBlock& block) {
  for (std::int64_t j = 0; j < block.rows; ++j) Add(block.row(j), block.y(0, static_cast<Eigen::Index>(j)));
}

SuperTwistingPrecision SuperTwistingPrecisionAccumulator::Result() const {
  SuperTwistingPrecision r = result_;
  // Every row was outside the band up to the last one: never converged.
  r.convergence_step = !any_row_ || last_outside_ == last_row_ ? -1 : last_outside_ + 1;
  return r;
}

SuperTwistingPrecision ComputeSuperTwistingPrecision(const Trajectory& trajectory, double band) {
  if (!trajectory.recorded) throw InvalidInputError("super-twisting precision: the trajectory was not recorded");
  SuperTwistingPrecisionAccumulator accumulator(band, trajectory.steps_taken, trajectory.h);
  for (std::int64_t k = 0; k <= trajectory.steps_taken; ++k) {
    accumulator.Add(k, trajectory.y(0, static_cast<Eigen::Index>(k)));
  }
  return accumulator.Result();
}

}  // namespace smcbench

// The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.
#include "problems/stepper/nonlinear_stepper.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include "problems/stepper/float_mode.h"
#include "problems/stepper/validation.h"
#include "solvers/core/number_text.h"

namespace smcbench {

using stepper_detail::Fail;

// ------------------------------------------------------------------------------------------------------------
// Scheme and options

void NonlinearScheme::Validate() const {
  constexpr const char* kOwner = "NonlinearScheme";
  stepper_detail::CheckStep(kOwner, h);
  if (!(theta >= 0.0 && theta <= 1.0)) Fail(kOwner, "theta must be in [0, 1], got " + NumberText(theta));
  if (!(gamma >= 0.0 && gamma <= 1.0)) Fail(kOwner, "gamma must be in [0, 1], got " + NumberText(gamma));
  if (!(rho >= 0.0) || !std::isfinite(rho)) Fail(kOwner, "rho must be finite and >= 0, got " + NumberText(rho));
}

std::string NonlinearScheme::Description() const {
  return "theta=" + NumberText(theta) + ", gamma=" + NumberText(gamma) + ", rho=" + NumberText(rho) +
         (sign == SignTreatment::kImplicit ? ", implicit sign" : ", explicit sign");
}

std::string_view ToString(NonlinearAlgorithm algorithm) {
  switch (algorithm) {
    case NonlinearAlgorithm::kMcp: return "mcp";
    case NonlinearAlgorithm::kNewtonMlcp: return "newton-mlcp";
    case NonlinearAlgorithm::kClosedForm: return "closed-form";
  }
  return "unknown";
}

std::optional<NonlinearAlgorithm> NonlinearAlgorithmFromString(std::string_view name) {
  if (name == "mcp") return NonlinearAlgorithm::kMcp;
  if (name == "newton-mlcp") return NonlinearAlgorithm::kNewtonMlcp;
  if (name == "closed-form") return NonlinearAlgorithm::kClosedForm;
  return std::nullopt;
}

bool NonlinearStepperOptions::IsValid(std::string* why) const {
  if (!stepper.IsValid(why)) return false;
  if (!(newton_tolerance > 0.0) || !std::isfinite(newton_tolerance)) {
    if (why) *why = "newton_tolerance must be a positive finite number, got " + NumberText(newton_tolerance);
    return false;
  }
  if (newton_max_iterations < 1) {
    if (why) *why = "newton_max_iterations must be >= 1, got " + std::to_string(newton_max_iterations);
    return false;
  }
  if (algorithm != NonlinearAlgorithm::kMcp && algorithm != NonlinearAlgorithm::kNewtonMlcp) {
    if (why) *why = "algorithm must be mcp or newton-mlcp (closed-form solves the super-twisting scenes' steps only)";
    return false;
  }
  return true;
}

// ------------------------------------------------------------------------------------------------------------
// OneStepMCP

namespace {

// The bounds of `eq:MCP3`: x free, s ∈ [−1, 1]. Each validates system and scheme first (the MCP base is
// constructed before any member, and the two calls may run in either order).
Vector OneStepBound(const NonlinearSignSystem& system, const NonlinearScheme& scheme, bool upper) {
  system.Validate();
  scheme.Validate();
  Vector b(system.n + system.m);
  b.head(system.n).setConstant(upper ? kInf : -kInf);
  b.tail(system.m).setConstant(upper ? 1.0 : -1.0);
  return b;
}

}  // namespace

OneStepMCP::OneStepMCP(NonlinearSignSystem system, const NonlinearScheme& scheme)
    : MCP(OneStepBound(system, scheme, false), OneStepBound(system, scheme, true), "one-step eq:MCP3"),
      system_(std::move(system)),
      scheme_(scheme) {
  const int n = system_.n, m = system_.m;
  x_k_ = Vector::Zero(n);
  x_.resize(n), s_.resize(m), x_theta_.resize(n), x_gamma_.resize(n), f_.resize(n), y_.resize(m);
  zero_ = Vector::Zero(n + m);
  F0_.resize(n + m);
  G_.resize(n, m), Jf_.resize(n, n), Jg_.resize(n, n), H_.resize(m, n);
}

void OneStepMCP::SetStep(double t_k, const Vector& x_k) {
  t_k_ = t_k;
  x_k_ = x_k;
}

void OneStepMCP::Blend(const Eigen::Ref<const Vector>& x) const {
  const double theta = scheme_.theta, gamma = scheme_.gamma;
  x_theta_ = theta * x + (1.0 - theta) * x_k_;
  x_gamma_ = gamma * x + (1.0 - gamma) * x_k_;
}

void OneStepMCP::Evaluate(const Vector& z, Vector* F) const {
  const int n = system_.n, m = system_.m;
  const double h = scheme_.h;
  // t_{k+θ} = θ t_{k+1} + (1 − θ) t_k.
  const double t_theta = t_k_ + scheme_.theta * h;
  x_ = z.head(n);
  s_ = z.tail(m);
  Blend(x_);
  // R(x, s) = (1 + hρ)(x − x_k) − h f(x_{k+θ}, t_{k+θ}) + h g(x_{k+γ}) s   (`eq:NL3` with the ρ-shift of `neuf`).
  auto R = F->head(n);
  R = (1.0 + h * scheme_.rho) * (x_ - x_k_);
  if (system_.f) {
    system_.f(t_theta, x_theta_, f_);
    R.noalias() -= h * f_;
  }
  system_.g(x_gamma_, G_);
  R.noalias() += (h * G_) * s_;
  system_.h(x_, y_);
  F->tail(m) = -y_;
}

void OneStepMCP::JacobianDense(const Vector& z, DenseMatrix* J) const {
  const int n = system_.n, m = system_.m;
  const double h = scheme_.h;
  const double t_theta = t_k_ + scheme_.theta * h;
  if (J->rows() != n + m || J->cols() != n + m) J->resize(n + m, n + m);
  x_ = z.head(n);
  s_ = z.tail(m);
  Blend(x_);
  // `eq:JacMCLP`: [[(1 + hρ) I − hθ ∇f + hγ ∇g·s, h g], [−∇h, 0]].
  auto Jxx = J->topLeftCorner(n, n);
  Jxx.setIdentity();
  Jxx *= 1.0 + h * scheme_.rho;
  if (system_.f) {
    system_.f_jacobian(t_theta, x_theta_, Jf_);
    Jxx.noalias() -= (h * scheme_.theta) * Jf_;
  }
  if (system_.g_jacobian_s) {
    system_.g_jacobian_s(x_gamma_, s_, Jg_);
    Jxx.noalias() += (h * scheme_.gamma) * Jg_;
  }
  system_.g(x_gamma_, G_);
  J->topRightCorner(n, m) = h * G_;
  system_.h_jacobian(x_, H_);
  J->bottomLeftCorner(m, n) = -H_;
  J->bottomRightCorner(m, m).setZero();
}

double OneStepMCP::ResidualScale() const {
  // Same rule as Solver::Solve(const MCP&): Π_[l,u](0) = (0, 0) here (x free, 0 ∈ [−1, 1]).
  Evaluate(zero_, &F0_);
  const double scale = 1.0 + F0_.cwiseAbs().maxCoeff();
  return std::isfinite(scale) ? scale : 1.0;
}

void OneStepMCP::Linearize(const Vector& x, const Vector& s, DenseMatrix* M, DenseMatrix* G, Vector* r, Vector* y,
                           DenseMatrix* H) const {
  const double h = scheme_.h;
  const double t_theta = t_k_ + scheme_.theta * h;
  Blend(x);
  // M_α = (1 + hρ) I − hθ ∇f(x_{k+θ}, t_{k+θ}) + hγ ∇g(x_{k+γ})·s^α   (`eq:NL9`).
  M->setIdentity();
  *M *= 1.0 + h * scheme_.rho;
  // r_α = (1 + hρ)(x_k − x^α) + h f(x^α_{k+θ}, t_{k+θ}) = −R(x^α, 0).
  *r = (1.0 + h * scheme_.rho) * (x_k_ - x);
  if (system_.f) {
    system_.f(t_theta, x_theta_, f_);
    r->noalias() += h * f_;
    system_.f_jacobian(t_theta, x_theta_, Jf_);
    M->noalias() -= (h * scheme_.theta) * Jf_;
  }
  if (system_.g_jacobian_s) {
    system_.g_jacobian_s(x_gamma_, s, Jg_);
    M->noalias() += (h * scheme_.gamma) * Jg_;
  }
  system_.g(x_gamma_, *G);
  system_.h(x, *y);
  system_.h_jacobian(x, *H);
}

// ------------------------------------------------------------------------------------------------------------
// The stepper

struct NonlinearStepper::Workspace {
  Workspace(NonlinearSignSystem system, const NonlinearScheme& scheme)
      : mcp(std::move(system), scheme), lu(mcp.n()) {
    const int n = mcp.n(), m = mcp.m();
    x.resize(n), xn.resize(n), xa.resize(n), r.resize(n), v.resize(n);
    s.resize(m), sn.resize(m), sa.resize(m), y.resize(m), b.resize(m), q.resize(m);
    l = Vector::Constant(m, -1.0);
    u = Vector::Constant(m, 1.0);
    z.resize(n + m), F.resize(n + m);
    Mx.resize(n, n), G.resize(n, m), V.resize(n, m), H.resize(m, n), W.resize(m, m);
    probe_f.resize(n), probe_y.resize(m), ones = Vector::Ones(m);
    probe_J.resize(n, n), probe_G.resize(n, m), probe_H.resize(m, n);
    const std::string text = mcp.scheme().Description();
    description_mcp = text + ", " + std::string(ToString(NonlinearAlgorithm::kMcp));
    description_newton = text + ", " + std::string(ToString(NonlinearAlgorithm::kNewtonMlcp));
    description_explicit = text;
  }

  // What one step produced. message is written only on failure (allocation off the hot path).
  struct Step {
    SolveStatus status = SolveStatus::kNotRun;
    int backend_iterations = 0;
    int newton_iterations = 0;
    double residual = 0.0;
  };

  void StepMcp(std::int64_t k, Solver* solver, const NonlinearStepperOptions& options, Step* step);
  void StepNewton(std::int64_t k, Solver* solver, bool implicit, const NonlinearStepperOptions& options,
                  Step* step);
  // Run's arguments, and the callables at x0 (a NaN there is a modelling error, better reported now than as a
  // failed step 1): InvalidInputError naming the field.
  void CheckRunInputs(const Vector& x0, std::int64_t num_steps, const Solver* solver,
                      const NonlinearStepperOptions& options);
  // Bookkeeping of a failed step k (off the hot path); returns true if the run stops there.
  bool RecordFailure(std::int64_t k, const Step& step, bool finite, FailurePolicy policy, Trajectory* out);

  OneStepMCP mcp;
  Eigen::PartialPivLU<DenseMatrix> lu;
  Vector x, xn, xa, r, v;       // n
  Vector s, sn, sa, y, b, q;    // m
  Vector l, u;                  // the relay box of the MLCP
  std::optional<BoxMLCP> mlcp_storage;  // Algorithm 2's m×m box-MLCP, built at its first use
  Vector z, F;                  // n + m
  DenseMatrix Mx, G, V, H, W;
  SolverOptions solver_options;
  SolveResult result;
  std::string message;
  NewtonStats stats;
  // Run-level buffers, kept so that a repeated run allocates nothing.
  Vector probe_f, probe_y, ones;
  DenseMatrix probe_J, probe_G, probe_H;
  std::string description_mcp, description_newton, description_explicit;
  TrajectoryStream stream;  // StepperOptions::sink's buffer
};

namespace {

constexpr const char* kRunOwner = "NonlinearStepper::Run";

void CheckFiniteOutput(const char* what, const Vector& v) {
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) {
      Fail(kRunOwner, std::string(what) + "[" + std::to_string(i) + "] is " + (std::isnan(v[i]) ? "NaN" : "infinite"));
    }
  }
}

void CheckFiniteOutput(const char* what, const DenseMatrix& A) { stepper_detail::CheckFinite(kRunOwner, what, A); }

}  // namespace

// Algorithm 1: the MCP `eq:MCP3` solved by the backend, warm-started from (x_k, s_k).
void NonlinearStepper::Workspace::StepMcp(std::int64_t k, Solver* solver, const NonlinearStepperOptions& options,
                                          Step* step) {
  const int n = mcp.n(), m = mcp.m();
  if (options.stepper.warm_start) {
    solver_options.warm_start.head(n) = x;
    solver_options.warm_start.tail(m) = s;
  }
  solver->Solve(mcp, solver_options, &result);
  xn = result.z.head(n);
  sn = result.z.tail(m);
  step->status = result.status;
  step->backend_iterations = result.iterations;
  step->newton_iterations = 0;
  step->residual = result.residual_rel;
  if (!result.solved()) {
    message = "step " + std::to_string(k) + ": MCP backend '" + std::string(result.solver) + "' returned " +
              std::string(ToString(result.status)) + " (relative residual " + NumberText(result.residual_rel) + ")";
    if (!result.message.empty()) message += ": " + result.message;
  }
}

// Algorithm 2 (implicit) or Newton's method on the smooth step equation (explicit sign, s fixed to sgn(y_k)).
void NonlinearStepper::Workspace::StepNewton(std::int64_t k, Solver* solver, bool implicit,
                                             const NonlinearStepperOptions& options, Step* step) {
  const int n = mcp.n(), m = mcp.m();
  const double h = mcp.scheme().h;
  const double tol = options.newton_tolerance;
  const int budget = options.newton_max_iterations;
  step->backend_iterations = 0;
  step->newton_iterations = 0;

  z.head(n) = x;
  if (implicit) {
    z.tail(m) = s;  // s^0 = s_k (`Algo:EulerSliding-MCLP`)
  } else {
    // Explicit sign: s_{k+1} = sgn(y_k), sgn(0) := 0.
    for (int i = 0; i < m; ++i) z[n + i] = y[i] > 0.0 ? 1.0 : (y[i] < 0.0 ? -1.0 : 0.0);
  }
  const double scale = mcp.ResidualScale();
  // The merit: the natural residual of OneStepMCP (implicit), or ‖R‖∞ of the x rows (explicit: s is not a
  // complementarity variable there).
  const auto merit = [&]() {
    if (implicit) return mcp.NaturalResidual(z, &F, scale).rel;
    mcp.Evaluate(z, &F);
    const double a = F.head(n).cwiseAbs().maxCoeff();
    return std::isnan(a) ? kInf : a / scale;
  };
  double res = merit();
  const auto finish = [&](SolveStatus status) {
    xn = z.head(n);
    sn = z.tail(m);
    step->status = status;
    step->residual = res;
  };
  if (res <= tol) return finish(SolveStatus::kSolved);  // (x_k, s_k) already solves the step: nothing to do

  for (int it = 1; it <= budget; ++it) {
    xa = z.head(n);
    sa = z.tail(m);
    mcp.Linearize(xa, sa, &Mx, &G, &r, &y, &H);
    step->newton_iterations = it;
    if (!Mx.allFinite() || !G.allFinite() || !r.allFinite() || !y.allFinite() || !H.allFinite()) {
      res = kInf;
      message = "step " + std::to_string(k) + ", Newton iteration " + std::to_string(it) +
                ": f, g, h or a Jacobian is not finite at the iterate";
      return finish(SolveStatus::kNumericalFailure);
    }
    lu.compute(Mx);
    // Rank test on the pivots of the partial-pivoting LU (no allocation, unlike rcond()).
    const auto pivots = lu.matrixLU().diagonal().cwiseAbs();
    const double largest = std::max(pivots.maxCoeff(), Mx.cwiseAbs().maxCoeff());
    if (!(pivots.minCoeff() > n * std::numeric_limits<double>::epsilon() * largest)) {
      message = "step " + std::to_string(k) + ", Newton iteration " + std::to_string(it) +
                ": M = (1+h*rho) I - h*theta*grad f + h*gamma*grad g.s is singular (smallest pivot " +
                NumberText(pivots.minCoeff()) + ", largest " + NumberText(largest) + ")";
      return finish(SolveStatus::kSingular);
    }
    V = lu.solve(G);  // M_α⁻¹ g
    v = lu.solve(r);  // M_α⁻¹ r_α
    if (implicit) {
      // `eq:NL15`: W = h ∇h M⁻¹ g, b = h(x^α) + ∇h M⁻¹ r_α; the box-MLCP has M = W, q = −b on [−1, 1]ᵐ.
      W.noalias() = h * (H * V);
      b = y;
      b.noalias() += H * v;
      q = -b;
      if (!W.allFinite() || !q.allFinite()) {
        res = kInf;
        message = "step " + std::to_string(k) + ", Newton iteration " + std::to_string(it) +
                  ": the MLCP data W, b are not finite";
        return finish(SolveStatus::kNumericalFailure);
      }
      // One problem for the whole run, M and q replaced in place: set_M takes its matrix by value, so the copy of
      // W is the one allocation per Newton iteration here (M changes every iteration, and so does matrix_id).
      if (!mlcp_storage) {
        mlcp_storage.emplace(W, q, l, u);
      } else {
        mlcp_storage->set_M(W);
        mlcp_storage->set_q(q);
      }
      const BoxMLCP& mlcp = *mlcp_storage;
      if (options.stepper.warm_start) solver_options.warm_start = sa;
      solver->Solve(mlcp, solver_options, &result);
      if (options.stepper.observer) options.stepper.observer->OnStep(k, it, mlcp, result);
      step->backend_iterations += result.iterations;
      sn = result.z;
      if (!result.solved()) {
        z.tail(m) = sn;
        z.head(n) = xa + v;
        z.head(n).noalias() -= h * (V * sn);
        res = mcp.NaturalResidual(z, &F, scale).rel;
        message = "step " + std::to_string(k) + ", Newton iteration " + std::to_string(it) + ": MLCP backend '" +
                  std::string(result.solver) + "' returned " + std::string(ToString(result.status)) +
                  " (MLCP relative residual " + NumberText(result.residual_rel) + ")";
        if (!result.message.empty()) message += ": " + result.message;
        return finish(result.status);
      }
    } else {
      sn = sa;
    }
    // `eq:NL11`: x^{α+1} = x^α + M_α⁻¹ (r_α − h g s^{α+1}).
    z.head(n) = xa + v;
    z.head(n).noalias() -= h * (V * sn);
    z.tail(m) = sn;
    res = merit();
    if (!z.allFinite() || !std::isfinite(res)) {
      res = kInf;
      message = "step " + std::to_string(k) + ", Newton iteration " + std::to_string(it) +
                ": the Newton iterate or its residual is not finite";
      return finish(SolveStatus::kNumericalFailure);
    }
    if (res <= tol) return finish(SolveStatus::kSolved);
  }
  message = "step " + std::to_string(k) + ": Newton did not converge in " + std::to_string(budget) +
            " iteration(s): relative residual " + NumberText(res) + " > newton_tolerance " + NumberText(tol);
  finish(SolveStatus::kIterationLimit);
}

void NonlinearStepper::Workspace::CheckRunInputs(const Vector& x0, std::int64_t num_steps, const Solver* solver,
                                                 const NonlinearStepperOptions& options) {
  const NonlinearSignSystem& sys = mcp.system();
  stepper_detail::CheckSize(kRunOwner, "x0", x0, sys.n);
  ValidateFinite(kRunOwner, "x0", x0);
  if (num_steps < 0) Fail(kRunOwner, "num_steps must be >= 0, got " + std::to_string(num_steps));
  if (mcp.scheme().sign == SignTreatment::kImplicit && solver == nullptr) {
    Fail(kRunOwner, "solver is null but the implicit scheme solves a one-step problem at every step");
  }
  std::string why;
  if (!options.IsValid(&why)) Fail(kRunOwner, "options: " + why);
  const double t0 = options.stepper.t0;
  // The callables at x0.
  if (sys.f) {
    sys.f(t0, x0, probe_f);
    CheckFiniteOutput("f(t0, x0)", probe_f);
    sys.f_jacobian(t0, x0, probe_J);
    CheckFiniteOutput("f_jacobian(t0, x0)", probe_J);
  }
  sys.g(x0, probe_G);
  CheckFiniteOutput("g(x0)", probe_G);
  if (sys.g_jacobian_s) {
    sys.g_jacobian_s(x0, ones, probe_J);
    CheckFiniteOutput("g_jacobian_s(x0, 1)", probe_J);
  }
  sys.h(x0, probe_y);
  CheckFiniteOutput("h(x0)", probe_y);
  sys.h_jacobian(x0, probe_H);
  CheckFiniteOutput("h_jacobian(x0)", probe_H);
}

bool NonlinearStepper::Workspace::RecordFailure(std::int64_t k, const Step& step, bool finite, FailurePolicy policy,
                                                Trajectory* out) {
  SolveStatus status = step.status;
  if (!finite) status = x.hasNaN() || s.hasNaN() ? SolveStatus::kNumericalFailure : SolveStatus::kDiverged;
  if (out->recorded) out->status[static_cast<Eigen::Index>(k)] = status;
  if (stream.active()) stream.SetLastStatus(status);
  ++out->failed_steps;
  if (out->first_failed_step < 0) {
    out->first_failed_step = k;
    out->first_failure_status = status;
    out->first_failure_residual = step.residual;
    out->first_failure_message =
        finite ? message
               : "step " + std::to_string(k) + ": state x_" + std::to_string(k) + " is not finite" +
                     (step.status != SolveStatus::kSolved ? "; " + message : std::string());
  }
  if (!finite || policy == FailurePolicy::kStop) {
    out->stopped_early = true;
    return true;
  }
  return false;
}

NonlinearStepper::NonlinearStepper(NonlinearSignSystem system, const NonlinearScheme& scheme)
    : ws_(std::make_unique<Workspace>(std::move(system), scheme)) {}

NonlinearStepper::~NonlinearStepper() = default;
NonlinearStepper::NonlinearStepper(NonlinearStepper&&) noexcept = default;
NonlinearStepper& NonlinearStepper::operator=(NonlinearStepper&&) noexcept = default;

const NonlinearScheme& NonlinearStepper::scheme() const { return ws_->mcp.scheme(); }
const NonlinearSignSystem& NonlinearStepper::system() const { return ws_->mcp.system(); }
const OneStepMCP& NonlinearStepper::problem() const { return ws_->mcp; }
const NewtonStats& NonlinearStepper::newton_stats() const { return ws_->stats; }

void NonlinearStepper::Run(const Vector& x0, std::int64_t num_steps, Solver* solver,
                           const NonlinearStepperOptions& options, Trajectory* out) {
  Workspace& w = *ws_;
  const NonlinearSignSystem& sys = w.mcp.system();
  const NonlinearScheme& scheme = w.mcp.scheme();
  const int n = sys.n, m = sys.m;
  const bool implicit = scheme.sign == SignTreatment::kImplicit;
  const bool use_mcp = implicit && options.algorithm == NonlinearAlgorithm::kMcp;

  w.CheckRunInputs(x0, num_steps, solver, options);
  const double t0 = options.stepper.t0;

  // ---- trajectory and per-run state
  const bool record = options.stepper.record;
  const Eigen::Index columns = record ? static_cast<Eigen::Index>(num_steps + 1) : 0;
  out->Reset(n, m, scheme.h, t0,
             !implicit ? w.description_explicit : (use_mcp ? w.description_mcp : w.description_newton), num_steps,
             record, /*input=*/false);
  NewtonStats& stats = w.stats;
  stats.iterations.assign(columns, 0);
  stats.total_iterations = 0;
  stats.max_iterations = 0;

  // Copy the backend options but keep our warm-start storage (copying an empty warm_start would free it).
  Vector warm_storage = std::move(w.solver_options.warm_start);
  w.solver_options = options.stepper.solver;
  w.solver_options.warm_start = std::move(warm_storage);
  w.solver_options.measure_time = false;
  w.solver_options.warm_start.resize(options.stepper.warm_start ? (use_mcp ? n + m : m) : 0);

  const auto record_row = [&](std::int64_t k, double t, int iterations, double residual, SolveStatus status) {
    out->SetRow(k, t, w.x, w.s, w.y, iterations, residual, status);
  };

  w.x = x0;
  w.s.setZero();
  sys.h(w.x, w.y);
  if (record) record_row(0, t0, 0, 0.0, SolveStatus::kNotRun);
  TrajectoryStream& stream = w.stream;
  stream.Start(n, m, options.stepper.sink);
  if (stream.active()) stream.Add(0, t0, w.x, w.s, w.y, 0, 0.0, SolveStatus::kNotRun, n, m);
  const ScopedFlushSubnormals flush(options.stepper.subnormals == SubnormalPolicy::kFlushToZero);
  // SubnormalPolicy::kZeroState (implicit steps): a component of x_{k+1} below the normal range is 0.
  const double zero_below = implicit && options.stepper.subnormals == SubnormalPolicy::kZeroState
                                ? std::numeric_limits<double>::min()
                                : 0.0;

  double max_residual = 0.0;
  std::int64_t total_iterations = 0;
  int max_iterations = 0;
  Workspace::Step step;
  std::int64_t k = 0;
  while (k < num_steps) {
    const double t_k = t0 + static_cast<double>(k) * scheme.h;
    const double t_next = t0 + static_cast<double>(k + 1) * scheme.h;
    w.mcp.SetStep(t_k, w.x);
    if (use_mcp) {
      w.StepMcp(k + 1, solver, options, &step);
    } else {
      w.StepNewton(k + 1, solver, implicit, options, &step);
    }
    for (int i = 0; i < n; ++i) {
      if (std::abs(w.xn[i]) < zero_below) w.xn[i] = 0.0;
    }
    w.x = w.xn;
    w.s = w.sn;
    sys.h(w.x, w.y);
    ++k;
    total_iterations += step.backend_iterations;
    max_iterations = std::max(max_iterations, step.backend_iterations);
    max_residual = std::isnan(step.residual) ? kInf : std::max(max_residual, step.residual);
    stats.total_iterations += step.newton_iterations;
    stats.max_iterations = std::max(stats.max_iterations, step.newton_iterations);
    if (record) {
      record_row(k, t_next, step.backend_iterations, step.residual, step.status);
      stats.iterations[static_cast<std::size_t>(k)] = step.newton_iterations;
    }
    if (stream.active()) {
      stream.Add(k, t_next, w.x, w.s, w.y, step.backend_iterations, step.residual, step.status, n, m);
    }
    const bool finite = w.x.allFinite() && w.s.allFinite();
    if ((!finite || step.status != SolveStatus::kSolved) &&
        w.RecordFailure(k, step, finite, options.stepper.on_failure, out)) {
      break;
    }
  }
  stream.Flush();
  out->max_residual = max_residual;
  out->total_iterations = total_iterations;
  out->max_iterations = max_iterations;
  out->Truncate(k);
  if (record && k < num_steps) stats.iterations.resize(static_cast<std::size_t>(k + 1));
  out->x_final = w.x;
  out->s_final = w.s;
  out->y_final = w.y;
}

Trajectory NonlinearStepper::Run(const Vector& x0, std::int64_t num_steps, Solver* solver,
                                 const NonlinearStepperOptions& options) {
  Trajectory out;
  Run(x0, num_steps, solver, options, &out);
  return out;
}

}  // namespace smcbench

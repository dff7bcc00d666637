// The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.
#include "problems/stepper/linear_stepper.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>
#include <utility>

#include "problems/stepper/discretization_detail.h"
#include "problems/stepper/float_mode.h"
#include "problems/stepper/step_verdict.h"
#include "problems/stepper/validation.h"
#include "solvers/avi/avi_solver.h"
#include "solvers/core/number_text.h"

namespace smcbench {

using stepper_detail::Fail;

bool StepperOptions::IsValid(std::string* why) const {
  std::string solver_why;
  if (!solver.IsValid(&solver_why)) {
    if (why) *why = "solver options: " + solver_why;
    return false;
  }
  if (!std::isfinite(t0)) {
    if (why) *why = "t0 must be finite, got " + NumberText(t0);
    return false;
  }
  return true;
}

namespace {

constexpr const char* kRunOwner = "LinearStepper::Run";

// Shared argument checks of both paths.
void CheckRunArguments(const char* owner, int n, SignTreatment sign, const Vector& x0, std::int64_t num_steps,
                       const Solver* solver, const StepperOptions& options) {
  stepper_detail::CheckSize(owner, "x0", x0, n);
  ValidateFinite(owner, "x0", x0);
  if (num_steps < 0) Fail(owner, "num_steps must be >= 0, got " + std::to_string(num_steps));
  if (sign == SignTreatment::kImplicit && solver == nullptr) {
    Fail(owner, "solver is null but the implicit scheme solves a box-MLCP at every step");
  }
  std::string why;
  if (!options.IsValid(&why)) Fail(owner, "options: " + why);
}

// Sizes *out for a run and resets its counters (Trajectory::Reset). Allocates only when the sizes grow.
void PrepareTrajectory(const OneStepData& d, std::int64_t num_steps, const StepperOptions& options,
                       Trajectory* out) {
  out->Reset(d.n(), d.m(), d.h, options.t0, d.description, num_steps, options.record, d.has_input());
}

// Trims the history after an early stop and stores the final state.
template <typename X, typename S, typename Y>
void FinishTrajectory(std::int64_t steps_taken, const X& x, const S& s, const Y& y, Trajectory* out) {
  out->Truncate(steps_taken);
  out->x_final = x;
  out->s_final = s;
  out->y_final = y;
}

// Per-run counters, kept in locals during the loop (stores through *out would force the compiler to reload the
// state every step) and written to *out once at the end.
struct Counters {
  double max_residual = 0.0;
  std::int64_t total_iterations = 0;
  int max_iterations = 0;
  double max_step_x_error = 0.0;
  std::int64_t refined_steps = 0;

  void Add(int iterations, double residual) {
    total_iterations += iterations;
    if (iterations > max_iterations) max_iterations = iterations;
    // A NaN residual must not hide behind max(): treat it as +∞.
    max_residual = std::isnan(residual) ? kInf : std::max(max_residual, residual);
  }
  void Store(Trajectory* out) const {
    out->max_residual = max_residual;
    out->total_iterations = total_iterations;
    out->max_iterations = max_iterations;
    out->max_step_x_error = max_step_x_error;
    out->refined_steps = refined_steps;
  }
  // The step verdict's bookkeeping of an exact step (step_verdict.h): the answer's error in x_{k+1} against it.
  void AddStepCheck(const StepCheck& check, double allowance) {
    max_step_x_error = std::max(max_step_x_error, check.x_error);
    if (check.x_error > allowance) ++refined_steps;
  }
};

// Bookkeeping of a failed step k (backend status != kSolved, or a non-finite state); returns true if the run must
// stop after it. Off the hot path: only failed steps get here.
bool HandleFailure(std::int64_t k, SolveStatus status, double residual, bool state_finite, bool state_has_nan,
                   const std::string* message, FailurePolicy policy, TrajectoryStream* stream, Trajectory* out) {
  if (!state_finite) status = state_has_nan ? SolveStatus::kNumericalFailure : SolveStatus::kDiverged;
  if (out->recorded) out->status[k] = status;
  if (stream->active()) stream->SetLastStatus(status);
  ++out->failed_steps;
  if (out->first_failed_step < 0) {
    out->first_failed_step = k;
    out->first_failure_status = status;
    out->first_failure_residual = residual;
    if (!state_finite) {
      out->first_failure_message = std::string("state x_") + std::to_string(k) + " is not finite (" +
                                   (state_has_nan ? "NaN" : "overflow") + ")";
      if (message && !message->empty()) out->first_failure_message += "; backend: " + *message;
    } else {
      out->first_failure_message = message ? *message : std::string();
    }
  }
  if (!state_finite || policy == FailurePolicy::kStop) {
    out->stopped_early = true;
    return true;
  }
  return false;
}

// The message of a step the backend called solved but that has no exact step on its active set.
std::string NoExactStepMessage(const std::string& backend_message) {
  std::string text =
      "step verdict: the backend's answer has no exact step on its active set (it is not a solution to rounding)";
  if (!backend_message.empty()) text += "; backend: " + backend_message;
  return text;
}

// SubnormalPolicy::kZeroState: a state component below this magnitude after an implicit step is set to 0 (0: the
// rule is off, nothing is below it).
double ZeroStateBelow(const StepperOptions& options, bool implicit) {
  return implicit && options.subnormals == SubnormalPolicy::kZeroState ? std::numeric_limits<double>::min() : 0.0;
}

}  // namespace

// ------------------------------------------------------------------------------------------------------------
// The pre-factored kernel. N, M are the compile-time sizes (Eigen::Dynamic for the general fallback); the same
// code serves both, with every temporary a member so the dynamic case does not allocate either.

class LinearStepper::Kernel {
 public:
  virtual ~Kernel() = default;
  virtual bool fixed_size() const = 0;
  // avi: the one-step AVI of a polytope law (null for the box).
  virtual void Run(const OneStepData& d, BoxMLCP* problem, const AffineVI* avi, const Vector& x0,
                   std::int64_t num_steps, Solver* solver, const StepperOptions& options, Trajectory* out) = 0;
};

namespace {

template <int N, int M>
class KernelImpl final : public LinearStepper::Kernel {
 public:
  using VecN = Eigen::Matrix<double, N, 1>;
  using VecM = Eigen::Matrix<double, M, 1>;
  using MatNN = Eigen::Matrix<double, N, N>;
  using MatNM = Eigen::Matrix<double, N, M>;
  using MatMN = Eigen::Matrix<double, M, N>;
  using MatMM = Eigen::Matrix<double, M, M>;

  explicit KernelImpl(const OneStepData& d) {
    const int n = d.n(), m = d.m();
    R_ = d.R;
    S_ = d.S;
    C_ = d.C;
    D_ = d.D;
    p_ = d.p;
    CR_ = d.C * d.R;      // q = −(C R x_k + C p_k + D), `eq:TDS3`
    c0_ = d.C * d.p + d.D;
    if (d.has_forcing()) {
      P_ = d.P;
      CP_ = d.C * d.P;
    } else {
      P_.setZero(n, n);
      CP_.setZero(m, n);
    }
    if (d.has_input()) {
      Ux_ = d.input_x;
      Us_ = d.input_s;
    } else {
      Ux_.setZero(m, n);
      Us_.setZero(m, m);
    }
    x_.resize(n), xn_.resize(n), b_.resize(n), g_prev_.resize(n), g_next_.resize(n), gbar_.resize(n);
    if (d.sign == SignTreatment::kImplicit) {
      refiner_.Reset(d.OneStepMatrix(), d.S, d.has_polytope_law() ? d.law.H : DenseMatrix(0, m),
                     d.has_polytope_law() ? d.law.K : Vector());
    }
    s_.resize(m), q_.resize(m), y_.resize(m), u_.resize(m), e_.resize(m);
  }

  bool fixed_size() const override { return N != Eigen::Dynamic && M != Eigen::Dynamic; }

  // K·u of StepperOptions::zero_rounding_residue: K = n + m + 1 terms per component (+ n with forcing, + 2J + 1
  // with a disturbance of J sinusoids), u = ε/2.
  static double ResidueFactor(int n, int m, bool forced, const OneStepData& d) {
    return static_cast<double>(n + m + 1 + (forced ? n : 0) + d.disturbance.terms()) * 0.5 *
           std::numeric_limits<double>::epsilon();
  }

  void Run(const OneStepData& d, BoxMLCP* problem, const AffineVI* avi, const Vector& x0, std::int64_t num_steps,
           Solver* solver, const StepperOptions& options, Trajectory* out) override {
    // Fixed sizes: the matrices and the state are copied into locals the compiler keeps in registers. Dynamic
    // sizes: references to the member buffers (a local copy would allocate).
    constexpr bool kFixed = N != Eigen::Dynamic && M != Eigen::Dynamic;
    using CMatNN = std::conditional_t<kFixed, const MatNN, const MatNN&>;
    using CMatNM = std::conditional_t<kFixed, const MatNM, const MatNM&>;
    using CMatMN = std::conditional_t<kFixed, const MatMN, const MatMN&>;
    using CVecN = std::conditional_t<kFixed, const VecN, const VecN&>;
    using CVecM = std::conditional_t<kFixed, const VecM, const VecM&>;
    using WVecN = std::conditional_t<kFixed, VecN, VecN&>;
    using WVecM = std::conditional_t<kFixed, VecM, VecM&>;
    CMatNN R = R_, P = P_;
    CMatNM S = S_;
    CMatMN C = C_, CR = CR_, CP = CP_, Ux = Ux_;
    using CMatMM = std::conditional_t<kFixed, const MatMM, const MatMM&>;
    CMatMM Us = Us_;
    CVecN p = p_;
    CVecM D = D_, c0 = c0_;
    WVecN x = x_, xn = xn_, b = b_, g_prev = g_prev_, g_next = g_next_, gbar = gbar_;
    WVecM s = s_, q = q_, y = y_, u = u_, e = e_;

    const bool implicit = d.sign == SignTreatment::kImplicit;
    const bool forced = d.has_forcing();
    const bool offset = d.has_relation_offset();
    const bool record = options.record;
    const bool stream = options.sink != nullptr;
    const bool need_y = record || stream || !implicit;
    // u_k = Ux x_k + Us s_{k+1} for the outputs only: a run that reports nothing computes no input.
    const bool report_input = d.has_input() && (record || stream);
    const bool disturbed = d.has_disturbance();
    // A polytope law solves the AVI through its exact reduction (AviSession: built once per run, allocation-free
    // per step), warm-started as the box path: the reduction's last active set first, the previous answer (λ, μ)
    // as the backend's start.
    const bool polytope = implicit && avi != nullptr;
    const bool warm = options.warm_start && !polytope;
    const bool warm_avi = options.warm_start && polytope;
    const double h = d.h;
    const double t0 = options.t0;
    const double theta = d.forcing_theta;
    const int m = M != Eigen::Dynamic ? M : d.m();  // a compile-time constant for the fixed kernels
    const int n = N != Eigen::Dynamic ? N : d.n();
    const bool zero_residue = implicit && options.zero_rounding_residue;
    const double residue_factor = ResidueFactor(n, m, forced, d);
    const double zero_below = ZeroStateBelow(options, implicit);
    const bool refine = implicit && options.refine_steps;
    // Every run judges its steps alike: the active sets a previous run left cached do not carry over.
    if (refine) refiner_.ForgetActiveSets();
    const double tolerance = options.solver.tolerance;
    const Eigen::Index law_rows = polytope ? d.law.H.rows() : 0;
    StepObserver* const observer = options.observer;
    stream_.Start(n, m, options.sink, d.has_input());

    // The backend's options: copied once; per step only warm_start's values change (same size: no allocation).
    solver_options_ = options.solver;
    solver_options_.measure_time = false;
    solver_options_.warm_start.resize(warm ? m : 0);

    x = x0;
    s.setZero();
    y = D;
    y.noalias() += C * x;
    if (offset) {
      d.relation_offset(t0, e);
      y += e;
    }
    if (record) Record(0, t0, x, s, y, 0, 0.0, SolveStatus::kNotRun, out);
    if (stream) stream_.Add(0, t0, x, s, y, 0, 0.0, SolveStatus::kNotRun, n, m);
    if (forced) d.forcing(t0, g_prev);

    // Every step solves through one session (solvers/core/session.h): the checks that cannot change during the run
    // are made once, and each step first tries the previous step's active set (on a sliding surface, the same).
    SolveSession* const session = implicit && !polytope ? &SessionFor(solver, *problem, options.session) : nullptr;
    if (polytope) {
      avi_session_.reset();
      avi_session_.emplace(*avi, *solver, solver_options_, options.session);
      avi_q_.resize(m);
    }
    bool previous_avi_solved = false;  // the last AVI step's answer is a usable warm start
    const SolveResult& step_result = polytope ? avi_session_->result() : result_;

    Counters counters;
    std::int64_t k = 0;
    while (k < num_steps) {
      const double t_next = t0 + static_cast<double>(k + 1) * h;
      if (forced) {
        // θ-weighted forcing: ḡ = θ g(t_{k+1}) + (1 − θ) g(t_k); g(t_{k+1}) is reused as g(t_k) next step.
        d.forcing(t_next, g_next);
        gbar = theta * g_next + (1.0 - theta) * g_prev;
        g_prev = g_next;
      }
      // e(t_{k+1}): in q (implicit) and in y_{k+1}.
      if (offset) d.relation_offset(t_next, e);
      SolveStatus status = SolveStatus::kNotRun;
      int iterations = 0;
      double residual = 0.0;
      StepCheck step_check;
      bool no_exact_step = false;
      if (implicit) {
        q = -c0;
        q.noalias() -= CR * x;
        if (forced) q.noalias() -= CP * gbar;
        if (offset) q -= e;
        if (!q.allFinite()) {
          // Only when C R x_k overflows; set_q would throw, and this must be a status.
          status = SolveStatus::kNumericalFailure;
          residual = kInf;
        } else {
          // Plain loops (unrolled for fixed m): Eigen's fixed ↔ dynamic assignments are out-of-line calls.
          if (warm) {
            double* ws = solver_options_.warm_start.data();
            for (int i = 0; i < m; ++i) ws[i] = s[i];
          }
          if (polytope) {
            // A dynamic copy of q: Solve's Ref<const Vector> would copy (allocate) a fixed-size one.
            for (int i = 0; i < m; ++i) avi_q_[i] = q[i];
            const bool from_previous = warm_avi && previous_avi_solved;
            avi_session_->Solve(avi_q_, from_previous ? &avi_session_->solution() : nullptr);
            previous_avi_solved = step_result.status == SolveStatus::kSolved;
            if (observer) observer->OnStep(k + 1, 0, avi_session_->reduction().problem, step_result);
            if (step_result.z.size() >= m) {
              const double* lambda = step_result.z.data();  // z = (λ, μ̃): λ is s_{k+1}
              for (int i = 0; i < m; ++i) s[i] = lambda[i];
            }
          } else {
            session->Solve(q, &result_, warm ? &solver_options_.warm_start : nullptr);
            if (observer) observer->OnStep(k + 1, 0, session->problem(), result_);
            const double* z = result_.z.data();
            for (int i = 0; i < m; ++i) s[i] = z[i];
          }
          status = step_result.status;
          iterations = step_result.iterations;
          residual = step_result.residual_rel;
          if (refine && status == SolveStatus::kSolved) {
            // The step verdict: continue from the exact step on the answer's active set, or report the step.
            const AviSolution* answer = polytope ? &avi_session_->solution() : nullptr;
            const double* mu = answer != nullptr && answer->mu.size() == law_rows ? answer->mu.data() : nullptr;
            step_check = refiner_.Refine(q.data(), mu, s.data());
            if (!step_check.exact) {
              status = SolveStatus::kInaccurate;
              no_exact_step = true;
            }
          }
        }
        counters.Add(iterations, residual);
      } else {
        // Explicit sign: s_{k+1} = sgn(y_k), sgn(0) := 0 (the classical implementation that chatters).
        // Branch-free: the sign alternates every step once the scheme chatters.
        s = (y.array() > 0.0).template cast<double>() - (y.array() < 0.0).template cast<double>();
      }
      if (report_input) {
        // Row k's input, applied over [t_k, t_{k+1}): known now that s_{k+1} is.
        u.noalias() = Ux * x;
        u.noalias() += Us * s;
        if (record) out->u.col(static_cast<Eigen::Index>(k)) = u;
        if (stream) stream_.SetLastInput(u, m);
      }
      // x_{k+1} = R x_k + p_k − S s_{k+1}, `eq:TDS1`.
      xn = p;
      xn.noalias() += R * x;
      if (forced) xn.noalias() += P * gbar;
      // The disturbance acts on the plant only: it never entered q above.
      if (disturbed) d.AddDisturbance(t0 + static_cast<double>(k) * h, xn);
      if (zero_residue) {
        // a = xn, b = S s: a component within the rounding bound of a − b is 0 (StepperOptions).
        b.noalias() = S * s;
        // And one below the normal range is 0 (SubnormalPolicy::kZeroState; zero_below = 0 turns it off).
        for (int i = 0; i < n; ++i) {
          const double v = xn[i] - b[i];
          const double magnitude = std::abs(v);
          x[i] = magnitude <= residue_factor * (std::abs(xn[i]) + std::abs(b[i])) || magnitude < zero_below ? 0.0 : v;
        }
      } else {
        xn.noalias() -= S * s;
        x = xn;
        for (int i = 0; i < n; ++i) {
          if (std::abs(x[i]) < zero_below) x[i] = 0.0;
        }
      }
      // y_k feeds the explicit sign and the record; an unrecorded implicit run needs only y_final (below).
      if (need_y) {
        y = D;
        y.noalias() += C * x;
        if (offset) y += e;
      }
      if (step_check.exact) {
        counters.AddStepCheck(step_check, StepAllowance(tolerance, refiner_.input_scale(), x.cwiseAbs().maxCoeff()));
      }
      ++k;
      if (record) Record(k, t_next, x, s, y, iterations, residual, status, out);
      if (stream) stream_.Add(k, t_next, x, s, y, iterations, residual, status, n, m);
      const bool finite = x.allFinite();
      if (!finite || (implicit && status != SolveStatus::kSolved)) {
        const bool has_nan = !finite && x.hasNaN();
        if (no_exact_step) no_exact_message_ = NoExactStepMessage(step_result.message);
        if (HandleFailure(k, status, residual, finite, has_nan,
                          no_exact_step ? &no_exact_message_ : (implicit ? &step_result.message : nullptr),
                          options.on_failure, &stream_, out)) {
          break;
        }
      }
    }
    if (!need_y) {
      y = D;
      y.noalias() += C * x;
      if (offset) y += e;
    }
    if (session != nullptr && k > 0) problem->set_q(session->problem().q());  // LinearStepper::problem(): the last q
    stream_.Flush();
    counters.Store(out);
    FinishTrajectory(k, x, s, y, out);
  }

 private:
  // The session of this run: the previous run's when the backend and the problem are the same (its options replaced,
  // the remembered active set kept: a second run allocates nothing), else a new one.
  SolveSession& SessionFor(Solver* solver, const BoxMLCP& problem, const SessionOptions& session_options) {
    if (session_ && session_solver_ == solver && session_->problem().matrix_id() == problem.matrix_id() &&
        session_->session_options().reuse_active_set == session_options.reuse_active_set) {
      session_->set_options(solver_options_);
    } else {
      session_.emplace(solver->Prepare(problem, solver_options_, session_options));
      session_solver_ = solver;
    }
    return *session_;
  }

  template <typename X, typename S, typename Y>
  static void Record(std::int64_t k, double t, const X& x, const S& s, const Y& y, int iterations, double residual,
                     SolveStatus status, Trajectory* out) {
    out->SetRow(k, t, x, s, y, iterations, residual, status);
  }

  MatNN R_, P_;
  MatNM S_;
  MatMN C_, CR_, CP_, Ux_;
  MatMM Us_;
  VecN p_;
  VecM D_, c0_;
  VecN x_, xn_, b_, g_prev_, g_next_, gbar_;
  VecM s_, q_, y_, u_, e_;  // e_: e(t) of the relation
  SolverOptions solver_options_;
  SolveResult result_;
  StepRefiner refiner_;                    // the step verdict (implicit steps)
  std::string no_exact_message_;           // a failed step verdict's message
  std::optional<AviSession> avi_session_;  // a polytope law's run
  Vector avi_q_;                           // q handed to it (size m)
  TrajectoryStream stream_;
  std::optional<SolveSession> session_;
  Solver* session_solver_ = nullptr;  // the backend session_ was prepared with
};

// Fixed-size kernels for n ≤ 4, m ≤ 2 (every linear scene of docs/scenes.md); the dynamic kernel otherwise.
template <int N>
std::unique_ptr<LinearStepper::Kernel> MakeForM(const OneStepData& d) {
  if (d.m() == 1) return std::make_unique<KernelImpl<N, 1>>(d);
  if (d.m() == 2) return std::make_unique<KernelImpl<N, 2>>(d);
  return std::make_unique<KernelImpl<Eigen::Dynamic, Eigen::Dynamic>>(d);
}

std::unique_ptr<LinearStepper::Kernel> MakeKernel(const OneStepData& d) {
  switch (d.n()) {
    case 1: return MakeForM<1>(d);
    case 2: return MakeForM<2>(d);
    case 3: return MakeForM<3>(d);
    case 4: return MakeForM<4>(d);
    default: return std::make_unique<KernelImpl<Eigen::Dynamic, Eigen::Dynamic>>(d);
  }
}

}  // namespace

LinearStepper::LinearStepper(OneStepData data) : data_(std::move(data)) {
  data_.Validate();
  // M = C S and the box [−1, 1]^m are constant (`eq:TDS3`); q is replaced in place every step.
  problem_ = std::make_unique<BoxMLCP>(BoxMLCP::Relay(data_.OneStepMatrix(), Vector::Zero(data_.m()), -1.0, 1.0,
                                                      "one-step " + data_.description));
  if (data_.has_polytope_law()) {
    // The same M over P = {s : H s ≥ K}; AffineVI checks that P is not empty.
    avi_ = std::make_unique<AffineVI>(problem_->dense_matrix(), Vector::Zero(data_.m()), data_.law.H, data_.law.K,
                                      "one-step " + data_.description);
  }
  kernel_ = MakeKernel(data_);
}

LinearStepper::~LinearStepper() = default;
LinearStepper::LinearStepper(LinearStepper&&) noexcept = default;
LinearStepper& LinearStepper::operator=(LinearStepper&&) noexcept = default;

bool LinearStepper::uses_fixed_size_kernel() const { return kernel_->fixed_size(); }

void LinearStepper::Run(const Vector& x0, std::int64_t num_steps, Solver* solver, const StepperOptions& options,
                        Trajectory* out) {
  CheckRunArguments(kRunOwner, data_.n(), data_.sign, x0, num_steps, solver, options);
  PrepareTrajectory(data_, num_steps, options, out);
  const ScopedFlushSubnormals flush(options.subnormals == SubnormalPolicy::kFlushToZero);
  kernel_->Run(data_, problem_.get(), avi_.get(), x0, num_steps, solver, options, out);
}

Trajectory LinearStepper::Run(const Vector& x0, std::int64_t num_steps, Solver* solver,
                              const StepperOptions& options) {
  Trajectory out;
  Run(x0, num_steps, solver, options, &out);
  return out;
}

// ------------------------------------------------------------------------------------------------------------

void SimulateRebuildingEachStep(const LinearModel& model, Method method, double h, double theta, const Vector& x0,
                                std::int64_t num_steps, Solver* solver, const StepperOptions& options,
                                Trajectory* out) {
  constexpr const char* kOwner = "SimulateRebuildingEachStep";
  const OneStepData first = Discretize(model, method, h, theta);  // validates everything once
  CheckRunArguments(kOwner, first.n(), first.sign, x0, num_steps, solver, options);
  PrepareTrajectory(first, num_steps, options, out);
  const ScopedFlushSubnormals flush(options.subnormals == SubnormalPolicy::kFlushToZero);
  // A ZOH plant run with a θ-method is its closed loop; form it once (a model change, not a discretization).
  LinearModel effective = model;
  if (const auto* zsys = std::get_if<ZohSmcSystem>(&model)) {
    if (method == Method::kImplicit || method == Method::kExplicit) effective = ClosedLoop(*zsys);
  }

  const bool implicit = first.sign == SignTreatment::kImplicit;
  const int n = first.n(), m = first.m();
  SolverOptions solver_options = options.solver;
  solver_options.measure_time = false;
  SolveResult result;
  Vector x = x0, s = Vector::Zero(m), y = first.C * x + first.D;
  Vector g_prev(n), g_next(n), gbar(n), e = Vector::Zero(m);
  if (first.has_relation_offset()) {
    first.relation_offset(options.t0, e);
    y += e;
  }
  if (first.has_forcing()) first.forcing(options.t0, g_prev);
  TrajectoryStream stream;
  stream.Start(n, m, options.sink, first.has_input());
  const auto record = [&](std::int64_t k, double t, int iterations, double residual, SolveStatus status) {
    if (options.record) out->SetRow(k, t, x, s, y, iterations, residual, status);
    if (stream.active()) stream.Add(k, t, x, s, y, iterations, residual, status, n, m);
  };
  record(0, options.t0, 0, 0.0, SolveStatus::kNotRun);
  const double zero_below = ZeroStateBelow(options, implicit);

  StepRefiner refiner;  // the step verdict, as the prefactored kernels (rebuilt each step with the data)
  std::string no_exact_message;
  Counters counters;
  std::int64_t k = 0;
  while (k < num_steps) {
    const double t_next = options.t0 + static_cast<double>(k + 1) * h;
    // Re-discretize as a general simulator would (time-varying E would need it; here it is the baseline).
    const OneStepData d = stepper_detail::DiscretizeUnchecked(effective, method, h, theta);
    Vector p = d.p;
    if (d.has_forcing()) {
      d.forcing(t_next, g_next);
      gbar = d.forcing_theta * g_next + (1.0 - d.forcing_theta) * g_prev;
      g_prev = g_next;
      p += d.P * gbar;
    }
    if (d.has_relation_offset()) d.relation_offset(t_next, e);
    SolveStatus status = SolveStatus::kNotRun;
    int iterations = 0;
    double residual = 0.0;
    StepCheck step_check;
    bool no_exact_step = false;
    if (implicit) {
      Vector q = -(d.C * (d.R * x) + d.C * p + d.D + e);  // `eq:TDS3`, e(t_{k+1}) of the relation
      const Vector q_step = q;  // for the step verdict: q is moved into the problem below
      if (!q.allFinite()) {
        status = SolveStatus::kNumericalFailure;
        residual = kInf;
      } else if (d.has_polytope_law()) {
        // A fresh AVI and its reduction every step, as a general simulator would (SolveAvi builds the reduction).
        const AffineVI avi(d.C * d.S, std::move(q), d.law.H, d.law.K);
        const AviResult r = SolveAvi(avi, *solver, solver_options);
        if (options.observer) {
          options.observer->OnStep(k + 1, 0, ReduceToBoxMlcp(avi, AviReductionScaling::kNormalized).problem, r.reduced);
        }
        if (r.solution.lambda.size() == m) s = r.solution.lambda;
        status = r.status;
        iterations = r.iterations;
        residual = r.reduced.residual_rel;
        result.message = r.message;
        if (options.refine_steps && status == SolveStatus::kSolved) {
          refiner.Reset(d.OneStepMatrix(), d.S, d.law.H, d.law.K);
          const double* mu = r.solution.mu.size() == d.law.H.rows() ? r.solution.mu.data() : nullptr;
          step_check = refiner.Refine(q_step.data(), mu, s.data());
        }
      } else {
        const BoxMLCP problem = BoxMLCP::Relay(d.C * d.S, std::move(q));
        if (options.warm_start) solver_options.warm_start = s;
        solver->Solve(problem, solver_options, &result);
        if (options.observer) options.observer->OnStep(k + 1, 0, problem, result);
        s = result.z;
        status = result.status;
        iterations = result.iterations;
        residual = result.residual_rel;
        if (options.refine_steps && status == SolveStatus::kSolved) {
          refiner.Reset(d.OneStepMatrix(), d.S, DenseMatrix(0, m), Vector());
          step_check = refiner.Refine(q_step.data(), nullptr, s.data());
        }
      }
      if (options.refine_steps && status == SolveStatus::kSolved && !step_check.exact) {
        status = SolveStatus::kInaccurate;
        no_exact_step = true;
      }
      counters.Add(iterations, residual);
    } else {
      for (int i = 0; i < m; ++i) s[i] = y[i] > 0.0 ? 1.0 : (y[i] < 0.0 ? -1.0 : 0.0);
    }
    if (d.has_input() && (options.record || stream.active())) {
      const Vector u = d.input_x * x + d.input_s * s;
      if (options.record) out->u.col(static_cast<Eigen::Index>(k)) = u;
      if (stream.active()) stream.SetLastInput(u, m);
    }
    // The disturbance acts on the plant only (never on q).
    if (d.has_disturbance()) d.AddDisturbance(options.t0 + static_cast<double>(k) * h, p);
    if (implicit && options.zero_rounding_residue) {
      // The same rule as the prefactored kernels (StepperOptions::zero_rounding_residue); p holds P ḡ here.
      const Vector a = d.R * x + p;
      const Vector b = d.S * s;
      const double factor = static_cast<double>(n + m + 1 + (d.has_forcing() ? n : 0) + d.disturbance.terms()) * 0.5 *
                            std::numeric_limits<double>::epsilon();
      for (int i = 0; i < n; ++i) {
        const double v = a[i] - b[i];
        const double magnitude = std::abs(v);
        x[i] = magnitude <= factor * (std::abs(a[i]) + std::abs(b[i])) || magnitude < zero_below ? 0.0 : v;
      }
    } else {
      x = d.R * x + p - d.S * s;
      for (int i = 0; i < n; ++i) {
        if (std::abs(x[i]) < zero_below) x[i] = 0.0;
      }
    }
    y = d.C * x + d.D + e;
    if (step_check.exact) {
      counters.AddStepCheck(step_check, StepAllowance(options.solver.tolerance, refiner.input_scale(),
                                                      x.cwiseAbs().maxCoeff()));
    }
    ++k;
    record(k, t_next, iterations, residual, status);
    const bool finite = x.allFinite();
    if (!finite || (implicit && status != SolveStatus::kSolved)) {
      if (no_exact_step) no_exact_message = NoExactStepMessage(result.message);
      if (HandleFailure(k, status, residual, finite, !finite && x.hasNaN(),
                        no_exact_step ? &no_exact_message : (implicit ? &result.message : nullptr),
                        options.on_failure, &stream, out)) {
        break;
      }
    }
  }
  stream.Flush();
  counters.Store(out);
  FinishTrajectory(k, x, s, y, out);
}

}  // namespace smcbench

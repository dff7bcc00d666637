// S8 `observer` (observer-based SMC with a parasitic actuator of time constant τ): chattering-free at θ = 1, the
// θ = 0 stability threshold in h by bisection, and θ = ½ against θ = 1 at τ = 0.5. Measured into ObserverStudy,
// then written. The paper's scenes: docs/scenes.md.
#include <cmath>
#include <ostream>

#include "tools/smcbench/paper/study.h"

namespace smcbench::paper {
namespace {

const std::string kScene = "observer";

struct ObserverStudy {
  // (a) τ = 0.001, h = 0.1, θ = 1.
  bool theta1_ok = false;  // the run completed
  Sliding theta1;
  Vector x_final, explicit_x_final;
  // (b) θ = 0: stable at h = 0.1, at the report's h = 0.005, and the bisected threshold [lo, hi].
  bool stable_at_01 = false, stable_at_0005 = false;
  bool bracket = false;  // stable at 1e-4 and unstable at 0.1, so the bisection ran
  double threshold_low = 1e-4, threshold_high = 0.1;
  int bisections = 0;
  bool stable_below_threshold = true;  // every h of a ×1.5 grid from 1e-4 up to the threshold
  // (c) τ = 0.5, h = 0.1: max error against a fine θ = ½ reference, for θ = 1 and θ = ½.
  double error_theta1 = 0.0, error_theta_half = 0.0;
  std::vector<FigureRun> figures;
};

void MeasureChatteringFree(Studies& st, const SimulationSettings& base, ObserverStudy* m) {
  const Trajectory tr = st.Run(kScene, base);
  m->theta1_ok = tr.ok();
  m->theta1 = Analyze(tr);
  m->x_final = tr.x_final;
  m->explicit_x_final = st.Run(kScene, Studies::Explicit(base)).x_final;
  st.KeepFigure(&m->figures, tr, "S8-observer-implicit-theta1", "S8 observer, tau = 0.001, h = 0.1, theta = 1");
}

// Stable: the run completes with finite states and the last tenth stays within 10 × ‖x0‖∞ (an unstable run grows
// like (h/τ − 1)^k and overflows).
void MeasureThreshold(Studies& st, const SimulationSettings& base, ObserverStudy* m) {
  const auto stable = [&](double h) {
    SimulationSettings s = base;
    s.theta = 0.0;
    s.h = h;
    s.stepper.record = false;
    const Trajectory tr = st.Run(kScene, s);
    return tr.ok() && tr.x_final.allFinite() && MaxAbs(tr.x_final) <= 10.0 * MaxAbs(base.x0);
  };
  m->stable_at_01 = stable(0.1);
  m->stable_at_0005 = stable(0.005);
  double& lo = m->threshold_low;
  double& hi = m->threshold_high;
  m->bracket = stable(lo) && !stable(hi);
  while (m->bracket && hi / lo > 1.0001) {
    const double mid = std::sqrt(lo * hi);
    (stable(mid) ? lo : hi) = mid;
    ++m->bisections;
  }
  // Monotonicity check of the verdict on a grid below the threshold.
  for (double h = 1e-4; h < lo; h *= 1.5) m->stable_below_threshold = m->stable_below_threshold && stable(h);
  if (m->bracket) {
    SimulationSettings s = base;
    s.theta = 0.0;
    s.h = hi * 1.05;
    s.T = 0.2;
    s.stepper.on_failure = FailurePolicy::kContinue;
    st.KeepFigure(&m->figures, st.Run(kScene, s), "S8-observer-theta0-unstable",
                  "S8 observer, theta = 0, h = " + G(s.h, 4) + " (unstable)");
  }
}

// θ = 1 against θ = ½, each compared with a fine θ = ½ reference (h = 1e-4).
void MeasureDamping(Studies& st, const SimulationSettings& base, ObserverStudy* m) {
  SimulationSettings ref = base;
  ref.parameters["tau"] = 0.5;
  ref.theta = 0.5;
  ref.h = 1e-4;
  const Trajectory reference = st.Run(kScene, ref);
  for (const double theta : {1.0, 0.5}) {
    SimulationSettings s = base;
    s.parameters["tau"] = 0.5;
    s.theta = theta;
    const Trajectory tr = st.Run(kScene, s);
    (theta == 1.0 ? m->error_theta1 : m->error_theta_half) = MaxErrorAgainst(tr, reference);
    st.KeepFigure(&m->figures, tr, "S8-observer-tau0.5-theta" + G(theta),
                  "S8 observer, tau = 0.5, h = 0.1, theta = " + G(theta));
  }
}

void WriteObserver(const ObserverStudy& m, Studies& st) {
  auto& md = st.section();
  json& d = st.data()["S8"];
  const Sliding& sl = m.theta1;
  md << "τ = 0.001, h = 0.1, θ = 1: surface reached at step " << sl.reaching_step << " (t = " << G(sl.reaching_time)
     << "), " << sl.sign_changes_after << " sign changes after, max |y| after " << G(sl.max_abs_y_after)
     << ", x_N = " << VecText(m.x_final) << ". Explicit Euler at the same h: x_N = " << VecText(m.explicit_x_final)
     << ".\n\n";
  d["theta1"] = {{"sliding", SlidingJson(sl)}, {"x_final", VecJson(m.x_final)},
                 {"explicit_x_final", VecJson(m.explicit_x_final)}};
  st.Claim("S8 observer", "τ = 0.001, h = 0.1, θ = γ = 1: chattering-free control",
           "reached at t = " + G(sl.reaching_time) + ", " + std::to_string(sl.sign_changes_after) +
               " sign changes after, max |y| after " + G(sl.max_abs_y_after),
           m.theta1_ok && sl.chattering_free() ? kHolds : kFails);

  const double lo = m.threshold_low, hi = m.threshold_high;
  md << "θ = 0 (explicit f, implicit sign), τ = 0.001, T = 10: stable at h = 0.1: " << (m.stable_at_01 ? "yes" : "no")
     << "; at h = 0.005 (the report's threshold): " << (m.stable_at_0005 ? "yes" : "no") << ". Bisection ("
     << m.bisections << " steps, criterion: run completes, ‖x_N‖∞ ≤ 10 ‖x0‖∞): stable for h ≤ " << G(lo, 5)
     << ", unstable for h ≥ " << G(hi, 5)
     << " (explicit Euler on the actuator's double eigenvalue −1/τ predicts h < 2τ = 0.002); every h on a "
     << "×1.5 grid from 1e-4 up to the threshold is stable: " << (m.stable_below_threshold ? "yes" : "no")
     << ".\n\n";
  d["theta0"] = {{"stable_at_0.1", m.stable_at_01}, {"stable_at_0.005", m.stable_at_0005}, {"threshold_low", lo},
                 {"threshold_high", hi}, {"bisections", m.bisections},
                 {"stable_below_threshold", m.stable_below_threshold}};
  st.Claim("S8 observer", "θ = 0 is unstable at h = 0.1", m.stable_at_01 ? "stable at h = 0.1" : "unstable at h = 0.1",
           m.stable_at_01 ? kFails : kHolds);
  st.Claim("S8 observer", "θ = 0: stability returns for h < 0.005",
           "bisection: threshold h* ∈ [" + G(lo, 5) + ", " + G(hi, 5) + "] (≈ 2τ); h = 0.005 is " +
               (m.stable_at_0005 ? "stable" : "unstable"),
           m.stable_at_0005 && m.bracket ? kHolds : kFails);

  md << "τ = 0.5, h = 0.1 against a θ = ½, h = 1e-4 reference: max over t_k of ‖x_k − x(t_k)‖∞ is "
     << G(m.error_theta1) << " for θ = 1 and " << G(m.error_theta_half) << " for θ = ½.\n\n";
  d["tau0.5"] = {{"max_error_theta1", m.error_theta1}, {"max_error_theta_half", m.error_theta_half}};
  st.Figures(m.figures);
  st.Claim("S8 observer", "τ = 0.5, h = 0.1: θ = ½ has less numerical damping than θ = 1",
           "max error against a fine reference: θ = 1 " + G(m.error_theta1) + ", θ = ½ " + G(m.error_theta_half),
           m.error_theta_half < m.error_theta1 ? kHolds : kFails);
}

}  // namespace

void StudyObserver(Studies& st) {
  st.BeginSection("S8 `observer`: observer-based SMC with a parasitic actuator of time constant τ",
                  "smcbench simulate observer --theta 0 --h 0.0019 --summary s8.json");
  const SimulationSettings base = st.Defaults(kScene);  // τ = 0.001, h = 0.1, θ = 1
  ObserverStudy m;
  MeasureChatteringFree(st, base, &m);
  MeasureThreshold(st, base, &m);
  MeasureDamping(st, base, &m);
  WriteObserver(m, st);
}

}  // namespace smcbench::paper

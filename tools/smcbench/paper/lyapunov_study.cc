// S7 `lyapunov` (x' = −x − u + α sin t): smooth stabilization with u strictly inside (−1, 1), and Proposition 2's
// order ≥ ½ in x against a fine reference. Measured into LyapunovStudy, then written.
// The paper's labels cited here (app2, Proposition 2): docs/glossary.md; its scenes: docs/scenes.md.
#include <algorithm>
#include <cmath>
#include <ostream>

#include "tools/smcbench/paper/study.h"

namespace smcbench::paper {
namespace {

const std::string kScene = "lyapunov";

struct LyapunovStudy {
  double h = 0.0;
  Sliding implicit, explicit_euler;
  double max_abs_u_after = 0.0;       // max |s_k| after reaching
  double max_dev_from_alpha_sin = 0.0;  // max |s_k − α sin t_k| after reaching
  double explicit_amplitude = 0.0;    // max |x| over the explicit run's last half
  // Proposition 2: max error of x against a θ = 0, h = 1e-5 run, per h, for θ = 0 (app2) and θ = 1.
  std::vector<double> hs, error_theta0, error_theta1;
  double order_theta0 = 0.0, order_theta1 = 0.0;
  std::vector<FigureRun> figures;
};

LyapunovStudy MeasureLyapunov(Studies& st) {
  LyapunovStudy m;
  const SimulationSettings s = st.Defaults(kScene);
  m.h = s.h;
  const Trajectory tr = st.Run(kScene, s);
  m.implicit = Analyze(tr);
  const Sliding& sl = m.implicit;
  const double alpha = s.parameters.count("alpha") ? s.parameters.at("alpha") : 0.1;
  for (std::int64_t k = std::max<std::int64_t>(sl.reaching_step + 1, 1); sl.reaching_step >= 0 && k <= tr.steps_taken;
       ++k) {
    m.max_abs_u_after = std::max(m.max_abs_u_after, std::abs(tr.s(0, k)));
    m.max_dev_from_alpha_sin = std::max(m.max_dev_from_alpha_sin, std::abs(tr.s(0, k) - alpha * std::sin(tr.time(k))));
  }
  const Trajectory ex = st.Run(kScene, Studies::Explicit(s));
  m.explicit_euler = Analyze(ex);
  for (std::int64_t k = ex.steps_taken / 2; k <= ex.steps_taken; ++k) {
    m.explicit_amplitude = std::max(m.explicit_amplitude, std::abs(ex.x(0, k)));
  }
  st.KeepFigure(&m.figures, tr, "S7-lyapunov-implicit", "S7 lyapunov, implicit Euler, h = " + G(s.h));
  st.KeepFigure(&m.figures, ex, "S7-lyapunov-explicit", "S7 lyapunov, explicit Euler, h = " + G(s.h));
  // Proposition 2 (order ≥ ½ in x, proved for the semi-implicit scheme app2: θ = 0) on the one scene of its class
  // without a closed-form solution: against a θ = 0, h = 1e-5 reference.
  SimulationSettings rs = s;
  rs.theta = 0.0;
  rs.h = 1e-5;
  const Trajectory ref = st.Run(kScene, rs);
  m.hs = {0.1, 0.05, 0.02, 0.01, 0.005, 0.002, 0.001};
  for (const double h : m.hs) {
    SimulationSettings a = s;
    a.h = h;
    a.theta = 0.0;
    m.error_theta0.push_back(MaxErrorAgainst(st.Run(kScene, a), ref));
    a.theta = 1.0;
    m.error_theta1.push_back(MaxErrorAgainst(st.Run(kScene, a), ref));
  }
  m.order_theta0 = FittedOrder(m.hs, m.error_theta0);
  m.order_theta1 = FittedOrder(m.hs, m.error_theta1);
  return m;
}

void WriteLyapunov(const LyapunovStudy& m, Studies& st) {
  auto& md = st.section();
  const Sliding& sl = m.implicit;
  md << "Implicit, h = " << G(m.h) << ": x = 0 from step " << sl.reaching_step << " (t = " << G(sl.reaching_time)
     << "); after it max |u| = max |s| = " << G(m.max_abs_u_after) << ", max |s_k − α sin t_k| = "
     << G(m.max_dev_from_alpha_sin) << ". Explicit: " << m.explicit_euler.sign_changes_total
     << " sign changes of u, max |x| over the last half " << G(m.explicit_amplitude) << ".\n\n";
  st.Figures(m.figures);
  st.data()["S7"] = {{"implicit", SlidingJson(sl)}, {"max_abs_u_after", m.max_abs_u_after},
                     {"max_dev_from_alpha_sin", m.max_dev_from_alpha_sin},
                     {"explicit", SlidingJson(m.explicit_euler)},
                     {"explicit_amplitude_last_half", m.explicit_amplitude}};
  md << "Proposition 2 (‖x(t) − x_N(t)‖ ≤ η√h, proved for the semi-implicit scheme `app2`, θ = 0): max over the "
        "grid of |x_k − x(t_k)| against a θ = 0, h = 1e-5 run.\n\n";
  TableHeader(md, {"h", "θ = 0 (app2)", "θ = 1"});
  for (std::size_t i = 0; i < m.hs.size(); ++i) {
    md << "| " << G(m.hs[i]) << " | " << G(m.error_theta0[i]) << " | " << G(m.error_theta1[i]) << " |\n";
  }
  md << "| fitted order | " << G(m.order_theta0) << " | " << G(m.order_theta1) << " |\n\n";
  st.data()["S7_proposition2"] = {{"h", m.hs}, {"error_theta0", m.error_theta0}, {"error_theta1", m.error_theta1},
                                  {"order_theta0", m.order_theta0}, {"order_theta1", m.order_theta1}};
  st.Claim("S7 lyapunov", "Proposition 2: ‖x(t) − x_N(t)‖ ≤ η√h (order ≥ ½), semi-implicit scheme",
           "max-norm error order of x over h = 0.1 … 0.001 against an h = 1e-5 reference: " + G(m.order_theta0) +
               " (θ = 0), " + G(m.order_theta1) + " (θ = 1): the bound holds with room (order 1 observed)",
           m.order_theta0 >= 0.45 ? kHolds : kFails);
  st.Claim("S7 lyapunov", "implicit: smooth stabilization at x = 0 with u strictly inside (−1, 1) cancelling γ(t)",
           "x = 0 from t = " + G(sl.reaching_time) + ", then max |u| = " + G(m.max_abs_u_after) +
               " < 1, |u − α sin t| ≤ " + G(m.max_dev_from_alpha_sin) + "; explicit: " +
               std::to_string(m.explicit_euler.sign_changes_total) + " sign changes of u",
           sl.chattering_free() && m.max_abs_u_after < 1.0 ? kHolds : kFails);
}

}  // namespace

void StudyLyapunov(Studies& st) {
  st.BeginSection("S7 `lyapunov`: x' = −x − u + α sin t, u ∈ sgn(x)", "smcbench simulate lyapunov --plot s7.png");
  WriteLyapunov(MeasureLyapunov(st), st);
}

}  // namespace smcbench::paper

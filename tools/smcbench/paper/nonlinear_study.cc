// S9 `hypomonotone` and S10 `arctan`, the nonlinear scenes: Algorithm 1 (one MCP per step) against Algorithm 2
// (Newton with an MLCP per iterate) on every backend, convergence of x, then S9's closed-form step and Lemma youpi
// or S10's arrival time. Measured into NonlinearStudy, then written.
// The paper's labels cited here (Algorithm 1/2, Lemma youpi, Proposition 2): docs/glossary.md; scenes: docs/scenes.md.
#include <algorithm>
#include <cmath>
#include <ostream>

#include "problems/stepper/metrics.h"
#include "solvers/registry/registry.h"
#include "tools/smcbench/paper/study.h"

namespace smcbench::paper {
namespace {

// One backend's Algorithm 2 run against Algorithm 1's.
struct Algorithm2Run {
  std::string backend;
  bool ok = false;
  double max_residual = 0.0;
  double max_diff = 0.0;  // max |x_Alg2 − x_Alg1| over the run, NaN when either run failed
  double reaching_time = 0.0;
};

// One h of Lemma youpi's table (S9).
struct YoupiRow {
  double h = 0.0;
  bool ok = false;  // completed, chattering-free, |x| ≤ 1e-12 after reaching
  Sliding sliding;
  double max_abs_after = 0.0;
  std::string failure;  // the run's first failure message, when it failed
};

struct NonlinearStudy {
  std::string id, name;
  bool hypomonotone = false;
  bool algorithm1_ok = false;
  double algorithm1_max_residual = 0.0, algorithm1_reaching_time = 0.0;
  std::vector<Algorithm2Run> algorithm2;
  // x against the exact solution (Algorithm 2, the default backend).
  std::vector<double> hs, error_l1, error_l2, error_max;
  double order_l1 = 0.0, order_l2 = 0.0, order_max = 0.0;
  // S9: the closed-form step over Algorithm 1's run, and Lemma youpi.
  int closed_form_steps = 0;
  double closed_form_deviation = 0.0;
  std::vector<YoupiRow> youpi;
  // S10: arrival against the exact t* = |x0| + |x0|³/3.
  double h = 0.0, t_star = 0.0;
  Sliding arrival;
  ErrorNorms x_error;
  std::vector<FigureRun> figures;
};

void MeasureAlgorithms(Studies& st, SimulationSettings s, NonlinearStudy* m, Trajectory* a1) {
  const std::string& name = m->name;
  s.algorithm = NonlinearAlgorithm::kMcp;
  *a1 = st.Run(name, s, "newton");
  m->algorithm1_ok = a1->ok();
  m->algorithm1_max_residual = a1->max_residual;
  m->algorithm1_reaching_time = Analyze(*a1).reaching_time;
  s.algorithm = NonlinearAlgorithm::kNewtonMlcp;
  for (auto backend : SolverNames()) {
    const Trajectory a2 = st.Run(name, s, std::string(backend));
    Algorithm2Run run;
    run.backend = std::string(backend);
    run.ok = a2.ok();
    run.max_residual = a2.max_residual;
    run.max_diff = a2.ok() && a1->ok() ? (a2.x - a1->x).cwiseAbs().maxCoeff() : std::nan("");
    run.reaching_time = Analyze(a2).reaching_time;
    m->algorithm2.push_back(run);
  }
  st.KeepFigure(&m->figures, *a1, m->id + "-" + name + "-implicit", m->id + " " + name + ", implicit, Algorithm 1");
  st.KeepFigure(&m->figures, st.Run(name, Studies::Explicit(st.Defaults(name))), m->id + "-" + name + "-explicit",
                m->id + " " + name + ", explicit Euler");
}

void MeasureConvergence(Studies& st, NonlinearStudy* m) {
  m->hs = {0.1, 0.05, 0.02, 0.01, 0.005, 0.002, 0.001};
  for (const double h : m->hs) {
    SimulationSettings sh = st.Defaults(m->name);
    sh.h = h;
    const SolutionErrors e = ComputeErrors(st.Run(m->name, sh), *st.scene(m->name).Exact(sh));
    m->error_l1.push_back(e.x->l1), m->error_l2.push_back(e.x->l2), m->error_max.push_back(e.x->max);
  }
  m->order_l1 = FittedOrder(m->hs, m->error_l1);
  m->order_l2 = FittedOrder(m->hs, m->error_l2);
  m->order_max = FittedOrder(m->hs, m->error_max);
}

// The closed form x_{k+1} = (x_k − h sgn x_k)/(1 + h sgn x_k) for |x_k| > h, ρ = 0, and Lemma youpi.
void MeasureHypomonotone(Studies& st, const Trajectory& a1, double h0, NonlinearStudy* m) {
  for (std::int64_t k = 0; k < a1.steps_taken; ++k) {
    const double x = a1.x(0, k);
    if (std::abs(x) <= h0) continue;
    const double sg = x > 0 ? 1.0 : -1.0;
    m->closed_form_deviation = std::max(m->closed_form_deviation, std::abs(a1.x(0, k + 1) - (x - h0 * sg) / (1.0 + h0 * sg)));
    ++m->closed_form_steps;
  }
  for (const double h : {0.1, 0.3, 0.5, 0.9, 1.5}) {
    SimulationSettings sh = st.Defaults(m->name);
    sh.h = h;
    sh.T = std::max(sh.T, 10 * h);
    const Trajectory tr = st.Run(m->name, sh);
    YoupiRow row;
    row.h = h;
    row.sliding = Analyze(tr);
    const Sliding& sl = row.sliding;
    for (std::int64_t k = std::max<std::int64_t>(sl.reaching_step, 0); sl.reaching_step >= 0 && k <= tr.steps_taken;
         ++k) {
      row.max_abs_after = std::max(row.max_abs_after, std::abs(tr.x(0, k)));
    }
    row.ok = tr.ok() && sl.chattering_free() && row.max_abs_after <= 1e-12;
    if (!tr.ok()) row.failure = tr.first_failure_message;
    m->youpi.push_back(row);
  }
}

NonlinearStudy MeasureNonlinear(Studies& st, const std::string& id, const std::string& name) {
  NonlinearStudy m;
  m.id = id;
  m.name = name;
  m.hypomonotone = name == "hypomonotone";
  SimulationSettings s = st.Defaults(name);
  s.algorithm = NonlinearAlgorithm::kNewtonMlcp;
  m.h = s.h;
  Trajectory a1;
  MeasureAlgorithms(st, s, &m, &a1);
  MeasureConvergence(st, &m);
  if (m.hypomonotone) {
    MeasureHypomonotone(st, a1, s.h, &m);
  } else {
    const double x0 = s.x0[0];
    m.t_star = std::abs(x0) + std::pow(std::abs(x0), 3) / 3.0;
    m.arrival = Analyze(a1);
    m.x_error = *ComputeErrors(a1, *st.scene(name).Exact(s)).x;
  }
  return m;
}

void WriteAlgorithms(const NonlinearStudy& m, Studies& st, json& d) {
  auto& md = st.section();
  TableHeader(md, {"path", "backend", "steps ok", "max residual", "max abs(x − x_Alg1)", "reaching t"});
  md << "| Algorithm 1 (MCP) | newton | " << (m.algorithm1_ok ? "yes" : "NO") << " | " << G(m.algorithm1_max_residual)
     << " | 0 | " << G(m.algorithm1_reaching_time) << " |\n";
  bool all_ok = m.algorithm1_ok;
  double max_diff = 0.0;
  std::string external_failures;
  for (const Algorithm2Run& r : m.algorithm2) {
    if (IsExternal(r.backend)) {
      if (!r.ok) AppendListItem(&external_failures, r.backend);
    } else {
      all_ok = all_ok && r.ok;
      if (!std::isnan(r.max_diff)) max_diff = std::max(max_diff, r.max_diff);
    }
    md << "| Algorithm 2 (Newton + MLCP) | " << r.backend << " | " << (r.ok ? "yes" : "NO") << " | "
       << G(r.max_residual) << " | " << G(r.max_diff) << " | " << G(r.reaching_time) << " |\n";
    d["algorithm2"].push_back({{"backend", r.backend}, {"ok", r.ok}, {"max_residual", r.max_residual},
                               {"max_diff_from_algorithm1", r.max_diff}});
  }
  md << "\n";
  st.Figures(m.figures);
  st.Claim(m.id + " " + m.name, "Algorithm 1 (MCP) and Algorithm 2 (Newton + any MLCP backend) agree",
           "every smcbench backend: max |x_Alg2 − x_Alg1| over the run = " + G(max_diff) +
               " (tolerance 1e-10 on each step)" +
               (external_failures.empty() ? "" : "; external adapters that fail a step: " + external_failures),
           all_ok && max_diff <= 1e-8 ? kHolds : kFails);
  d["max_diff"] = max_diff;
}

void WriteConvergence(const NonlinearStudy& m, Studies& st, json& d) {
  st.section() << "Error of x against the exact solution, h = 0.1 … 0.001 (" << m.hs.size()
               << " values): fitted orders L1 " << G(m.order_l1) << ", L2 " << G(m.order_l2) << ", max "
               << G(m.order_max) << " (max error " << G(m.error_max.front()) << " at h = 0.1, "
               << G(m.error_max.back()) << " at h = 0.001).\n\n";
  d["x_convergence"] = {{"h", m.hs}, {"l1", m.error_l1}, {"l2", m.error_l2}, {"max", m.error_max},
                        {"orders", {{"l1", m.order_l1}, {"l2", m.order_l2}, {"max", m.order_max}}}};
  st.Claim(m.id + " " + m.name, "convergence of x (Proposition 2's order ≥ ½, outside its class (2) assumptions)",
           "fitted orders of x against the exact solution: L1 " + G(m.order_l1) + ", L2 " + G(m.order_l2) +
               ", max " + G(m.order_max),
           m.order_max >= 0.45 ? kHolds : kFails);
}

void WriteHypomonotone(const NonlinearStudy& m, Studies& st, json& d) {
  auto& md = st.section();
  d["closed_form"] = {{"steps_checked", m.closed_form_steps}, {"max_deviation", m.closed_form_deviation}};
  md << "Closed-form step (ρ = 0, |x_k| > h): " << m.closed_form_steps << " steps checked, max deviation "
     << G(m.closed_form_deviation) << ".\n\n";
  st.Claim("S9 hypomonotone", "ρ = 0, |x_k| > h: x_{k+1} = (x_k − h sgn x_k)/(1 + h sgn x_k)",
           std::to_string(m.closed_form_steps) + " steps of the run, max deviation " + G(m.closed_form_deviation),
           m.closed_form_steps > 0 && m.closed_form_deviation <= 1e-12 ? kHolds : kFails);
  TableHeader(md, {"h", "reaching step (t)", "max abs x after", "sign changes after"});
  bool youpi = true;
  std::string text;
  for (const YoupiRow& r : m.youpi) {
    const Sliding& sl = r.sliding;
    if (r.h < 1.0) youpi = youpi && r.ok;
    AppendListItem(&text,
                   "h = " + G(r.h) + ": " +
                       (r.ok ? "at 0 from t = " + G(sl.reaching_time) : "not reached/stays: " + r.failure),
                   "; ");
    md << "| " << G(r.h) << " | " << sl.reaching_step << " (" << G(sl.reaching_time) << ") | " << G(r.max_abs_after)
       << " | " << sl.sign_changes_after << " |\n";
    d["lemma_youpi"].push_back(
        {{"h", r.h}, {"ok", r.ok}, {"sliding", SlidingJson(sl)}, {"max_abs_x_after", r.max_abs_after}});
  }
  md << "\n";
  st.Claim("S9 hypomonotone", "Lemma youpi: for 0 < h < 1, x reaches 0 in finite time and stays",
           text + " (h = 1.5 is outside the lemma)", youpi ? kHolds : kFails);
}

void WriteArctan(const NonlinearStudy& m, Studies& st, json& d) {
  const Sliding& sl = m.arrival;
  st.section() << "Exact arrival t* = |x0| + |x0|³/3 = " << G(m.t_star, 6) << "; discrete arrival t = "
               << G(sl.reaching_time, 6) << "; error of x: max " << G(m.x_error.max) << ", L1 " << G(m.x_error.l1)
               << ".\n\n";
  d["t_star"] = m.t_star;
  d["reaching_time"] = sl.reaching_time;
  d["x_error"] = {{"l1", m.x_error.l1}, {"l2", m.x_error.l2}, {"max", m.x_error.max}};
  st.Claim("S10 arctan", "(not simulated in the report) reaches 0 in finite time, near the exact t*",
           "t* = " + G(m.t_star, 5) + ", discrete arrival at t = " + G(sl.reaching_time, 5) + ", " +
               std::to_string(sl.sign_changes_after) + " sign changes after",
           sl.chattering_free() && std::abs(sl.reaching_time - m.t_star) <= 2 * m.h ? kHolds : kFails);
}

}  // namespace

void StudyNonlinear(Studies& st) {
  for (const std::string name : {"hypomonotone", "arctan"}) {
    const std::string id = name == "hypomonotone" ? "S9" : "S10";
    st.BeginSection(id + " `" + name + "`: " + st.scene(name).info().description,
                    "smcbench simulate " + name + " --algorithm mcp --summary a1.json");
    const NonlinearStudy m = MeasureNonlinear(st, id, name);
    json& d = st.data()[id];
    WriteAlgorithms(m, st, d);
    WriteConvergence(m, st, d);
    if (m.hypomonotone) {
      WriteHypomonotone(m, st, d);
    } else {
      WriteArctan(m, st, d);
    }
  }
}

}  // namespace smcbench::paper

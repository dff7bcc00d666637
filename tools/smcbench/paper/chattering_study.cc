// S2, S5, S6: the implicit scheme reaches the surface and stays without chattering; the explicit one ends on a
// period-2 orbit (S2, S5) or chatters (S6). Measured into ChatteringStudy, then written.
// The paper's scenes: docs/scenes.md.
#include <ostream>

#include "problems/scenes/run_summary.h"
#include "problems/stepper/metrics.h"
#include "tools/smcbench/paper/study.h"

namespace smcbench::paper {
namespace {

// Explicit runs are continued to this horizon before looking for a cycle (transients of the explicit schemes die
// out slowly: 10 s is not enough at h = 0.1 on S2).
constexpr double kCycleHorizon = 100.0;
// |σ| at or below this counts as on the surface for the input-chattering columns (ChatteringMetrics): far below
// an explicit scheme's O(h) band, far above the rounding an implicit ZOH step leaves.
constexpr double kInputReachTolerance = 1e-9;

// One run of the table.
struct SchemeRun {
  std::string scheme;  // "implicit Euler", "explicit ZOH", "implicit Euler on the closed loop", …
  bool implicit = false;
  double h = 0.0, T = 0.0;
  bool ok = false;  // implicit runs: completed, chattering-free, not a period-2 orbit
  Sliding sliding;
  Cycle cycle;
  Vector x_final;
  double max_residual = 0.0;
  ChatteringMetrics input;
  double t0 = 0.0, step = 0.0;  // the run's own start time and step, for ChatteringJson
};

struct ChatteringStudy {
  std::string implicit_name, explicit_name;
  double T = 0.0;  // the implicit runs' horizon
  std::vector<SchemeRun> implicit_runs, explicit_runs;
  std::vector<SchemeRun> closed_loop_euler;  // ZOH scenes: the Euler discretization, implicit then explicit
  std::vector<FigureRun> figures;
};

SchemeRun Measure(const std::string& scheme, bool implicit, const SimulationSettings& s, const Trajectory& tr) {
  SchemeRun run;
  run.scheme = scheme;
  run.implicit = implicit;
  run.h = s.h;
  run.T = s.T;
  run.sliding = Analyze(tr);
  run.cycle = DetectCycle(tr);
  run.x_final = tr.x_final;
  run.max_residual = tr.max_residual;
  run.input = ComputeChattering(tr, kInputReachTolerance);
  run.t0 = tr.t0;
  run.step = tr.h;
  run.ok = tr.ok() && run.sliding.chattering_free() && run.cycle.period != 2;
  return run;
}

ChatteringStudy MeasureChattering(Studies& st, const std::string& id, const std::string& name,
                                  const std::vector<double>& h_impl, const std::vector<double>& h_expl) {
  ChatteringStudy m;
  const SimulationSettings base = st.Defaults(name);
  const bool zoh = base.method == Method::kZoh;
  m.implicit_name = zoh ? "implicit ZOH" : "implicit Euler";
  m.explicit_name = zoh ? "explicit ZOH" : "explicit Euler";
  m.T = base.T;
  for (const double h : h_impl) {
    SimulationSettings s = base;
    s.h = h;
    const Trajectory tr = st.Run(name, s);
    m.implicit_runs.push_back(Measure(m.implicit_name, true, s, tr));
    if (h == base.h) {
      st.KeepFigure(&m.figures, tr, id + "-" + name + "-implicit-h" + G(h),
                    id + " " + name + ", " + m.implicit_name + ", h = " + G(h));
    }
  }
  for (const double h : h_expl) {
    SimulationSettings s = Studies::Explicit(base);
    s.h = h;
    if (h == h_expl.front()) {
      st.KeepFigure(&m.figures, st.Run(name, s), id + "-" + name + "-explicit-h" + G(h),
                    id + " " + name + ", " + m.explicit_name + ", h = " + G(h));
    }
    s.T = kCycleHorizon;
    m.explicit_runs.push_back(Measure(m.explicit_name, false, s, st.Run(name, s)));
  }
  // ZOH scenes: the Euler discretization of the same closed loop, for comparison (docs/scenes.md S5).
  if (zoh) {
    for (const bool implicit : {true, false}) {
      SimulationSettings s = base;
      s.method = Method::kImplicit;
      if (!implicit) s = Studies::Explicit(s), s.T = kCycleHorizon;
      m.closed_loop_euler.push_back(Measure(std::string(implicit ? "implicit" : "explicit") +
                                                " Euler on the closed loop",
                                            implicit, s, st.Run(name, s)));
    }
  }
  return m;
}

void WriteRow(std::ostream& md, const SchemeRun& r) {
  const Sliding& sl = r.sliding;
  md << "| " << r.scheme << " | " << G(r.h) << " | " << sl.reaching_step << " (" << G(sl.reaching_time) << ") | "
     << G(sl.max_abs_y_after) << " | "
     << (r.implicit ? std::to_string(sl.saturated_switches_after) + " (" + std::to_string(sl.sign_changes_after) + ")"
                    : "- (" + std::to_string(sl.sign_changes_total) + " over the run)")
     << " | "
     << (r.input.has_input && r.input.from_step >= 0 ? G(r.input.u_total_variation) + ", " + G(r.input.u_max_jump)
                                                     : std::string("-"))
     << " | " << CycleText(r.cycle) << " | " << VecText(r.x_final) << " |\n";
}

void WriteChattering(const ChatteringStudy& m, Studies& st, const std::string& id, const std::string& name,
                     bool period_two) {
  auto& md = st.section();
  json& d = st.data()[id];
  md << "Implicit runs over T = " << G(m.T) << "; explicit runs continued to T = " << G(kCycleHorizon)
     << " before looking for a cycle in the last quarter. 'Switches' counts s jumping between the bounds ±1 after "
        "the surface is reached (bang-bang chattering); an interior s that crosses 0 is the equivalent control. "
        "The input chattering (ZOH: the control u applied over each step, docs/smc.md) is measured from the first "
        "time σ reaches 0: total variation of u and its largest jump |u_{k+1} − u_k|.\n\n";
  TableHeader(md, {"scheme", "h", "reaching step (t)", "max abs y after", "switches ±1 after (sign changes)",
                   "input after reaching: total variation, max jump", "cycle at the end", "x_N"});
  bool impl_ok = true;
  std::string impl_text;
  for (const SchemeRun& r : m.implicit_runs) {
    impl_ok = impl_ok && r.ok;
    AppendListItem(&impl_text,
                   "h = " + G(r.h) + ": on the surface from t = " + G(r.sliding.reaching_time) +
                       ", max |y| after " + G(r.sliding.max_abs_y_after) + ", " +
                       std::to_string(r.sliding.saturated_switches_after) + " switches",
                   "; ");
    WriteRow(md, r);
    d["implicit"].push_back({{"h", r.h}, {"ok", r.ok}, {"sliding", SlidingJson(r.sliding)},
                             {"cycle", CycleJson(r.cycle)}, {"x_final", VecJson(r.x_final)},
                             {"max_residual", r.max_residual}, {"chattering", ChatteringJson(r.input, r.t0, r.step)}});
  }
  bool expl_ok = true;
  std::string expl_text;
  for (const SchemeRun& r : m.explicit_runs) {
    expl_ok = expl_ok && (period_two ? r.cycle.period == 2
                                     : (r.cycle.period >= 2 || r.cycle.period == 0) && r.sliding.reaching_step < 0);
    AppendListItem(&expl_text, "h = " + G(r.h) + ": " + CycleText(r.cycle), "; ");
    WriteRow(md, r);
    d["explicit"].push_back({{"h", r.h}, {"T", r.T}, {"sliding", SlidingJson(r.sliding)},
                             {"cycle", CycleJson(r.cycle)}, {"x_final", VecJson(r.x_final)},
                             {"chattering", ChatteringJson(r.input, r.t0, r.step)}});
  }
  for (const SchemeRun& r : m.closed_loop_euler) {
    WriteRow(md, r);
    d[r.implicit ? "euler_implicit" : "euler_explicit"] = {
        {"sliding", SlidingJson(r.sliding)}, {"cycle", CycleJson(r.cycle)}, {"x_final", VecJson(r.x_final)}};
  }
  md << "\n";
  st.Figures(m.figures);
  std::string hs;
  for (const SchemeRun& r : m.implicit_runs) AppendListItem(&hs, G(r.h));
  st.Claim(id + " " + name,
           m.implicit_name + " reaches the sliding surface in finite time and stays on it without chattering at h = " +
               hs,
           impl_text, impl_ok ? kHolds : kFails);
  st.Claim(id + " " + name,
           period_two ? m.explicit_name + " ends on a period-2 orbit around the surface"
                      : m.explicit_name + " chatters (as S5; S5's claim is a period-2 orbit)",
           expl_text + (period_two ? "" : " (never stays on the surface)"), expl_ok ? kHolds : kFails);
}

}  // namespace

void StudyChattering(Studies& st, const std::string& id, const std::string& name, const std::vector<double>& h_impl,
                     const std::vector<double>& h_expl, const std::string& command, bool period_two) {
  st.BeginSection(id + " `" + name + "`: " + st.scene(name).info().description, command);
  const ChatteringStudy m = MeasureChattering(st, id, name, h_impl, h_expl);
  WriteChattering(m, st, id, name, period_two);
}

}  // namespace smcbench::paper

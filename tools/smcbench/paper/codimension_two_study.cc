// S3 `multi-surface` and S4 `filippov`: codimension-2 sliding, implicit against explicit Euler. Each measured into
// a SurfacesStudy, then written. The paper's scenes (and Lemma oups): docs/scenes.md, docs/glossary.md.
#include <ostream>

#include "tools/smcbench/paper/study.h"

namespace smcbench::paper {
namespace {

// The scene's own run, implicit and explicit Euler.
struct SurfacesStudy {
  double h = 0.0, T = 0.0;
  Sliding implicit, explicit_euler;
  Vector x_final, x_final_explicit;
  std::vector<FigureRun> figures;
};

SurfacesStudy MeasureSurfaces(Studies& st, const std::string& id, const std::string& name) {
  SurfacesStudy m;
  const SimulationSettings s = st.Defaults(name);
  m.h = s.h;
  m.T = s.T;
  const Trajectory tr = st.Run(name, s);
  m.implicit = Analyze(tr);
  const Trajectory ex = st.Run(name, Studies::Explicit(s));
  m.explicit_euler = Analyze(ex);
  m.x_final = tr.x_final;
  m.x_final_explicit = ex.x_final;
  st.KeepFigure(&m.figures, tr, id + "-" + name + "-implicit", id + " " + name + ", implicit Euler, h = " + G(m.h));
  st.KeepFigure(&m.figures, ex, id + "-" + name + "-explicit", id + " " + name + ", explicit Euler, h = " + G(m.h));
  return m;
}

json SurfacesJson(const SurfacesStudy& m) {
  return {{"implicit", SlidingJson(m.implicit)}, {"explicit", SlidingJson(m.explicit_euler)},
          {"x_final", VecJson(m.x_final)}, {"x_final_explicit", VecJson(m.x_final_explicit)}};
}

void WriteMultiSurface(const SurfacesStudy& m, Studies& st) {
  const Sliding& sl = m.implicit;
  const std::int64_t r1 = sl.surface_reaching[0], r2 = sl.surface_reaching[1];
  st.section() << "Implicit Euler, h = " << G(m.h) << ": surface 1 (x1 + 2 x2 = 0) reached at step " << r1
               << " (t = " << G(r1 * m.h) << "), surface 2 (2 x1 − x2 = 0) at step " << r2 << " (t = " << G(r2 * m.h)
               << "); sign changes of s after reaching: " << sl.sign_changes_after << "; x_N = " << VecText(m.x_final)
               << ". Explicit Euler: " << m.explicit_euler.sign_changes_total << " sign changes of s, x_N = "
               << VecText(m.x_final_explicit) << ".\n\n";
  st.Figures(m.figures);
  st.data()["S3"] = SurfacesJson(m);
  const bool order = r1 >= 0 && r2 >= 0 && r1 < r2;
  st.Claim("S3 multi-surface", "reaches x1 + 2x2 = 0 first without chattering, slides on it to 2x1 − x2 = 0",
           "surface 1 at t = " + G(r1 * m.h) + ", surface 2 at t = " + G(r2 * m.h) + ", " +
               std::to_string(sl.sign_changes_after) + " sign changes after reaching",
           order && sl.sign_changes_after == 0 ? kHolds : kFails);
  st.Claim("S3 multi-surface", "rests at the origin", "‖x_N‖∞ = " + G(MaxAbs(m.x_final)) + " at T = " + G(m.T),
           MaxAbs(m.x_final) <= 1e-12 ? kHolds : kFails);
}

void WriteFilippov(const SurfacesStudy& m, Studies& st) {
  const Sliding& sl = m.implicit;
  st.section() << "Implicit Euler, h = " << G(m.h) << ": both surfaces (the origin) reached at step "
               << sl.reaching_step << " (t = " << G(sl.reaching_time) << "), " << sl.sign_changes_after
               << " sign changes after, max |y| after " << G(sl.max_abs_y_after) << ", x_N = " << VecText(m.x_final)
               << ". Explicit Euler: " << m.explicit_euler.sign_changes_total << " sign changes of s over the run, x_N = "
               << VecText(m.x_final_explicit) << ".\n\n";
  st.Figures(m.figures);
  st.data()["S4"] = SurfacesJson(m);
  st.Claim("S4 filippov", "reaches the origin without chattering (although Lemma oups' conditions fail)",
           "origin reached at t = " + G(sl.reaching_time) + ", ‖x_N‖∞ = " + G(MaxAbs(m.x_final)) + ", " +
               std::to_string(sl.sign_changes_after) + " sign changes after; explicit: " +
               std::to_string(m.explicit_euler.sign_changes_total) + " sign changes",
           sl.chattering_free() && MaxAbs(m.x_final) <= 1e-9 ? kHolds : kFails);
}

}  // namespace

void StudyCodimensionTwo(Studies& st) {
  st.BeginSection("S3 `multi-surface`: B = C = [[1, 2], [2, −1]]", "smcbench simulate multi-surface --plot s3.png");
  WriteMultiSurface(MeasureSurfaces(st, "S3", "multi-surface"), st);
  st.BeginSection("S4 `filippov`: B = [[1, −2], [2, 1]], C = I", "smcbench simulate filippov --plot s4.png");
  WriteFilippov(MeasureSurfaces(st, "S4", "filippov"), st);
}

}  // namespace smcbench::paper

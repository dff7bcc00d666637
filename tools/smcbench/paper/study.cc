// The shared part of `smcbench paper` (study.h): run context, measures of a run, table formatting.
#include "tools/smcbench/paper/study.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <ostream>

#include "bench/figures/gnuplot_figure.h"
#include "bench/figures/trajectory_plot.h"
#include "problems/scenes/registry.h"
#include "problems/stepper/metrics.h"
#include "solvers/registry/registry.h"

namespace smcbench::paper {

namespace fs = std::filesystem;

VerdictCounts CountVerdicts(const std::vector<PaperClaim>& claims) {
  VerdictCounts counts;
  for (const PaperClaim& c : claims) {
    counts.holds += c.verdict == kHolds;
    counts.partly += c.verdict == kPartly;
    counts.fails += c.verdict == kFails;
    counts.measured += c.verdict == kMeasured;
  }
  return counts;
}

std::string G(double v, int digits) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
  return buffer;
}

std::string VecText(const Eigen::Ref<const Vector>& v, int digits) {
  std::string text = "(";
  for (Eigen::Index i = 0; i < v.size(); ++i) text += (i ? ", " : "") + G(v[i], digits);
  return text + ")";
}

json VecJson(const Eigen::Ref<const Vector>& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

double MaxAbs(const Eigen::Ref<const Vector>& v) { return v.size() ? v.cwiseAbs().maxCoeff() : 0.0; }

void AppendListItem(std::string* list, const std::string& item, const char* separator) {
  if (!list->empty()) *list += separator;
  *list += item;
}

double FittedOrder(const std::vector<double>& hs, const std::vector<double>& errs) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int k = 0;
  for (std::size_t i = 0; i < hs.size(); ++i) {
    if (!(errs[i] > 0.0) || !std::isfinite(errs[i])) continue;
    const double x = std::log(hs[i]), y = std::log(errs[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y, ++k;
  }
  if (k < 2) return std::nan("");
  return (k * sxy - sx * sy) / (k * sxx - sx * sx);
}

double MaxErrorAgainst(const Trajectory& tr, const Trajectory& ref) {
  const std::int64_t stride = std::llround(tr.h / ref.h);
  double err = 0.0;
  for (std::int64_t k = 0; k <= tr.steps_taken && k * stride <= ref.steps_taken; ++k) {
    err = std::max(err, MaxAbs(tr.x.col(k) - ref.x.col(k * stride)));
  }
  return err;
}

Sliding Analyze(const Trajectory& tr) {
  const TrajectoryMetrics m = ComputeMetrics(tr, kReachTol);
  Sliding s;
  s.reaching_step = m.reaching_step;
  if (m.reaching_step >= 0) s.reaching_time = tr.time(m.reaching_step);
  for (const SurfaceMetrics& sm : m.surfaces) {
    s.max_abs_y_after = std::max(s.max_abs_y_after, sm.max_abs_y_after);
    s.sign_changes_after += sm.sign_changes_after;
    s.sign_changes_total += sm.sign_changes_total;
    s.surface_reaching.push_back(sm.reaching_step);
  }
  for (int i = 0; s.reaching_step >= 0 && i < tr.m; ++i) {
    int last = 0;
    for (std::int64_t k = std::max<std::int64_t>(s.reaching_step, 1); k <= tr.steps_taken; ++k) {
      const double v = tr.s(i, k);
      const int bound = v >= 1.0 - 1e-9 ? 1 : (v <= -1.0 + 1e-9 ? -1 : 0);
      if (bound != 0 && last != 0 && bound != last) ++s.saturated_switches_after;
      if (bound != 0) last = bound;
    }
  }
  return s;
}

json SlidingJson(const Sliding& s) {
  return {{"reaching_step", s.reaching_step},
          {"reaching_time", std::isnan(s.reaching_time) ? json(nullptr) : json(s.reaching_time)},
          {"max_abs_y_after_reaching", s.max_abs_y_after},
          {"sign_changes_after_reaching", s.sign_changes_after},
          {"sign_changes_total", s.sign_changes_total},
          {"saturated_switches_after_reaching", s.saturated_switches_after},
          {"surface_reaching_steps", s.surface_reaching}};
}

Cycle DetectCycle(const Trajectory& tr) {
  Cycle c;
  const std::int64_t N = tr.steps_taken;
  c.horizon_steps = N;
  const std::int64_t window = std::max<std::int64_t>(16, N / 4);
  if (!tr.recorded || N < window + 8) return c;
  double scale = 1.0;
  for (std::int64_t k = N - window; k <= N; ++k) scale = std::max(scale, MaxAbs(tr.x.col(k)));
  c.a = tr.x.col(N - 1);
  c.b = tr.x.col(N);
  for (int p = 1; p <= 8; ++p) {
    double drift = 0.0;
    for (std::int64_t k = N - window; k + p <= N; ++k) drift = std::max(drift, MaxAbs(tr.x.col(k + p) - tr.x.col(k)));
    if (p == 2) c.drift = drift;
    if (c.period == 0 && drift <= 1e-9 * scale) c.period = p;
  }
  return c;
}

std::string CycleText(const Cycle& c) {
  if (c.period == 0) return "none within 8 steps (drift of period 2: " + G(c.drift) + ")";
  if (c.period == 1) return "none: converges to a fixed point";
  if (c.period == 2) return "period 2: " + VecText(c.a, 4) + " ↔ " + VecText(c.b, 4);
  return "period " + std::to_string(c.period);
}

json CycleJson(const Cycle& c) {
  return {{"period", c.period}, {"point_a", VecJson(c.a)}, {"point_b", VecJson(c.b)}, {"drift_period2", c.drift},
          {"steps", c.horizon_steps}};
}

bool IsExternal(std::string_view backend) { return IsExternalBackendName(backend); }

void TableHeader(std::ostream& out, std::initializer_list<const char*> columns) {
  out << "|";
  for (const char* c : columns) out << " " << c << " |";
  out << "\n|";
  for (std::size_t i = 0; i < columns.size(); ++i) out << "---|";
  out << "\n";
}

const Scene& Studies::scene(const std::string& name) {
  auto& slot = scenes_[name];
  if (!slot) slot = LoadScene(name);
  return *slot;
}

Solver* Studies::solver(const std::string& name) {
  auto& slot = solvers_[name];
  if (!slot) slot = CreateSolver(name);
  return slot.get();
}

SimulationSettings Studies::Defaults(const std::string& name) {
  SimulationSettings s = scene(name).defaults();
  s.stepper.record = true;
  return s;
}

SimulationSettings Studies::Explicit(SimulationSettings s) {
  s.method = s.method == Method::kZoh ? Method::kZohExplicit : Method::kExplicit;
  if (s.method == Method::kExplicit) s.theta = s.gamma = 0.0;
  return s;
}

Trajectory Studies::Run(const std::string& name, const SimulationSettings& s, const std::string& backend) {
  Solver* so = IsImplicit(s.method) ? solver(backend.empty() ? options_.solver : backend) : nullptr;
  return scene(name).Run(s, so);
}

void Studies::KeepFigure(std::vector<FigureRun>* figures, const Trajectory& tr, const std::string& stem,
                         const std::string& title) const {
  if (options_.plots) figures->push_back({tr, stem, title});
}

void Studies::Figures(const std::vector<FigureRun>& figures) {
  for (const FigureRun& f : figures) Figure(f.run, f.stem, f.title);
}

void Studies::Figure(const Trajectory& tr, const std::string& stem, const std::string& title) {
  if (!options_.plots) return;
  const std::string png = stem + ".png";
  PlotTrajectory(tr, title, (fs::path(options_.out_dir) / png).string());
  figures_ << "![" << title << "](" << png << ")\n\n";
}

void Studies::ConvergenceFigure(const std::string& stem, const std::string& title, const std::vector<double>& hs,
                                const std::vector<std::array<double, 3>>& errs) {
  if (!options_.plots) return;
  const fs::path dat = fs::temp_directory_path() / ("smcbench-paper-" + stem + ".dat");
  {
    std::ofstream out(dat);
    for (std::size_t i = 0; i < hs.size(); ++i) {
      out << G(hs[i], 17) << ' ' << G(errs[i][0], 17) << ' ' << G(errs[i][1], 17) << ' ' << G(errs[i][2], 17)
          << '\n';
    }
  }
  const std::string png = stem + ".png", data = GnuplotQuote(dat.string());
  std::ostringstream g;
  g << GnuplotPngPreamble(900, 650, (fs::path(options_.out_dir) / png).string())
    << "set logscale xy\nset grid\nset key top left\nset xlabel 'h'\nset ylabel 'error of s'\nset title "
    << GnuplotQuote(title) << "\nplot " << data << " using 1:2 with linespoints pt 7 lw 2 title 'L1', " << data
    << " using 1:3 with linespoints pt 5 lw 2 title 'L2', " << data
    << " using 1:4 with linespoints pt 9 lw 2 title 'max', x lw 1 dt 2 title 'slope 1', "
    << "sqrt(x) lw 1 dt 3 title 'slope 1/2'\n";
  RunGnuplot(g.str(), (fs::path(options_.out_dir) / png).string(), "paper");
  std::error_code ec;
  fs::remove(dat, ec);
  figures_ << "![" << title << "](" << png << ")\n\n";
}

void Studies::Claim(const std::string& scene, const std::string& claim, const std::string& measured,
                    const char* verdict) {
  claims_.push_back({scene, claim, measured, verdict});
  log_ << "  [" << verdict << "] " << scene << ": " << claim << "\n";
}

void Studies::BeginSection(const std::string& heading, const std::string& command) {
  FlushFigures();
  section_ << "## " << heading << "\n\n";
  if (!command.empty()) section_ << "Reproduce one run: `" << command << "`\n\n";
  log_ << heading << "\n";
}

void Studies::FlushFigures() {
  section_ << figures_.str();
  figures_.str("");
}

}  // namespace smcbench::paper

#include "tools/smcbench/smc_sweep.h"

#include <CLI/CLI.hpp>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>

#include "bench/figures/gnuplot_figure.h"
#include "problems/scenes/scene.h"
#include "problems/scenes/registry.h"
#include "solvers/core/number_text.h"
#include "solvers/registry/registry.h"
#include "tools/smcbench/output_paths.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;
constexpr const char* kMadeBy = "smc-sweep";
// |σ| within this is "on the surface" for the reaching time (ChatteringMetrics): far below an O(h) band.
constexpr double kReachTolerance = 1e-9;

[[noreturn]] void Fail(const std::string& what) { throw InvalidInputError(std::string(kMadeBy) + ": " + what); }

// Least-squares slope of log y against log h over the points with y > 0 (NaN with fewer than two).
double LogLogSlope(const std::vector<std::pair<double, double>>& points) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int count = 0;
  for (auto [h, y] : points) {
    if (!(y > 0.0)) continue;
    const double lx = std::log(h), ly = std::log(y);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
    ++count;
  }
  if (count < 2) return std::nan("");
  const double denominator = count * sxx - sx * sx;
  return denominator == 0.0 ? std::nan("") : (count * sxy - sx * sy) / denominator;
}

// One curve per method of (h, value) on log-log axes: dir/STEM.{png,svg,dat,gp}.
void PlotAgainstH(const SmcSweepResult& result, const std::string& dir, const std::string& stem,
                  const std::string& ylabel, double ChatteringMetrics::*field) {
  std::ostringstream data, body;
  body << "set logscale xy\nset grid\nset key top left\nset xlabel 'h'\nset ylabel " << GnuplotQuote(ylabel)
       << "\nset title " << GnuplotQuote(result.scene + ": " + ylabel + " against h") << "\nplot ";
  int index = 0;
  for (const char* method : {"zoh", "zoh-explicit"}) {
    data << "# " << method << ": h " << ylabel << "\n";
    for (const SmcSweepRow& row : result.rows) {
      if (row.method == method) data << NumberText(row.h) << ' ' << NumberText(row.chattering.*field) << '\n';
    }
    data << "\n\n";
    body << (index ? ", " : "") << GnuplotQuote(stem + ".dat") << " index " << index
         << " using 1:2 with linespoints lw 2 " << (index ? "dt 2 pt 6" : "dt 1 pt 7") << " title "
         << GnuplotQuote(std::string(method) + (index ? " (explicit)" : " (implicit)"));
    ++index;
  }
  body << "\n";
  WriteGnuplotFigure(dir, stem, data.str(), body.str(), 900, 550, kMadeBy);
}

std::string Markdown(const SmcSweepResult& r, const SmcSweepOptions& options, bool figures) {
  std::ostringstream md;
  md << "# σ band and input chattering against h: " << r.scene << "\n\n"
     << "Made by `smcbench smc-sweep " << options.scene << " --h ";
  for (std::size_t i = 0; i < options.steps.size(); ++i) md << (i ? "," : "") << NumberText(options.steps[i]);
  md << "`. Keys as in docs/smc.md (`chattering` of `simulate --summary`): from the first time σ reaches 0, the "
        "band max |σ|, the input's total variation and largest jump, sign changes of the switching part.\n\n"
     << "| method | h | reached at t | σ band | u total variation | max abs Δu | sign changes | completed |\n"
     << "|---|---:|---:|---:|---:|---:|---:|---|\n";
  for (const SmcSweepRow& row : r.rows) {
    const ChatteringMetrics& c = row.chattering;
    md << "| " << row.method << " | " << NumberText(row.h) << " | "
       << (c.from_step >= 0 ? NumberText(static_cast<double>(c.from_step) * row.h) : std::string("never")) << " | "
       << NumberText(c.sigma_band) << " | " << NumberText(c.u_total_variation) << " | " << NumberText(c.u_max_jump)
       << " | " << c.switching_sign_changes << " | " << (row.completed ? "yes" : "no") << " |\n";
  }
  const auto order = [](double v) { return std::isnan(v) ? std::string("-") : NumberText(std::round(v * 100) / 100); };
  md << "\nFitted orders in h (least-squares slope of log value against log h): σ band implicit "
     << order(r.band_order_implicit) << ", explicit " << order(r.band_order_explicit)
     << "; u total variation implicit " << order(r.variation_order_implicit) << ", explicit "
     << order(r.variation_order_explicit) << ".\n\n";
  if (figures) {
    for (const char* stem : {"sigma-band", "input-variation"}) {
      md << "![" << stem << "](" << stem << ".png)\n\n([SVG](" << stem << ".svg), [data](" << stem
         << ".dat), [gnuplot script](" << stem << ".gp))\n\n";
    }
  }
  return md.str();
}

}  // namespace

SmcSweepResult RunSmcSweep(const SmcSweepOptions& input) {
  SmcSweepOptions options = input;
  if (!options.out_dir.empty()) CheckOutputFolder("--out", options.out_dir);  // before any run
  if (options.steps.empty()) options.steps = kDefaultSweepSteps;
  for (double h : options.steps) {
    if (!(h > 0.0) || !std::isfinite(h)) Fail("--h: every step must be a finite number > 0, got " + NumberText(h));
  }
  if (!(options.horizon >= 0.0) || !std::isfinite(options.horizon)) {
    Fail("--T must be a finite number >= 0, got " + NumberText(options.horizon));
  }
  if (options.plots && !options.out_dir.empty() && !GnuplotAvailable()) {
    Fail("the figures need gnuplot (Debian package gnuplot-nox), which is not on PATH; --no-plots writes the table only");
  }
  const std::unique_ptr<Scene> scene = LoadScene(options.scene);
  const LinearPlant* linear = scene->linear_plant();
  if (!linear || linear->system_type() != "zoh") {
    Fail("scene '" + scene->info().name + "' is not a ZOH plant (system type zoh): the sweep compares zoh and "
         "zoh-explicit");
  }
  std::unique_ptr<Solver> solver = CreateSolver(options.solver);
  SmcSweepResult result;
  result.scene = scene->info().name;
  for (Method method : {Method::kZoh, Method::kZohExplicit}) {
    for (double h : options.steps) {
      SimulationSettings s = scene->defaults();
      s.method = method;
      s.h = h;
      if (options.horizon > 0.0) s.T = options.horizon;
      s.stepper.record = false;
      ChatteringAccumulator chattering(scene->info().m, kReachTolerance);
      s.stepper.sink = &chattering;
      Trajectory tr;
      scene->Run(s, method == Method::kZoh ? solver.get() : nullptr, &tr);
      result.rows.push_back({std::string(ToString(method)), h, chattering.Result(), tr.ok()});
    }
  }
  const auto points = [&](const char* method, double ChatteringMetrics::*field) {
    std::vector<std::pair<double, double>> p;
    for (const SmcSweepRow& row : result.rows) {
      if (row.method == method && row.chattering.from_step >= 0) p.push_back({row.h, row.chattering.*field});
    }
    return p;
  };
  result.band_order_implicit = LogLogSlope(points("zoh", &ChatteringMetrics::sigma_band));
  result.band_order_explicit = LogLogSlope(points("zoh-explicit", &ChatteringMetrics::sigma_band));
  result.variation_order_implicit = LogLogSlope(points("zoh", &ChatteringMetrics::u_total_variation));
  result.variation_order_explicit = LogLogSlope(points("zoh-explicit", &ChatteringMetrics::u_total_variation));
  const bool figures = options.plots && !options.out_dir.empty();
  result.markdown = Markdown(result, options, figures);
  if (!options.out_dir.empty()) {
    std::error_code ec;
    fs::create_directories(options.out_dir, ec);
    if (ec) Fail("--out: cannot create '" + options.out_dir + "': " + ec.message());
    if (figures) {
      PlotAgainstH(result, options.out_dir, "sigma-band", "sigma band", &ChatteringMetrics::sigma_band);
      PlotAgainstH(result, options.out_dir, "input-variation", "u total variation",
                   &ChatteringMetrics::u_total_variation);
    }
    std::ofstream md(fs::path(options.out_dir) / "smc-sweep.md");
    md << result.markdown;
    if (!md) Fail("--out: cannot write '" + (fs::path(options.out_dir) / "smc-sweep.md").string() + "'");
  }
  return result;
}

// ------------------------------------------------------------------------------------------------------------

SmcSweepCommand::SmcSweepCommand(CLI::App* app)
    : options_(std::make_unique<SmcSweepOptions>()), steps_text_(std::make_unique<std::string>()) {
  command_ = app->add_subcommand("smc-sweep",
                                 "ZOH scene: sigma band and input chattering against h, implicit (zoh) vs explicit "
                                 "(zoh-explicit), table + figures (docs/smc.md)");
  command_->add_option("SCENE", options_->scene, "registered name or scene file of system type zoh")->required();
  command_->add_option("--h", *steps_text_, "comma-separated time steps (default 0.02,0.01,0.005,0.0025,0.00125)");
  command_->add_option("--T", options_->horizon, "horizon (default: the scene's)");
  command_->add_option("--solver", options_->solver, "backend of the implicit runs (default auto)");
  command_->add_option("--out", options_->out_dir, "folder for smc-sweep.md and the figures (created)");
  command_->add_flag("--no-plots", no_plots_, "the table only (no gnuplot needed)");
}

SmcSweepCommand::~SmcSweepCommand() = default;

bool SmcSweepCommand::parsed() const { return command_->parsed(); }

int SmcSweepCommand::Run(std::ostream& out, std::ostream& err) const {
  (void)err;
  SmcSweepOptions options = *options_;
  options.plots = !no_plots_;
  if (!steps_text_->empty()) {
    std::stringstream ss(*steps_text_);
    for (std::string item; std::getline(ss, item, ',');) {
      double value = 0.0;
      const auto parsed = std::from_chars(item.data(), item.data() + item.size(), value);
      if (item.empty() || parsed.ec != std::errc() || parsed.ptr != item.data() + item.size()) {
        Fail("--h: '" + item + "' is not a number (expected h1,h2,...)");
      }
      options.steps.push_back(value);
    }
  }
  const SmcSweepResult result = RunSmcSweep(options);
  out << result.markdown;
  if (!options.out_dir.empty()) out << "wrote " << (fs::path(options.out_dir) / "smc-sweep.md").string() << "\n";
  return 0;
}

}  // namespace smcbench

// `smcbench smc-sweep`: the study a control engineer asks of an SMC implementation — for one ZOH scene,
// the steady-state band of σ and the input's total variation against h, implicit (`zoh`) against explicit
// (`zoh-explicit`), as a markdown table with the fitted orders in h and two log-log figures (PNG + SVG, each beside
// its data and gnuplot script). A subcommand rather than a `paper` study: it takes any ZOH scene file and its own
// list of h, runs in well under a second, and is not one of the paper's claims.
#pragma once

#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "problems/stepper/metrics.h"

namespace CLI {
class App;
}

namespace smcbench {

struct SmcSweepOptions {
  std::string scene;                 // registered name or scene file of system type zoh
  std::vector<double> steps;         // h values, each > 0; empty: kDefaultSweepSteps
  double horizon = 0.0;              // T; 0: the scene's
  std::string solver = "auto";       // backend of the implicit runs
  std::string out_dir;               // where smc-sweep.md and the figures go (created); empty: no files
  bool plots = true;                 // the figures (needs gnuplot)
};

inline const std::vector<double> kDefaultSweepSteps = {0.02, 0.01, 0.005, 0.0025, 0.00125};

struct SmcSweepRow {
  std::string method;  // "zoh" or "zoh-explicit"
  double h = 0.0;
  ChatteringMetrics chattering;
  bool completed = false;
};

struct SmcSweepResult {
  std::string scene;
  std::vector<SmcSweepRow> rows;  // per method, h in the given order
  // Least-squares slopes of log(σ band) and log(u total variation) against log h, per method (NaN: < 2 points).
  double band_order_implicit = 0.0, band_order_explicit = 0.0;
  double variation_order_implicit = 0.0, variation_order_explicit = 0.0;
  std::string markdown;
};

// Runs the sweep; writes out_dir/smc-sweep.md and, with plots, the figures sigma-band.* and input-variation.*.
// InvalidInputError naming the option: unknown scene, a scene that is not of type zoh, h ≤ 0, T < 0, unknown
// backend, gnuplot missing with plots on.
SmcSweepResult RunSmcSweep(const SmcSweepOptions& options);

class SmcSweepCommand {
 public:
  explicit SmcSweepCommand(CLI::App* app);
  ~SmcSweepCommand();
  bool parsed() const;
  int Run(std::ostream& out, std::ostream& err) const;

 private:
  CLI::App* command_;
  std::unique_ptr<SmcSweepOptions> options_;
  std::unique_ptr<std::string> steps_text_;
  bool no_plots_ = false;
};

}  // namespace smcbench

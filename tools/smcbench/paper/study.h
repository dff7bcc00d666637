// What the studies of `smcbench paper` share: the run context (scenes, backends, the report being built), the
// measures every study takes of a run (sliding, cycles, fitted orders) and the number formatting of the tables.
// Each study (one file per scene group, paper/*_study.cc) measures first into a plain struct, then writes its
// markdown, JSON and claim rows from that struct alone.
// The paper's labels cited here (eq:..., Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <iosfwd>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "problems/scenes/scene.h"
#include "problems/stepper/trajectory.h"
#include "solvers/core/solver.h"
#include "tools/smcbench/paper.h"

namespace smcbench::paper {

using json = nlohmann::json;

// |y| at or below this counts as "on the surface" (10× the backends' tolerance on the one-step residual).
inline constexpr double kReachTol = 1e-9;

inline constexpr const char* kHolds = "holds";
inline constexpr const char* kPartly = "partly";
inline constexpr const char* kFails = "does not hold";
inline constexpr const char* kMeasured = "measured";

// How many claim rows got each verdict (the summary line of the report and of the command).
struct VerdictCounts {
  int holds = 0, partly = 0, fails = 0, measured = 0;
};
VerdictCounts CountVerdicts(const std::vector<PaperClaim>& claims);

// Short numbers for the tables: 3 significant digits by default; "NaN", "inf", "-inf" for the others.
std::string G(double v, int digits = 3);
// "(a, b, c)" with G.
std::string VecText(const Eigen::Ref<const Vector>& v, int digits = 3);
json VecJson(const Eigen::Ref<const Vector>& v);
// ‖v‖∞, 0 for an empty vector.
double MaxAbs(const Eigen::Ref<const Vector>& v);
// "a, b, c" from the items (appends ", " before each but the first).
void AppendListItem(std::string* list, const std::string& item, const char* separator = ", ");

// Least-squares slope of log(err) against log(h) over the points with 0 < err < ∞ (NaN if fewer than two).
double FittedOrder(const std::vector<double>& hs, const std::vector<double>& errs);

// max_k ‖x_k − x_ref(t_k)‖∞ against a recorded reference run whose step divides tr's.
double MaxErrorAgainst(const Trajectory& tr, const Trajectory& ref);

// Sliding behaviour of a recorded run, on every surface at once.
struct Sliding {
  std::int64_t reaching_step = -1;  // all surfaces
  double reaching_time = std::nan("");
  double max_abs_y_after = 0.0;
  std::int64_t sign_changes_after = 0;
  std::int64_t sign_changes_total = 0;
  std::vector<std::int64_t> surface_reaching;  // per surface
  // Switches of s between the bounds (+1 ↔ −1, |s| ≥ 1 − 1e-9 on both sides) after reaching: bang-bang chattering.
  // An interior s that changes sign smoothly (S7's u = α sin t) is the equivalent control, not chattering.
  std::int64_t saturated_switches_after = 0;
  bool chattering_free() const { return reaching_step >= 0 && saturated_switches_after == 0; }
};
Sliding Analyze(const Trajectory& tr);
json SlidingJson(const Sliding& s);

// A cycle at the end of a run: the smallest p ≤ 8 with x_{k+p} = x_k (to 1e-9 relative) over the last quarter
// of the run (≥ 16 steps). p = 1 is a fixed point (the implicit schemes' rest state), p = 2 the report's orbit.
struct Cycle {
  int period = 0;      // 0: none found
  Vector a, b;         // x_{N−1}, x_N (the two points when period = 2)
  double drift = 0.0;  // max over the window of ‖x_{k+2} − x_k‖∞ (how far from period 2)
  std::int64_t horizon_steps = 0;
};
Cycle DetectCycle(const Trajectory& tr);
std::string CycleText(const Cycle& c);
json CycleJson(const Cycle& c);

// The paper's claims are about the schemes: they are judged on smcbench's own backends; external adapters
// (siconos-*) appear in the tables where every backend is listed, and are compared in the benchmarks.
bool IsExternal(std::string_view backend);

// Markdown table header: "| a | b |\n|---|---|\n".
void TableHeader(std::ostream& out, std::initializer_list<const char*> columns);

// A run kept for a figure: drawn when the study writes (measuring draws nothing). Kept only when plots are on.
struct FigureRun {
  Trajectory run;
  std::string stem;   // file name without .png
  std::string title;
};

// Everything the studies share: the scenes, the backends, the figure writer and the report being built.
class Studies {
 public:
  Studies(const PaperOptions& options, std::ostream& log) : options_(options), log_(log) {}

  const Scene& scene(const std::string& name);
  Solver* solver(const std::string& name);

  // The scene's own settings (recording, stop at the first failure).
  SimulationSettings Defaults(const std::string& name);
  // Classical explicit Euler (θ = γ = 0, s_{k+1} = sgn(y_k)) or explicit ZOH.
  static SimulationSettings Explicit(SimulationSettings s);

  // One run of a scene; implicit steps by `backend` (empty: the --solver one).
  Trajectory Run(const std::string& name, const SimulationSettings& s, const std::string& backend = "");

  // Keeps a run for a figure in *figures (nothing when plots are off).
  void KeepFigure(std::vector<FigureRun>* figures, const Trajectory& tr, const std::string& stem,
                  const std::string& title) const;
  // Draws the kept figures (PNG) and adds their image lines to the current section (after its tables).
  void Figures(const std::vector<FigureRun>& figures);
  // A log-log figure of error norms against h (the S1 convergence study).
  void ConvergenceFigure(const std::string& stem, const std::string& title, const std::vector<double>& hs,
                         const std::vector<std::array<double, 3>>& errs);

  void Claim(const std::string& scene, const std::string& claim, const std::string& measured, const char* verdict);
  // Ends the current section with its figures (kept out of its tables) and starts the next.
  void BeginSection(const std::string& heading, const std::string& command);
  std::ostringstream& section() { return section_; }
  void FlushFigures();
  json& data() { return data_; }
  const std::vector<PaperClaim>& claims() const { return claims_; }
  const PaperOptions& options() const { return options_; }

 private:
  // A figure of a run: PNG plus a markdown image line.
  void Figure(const Trajectory& tr, const std::string& stem, const std::string& title);

  const PaperOptions& options_;
  std::ostream& log_;
  std::map<std::string, std::unique_ptr<Scene>> scenes_;
  std::map<std::string, std::unique_ptr<Solver>> solvers_;
  std::vector<PaperClaim> claims_;
  std::ostringstream section_, figures_;
  json data_ = json::object();
};

// The studies, in the order of the report (each: one section, its claim rows, its key of paper.json).
void StudySign(Studies& st);  // S1
// S2, S5, S6. period_two: the claim is a period-2 orbit (S2, S5); otherwise "the explicit scheme chatters" (S6).
void StudyChattering(Studies& st, const std::string& id, const std::string& name, const std::vector<double>& h_impl,
                     const std::vector<double>& h_expl, const std::string& command, bool period_two = true);
void StudyCodimensionTwo(Studies& st);  // S3, S4
void StudyLyapunov(Studies& st);        // S7
void StudyObserver(Studies& st);        // S8
void StudyNonlinear(Studies& st);       // S9, S10
void StudyParasitic(Studies& st);       // S11

}  // namespace smcbench::paper

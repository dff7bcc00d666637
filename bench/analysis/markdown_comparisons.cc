// Ours against the generic sparse path, Siconos and each library's best; the tolerance ladder and the speed against
// error; the scale table (markdown_sections.h).
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "bench/analysis/class_tables.h"
#include "bench/analysis/markdown_cells.h"
#include "bench/analysis/markdown_sections.h"
#include "bench/analysis/peer_tables.h"
#include "bench/analysis/record_facts.h"
#include "bench/analysis/report_figures.h"
#include "bench/analysis/suite_tables.h"
#include "bench/analysis/sweep_tables.h"

#include "bench/replay/floor.h"

namespace smcbench::markdown {

void WriteSparsePathComparison(std::ostream& md, const SparsePathComparison& c) {
  if (c.speedups.empty()) return;
  const auto& ratios = c.speedups;
  const auto& floors = c.over_floor;
  md << "Fastest correct backend on each problem against the generic sparse path (the same problems with M stored "
        "sparse, solved by `newton` with its UMFPACK sparse LU forced, `newton.linear_solver=sparse`): speed-up median "
     << G(ratios[ratios.size() / 2]) << "×, min " << G(ratios.front()) << "×, max " << G(ratios.back())
     << "× over " << ratios.size() << " problems (goal ≥ 10×). Distance from the arithmetic alone (m³/3 + 4m² "
        "flops at 1 flop/ns): the fastest solve takes median "
     << G(floors[floors.size() / 2]) << "× that floor — the rest is the fixed cost of a call (option checks, "
        "cold start, the merit function).\n\n";
}

void WriteRatioTable(std::ostream& md, const std::map<int, std::vector<double>>& ratios) {
  md << "| m | problems | median ratio | min | max |\n|---|---|---|---|---|\n";
  for (const auto& [m, r] : ratios) {
    md << "| " << m << " | " << r.size() << " | " << G(r[r.size() / 2]) << "× | " << G(r.front()) << "× | "
       << G(r.back()) << "× |\n";
  }
  md << "\n";
}

// The headline compares in-process times only; the through-worker ones get a labelled footnote.
void WriteSiconosComparison(std::ostream& md, const SiconosComparison& c) {
  if (!c.in_process.empty()) {
    md << "Our best backend against Siconos' best (`siconos-*`; on each problem the fastest correct answer of each "
          "side), both timed in process: each problem's first Siconos solve, untimed, is the probe in the backend's "
          "isolation worker (a crash or hang there is a status); once it came back, the timed solves call Siconos directly (`isolate=first`, see "
          "`solvers/siconos/README.md`). On the problems both solve — Siconos time / our time:\n\n";
    WriteRatioTable(md, c.in_process);
  }
  if (!c.through_worker.empty()) {
    md << (c.in_process.empty() ? "" : "Footnote: ")
       << "Siconos records timed through the isolation worker (≈ 7 µs of inter-process communication per solve "
          "included: `isolate=always`, a problem whose probe crashed or timed out, or results from before the "
          "probe policy) — IPC-inclusive Siconos time / our time, not a comparison of the solvers:\n\n";
    WriteRatioTable(md, c.through_worker);
  }
}

// The tolerance ladder: success per backend at each tolerance of the sweep (BuildToleranceLadder).
void WriteToleranceLadder(std::ostream& md, const SuiteResults& suite) {
  const ToleranceLadder ladder = BuildToleranceLadder(suite);
  if (ladder.rows.empty()) return;
  std::set<std::string> problems;
  for (const auto& r : suite.replay.sweep) problems.insert(InstanceOf(r));
  md << "**Tolerance ladder**: success (solved + correctly refused) per backend and tolerance on the "
     << problems.size() << " swept problems (`bench` sweeps 16 per suite spread evenly over it, 2 with `--quick`). "
        "Each rung is its own solve at that tolerance — an untimed warm-up, then at most 3 timed samples — judged at "
        "that tolerance; the times are in the folded table below. With the polish on (the default) an answer with "
        "the right active set is exact at every rung (`--no-polish` shows the algorithms' own trade-off). Blank: "
        "not run (`--backend-budget` spent).\n\n| backend | ";
  for (double t : ladder.tolerances) md << "tol " << G(t) << " | ";
  md << "\n|---|";
  for (std::size_t i = 0; i < ladder.tolerances.size(); ++i) md << "---|";
  md << "\n";
  for (const auto& row : ladder.rows) {
    md << "| " << row.solver << " | ";
    for (std::size_t k = 0; k < ladder.tolerances.size(); ++k) md << Fraction(row.correct[k], row.problems[k]) << " | ";
    md << "\n";
  }
  md << "\n";
}

// Speed against error: the tolerance sweep. Two errors: the forward error ‖z − z*‖∞ (what a user reads, on the
// swept problems with a unique certified reference) and the residual reached (every swept problem).
void WriteToleranceSweep(std::ostream& md, const SuiteResults& suite, const std::string& dir, bool plots) {
  if (suite.replay.sweep.empty()) return;
  md << "<details><summary>Speed against error, per backend and tolerance (medians over the swept problems; "
        "forward error over those with a unique certified reference)</summary>\n\n"
     << "| backend | tolerance | forward error (median) | with z* | achieved residual (median) | achieved "
        "residual, eq. (median) | time (median) | solved |\n|---|---|---|---|---|---|---|---|\n";
  std::map<std::string, std::vector<std::pair<double, double>>> by_forward, by_residual;
  for (const SweepRow& row : SweepRows(suite)) {
    md << "| " << row.solver << " | " << G(row.tolerance) << " | " << G(row.forward_error) << " | "
       << row.with_reference << "/" << row.problems << " | " << G(row.residual) << " | " << G(row.residual_scaled)
       << " | " << Seconds(row.time) << " | " << row.solved << "/" << row.problems << " |\n";
    by_residual[row.solver].emplace_back(std::max(row.residual, 1e-17), row.time);
    // Time over the same problems as the error: the median time of those with a reference.
    if (row.with_reference > 0) {
      by_forward[row.solver].emplace_back(std::max(row.forward_error, 1e-17), row.time_with_reference);
    }
  }
  md << "\n</details>\n\n";
  if (plots && !by_forward.empty()) {
    const std::string stem = "speed-forward-error-" + Safe(suite.suite);
    PlotCurves(by_forward, dir, stem, "forward error |z - z*|inf (median; problems with a unique certified z*)",
               "time per solve [s]", "Speed against forward error, suite " + suite.suite);
    md << FigureMarkdown("speed against forward error, " + suite.suite, stem);
  }
  if (plots) {
    const std::string stem = "speed-residual-" + Safe(suite.suite);
    PlotCurves(by_residual, dir, stem, "achieved relative natural residual (median)", "time per solve [s]",
               "Speed against residual, suite " + suite.suite);
    md << FigureMarkdown("speed against residual, " + suite.suite, stem);
  }
}

// The growth exponent of the floor's times in m (GrowthExponent of the floor records as one backend's).
double FloorGrowthExponent(const SuiteResults& suite) {
  SuiteResults floor;
  floor.replay.records = suite.replay.floor;
  return GrowthExponent(floor, kFloorSolver);
}

// Scale: time against m with the fitted exponent (the scale suite, when it has at least three sizes).
void WriteScaleTable(std::ostream& md, const SuiteResults& suite) {
  std::set<int> sizes;
  for (const auto& r : suite.replay.records) sizes.insert(r.size);
  if (sizes.size() < 3 || suite.suite != "scale") return;
  md << "| backend | fitted exponent of time in m | ";
  for (int m : sizes) md << "m = " << m << " | ";
  md << "\n|---|---|";
  for (std::size_t i = 0; i < sizes.size(); ++i) md << "---|";
  md << "\n";
  for (const std::string& solver : SolversIn(suite.replay.records)) {
    md << "| " << solver << " | " << G(GrowthExponent(suite, solver)) << " | ";
    for (int m : sizes) {
      std::string cell = "–";
      for (const auto& r : suite.replay.records) {
        if (r.solver == solver && r.size == m) {
          cell = r.verdict == Verdict::kSolved ? Seconds(r.time_median) : std::string(ToString(r.status));
        }
      }
      md << cell << " | ";
    }
    md << "\n";
  }
  if (!suite.replay.floor.empty()) {  // not a backend: the time of one factorization, for comparison
    md << "| *floor: one factorization* | " << G(FloorGrowthExponent(suite)) << " | ";
    for (int m : sizes) {
      std::vector<double> t;
      for (const auto& r : suite.replay.floor) {
        if (r.size == m && r.samples > 0) t.push_back(r.time_median);
      }
      std::sort(t.begin(), t.end());
      md << (t.empty() ? std::string("–") : Seconds(MedianOfSorted(t))) << " | ";
    }
    md << "\n";
  }
  md << "\n";
}

// The cold peer table again per class × band (OursAgainstPeersPerClass), with our best over the floor.
void WritePeerRatiosPerClass(std::ostream& md, const SuiteResults& suite, const std::set<std::string>& families) {
  const std::vector<PeerClassRow> rows = OursAgainstPeersPerClass(suite);
  if (rows.empty()) return;
  const bool floor = !suite.replay.floor.empty();
  md << "**The same per class** (matrix class and bounds from the problems' tags × size band, cold): library's best "
        "/ ours as above"
     << (floor ? "; *ours / floor*: our fastest correct time over one factorization of M, median [min – max] (n)"
               : "; floor not measured in this run")
     << ".\n\n| class | size band |";
  for (const std::string& f : families) md << " " << f << " |";
  if (floor) md << " ours / floor |";
  md << "\n|---|---|";
  for (std::size_t i = 0; i < families.size() + (floor ? 1 : 0); ++i) md << "---|";
  md << "\n";
  for (const PeerClassRow& row : rows) {
    if (row.by_peer.empty()) continue;  // no library solved a problem of the class that we solved too
    md << "| " << ClassName(row.problem_class) << " | " << ToString(row.problem_class.band) << " |";
    for (const std::string& f : families) {
      const auto it = row.by_peer.find(f);
      md << " " << (it == row.by_peer.end() ? std::string() : RatioSpread(it->second)) << " |";
    }
    if (floor) md << " " << RatioSpread(row.ours_over_floor) << " |";
    md << "\n";
  }
  md << "\n";
}

// Ours against the best of each external library per band, cold and warm (OursAgainstPeersPerBand).
void WritePeerRatios(std::ostream& md, const SuiteResults& suite) {
  const std::vector<PeerRatioRow> rows = OursAgainstPeersPerBand(suite);
  if (rows.empty()) return;
  std::set<std::string> families;
  for (const PeerRatioRow& row : rows) {
    for (const auto& [family, ratios] : row.by_peer) families.insert(family);
  }
  md << "**Ours against each library's best, per size band, cold and warm**: on each problem (warm: each "
        "sequence, time per step) the fastest correct answer of our backends and of each library's (`siconos-*`, "
        "`bullet-*`, `dart-*`); the library's time / ours, median [min – max] over the problems both solve (n). "
        "Above 1×: ours is faster.\n\n| size band | track |";
  for (const std::string& f : families) md << " " << f << " |";
  md << "\n|---|---|";
  for (std::size_t i = 0; i < families.size(); ++i) md << "---|";
  md << "\n";
  for (const PeerRatioRow& row : rows) {
    md << "| " << ToString(row.band) << " | " << (row.warm ? "warm" : "cold") << " |";
    for (const std::string& f : families) {
      const auto it = row.by_peer.find(f);
      if (it == row.by_peer.end()) {
        md << " |";
        continue;
      }
      const std::vector<double>& r = it->second;
      md << " " << G(r[r.size() / 2]) << "× [" << G(r.front()) << " – " << G(r.back()) << "] (" << r.size() << ") |";
    }
    md << "\n";
  }
  md << "\n";
  WritePeerRatiosPerClass(md, suite, families);
}

}  // namespace smcbench::markdown

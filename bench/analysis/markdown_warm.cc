// Per size band again, the warm track of a suite, and the time-stepper's warm/cold table and work-precision figures
// (markdown_sections.h).
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
#include <cstdint>

#include "bench/replay/warm_track.h"

namespace smcbench::markdown {

// The bands a suite's records fall in, smallest first.
std::vector<SizeBand> BandsOf(const std::vector<ReplayRecord>& records) {
  std::set<SizeBand> bands;
  for (const ReplayRecord& r : records) bands.insert(SizeBandOf(r.size));
  return {bands.begin(), bands.end()};
}

// Every backend table and profile again per size band (one table and one figure per band), when the suite spans
// more than one band: rankings flip with size.
void WritePerBand(std::ostream& md, const SuiteResults& suite, const std::string& dir, bool plots,
                  const std::string& what) {
  const std::vector<SizeBand> bands = BandsOf(suite.replay.records);
  if (bands.size() < 2) {
    if (bands.size() == 1) md << "Every " << what << " record is in the band " << ToString(bands[0]) << ".\n\n";
    return;
  }
  md << "**Per size band (" << what << ")**: the table above again, one band at a time (penalties from the band's "
        "problems alone)" << (plots ? ", with its performance profile" : "") << ".\n\n";
  for (SizeBand band : bands) {
    const SuiteResults slice = SizeBandSlice(suite, band);
    md << "*" << what << ", " << ToString(band) << "* (" << slice.problems << " problems):\n\n";
    WriteBackendTableOnly(md, slice);
    if (plots) WritePerformanceProfile(md, slice, dir, /*explain=*/false);
  }
}

// The warm track of a suite: per backend over its sequences (time per step), the winners per band, the profile, per
// band again, and per sequence its counts.
void WriteWarmTrack(std::ostream& md, const SuiteResults& suite, const std::string& dir, bool plots) {
  if (suite.warm.empty()) return;
  const SuiteResults warm = WarmTrackAsSuite(suite);
  md << "### Warm track of suite `" << suite.suite << "`\n\n"
     << warm.problems << " sequences of one-step problems (M, l, u fixed, q moving) replayed in order, every step "
        "started from the previous step's answer by each backend's own warm mechanism: ours through one solve "
        "session whose reused active set answers when it still fits; `siconos-*`, `bullet-*` and `dart-*` through "
        "the same adapter instance kept alive (Siconos' direct solvers keep their cache) with the previous answer "
        "as start. Time = seconds per step, the median over repeats of the whole sequence (its set-up included). "
        "A sequence counts as solved only when every step is solved by the verdict of the cold records.\n\n";
  WriteBackendTableOnly(md, warm);
  WriteBandWinners(md, warm);
  if (plots) WritePerformanceProfile(md, warm, dir, /*explain=*/false);
  WritePerBand(md, warm, dir, plots, "warm");
  // Per sequence: the counts, and its fastest correct backend.
  std::map<std::string, std::vector<const WarmRecord*>> by_sequence;
  for (const WarmRecord& w : suite.warm) by_sequence[w.record.problem].push_back(&w);
  md << "Per sequence: steps, active-set changes between consecutive steps (of the fastest correct backend's "
        "answers), its pivots or iterations over the sequence, and our fastest backend's reused-set steps and "
        "fallbacks (steps where the previous active set did not answer and the backend ran).\n\n"
        "| sequence | source | m | steps | active-set changes | fastest correct | time per step | its iterations | "
        "ours fastest | reused / fallbacks | correct backends |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& [sequence, records] : by_sequence) {
    const WarmRecord* best = nullptr;
    const WarmRecord* ours = nullptr;
    int correct = 0;
    for (const WarmRecord* w : records) {
      if (w->record.verdict != Verdict::kSolved) continue;
      ++correct;
      if (!best || w->record.time_median < best->record.time_median) best = w;
      if (w->counts.reuse && (!ours || w->record.time_median < ours->record.time_median)) ours = w;
    }
    const WarmRecord& head = *records.front();
    md << "| " << sequence << " | " << ToString(head.source) << " | " << head.record.size << " | "
       << head.counts.steps << " | " << (best ? std::to_string(best->counts.active_set_changes) : "") << " | "
       << (best ? best->record.solver : "none") << " | " << (best ? Seconds(best->record.time_median) : "") << " | "
       << (best ? std::to_string(best->counts.iterations) : "") << " | " << (ours ? ours->record.solver : "")
       << " | "
       << (ours ? std::to_string(ours->counts.reused_steps) + " / " + std::to_string(ours->counts.fallbacks) : "")
       << " | " << correct << "/" << records.size() << " |\n";
  }
  md << "\n";
}

// The time-stepper: warm against cold starts, per scene and backend (records come in warm, cold pairs).
void WriteWarmStart(std::ostream& md, const StepperStudy& st) {
  md << "## Time-stepper: warm against cold starts\n\n"
     << "Each scene's own run (docs/scenes.md settings), every step's one-step problem started from the previous s "
        "(warm) or from Π(0) (cold).\n\n| scene | backend | warm: time/step | cold: time/step | cold/warm | "
        "iterations/step warm | cold |\n|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i + 1 < st.warm_start.size(); i += 2) {
    const auto& w = st.warm_start[i];
    const auto& c = st.warm_start[i + 1];
    md << "| " << w.scene << " | " << w.solver << (w.ok && c.ok ? "" : " (failed steps)") << " | "
       << Seconds(w.seconds_per_step) << " | " << Seconds(c.seconds_per_step) << " | "
       << G(c.seconds_per_step / w.seconds_per_step) << " | " << G(w.iterations_per_step) << " | "
       << G(c.iterations_per_step) << " |\n";
  }
}

using WorkPrecisionLines = std::map<std::string, std::vector<const WorkPrecisionRecord*>>;  // label → h halved

// One scene's line of the work-precision section: per label, x error and time from the largest h to the smallest.
void WriteWorkPrecisionText(std::ostream& md, const std::string& scene, const WorkPrecisionLines& lines) {
  md << "**" << scene << "**: ";
  for (const auto& [label, rs] : lines) {
    md << label << ": x error " << G(rs.front()->error) << " → " << G(rs.back()->error) << " in "
       << Seconds(rs.front()->seconds) << " → " << Seconds(rs.back()->seconds);
    double worst_s = kNaN;
    std::int64_t certified = 0, steps = 0;
    for (const auto* r : rs) {
      worst_s = MaxDefined(worst_s, r->s_forward_error);
      certified += r->s_certified_steps;
      steps += r->steps;
    }
    if (certified > 0) md << ", s per-step error ≤ " << G(worst_s) << " (" << certified << "/" << steps << " steps)";
    md << "; ";
  }
  md << "\n\n";
}

// One scene's work-precision figures: time against the x error, and against the per-step error of s.
void WriteWorkPrecisionFigures(std::ostream& md, const std::string& dir, const std::string& scene,
                               const WorkPrecisionLines& lines) {
  std::map<std::string, std::vector<std::pair<double, double>>> by_x, by_s;
  for (const auto& [label, rs] : lines) {
    for (const auto* r : rs) {
      by_x[label].emplace_back(std::max(r->error, 1e-17), r->seconds);
      // A certified exact answer has error 0: drawn at 1e-17, the bottom of the axis.
      if (!std::isnan(r->s_forward_error)) by_s[label].emplace_back(std::max(r->s_forward_error, 1e-17), r->seconds);
    }
  }
  const std::string stem = "work-precision-" + Safe(scene);
  PlotCurves(by_x, dir, stem, "trajectory error of x against a finer reference run (max)", "run time [s]",
             "Work-precision (trajectory error of x), " + scene, /*sort_by_x=*/false);
  md << FigureMarkdown("work-precision, " + scene, stem);
  if (by_s.empty()) return;
  const std::string stem_s = "work-precision-s-" + Safe(scene);
  PlotCurves(by_s, dir, stem_s, "per-step forward error of s against certified solutions (max; 1e-17 = exact)",
             "run time [s]", "Work-precision (per-step forward error of s), " + scene, /*sort_by_x=*/false);
  md << FigureMarkdown("work-precision against the per-step error of s, " + scene, stem_s);
}

void WriteWorkPrecision(std::ostream& md, const StepperStudy& st, const std::string& dir, bool plots) {
  md << "\n## Time-stepper: work-precision\n\nRun time (set-up included, median of repeats) against two errors, h "
        "halved from the scene's own: the **trajectory error of x** (max over the grid of ‖x_k − x_ref(t_k)‖∞, "
        "x_ref a finer reference run: implicit Euler with lemke at the smallest h / "
     << G(st.reference_h_factor)
     << "; mostly discretization error), and the **per-step forward error of s** (max of ‖s_k − s*_k‖∞ over "
        "the steps the backend solved, s*_k the certified solution of step k's own one-step problem where it is "
        "proven unique: the solver's error alone, in the units of the control; 0 = exact).\n\n";
  std::map<std::string, WorkPrecisionLines> by_scene;
  for (const auto& r : st.work_precision) {
    by_scene[r.scene][r.method == "explicit" ? std::string("explicit Euler") : "implicit, " + r.solver].push_back(&r);
  }
  for (const auto& [scene, lines] : by_scene) {
    WriteWorkPrecisionText(md, scene, lines);
    if (plots) WriteWorkPrecisionFigures(md, dir, scene, lines);
  }
}

}  // namespace smcbench::markdown

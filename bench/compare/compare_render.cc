// compare.md, compare.json and the terminal table of a RunComparison: compare_render.h.
#include "bench/compare/compare_render.h"

#include <cstdio>
#include <sstream>
#include <string>

namespace smcbench {
namespace {

std::string Seconds(double s) {
  char text[32];
  if (s >= 1.0) {
    std::snprintf(text, sizeof text, "%.3g s", s);
  } else if (s >= 1e-3) {
    std::snprintf(text, sizeof text, "%.3g ms", s * 1e3);
  } else if (s >= 1e-6) {
    std::snprintf(text, sizeof text, "%.3g µs", s * 1e6);
  } else {
    std::snprintf(text, sizeof text, "%.3g ns", s * 1e9);
  }
  return text;
}

std::string Ratio(double r) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", r);
  return text;
}

std::string ChangeLine(const VerdictChange& c) {
  std::string line = std::string(ToString(c.kind)) + ": " + c.suite + " " + c.problem +
                     (c.start.empty() ? "" : "@" + c.start) + " " + c.solver +
                     (c.mode == "cold" ? "" : " " + c.mode + " tol " + Ratio(c.tolerance)) + ": " +
                     std::string(ToString(c.verdict_a)) + " (" + std::string(ToString(c.status_a)) + ") -> " +
                     std::string(ToString(c.verdict_b)) + " (" + std::string(ToString(c.status_b)) + ")";
  if (!c.message_b.empty() && c.verdict_b != Verdict::kSolved && c.verdict_b != Verdict::kCorrectlyRefused) line += ": " + c.message_b;
  return line;
}

// "×1.12": a factor to three digits.
std::string Times(double factor) { return "×" + Ratio(factor); }

// One sentence on the drift for compare.md and the terminal, "" when there is nothing to say.
std::string DriftText(const RunComparison& c) {
  const Drift& d = c.drift;
  const std::string floor = d.has_floor ? "the floor (one factorization of M per problem, " +
                                              std::to_string(d.floor_problems) + " problems) " + Times(d.floor.ratio)
                                        : "no floor records";
  const std::string groups = d.agreeing_groups == static_cast<int>(c.groups.size())
                                 ? "all " + std::to_string(c.groups.size()) + " groups"
                                 : std::to_string(d.agreeing_groups) + " of " + std::to_string(c.groups.size()) +
                                       " groups";
  const std::string divided = d.divided ? " Ratios divided by " + Ratio(d.factor) + " before flagging."
                                          : " Not divided out (--keep-drift): flagged on the raw ratios.";
  switch (d.source) {
    case DriftSource::kFloor:
      return groups + " " + Times(d.factor) + " with " + floor + ": machine drift." + divided;
    case DriftSource::kGroups:
      return groups + " " + Times(d.factor) + " (" + floor + (d.has_floor ? ", which disagrees" : "") +
             "): machine drift? (or a change common to every backend)" + divided;
    case DriftSource::kNone:
      break;
  }
  const bool groups_moved = !c.groups.empty() && !WithinBand(d.median_group_ratio, c.flag_limit);
  if (d.has_floor && !WithinBand(d.floor.ratio, c.flag_limit)) {
    return floor + ", but most groups do not move with it: ratios not normalized.";
  }
  if (groups_moved) {
    return "median group " + Times(d.median_group_ratio) + " (" + floor + "), but " +
           (static_cast<int>(c.groups.size()) < kMinGroupsForDrift
                ? "fewer than " + std::to_string(kMinGroupsForDrift) + " groups to call it drift"
                : "most groups do not agree on a common factor") +
           ": ratios not normalized.";
  }
  return "";
}

std::string Cell(const std::string& text) {
  std::string out;
  for (char ch : text) out += ch == '|' ? std::string("\\|") : std::string(1, ch);
  return out;
}

std::string Iterations(double median) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", median);
  return text;
}

// The runs side by side: what differs named first, the machine warning, then every field.
void IdentitySection(const std::vector<IdentityRow>& rows, std::ostringstream& md) {
  if (rows.empty()) return;
  md << "## The runs\n\n";
  const std::string differences = DifferencesLine(rows);
  md << (differences.empty() ? "Same settings, build and machine." : "**Differs:** " + Cell(differences) + ".")
     << "\n\n";
  if (MachinesDiffer(rows)) {
    md << "> **Warning: the runs come from different machines.** Their times are not comparable: the ratios below "
          "measure the machines as much as the builds or settings.\n\n";
  }
  md << "| | field | A | B |\n|---|---|---|---|\n";
  for (const IdentityRow& row : rows) {
    md << "| " << ToString(row.part) << " | " << row.name << (row.differs() ? " **≠**" : "") << " | " << Cell(row.a)
       << " | " << Cell(row.b) << " |\n";
  }
  md << "\n";
}

void NoiseSection(const RunComparison& c, const CompareOptions& options, std::ostringstream& md) {
  const NoiseFloor& n = c.noise;
  md << "## Noise floor and drift\n\n"
     << "Noise floor (A/A calibration of each run from its own repeated samples): with s the median over its cold "
        "solved records of 1.4826·MAD/median (the relative spread of one sample), two repeated samples of a typical "
        "problem differ by a ratio within exp(1.96·√2·s) 95 % of the time: A "
     << Ratio(n.a) << " (s = " << Ratio(n.spread_a) << ", " << n.records_a << " records), B " << Ratio(n.b)
     << " (s = " << Ratio(n.spread_b) << ", " << n.records_b << " records). Flag limit: the larger of these and 1 + "
     << "--threshold (" << Ratio(1.0 + options.threshold) << "): **" << Ratio(c.flag_limit) << "**.\n\n"
     << "Drift: ";
  const std::string drift = DriftText(c);
  md << (drift.empty() ? "none beyond the flag limit (median group " + Times(c.drift.median_group_ratio) +
                             (c.drift.has_floor ? ", floor " + Times(c.drift.floor.ratio) : "") +
                             "): ratios not normalized."
                       : drift)
     << " A factor is taken as drift when it lies beyond the flag limit and more than half of the groups agree with "
        "it (their interval divided by it reaches [1/limit, limit]): the floor records' ratio first (one "
        "factorization of M per problem, code neither run changes), else the median group ratio (from "
     << kMinGroupsForDrift << " groups on). A change common to every backend cannot be told from a drift: "
        "`--keep-drift` flags on the raw ratios.\n\n";
}

}  // namespace

std::string CompareMarkdown(const RunComparison& c, const CompareOptions& options, const std::string& label_a,
                            const std::string& label_b, const std::string& figure_stem) {
  std::ostringstream md;
  const int percent = static_cast<int>(std::lround(options.confidence * 100.0));
  md << "# smcbench compare\n\nA: `" << label_a << "`  \nB: `" << label_b << "`\n\n"
     << c.matched_records << " records in both runs; " << c.regressions() << " verdict regression(s), "
     << c.slower_groups() << " group(s) flagged slower beyond the noise floor. "
     << (c.regressed() ? "**B regressed** (exit status 1)." : "No regression (exit status 0).") << "\n\n";
  IdentitySection(c.identity, md);
  NoiseSection(c, options, md);
  md << "## Verdict changes\n\n";
  if (c.verdict_changes.empty()) {
    md << "None: every record has the same verdict and status in both runs.\n\n";
  } else {
    md << "| change | suite | problem | backend | mode | A | B | B's message |\n|---|---|---|---|---|---|---|---|\n";
    for (const VerdictChange& v : c.verdict_changes) {
      md << "| " << ToString(v.kind) << " | " << v.suite << " | " << v.problem << (v.start.empty() ? "" : "@" + v.start)
         << " | " << v.solver << " | " << v.mode << (v.mode == "cold" ? "" : " " + Ratio(v.tolerance)) << " | "
         << ToString(v.verdict_a) << " (" << ToString(v.status_a) << ") | " << ToString(v.verdict_b) << " ("
         << ToString(v.status_b) << ") | " << v.message_b << " |\n";
    }
    md << "\n";
  }
  md << "## Time ratio B/A per suite, backend and size band\n\n"
     << "Ratio of the shifted geometric means (shift " << Seconds(options.shift_seconds)
     << ") of the per-problem median times, over the problems both runs solved. Interval: " << percent
     << " % paired bootstrap (" << options.resamples << " resamples, seed " << options.seed
     << "): problems resampled with replacement, each median drawn log-normally with its standard error "
        "1.2533·1.4826·MAD/√samples (the records keep median, MAD and sample count, not the samples). ÷ drift: the "
        "ratio divided by the drift factor "
     << Ratio(c.drift.divisor()) << ". Flagged SLOWER when the whole interval ÷ drift lies above the flag limit "
     << Ratio(c.flag_limit) << ", faster when below " << Ratio(1.0 / c.flag_limit)
     << ". Iterations: the median over the group's problems.\n\n";
  if (!figure_stem.empty()) {
    md << "![time ratios B/A with their intervals](" << figure_stem << ".png)\n\n([SVG](" << figure_stem
       << ".svg), [data](" << figure_stem << ".dat), [gnuplot script](" << figure_stem << ".gp))\n\n";
  }
  md << "| suite | backend | band | problems | SGM A | SGM B | B/A | " << percent
     << " % interval | ÷ drift | iterations A | iterations B | flag |\n"
     << "|---|---|---|---:|---:|---:|---:|---|---:|---:|---:|---|\n";
  for (const RatioGroup& g : c.groups) {
    md << "| " << g.suite << " | " << g.solver << " | " << ShortName(g.band) << " | " << g.problems << " | "
       << Seconds(g.sgm_a) << " | " << Seconds(g.sgm_b) << " | " << Ratio(g.time.ratio) << " | [" << Ratio(g.time.low)
       << ", " << Ratio(g.time.high) << "] | " << Ratio(g.time.ratio / c.drift.divisor()) << " | "
       << Iterations(g.iterations_a) << " | " << Iterations(g.iterations_b) << " | " << ToString(g.time.flag)
       << " |\n";
  }
  if (c.groups.empty()) md << "\nNo problem was solved in both runs: nothing to time.\n";
  if (!c.only_in_a.empty() || !c.only_in_b.empty()) {
    md << "\n" << c.only_in_a.size() << " record(s) only in A and " << c.only_in_b.size()
       << " only in B (other backend lists or a partial run) are left out";
    const std::vector<std::string>& first = c.only_in_a.empty() ? c.only_in_b : c.only_in_a;
    md << ", e.g. `" << first.front() << "`.\n";
  }
  return md.str();
}

nlohmann::json CompareJson(const RunComparison& c, const CompareOptions& options, const std::string& label_a,
                           const std::string& label_b) {
  using json = nlohmann::json;
  const auto flag = [](TimeFlag f) {
    return f == TimeFlag::kSlower ? "slower" : f == TimeFlag::kFaster ? "faster" : "none";
  };
  json j = {{"format", "smcbench-compare/1"}, {"a", label_a}, {"b", label_b}, {"regressed", c.regressed()},
            {"matched_records", c.matched_records}, {"regressions", c.regressions()},
            {"slower_groups", c.slower_groups()}, {"only_in_a", c.only_in_a.size()},
            {"only_in_b", c.only_in_b.size()}};
  j["differences"] = DifferencesLine(c.identity);
  j["machines_differ"] = MachinesDiffer(c.identity);
  j["runs"] = json::array();
  for (const IdentityRow& row : c.identity) {
    j["runs"].push_back({{"part", ToString(row.part)}, {"name", row.name}, {"a", row.a}, {"b", row.b},
                         {"differs", row.differs()}});
  }
  j["method"] = {
      {"ratio", "shifted geometric mean of the per-problem median times, B over A"},
      {"interval",
       "paired bootstrap: problems resampled, each median drawn log-normally with 1.2533*1.4826*MAD/sqrt(samples)"},
      {"noise_floor", "per run exp(1.96*sqrt(2)*s), s the median over its cold solved records of 1.4826*MAD/median"},
      {"flag", "interval divided by the drift entirely beyond the flag limit max(1 + threshold, noise floors)"},
      {"threshold", options.threshold}, {"confidence", options.confidence}, {"resamples", options.resamples},
      {"seed", options.seed}, {"shift_seconds", options.shift_seconds}, {"divide_drift", options.divide_drift}};
  const NoiseFloor& n = c.noise;
  j["noise_floor"] = {{"a", n.a}, {"b", n.b}, {"spread_a", n.spread_a}, {"spread_b", n.spread_b},
                      {"records_a", n.records_a}, {"records_b", n.records_b}};
  j["flag_limit"] = c.flag_limit;
  const Drift& d = c.drift;
  j["drift"] = {{"source", ToString(d.source)}, {"factor", d.factor}, {"divided", d.divided},
                {"agreeing_groups", d.agreeing_groups}, {"median_group_ratio", d.median_group_ratio},
                {"text", DriftText(c)}};
  j["drift"]["floor"] = d.has_floor ? json{{"ratio", d.floor.ratio}, {"low", d.floor.low}, {"high", d.floor.high},
                                           {"problems", d.floor_problems}}
                                    : json(nullptr);
  j["verdict_changes"] = json::array();
  for (const VerdictChange& v : c.verdict_changes) {
    j["verdict_changes"].push_back(
        {{"kind", ToString(v.kind)}, {"suite", v.suite}, {"problem", v.problem}, {"start", v.start},
         {"backend", v.solver}, {"mode", v.mode}, {"tolerance", v.tolerance}, {"verdict_a", ToString(v.verdict_a)},
         {"status_a", ToString(v.status_a)}, {"verdict_b", ToString(v.verdict_b)},
         {"status_b", ToString(v.status_b)}, {"message_b", v.message_b}});
  }
  j["groups"] = json::array();
  for (const RatioGroup& g : c.groups) {
    j["groups"].push_back({{"suite", g.suite}, {"backend", g.solver}, {"band", ShortName(g.band)},
                           {"problems", g.problems}, {"sgm_a", g.sgm_a}, {"sgm_b", g.sgm_b},
                           {"ratio", g.time.ratio}, {"low", g.time.low}, {"high", g.time.high},
                           {"ratio_over_drift", g.time.ratio / d.divisor()}, {"iterations_a", g.iterations_a},
                           {"iterations_b", g.iterations_b}, {"flag", flag(g.time.flag)}});
  }
  return j;
}

std::string CompareSummaryText(const RunComparison& c, const CompareOptions& options, std::size_t max_changes,
                               std::size_t max_groups) {
  std::ostringstream text;
  text << "compare: " << c.matched_records << " records in both runs, " << c.verdict_changes.size()
       << " verdict change(s) (" << c.regressions() << " regression(s)), " << c.groups.size() << " group(s), "
       << c.slower_groups() << " flagged slower (interval ÷ drift above the flag limit " << Ratio(c.flag_limit)
       << ": noise floor A " << Ratio(c.noise.a) << ", B " << Ratio(c.noise.b) << ", 1 + threshold "
       << Ratio(1.0 + options.threshold) << ")\n";
  if (!c.identity.empty()) {
    const std::string differences = DifferencesLine(c.identity);
    text << "  " << (differences.empty() ? "same settings, build and machine" : "differs: " + differences) << "\n";
    if (MachinesDiffer(c.identity)) text << "  WARNING: different machines: the times are not comparable\n";
  }
  if (const std::string drift = DriftText(c); !drift.empty()) text << "  drift: " << drift << "\n";
  for (std::size_t i = 0; i < std::min(max_changes, c.verdict_changes.size()); ++i) {
    text << "  " << ChangeLine(c.verdict_changes[i]) << "\n";
  }
  if (c.verdict_changes.size() > max_changes) {
    text << "  (and " << c.verdict_changes.size() - max_changes << " more verdict changes)\n";
  }
  const bool all = c.groups.size() <= max_groups;
  std::size_t width = 7;
  for (const RatioGroup& g : c.groups) width = std::max(width, g.suite.size() + g.solver.size() + 1);
  bool header = false;
  for (const RatioGroup& g : c.groups) {
    if (!all && g.time.flag == TimeFlag::kNone) continue;
    if (!header) {
      char line[200];
      std::snprintf(line, sizeof line, "  %-*s %-9s %5s %8s  %-19s %8s  %-15s\n", static_cast<int>(width), "backend",
                    "band", "n", "B/A", "interval", "÷drift", "iterations A→B");
      text << line;
      header = true;
    }
    const std::string interval = "[" + Ratio(g.time.low) + ", " + Ratio(g.time.high) + "]";
    const std::string iterations = Iterations(g.iterations_a) + "→" + Iterations(g.iterations_b);
    char line[320];
    std::snprintf(line, sizeof line, "  %-*s %-9s %5d %8s  %-19s %8s  %-15s %s\n", static_cast<int>(width),
                  (g.suite + "/" + g.solver).c_str(), std::string(ShortName(g.band)).c_str(), g.problems,
                  Ratio(g.time.ratio).c_str(), interval.c_str(), Ratio(g.time.ratio / c.drift.divisor()).c_str(),
                  iterations.c_str(), std::string(ToString(g.time.flag)).c_str());
    text << line;
  }
  if (!all) text << "  (only the flagged groups of " << c.groups.size() << "; every group in compare.md)\n";
  return text.str();
}

}  // namespace smcbench

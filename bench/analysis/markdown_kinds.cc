// The MCP suite's and the AVI suite's own sections (markdown_sections.h).
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

namespace smcbench::markdown {

// ---- The MCP section: a suite whose records are MCP problem × start (ReplayRecord::start). ----

// Per backend and start label: correct answers (solved + correctly refused) over the problems with that start.
void WriteMcpStarts(std::ostream& md, const SuiteResults& suite) {
  std::vector<std::string> labels;
  std::map<std::pair<std::string, std::string>, std::pair<int, int>> cells;  // (backend, label) → correct, total
  for (const auto& r : suite.replay.records) {
    if (std::find(labels.begin(), labels.end(), r.start) == labels.end()) labels.push_back(r.start);
    auto& [correct, total] = cells[{r.solver, r.start}];
    correct += IsCorrect(r);
    ++total;
  }
  md << "Success per start (solved + correctly refused / problems with that start; a start label names the "
        "published starting point of each problem):\n\n| backend | ";
  for (const auto& label : labels) md << "`" << Cell(label, 40) << "` | ";
  md << "\n|---|";
  for (std::size_t i = 0; i < labels.size(); ++i) md << "---|";
  md << "\n";
  for (const std::string& solver : SolversIn(suite.replay.records)) {
    md << "| " << solver << " | ";
    for (const auto& label : labels) {
      const auto it = cells.find({solver, label});
      md << (it == cells.end() ? std::string("–")
                               : std::to_string(it->second.first) + "/" + std::to_string(it->second.second))
         << " | ";
    }
    md << "\n";
  }
  md << "\n";
}

// Which backend fails where, and with what status: every record of an MCP suite (with_start: problem × start) or of
// the AVI suite that is not correct, wrong answers first (the first 40).
void WriteNotCorrectRecords(std::ostream& md, const SuiteResults& suite, bool with_start) {
  std::vector<const ReplayRecord*> failures;
  for (const auto& r : suite.replay.records) {
    if (!IsCorrect(r)) failures.push_back(&r);
  }
  if (failures.empty()) {
    md << "Every backend is right on every " << (with_start ? "problem × start" : "AVI") << ".\n\n";
    return;
  }
  std::stable_sort(failures.begin(), failures.end(), [](const ReplayRecord* a, const ReplayRecord* b) {
    return IsWrong(a->verdict) > IsWrong(b->verdict);
  });
  constexpr std::size_t kListed = 40;
  md << "Where the backends fail (" << failures.size() << (with_start ? " problem × start × backend" : " AVI × backend")
     << (failures.size() > kListed ? ", the first 40; results.csv has them all" : "")
     << "; wrong answers first):\n\n| " << (with_start ? "problem | start" : "AVI")
     << " | backend | verdict | status | message | residual (eq.) | forward error | allowance |\n"
     << "|" << (with_start ? "---|" : "") << "---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < std::min(failures.size(), kListed); ++i) {
    const ReplayRecord& r = *failures[i];
    const std::string verdict(ToString(r.verdict));
    md << "| " << r.problem << " | ";
    if (with_start) md << Cell(r.start, 40) << " | ";
    md << r.solver << " | " << (IsWrong(r.verdict) ? "**" + verdict + "**" : verdict) << " | " << ToString(r.status)
       << " | " << Cell(r.message) << " | " << G(r.residual_scaled) << " | " << G(r.forward_error) << " | "
       << G(r.forward_allowance) << " |\n";
  }
  md << "\n";
}

// Speed against forward error: one point per problem × start a backend answered, where the forward error is
// defined (a reference certified unique, or every solution listed).
void WriteMcpSpeedAgainstError(std::ostream& md, const SuiteResults& suite, const std::string& dir) {
  std::map<std::string, std::vector<std::pair<double, double>>> points;
  for (const auto& r : suite.replay.records) {
    if (std::isnan(r.forward_error) || r.samples == 0) continue;
    points[r.solver].emplace_back(std::max(std::isfinite(r.forward_error) ? r.forward_error : 1e300, 1e-17),
                                  std::max(r.time_median, 1e-9));
  }
  if (points.empty()) return;
  const std::string stem = "speed-forward-error-" + Safe(suite.suite);
  PlotCurves(points, dir, stem, "forward error |z - z*|inf against the nearest reference (1e-17 = exact)",
             "time per solve [s]", "Speed against forward error, MCP suite " + suite.suite, true, "points");
  md << FigureMarkdown("speed against forward error, MCP suite " + suite.suite, stem);
}

void WriteMcpSection(std::ostream& md, const SuiteResults& suite, const std::string& dir, bool plots) {
  std::set<std::string> problems, instances;
  for (const auto& r : suite.replay.records) problems.insert(r.problem), instances.insert(InstanceOf(r));
  const std::string certified = CertificateCounts(suite);
  md << "## MCP suite `" << suite.suite << "`: " << suite.description << "\n\n"
     << problems.size() << " nonlinear MCPs, " << instances.size()
     << " problem × start (each published starting point is its own instance; times are cold solves from it); "
        "references: "
     << (certified.empty() ? "–" : certified)
     << ". Only backends that solve MCPs run here (`smcbench list` says: accepts nonlinear MCP): the others have no "
        "record and are not counted. The verdict is the box's with F's Jacobian J at the answer in place of M: "
        "residual (eq.) is the scale-free MCP residual (row i divided by max_j |J_ij|·c_j, variables in their units "
        "c, relative to 1 + max_i |z_i|/c_i) and must be ≤ tol; the forward error is judged against the nearest "
        "reference when the references list every solution, else against one certified unique. Success and SGM "
        "time are over problem × start.\n\n";
  WriteBackendTable(md, suite);
  WriteSolvedNothing(md, suite);
  WriteStatusesAndClaims(md, suite);
  WriteBandWinners(md, suite);
  WriteMcpStarts(md, suite);
  WriteNotCorrectRecords(md, suite, /*with_start=*/true);
  if (plots) {
    WriteMcpSpeedAgainstError(md, suite, dir);
    WritePerformanceProfile(md, suite, dir);
  }
}

// ---- The AVI section: the `avi` suite's AVI × box backend records (bench/replay/avi_replay.h). ----

// The family of an AVI id "avi/<family>/...".
std::string AviFamily(const std::string& id) {
  const auto first = id.find('/');
  if (first == std::string::npos) return id;
  const auto second = id.find('/', first + 1);
  return id.substr(first + 1, second == std::string::npos ? std::string::npos : second - first - 1);
}

// Per backend: the verdicts and the median cold time over the AVIs it got right.
void WriteAviBackends(std::ostream& md, const SuiteResults& suite) {
  const std::map<std::string, double> floor = FloorTimes(suite);
  md << "| backend | AVIs | solved | correctly refused | **wrongly claimed** | **inaccurate** | **wrongly refused** | "
        "failed | median time (correct) |"
     << (floor.empty() ? "" : " time / floor |") << "\n|---|---:|---:|---:|---:|---:|---:|---:|---:|"
     << (floor.empty() ? "" : "---:|") << "\n";
  for (const std::string& solver : SolversIn(suite.replay.records)) {
    std::map<Verdict, int> count;
    std::vector<double> times;
    int total = 0;
    for (const auto& r : suite.replay.records) {
      if (r.solver != solver) continue;
      ++total;
      ++count[r.verdict];
      if (IsCorrect(r) && r.samples > 0) times.push_back(r.time_median);
    }
    md << "| " << solver << " | " << total << " | " << count[Verdict::kSolved] << " | "
       << count[Verdict::kCorrectlyRefused] << " | " << Count(count[Verdict::kWronglyClaimed]) << " | "
       << Count(count[Verdict::kInaccurate]) << " | " << Count(count[Verdict::kWronglyRefused]) << " | "
       << count[Verdict::kFailed] << " | " << (times.empty() ? std::string("–") : Seconds(MedianDefined(times)))
       << " |";
    if (!floor.empty()) md << " " << FloorRatioCell(FloorRatios(suite.replay.records, floor, solver)) << " |";
    md << "\n";
  }
  md << "\n";
  WriteFloorLine(md, suite);
}

// Per backend and family: correct answers (solved + correctly refused) over the family's AVIs.
void WriteAviFamilies(std::ostream& md, const SuiteResults& suite) {
  std::vector<std::string> families;
  std::map<std::pair<std::string, std::string>, std::pair<int, int>> cells;  // (backend, family) → correct, total
  for (const auto& r : suite.replay.records) {
    const std::string family = AviFamily(r.problem);
    if (std::find(families.begin(), families.end(), family) == families.end()) families.push_back(family);
    auto& [correct, total] = cells[{r.solver, family}];
    correct += IsCorrect(r);
    ++total;
  }
  md << "Correct answers per family (solved + correctly refused / AVIs of the family):\n\n| backend | ";
  for (const auto& family : families) md << family << " | ";
  md << "\n|---|";
  for (std::size_t i = 0; i < families.size(); ++i) md << "---:|";
  md << "\n";
  for (const std::string& solver : SolversIn(suite.replay.records)) {
    md << "| " << solver << " | ";
    for (const auto& family : families) {
      const auto& [correct, total] = cells[{solver, family}];
      md << correct << "/" << total << " | ";
    }
    md << "\n";
  }
  md << "\n";
}

void WriteAviSection(std::ostream& md, const SuiteResults& suite, const std::string& dir, bool plots) {
  std::set<std::string> problems;
  std::map<std::string, int> families;
  for (const auto& r : suite.replay.records) {
    if (problems.insert(r.problem).second) ++families[AviFamily(r.problem)];
  }
  std::string family_counts;
  for (const auto& [family, count] : families) {
    family_counts += (family_counts.empty() ? "" : ", ") + std::to_string(count) + " " + family;
  }
  const std::string certified = CertificateCounts(suite);
  md << "## AVI suite `" << suite.suite << "`: " << suite.description << "\n\n"
     << problems.size() << " affine variational inequalities 0 ∈ Mλ + q + N_P(λ), P = {Hλ ≥ K, Eλ = f} ("
     << family_counts << "); references (of the reduction): " << (certified.empty() ? "–" : certified)
     << ProvedCounts(suite) << ". Every backend that solves box-MLCPs runs here, on the exact reduction to a box-MLCP in (λ, μ, ν) "
        "(SolveAvi, docs/avi.md); times are cold SolveAvi calls (building the reduction, the backend's solve, the "
        "mapping back). The verdict is JudgeAvi's, recomputed from the answer, never the backend's flag: residual "
        "(eq.) is the natural residual of the normalized reduction (rows of H, E divided by their largest entry, "
        "M and q by max|M_ij|), and λ's complementarity and feasibility in units of λ must also be ≤ tol; the "
        "forward error ‖λ − λ*‖∞ is judged only where λ is unique (M + Mᵀ positive definite, or certified), so "
        "on the twisting steps (M singular, λ not unique) the residual rule alone decides. AVIs with no solution "
        "must be refused.\n\n";
  WriteAviBackends(md, suite);
  WriteAviFamilies(md, suite);
  WriteStatusesAndClaims(md, suite);
  WriteNotCorrectRecords(md, suite, /*with_start=*/false);
  if (plots) WritePerformanceProfile(md, suite, dir);
}

}  // namespace smcbench::markdown

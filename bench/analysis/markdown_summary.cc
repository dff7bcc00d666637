// The report's opening, its summary per class and per backend, the failure list and the appendix:
// markdown_sections.h.
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
#include "bench/analysis/report_markdown.h"

namespace smcbench::markdown {

// The report's opening: the command, the environment, the verdict and what the columns mean.
void WriteHeader(std::ostream& md, const std::string& dir, const BenchResults& results, const nlohmann::json& env) {
  md << "# smcbench benchmark report\n\n"
     << "Made by `smcbench report " << dir << "` from `" << dir << "/results.json`, produced by\n\n    "
     << results.command << "\n\n"
     << "Environment: "
     << (env.value("build_revision", std::string()).empty()
             ? "git " + env.value("git_sha", std::string("?")).substr(0, 12) +
                   (env.value("git_dirty", false) ? " (dirty tree)" : "")
             : "build " + env.value("build_revision", std::string()))
     << ", " << env.value("compiler", std::string("?"))
     << " " << env.value("build_type", std::string("")) << ", " << env.value("cpu", std::string("?")) << " ("
     << env.value("cores", 0) << " cores), " << env.value("date", std::string("")) << ".\n\n"
     << SharedHostWarning(results)
     << "The summary comes first; every table after it is defined in [the appendix](#appendix-the-verdict-and-the-"
        "timing) (the verdict, the wrong answers, the SGM time), and [each backend's failures](#failures-per-"
        "backend) are listed before it.\n\n";
}

// The appendix: the verdict and how times are measured (what the header said before the summary came first).
void WriteVerdictAppendix(std::ostream& md, const BenchResults& results) {
  md << "## Appendix: the verdict and the timing\n\n"
     << "**The verdict.** " << kVerdictInTwoSentences
     << " (docs/verdict.md says why each part is there.) Success = solved, or — on a problem known to have no "
        "solution — any non-solved status ('correctly refused'). The **wrong** answers, which must be 0: **wrongly "
        "claimed** (status solved where a recomputed residual says otherwise, or on a problem with no solution), "
        "**inaccurate** (the residuals pass but z is farther from the certified z* than its conditioning allows) "
        "and **wrongly refused** (status infeasible on a problem known to be solvable). `smcbench bench` exits "
        "with status 3 when there is any (backends named by `--allow-wrong` excepted). Residual = relative "
        "natural residual (1), residual (eq.) = the row-equilibrated one (2), forward error = ‖z − z*‖∞ where a "
        "certified reference proves z* unique (– where none does). Times are medians over repeated cold solves "
        "(each sample repeats the solve until it lasts ≥ 0.2 ms) after one untimed warm-up solve, which for a "
        "`siconos-*` backend is the probe in its isolation worker, so that its timed solves run in process; SGM is "
        "the shifted geometric mean (shift 1 µs) "
        "with a wrong or failed problem counted at 10× the slowest correct time on it (10 s where no backend got it "
        "right). "
     << (results.polish ? "Every answer went through the base layer's exact polish (the default: from the answer's "
                          "active set, the reduced system solved directly), so an answer with the right active set "
                          "is exact whatever the tolerance; `smcbench bench --no-polish` times the raw algorithms."
                        : "**No polish** (`--no-polish`): the raw algorithms' answers.")
     << " The **floor** of a problem is one factorization of its matrix (bench/replay/floor.h: Cholesky when its "
        "tags say SPD, else LU with partial pivoting; sparse ones for a sparse M; an MCP's Jacobian at the start, an "
        "AVI's reduced system), timed in the same run with the same protocol as a cold solve; it is never a "
        "backend and counts in no ranking.\n\n";
}

// The summary: per problem class the fastest correct backend, the most reliable one and the gap to the floor
// (SummarizeClasses), then per backend its failures and their most common cause (FailuresPerBackend).
void WriteSummary(std::ostream& md, const BenchResults& results) {
  const std::vector<ClassSummary> classes = SummarizeClasses(results);
  if (classes.empty()) return;
  bool floor = false;
  for (const SuiteResults& s : results.suites) floor = floor || !s.replay.floor.empty();
  md << "## Summary\n\nPer problem class (matrix class and bounds from the problems' tags × size band; every "
        "suite's cold records pooled): the **fastest correct** backend (no wrong answer in the class, smallest SGM "
        "time, a failure counted at the penalty), the **most reliable** (most correct answers, then fewest wrong), "
        "and the fastest's median time over the **floor** (one factorization of the problem's matrix, n problems)"
     << (floor ? "" : " — floor not measured in this run") << ".\n\n"
     << "| class | size band | problems | fastest correct | its correct | its SGM time | fastest / floor | most "
        "reliable | its correct | its wrong |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (const ClassSummary& c : classes) {
    md << "| " << ClassName(c.problem_class) << " | " << ToString(c.problem_class.band) << " | " << c.problems
       << " | ";
    if (c.fastest.empty()) {
      md << "none (every backend gave a wrong answer) | | | |";
    } else {
      md << "**" << c.fastest << "** | " << c.fastest_correct << "/" << c.problems << " | "
         << Seconds(c.fastest_sgm) << " | "
         << (c.floor_instances ? G(c.fastest_over_floor) + "× (" + std::to_string(c.floor_instances) + ")"
                               : std::string(floor ? "–" : "not measured"))
         << " |";
    }
    md << " " << c.most_reliable << " | " << c.reliable_correct << "/" << c.problems << " | "
       << Count(c.reliable_wrong) << " |\n";
  }
  md << "\nFailures per backend over the whole run (failed or wrong; the list of each is in [Failures per "
        "backend](#failures-per-backend)):\n\n| backend | records | not correct | **wrong** | most common cause "
        "|\n|---|---|---|---|---|\n";
  for (const BackendFailures& b : FailuresPerBackend(results)) {
    if (b.not_correct == 0) continue;
    md << "| " << b.solver << " | " << b.records << " | " << b.not_correct << " | " << Count(b.wrong) << " | "
       << FailureText(b.cause, b.not_correct) << " |\n";
  }
  std::vector<std::string> clean;
  for (const BackendFailures& b : FailuresPerBackend(results)) {
    if (b.not_correct == 0) clean.push_back(b.solver);
  }
  if (!clean.empty()) {
    md << "\nNo failure: ";
    for (std::size_t i = 0; i < clean.size(); ++i) md << (i ? ", " : "") << clean[i];
    md << ".";
  }
  md << "\n\n";
}

// Per backend, every cold record that is not correct: problem (suite/instance), class, status, verdict, message.
void WriteFailureList(std::ostream& md, const BenchResults& results) {
  const std::vector<BackendFailures> all = FailuresPerBackend(results);
  md << "## Failures per backend\n\nEvery cold record that is not correct (failed, or a wrong answer in bold), per "
        "backend, in the order of the results.\n\n";
  for (const BackendFailures& b : all) {
    if (b.not_correct == 0) continue;
    md << "### " << b.solver << ": " << b.not_correct << " of " << b.records << "\n\n| problem | class | status | "
          "verdict | message |\n|---|---|---|---|---|\n";
    for (const BackendFailures::Entry& e : b.entries) {
      const bool wrong = e.verdict != Verdict::kFailed;
      md << "| " << Cell(e.instance, 120) << " | " << e.problem_class << " | `" << ToString(e.status) << "` | "
         << (wrong ? "**" : "") << ToString(e.verdict) << (wrong ? "**" : "") << " | " << Cell(e.message) << " |\n";
    }
    md << "\n";
  }
}

}  // namespace smcbench::markdown

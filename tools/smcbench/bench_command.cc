#include "tools/smcbench/bench_command.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <ostream>

#include "bench/replay/replay.h"
#include "bench/replay/results_io.h"
#include "bench/replay/stepper_study.h"
#include "problems/generators/random_problems.h"
#include "problems/io/siconos_format.h"
#include "problems/library/capture.h"
#include "problems/library/problem_set_io.h"
#include "problems/library/references.h"
#include "problems/suites/families.h"
#include "problems/suites/hard_cases.h"
#include "solvers/reference/certify.h"
#include "solvers/registry/registry.h"
#include "tools/smcbench/bench_report.h"
#include "tools/smcbench/history_report.h"
#include "tools/smcbench/solve_report.h"

namespace smcbench {

namespace fs = std::filesystem;


std::vector<fs::path> SiconosCollectionFiles(const fs::path& dir) {
  if (!fs::is_directory(dir)) throw InvalidInputError("collection: '" + dir.string() + "' is not a directory");
  std::vector<fs::path> files;
  for (const char* sub : {"lcp", "relay", "mlcp"}) {
    if (!fs::is_directory(dir / sub)) continue;
    std::vector<fs::path> found;
    for (const auto& entry : fs::directory_iterator(dir / sub)) {
      const fs::path& p = entry.path();
      // The `_block` LCP files duplicate their dense twins in another storage: solving both adds nothing.
      if (p.extension() == ".dat" && p.stem().string().find("_block") == std::string::npos) found.push_back(p);
    }
    std::sort(found.begin(), found.end());
    files.insert(files.end(), found.begin(), found.end());
  }
  if (files.empty()) throw InvalidInputError("collection: no .dat files under " + dir.string() + "/{lcp,relay,mlcp}");
  return files;
}

ProblemSet SiconosSuite(const std::string& dir, std::vector<std::string>* rejected) {
  ProblemSet set;
  set.name = "siconos";
  set.description = "the Siconos Numerics test collection (LCP, relay, MLCP files of " + dir + ")";
  for (const fs::path& file : SiconosCollectionFiles(dir)) {
    const std::string kind = file.parent_path().filename().string();
    try {
      BoxMLCP problem = ReadSiconosFile(file.string());
      LibraryProblem p = MakeLibraryProblem("siconos/" + kind + "/" + file.stem().string(),
                                     "siconos:" + kind + "/" + file.filename().string(), std::move(problem));
      p.tags = {kind};
      set.problems.push_back(std::move(p));
    } catch (const InvalidInputError& e) {
      if (rejected) rejected->push_back(file.string() + ": " + e.what());
    }
  }
  return set;
}

ProblemSet TinySuite() {
  ProblemSet set;
  set.name = "tiny";
  set.description = "five small generated problems (CI's end-to-end run of bench and report)";
  const auto add = [&](MatrixFamily family, BoundKind bounds, int m, std::uint64_t seed) {
    GeneratorOptions g;
    g.family = family;
    g.bounds = bounds;
    g.size = m;
    g.seed = seed;
    GeneratedProblem gen = GenerateProblem(g);
    std::string id = "tiny/" + gen.problem.name();
    LibraryProblem p = MakeLibraryProblem(std::move(id), "generated:random_problems", std::move(gen.problem));
    p.seed = seed;
    p.expected = ExpectedOutcome::kSolvable;
    p.solution = gen.z_star;
    p.matrix.p_matrix = Tristate::kYes;
    p.matrix.symmetric = family == MatrixFamily::kSymmetricPositiveDefinite ? Tristate::kYes : Tristate::kNo;
    set.problems.push_back(std::move(p));
  };
  add(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kRelay, 2, 1);
  add(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kRelay, 8, 2);
  add(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kLCP, 4, 3);
  add(MatrixFamily::kDiagonallyDominant, BoundKind::kMixed, 6, 4);
  // Infeasible LCP: w_1 = −x_1 − x_2 − 1 < 0 for every z ≥ 0, so no z ≥ 0 has w ≥ 0.
  DenseMatrix M(2, 2);
  M << -1.0, -1.0, 0.0, 1.0;
  Vector q(2);
  q << -1.0, 1.0;
  LibraryProblem infeasible =
      MakeLibraryProblem("tiny/infeasible-lcp", "handmade", BoxMLCP::LCP(M, q, "infeasible-lcp"));
  infeasible.expected = ExpectedOutcome::kInfeasible;
  infeasible.tags = {"infeasible"};
  set.problems.push_back(std::move(infeasible));
  return set;
}

namespace {

ProblemSet BuildSuiteProblems(const std::string& name, const SuiteRequest& request) {
  if (name == "tiny") return TinySuite();
  if (name == "siconos") return SiconosSuite(request.siconos_dir);
  if (name == "paper") {
    PaperSuiteOptions o;
    if (request.quick) o.max_steps_per_scene = 8;
    return CapturePaperSuite(o);
  }
  if (name == "families") {
    FamiliesOptions o;
    if (request.quick) o.seeds = 1, o.max_size = 16;
    return FamiliesSuite(o);
  }
  if (name == "hard") return HardSuite(request.siconos_dir);
  if (name == "scale") {
    ScaleOptions o;
    if (request.quick) o.max_size = 1000;
    return ScaleSuite(o);
  }
  std::error_code ec;
  if (fs::is_regular_file(name, ec)) return ReadProblemSetFile(name);
  throw InvalidInputError("bench: unknown suite '" + name +
                          "' (known: paper, families, hard, siconos, scale, tiny, all, or a problem-set file)");
}

}  // namespace

ProblemSet BuildSuite(const std::string& name, const SuiteRequest& request) {
  ProblemSet set = BuildSuiteProblems(name, request);
  if (request.references) AttachReferences(&set);
  return set;
}

bool GlobMatch(std::string_view pattern, std::string_view text) {
  // Iterative wildcard matching with one backtrack point (the last '*'): linear in practice, no recursion.
  std::size_t p = 0, t = 0, star = std::string_view::npos, resume = 0;
  while (t < text.size()) {
    if (p < pattern.size() && (pattern[p] == '?' || pattern[p] == text[t])) {
      ++p, ++t;
    } else if (p < pattern.size() && pattern[p] == '*') {
      star = p++;
      resume = t;
    } else if (star != std::string_view::npos) {
      p = star + 1;
      t = ++resume;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

// ------------------------------------------------------------------------------------------------------------

const char* const kGenericSparsePath = "newton-sparse-path";

// The suites `bench` knows by name (anything else must be a problem-set file).
const char* const kSuiteNames[] = {"paper", "families", "hard", "siconos", "scale", "tiny", "all"};

struct BenchCommand::Flags {
  std::vector<std::string> suites, solvers, sets, allow_wrong;
  // Empty: a fresh folder ./smcbench-bench-YYYYMMDD-HHMMSS (DefaultOutputFolder), so a run without --out never
  // replaces earlier results, the committed results/bench included.
  std::string out, siconos_dir = "../shared/peer-data/siconos", report_dir, history;
  int repetitions = 7;
  double tol = 1e-10, time_limit = 10.0;
  // Seconds one backend may spend on one suite before its remaining problems there are skipped (0: no limit).
  double backend_budget = 60.0;
  double progress_every = 5.0;  // seconds between progress lines when stderr is not a terminal (0: none)
  bool overwrite = false, no_stepper = false, quick = false, report = false, no_plots = false,
       report_no_plots = false, no_polish = false;
};

BenchCommand::BenchCommand(CLI::App* app) : flags_(std::make_unique<Flags>()) {
  Flags& f = *flags_;
  bench_ = app->add_subcommand("bench", "replay problem suites on every backend: status, iterations, both "
                                        "residuals, forward error, verdict, median time and spread → "
                                        "DIR/results.{json,csv}. Exit status 3 when any answer is wrong (wrongly "
                                        "claimed, inaccurate or wrongly refused) on a backend not named by "
                                        "--allow-wrong, after writing the results (and report)");
  bench_->add_option("--suite", f.suites,
                     "paper | families | hard | siconos | scale | tiny | all | FILE (repeatable; default: paper "
                     "families hard siconos)");
  bench_->add_option("--solver", f.solvers, "backend (repeatable; default: every registered backend)");
  bench_->add_option("--set", f.sets, "typed backend option BACKEND.OPTION=VALUE (see `smcbench list`)");
  bench_->add_option("--out", f.out, "output folder (default: a fresh ./smcbench-bench-YYYYMMDD-HHMMSS); a folder "
                                     "that already holds results.json is refused unless --overwrite");
  bench_->add_flag("--overwrite", f.overwrite, "let --out name a folder with earlier results (tools/bench.sh "
                                               "passes it for results/bench)");
  bench_->add_option("--siconos-dir", f.siconos_dir, "the Siconos collection (default ../shared/peer-data/siconos)");
  bench_->add_option("--repetitions", f.repetitions, "timing samples per problem x backend (default 7)");
  bench_->add_option("--tol", f.tol, "tolerance on the relative and the row-equilibrated natural residual "
                                     "(default 1e-10)");
  bench_->add_option("--time-limit", f.time_limit, "seconds per solve (default 10)");
  bench_->add_option("--backend-budget", f.backend_budget,
                     "seconds one backend may spend on one suite (default 60, 0: no limit); past it the backend's "
                     "remaining problems of that suite are skipped and recorded as time limit, with a message");
  bench_->add_option("--progress-every", f.progress_every, "seconds between progress lines on stderr when it is "
                                                           "not a terminal (default 5, 0: none)");
  bench_->add_flag("--no-stepper", f.no_stepper, "skip the time-stepper studies (warm/cold, work-precision)");
  bench_->add_flag("--quick", f.quick, "smaller suites and fewer samples (CI)");
  bench_->add_flag("--report", f.report, "also write DIR/report.md (as `smcbench report DIR`)");
  bench_->add_flag("--no-plots", f.no_plots, "with --report: no PNG plots");
  bench_->add_flag("--no-polish", f.no_polish, "no exact polish of the backends' answers (SolverOptions::polish = "
                                              "false): time a raw algorithm");
  bench_->add_option("--allow-wrong", f.allow_wrong, "glob PATTERN of backends whose wrong answers do not set exit "
                                                     "status 3 (still reported), e.g. 'siconos-*' (repeatable)")
      ->type_name("PATTERN");

  report_ = app->add_subcommand("report", "turn DIR/results.json into DIR/report.md with PNG plots; with --history, "
                                          "plot the perf gate's history");
  report_->add_option("DIR", f.report_dir, "the folder `smcbench bench --out` wrote (with --history: where "
                                           "history.md goes; default the history file's folder)");
  report_->add_option("--history", f.history, "the perf gate's history CSV (tools/perf-check --history appends to "
                                              "results/history.csv) → DIR/history.{md,png}");
  report_->add_flag("--no-plots", f.report_no_plots, "no PNG plots (no gnuplot needed)");
}

BenchCommand::~BenchCommand() = default;
bool BenchCommand::bench_parsed() const { return bench_->parsed(); }
bool BenchCommand::report_parsed() const { return report_->parsed(); }

namespace {

// A one-line progress bar on a terminal; elsewhere (a log, CI) a plain line every `every` seconds, so a long run
// is seen to move. Short runs stay quiet either way.
class Progress {
 public:
  Progress(std::ostream& err, bool terminal, double every)
      : err_(err), terminal_(terminal), every_(every), start_(Clock::now()), last_line_(start_) {}
  void Update(std::size_t done, std::size_t total, const std::string& what) {
    if (total == 0) return;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    if (!terminal_) {
      if (!(every_ > 0.0) || std::chrono::duration<double>(Clock::now() - last_line_).count() < every_) return;
      last_line_ = Clock::now();
      char line[240];
      std::snprintf(line, sizeof line, "bench: %zu/%zu (%zu%%) after %.0f s: %.160s", done, total,
                    100 * done / total, elapsed, what.c_str());
      err_ << line << "\n" << std::flush;
      return;
    }
    if (elapsed < 2.0 && done < total) return;  // short runs stay quiet
    const int width = 30, filled = static_cast<int>(width * done / total);
    char line[160];
    std::snprintf(line, sizeof line, "\r[%s%s] %3zu%% %.0fs %-60.60s", std::string(filled, '#').c_str(),
                  std::string(width - filled, '.').c_str(), 100 * done / total, elapsed, what.c_str());
    err_ << line << std::flush;
  }
  // A phase with no count (the time-stepper studies): the bar shows it half way, a line says what runs.
  void Note(const std::string& what) {
    if (terminal_) return Update(1, 2, what);
    Update(0, 1, what);
  }
  void Finish() {
    if (terminal_) err_ << "\r" << std::string(110, ' ') << "\r" << std::flush;
  }

 private:
  using Clock = std::chrono::steady_clock;
  std::ostream& err_;
  bool terminal_;
  double every_;
  Clock::time_point start_, last_line_;
};

// One line on err when any answer is wrong (none: nothing), and the exit status: kExitWrongAnswers when a wrong
// answer comes from a backend no --allow-wrong pattern names, else 0. Sweep records count too: a wrong answer at a
// loose tolerance is still a wrong answer.
int SummarizeWrongAnswers(const BenchResults& results, const std::vector<std::string>& allow_wrong,
                          std::ostream& err) {
  std::map<Verdict, int> by_verdict;
  std::map<std::string, int> by_backend;
  int wrong = 0, excused = 0;
  for (const auto& s : results.suites) {
    for (const auto* records : {&s.replay.records, &s.replay.sweep}) {
      for (const ReplayRecord& r : *records) {
        if (!IsWrong(r.verdict)) continue;
        ++wrong;
        ++by_verdict[r.verdict];
        ++by_backend[r.solver];
        excused += std::any_of(allow_wrong.begin(), allow_wrong.end(),
                               [&](const std::string& pattern) { return GlobMatch(pattern, r.solver); });
      }
    }
  }
  if (wrong == 0) return 0;
  std::string verdicts, backends;
  for (const auto& [verdict, count] : by_verdict) {
    verdicts += (verdicts.empty() ? "" : ", ") + std::string(ToString(verdict)) + " " + std::to_string(count);
  }
  for (const auto& [backend, count] : by_backend) {
    backends += (backends.empty() ? "" : ", ") + backend + " " + std::to_string(count);
  }
  err << "bench: " << wrong << " wrong answer" << (wrong == 1 ? "" : "s") << " (" << verdicts << "; " << backends
      << ")" << (excused ? ", " + std::to_string(excused) + " of them allowed by --allow-wrong" : std::string())
      << "; see results.csv\n";
  return wrong > excused ? kExitWrongAnswers : 0;
}

// Everything `bench` can check before it builds a suite or solves anything, so a typo fails in a second, not after
// an hour: suite names (or readable problem-set files), the Siconos folder when its suites are asked for, backend
// names, --set values (tried on a fresh instance of the backend), numbers, and the output folder.
void CheckBenchRequest(const BenchCommand::Flags& f, const std::vector<std::string>& suites) {
  for (const std::string& name : suites) {
    const bool known = std::find(std::begin(kSuiteNames), std::end(kSuiteNames), name) != std::end(kSuiteNames);
    std::error_code ec;
    if (!known && !fs::is_regular_file(name, ec)) {
      throw InvalidInputError("bench: unknown suite '" + name +
                              "' (known: paper, families, hard, siconos, scale, tiny, all, or a problem-set file)");
    }
    if ((name == "siconos" || name == "hard") && !fs::is_directory(f.siconos_dir, ec)) {
      throw InvalidInputError("bench: suite " + name + " needs the Siconos collection: --siconos-dir '" +
                              f.siconos_dir + "' is not a folder");
    }
  }
  for (const auto& name : f.solvers) CreateSolver(name);  // InvalidInputError listing the known names
  for (const std::string& set : f.sets) {
    const auto dot = set.find('.'), eq = set.find('=');
    if (dot == std::string::npos || eq == std::string::npos || eq < dot) {
      throw InvalidInputError("bench: --set expects BACKEND.OPTION=VALUE, got '" + set + "'");
    }
    std::string error;
    if (!CreateSolver(set.substr(0, dot))->SetOption(set.substr(dot + 1, eq - dot - 1), set.substr(eq + 1), &error)) {
      throw InvalidInputError("bench: --set " + set + ": " + error);
    }
  }
  if (!(f.tol > 0.0) || !(f.time_limit > 0.0) || f.repetitions < 1 || !(f.backend_budget >= 0.0) ||
      !(f.progress_every >= 0.0)) {
    throw InvalidInputError("bench: --tol, --time-limit and --repetitions must be positive, --backend-budget and "
                            "--progress-every at least 0");
  }
  for (const std::string& pattern : f.allow_wrong) {
    if (pattern.empty()) throw InvalidInputError("bench: --allow-wrong needs a non-empty PATTERN");
  }
  std::error_code ec;
  if (!f.overwrite && fs::exists(fs::path(f.out) / "results.json", ec)) {
    throw InvalidInputError("bench: '" + f.out + "' already holds results.json: choose another --out, or add "
                            "--overwrite to replace them");
  }
}

// ./smcbench-bench-YYYYMMDD-HHMMSS (local time), with -2, -3, ... if that exists already.
std::string DefaultOutputFolder() {
  const std::time_t now = std::time(nullptr);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::localtime(&now));
  std::string name = std::string("smcbench-bench-") + stamp;
  std::error_code ec;
  for (int k = 2; fs::exists(name, ec); ++k) name = std::string("smcbench-bench-") + stamp + "-" + std::to_string(k);
  return name;
}

// ReplayProblemSet with a time budget per backend over the whole suite: each backend runs alone over chunks of
// the problems (one problem first, then chunks sized to a quarter of what is left of its budget at its pace so
// far), and once it has spent the budget its remaining problems get a record with status time limit and a message
// saying so, without being solved. A backend overshoots by at most one chunk (≥ one problem with its tolerance
// sweep). The records come back in ReplayProblemSet's order (problem, then backend). budget ≤ 0: no limit.
ReplayResults ReplayWithBackendBudget(const ProblemSet& set, const ReplayOptions& options, double budget,
                                      std::ostream& err) {
  if (!(budget > 0.0)) return ReplayProblemSet(set, options);
  std::vector<std::string> names = options.solvers;
  if (names.empty()) {
    for (auto n : SolverNames()) names.emplace_back(n);
  }
  const std::size_t n = set.problems.size();
  const std::size_t sweep_problems = std::min<std::size_t>(std::max(0, options.tolerance_sweep_problems), n);
  std::size_t iterative = 0;
  for (const auto& name : names) iterative += !CreateSolver(name)->info().exact;
  const std::size_t total = n * names.size() + sweep_problems * iterative;
  std::size_t done = 0;
  std::map<std::string, std::size_t> index_of;
  for (std::size_t i = 0; i < n; ++i) index_of[set.problems[i].id] = i;

  struct Keyed {
    std::size_t problem, backend;
    ReplayRecord record;
  };
  std::vector<Keyed> records, sweep;
  for (std::size_t b = 0; b < names.size(); ++b) {
    const bool exact = CreateSolver(names[b])->info().exact;
    double spent = 0.0;
    std::size_t chunk = 1;
    for (std::size_t first = 0; first < n;) {
      if (spent >= budget) {
        for (std::size_t i = first; i < n; ++i) {
          const LibraryProblem& p = set.problems[i];
          ReplayRecord r;
          r.suite = set.name;
          r.problem = p.id;
          r.solver = names[b];
          r.size = p.size();
          r.sparse = p.sparse();
          for (const auto& t : p.tags) r.tags += (r.tags.empty() ? "" : ",") + t;
          r.expected = p.expected;
          r.status = SolveStatus::kTimeLimit;
          char message[160];
          std::snprintf(message, sizeof message, "not run: %s spent its budget of %g s on suite %s (--backend-budget)",
                        names[b].c_str(), budget, set.name.c_str());
          r.message = message;
          r.verdict = Verdict::kFailed;  // not run is no answer, even on a problem with no solution
          r.residual_abs = r.residual_rel = r.residual_scaled = kInf;
          r.certificate = std::string(ToString(p.reference.certificate));
          r.tolerance = options.tolerance;
          records.push_back({i, b, std::move(r)});
          done += 1 + (i < sweep_problems && !exact);
        }
        err << "bench: " << names[b] << " skipped " << (n - first) << " of " << n << " problems of suite "
            << set.name << " after spending its budget of " << budget << " s (--backend-budget)\n";
        break;
      }
      const std::size_t last = std::min(n, first + chunk);
      ProblemSet part;
      part.name = set.name;
      part.description = set.description;
      part.problems.assign(set.problems.begin() + static_cast<std::ptrdiff_t>(first),
                           set.problems.begin() + static_cast<std::ptrdiff_t>(last));
      ReplayOptions o = options;
      o.solvers = {names[b]};
      o.tolerance_sweep_problems = static_cast<int>(first < sweep_problems ? std::min(last, sweep_problems) - first : 0);
      const std::size_t done_before = done;
      o.progress = [&](std::size_t local_done, std::size_t, const std::string& what) {
        done = done_before + local_done;
        if (options.progress) options.progress(done, total, what);
      };
      const auto start = std::chrono::steady_clock::now();
      ReplayResults part_results = ReplayProblemSet(part, o);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      spent += seconds;
      for (ReplayRecord& r : part_results.records) records.push_back({index_of[r.problem], b, std::move(r)});
      for (ReplayRecord& r : part_results.sweep) sweep.push_back({index_of[r.problem], b, std::move(r)});
      // Next chunk: a quarter of the budget left at this backend's pace, at most twice the last one.
      const double per_problem = seconds / static_cast<double>(last - first);
      const double fits = per_problem > 0.0 ? (budget - spent) / 4.0 / per_problem : 1e9;
      chunk = std::max<std::size_t>(1, std::min<std::size_t>(2 * chunk, static_cast<std::size_t>(std::max(0.0, fits))));
      first = last;
    }
  }
  const auto by_problem_then_backend = [](const Keyed& a, const Keyed& b) {
    return a.problem != b.problem ? a.problem < b.problem : a.backend < b.backend;
  };
  std::stable_sort(records.begin(), records.end(), by_problem_then_backend);
  std::stable_sort(sweep.begin(), sweep.end(), by_problem_then_backend);
  ReplayResults out;
  for (Keyed& k : records) out.records.push_back(std::move(k.record));
  for (Keyed& k : sweep) out.sweep.push_back(std::move(k.record));
  return out;
}

// The run at a glance on stdout: per suite and backend the verdict counts and the shifted geometric mean time.
void PrintSummaryTable(const BenchResults& results, double time_limit, std::ostream& out) {
  out << "| suite | backend | problems | solved | refused | failed | wrongly claimed | inaccurate | wrongly refused "
         "| SGM time |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const SuiteResults& suite : results.suites) {
    for (const BackendSummary& b : SummarizeSuite(suite, time_limit)) {
      out << "| " << suite.suite << " | " << b.solver << " | " << b.problems << " | " << b.solved << " | "
          << b.correctly_refused << " | " << b.failed << " | " << b.wrongly_claimed << " | " << b.inaccurate << " | "
          << b.wrongly_refused << " | " << FormatDuration(1e9 * b.shifted_geomean) << " |\n";
    }
  }
}

// The Siconos Numerics version the siconos-* backends were built against (the Debian package's, found by CMake:
// the headers carry no version macro), or empty when this build has none.
std::string SiconosVersion() {
#ifdef SMCBENCH_SICONOS_VERSION
  return SMCBENCH_SICONOS_VERSION;
#else
  return {};
#endif
}

// results.json's environment.libraries gets "siconos_numerics" when a siconos-* backend ran.
void RecordSiconosVersion(const BenchResults& results, const std::string& dir) {
  bool ran = false;
  for (const SuiteResults& s : results.suites) {
    for (const ReplayRecord& r : s.replay.records) ran = ran || r.solver.rfind("siconos-", 0) == 0;
  }
  const std::string version = SiconosVersion();
  if (!ran || version.empty()) return;
  const fs::path path = fs::path(dir) / "results.json";
  std::ifstream in(path);
  nlohmann::json document = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (document.is_discarded()) throw InvalidInputError("bench: cannot read back '" + path.string() + "'");
  in.close();
  document["environment"]["libraries"]["siconos_numerics"] = version;
  std::ofstream rewritten(path, std::ios::trunc);
  rewritten << document.dump(1) << "\n";
  if (!rewritten) throw InvalidInputError("bench: cannot write '" + path.string() + "'");
}

}  // namespace

int BenchCommand::RunBench(const std::string& command_line, std::ostream& out, std::ostream& err) const {
  const Flags& f = *flags_;
  std::vector<std::string> suites = f.suites;
  if (suites.empty()) suites = {"paper", "families", "hard", "siconos"};
  if (std::find(suites.begin(), suites.end(), "all") != suites.end()) {
    suites = {"paper", "families", "hard", "siconos", "scale"};
  }
  ReplayOptions options;
  options.solvers = f.solvers;
  options.settings = f.sets;
  options.tolerance = f.tol;
  options.time_limit_seconds = f.time_limit;
  options.repetitions = f.quick ? std::min(f.repetitions, 3) : f.repetitions;
  if (f.quick) {
    options.max_seconds_per_pair = 0.2;
    options.tolerance_sweep_problems = 2;
  }
  CheckBenchRequest(f, suites);
  const std::string out_dir = f.out.empty() ? DefaultOutputFolder() : f.out;
  {
    std::error_code ec;
    fs::create_directories(out_dir, ec);
    if (ec) throw InvalidInputError("bench: cannot create --out '" + out_dir + "': " + ec.message());
  }
  err << "bench: writing to " << out_dir << "\n";
  const bool terminal = &err == &std::cerr && ::isatty(2);
  Progress progress(err, terminal, f.progress_every);
  options.progress = [&](std::size_t done, std::size_t total, const std::string& what) {
    progress.Update(done, total, what);
  };
  options.polish = !f.no_polish;
  SuiteRequest request;
  request.siconos_dir = f.siconos_dir;
  request.quick = f.quick;
  request.references = false;  // attached below, timed

  BenchResults results;
  results.command = command_line;
  results.polish = options.polish;
  for (const std::string& name : suites) {
    const auto build_start = std::chrono::steady_clock::now();
    ProblemSet set = BuildSuite(name, request);
    set.Validate();
    const auto references_start = std::chrono::steady_clock::now();
    AttachReferences(&set);
    const double references_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - references_start).count();
    std::map<Certificate, int> certificates;
    for (const LibraryProblem& p : set.problems) ++certificates[p.reference.certificate];
    std::string certified;
    for (const auto& [certificate, count] : certificates) {
      certified += (certified.empty() ? "" : ", ") + std::to_string(count) + " " + std::string(ToString(certificate));
    }
    // Built (captured suites certify their problems while capturing), then the remaining references attached.
    char seconds[96];
    std::snprintf(seconds, sizeof seconds, "built in %.2f s; certified references in %.2f s",
                  std::chrono::duration<double>(references_start - build_start).count(), references_seconds);
    err << "bench: suite " << set.name << " (" << set.problems.size() << " problems, " << seconds << ": "
        << certified << ")\n";
    SuiteResults suite;
    suite.suite = set.name;
    suite.description = set.description;
    suite.problems = static_cast<int>(set.problems.size());
    suite.replay = ReplayWithBackendBudget(set, options, f.backend_budget, err);
    if (set.name == "paper" && (f.solvers.empty() ||
                                std::find(f.solvers.begin(), f.solvers.end(), "newton") != f.solvers.end())) {
      // The generic path the report compares against: the same problems with M stored sparse, solved by the
      // semismooth Newton backend through UMFPACK (what a general sparse complementarity code does).
      ProblemSet sparse;
      sparse.name = set.name;
      for (const LibraryProblem& p : set.problems) {
        const DenseMatrix& M = p.problem.dense_matrix();
        const SparseMatrix S = M.sparseView();
        LibraryProblem copy =
            MakeLibraryProblem(p.id, p.source, BoxMLCP(S, p.problem.q(), p.problem.l(), p.problem.u()));
        copy.expected = p.expected;
        copy.reference = p.reference;  // the same problem: judged against the same certified solution
        sparse.problems.push_back(std::move(copy));
      }
      ReplayOptions o = options;
      o.solvers = {"newton"};
      o.settings = {"newton.linear_solver=2"};  // UMFPACK even where the auto rule would factorize densely
      o.tolerance_sweep_problems = 0;
      for (ReplayRecord& r : ReplayWithBackendBudget(sparse, o, f.backend_budget, err).records) {
        r.solver = kGenericSparsePath;
        suite.replay.records.push_back(std::move(r));
      }
    }
    progress.Finish();
    results.suites.push_back(std::move(suite));
  }
  if (!f.no_stepper) {
    StepperStudyOptions so;
    so.solvers = f.solvers;
    if (so.solvers.empty()) {
      // External adapters run each solve in a child process: along 10⁴-step trajectories that is minutes; they
      // are timed on the replay suites instead (name them with --solver to include them here).
      for (auto n : SolverNames()) {
        if (n.rfind("siconos-", 0) != 0) so.solvers.emplace_back(n);
      }
    }
    if (f.quick) {
      so.warm_scenes = {"sign", "galias-yu-2007"};
      so.precision_scenes = {"galias-yu-2007"};
      so.refinements = 3;
      so.min_seconds = 0.002;
    }
    so.progress = [&](const std::string& what) { progress.Note(what); };
    so.polish = options.polish;
    // Per-step forward error of s in the work-precision runs: each step's one-step problem certified from the
    // backend's own answer (the cheapest candidate: usually its active set verifies at once). Its cost is
    // reported, since it adds to the main job's time.
    double certify_seconds = 0.0;
    std::int64_t certified_steps = 0;
    so.step_forward_error = [&](const BoxMLCP& problem, const Vector& z) {
      const auto start = std::chrono::steady_clock::now();
      const ReferenceSolution reference = Certify(problem, {z});
      certify_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      ++certified_steps;
      return reference.unique() ? (z - reference.z).cwiseAbs().maxCoeff() : kNaN;
    };
    err << "bench: time-stepper studies\n";
    const auto stepper_start = std::chrono::steady_clock::now();
    results.stepper = RunStepperStudy(so);
    results.has_stepper = true;
    progress.Finish();
    char line[160];
    std::snprintf(line, sizeof line, "bench: time-stepper studies took %.1f s, of which %.1f s certifying %lld steps",
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - stepper_start).count(),
                  certify_seconds, static_cast<long long>(certified_steps));
    err << line << "\n";
  }
  WriteBenchResults(results, out_dir);
  RecordSiconosVersion(results, out_dir);
  PrintSummaryTable(results, f.time_limit, out);
  out << "bench: wrote " << (fs::path(out_dir) / "results.json").string() << " and results.csv";
  if (f.report) {
    WriteBenchReport(out_dir, !f.no_plots);
    out << ", report.md";
  }
  out << "\n";
  return SummarizeWrongAnswers(results, f.allow_wrong, err);
}

int BenchCommand::RunReport(std::ostream& out, std::ostream&) const {
  const Flags& f = *flags_;
  if (f.history.empty() && f.report_dir.empty()) {
    throw InvalidInputError("report: give DIR (a `smcbench bench --out` folder) or --history FILE");
  }
  if (!f.history.empty()) {
    const std::string dir = !f.report_dir.empty() ? f.report_dir
                            : fs::path(f.history).has_parent_path() ? fs::path(f.history).parent_path().string()
                                                                     : std::string(".");
    WritePerfHistoryReport(f.history, dir, !f.report_no_plots);
    out << "report: wrote " << (fs::path(dir) / "history.md").string() << "\n";
    // The bench report too when DIR is a bench folder.
    if (f.report_dir.empty() || !fs::exists(fs::path(f.report_dir) / "results.json")) return 0;
  }
  WriteBenchReport(f.report_dir, !f.report_no_plots);
  out << "report: wrote " << (fs::path(f.report_dir) / "report.md").string() << "\n";
  return 0;
}

}  // namespace smcbench

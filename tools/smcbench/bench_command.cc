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
#include <sstream>

#include "bench/replay/jobs.h"
#include "bench/replay/mcp_replay.h"
#include "bench/replay/replay.h"
#include "bench/replay/results_io.h"
#include "bench/replay/stepper_study.h"
#include "problems/io/data_dirs.h"
#include "problems/library/references.h"
#include "problems/mcp/mcp_suite.h"
#include "solvers/reference/certify.h"
#include "solvers/registry/backend_settings.h"
#include "solvers/registry/registry.h"
#include "tools/smcbench/bench_report.h"
#include "tools/smcbench/history_report.h"
#include "tools/smcbench/solve_report.h"
#include "smcbench/version.h"

namespace smcbench {

namespace fs = std::filesystem;


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

// The suites `bench` knows by name (anything else must be a problem-set file).
const char* const kBenchSuiteNames[] = {"paper", "families", "hard", "siconos", "scale", "tiny", "mcp", "all"};
namespace {
// The nonlinear MCP suites among them (BuildMcpSuite), run on the backends with SolverInfo::mcp.
bool IsMcpSuiteName(const std::string& name) { return name == "mcp"; }
}  // namespace

struct BenchCommand::Flags {
  std::vector<std::string> suites, solvers, sets, allow_wrong;
  // Empty: a fresh folder ./smcbench-bench-YYYYMMDD-HHMMSS (DefaultOutputFolder), so a run without --out never
  // replaces earlier results, the committed results/bench included.
  std::string out, siconos_dir = DataDirectory(DataFolder::kSiconosCollection), report_dir, history;
  int repetitions = 7;
  double tol = 1e-10, time_limit = 10.0;
  // Seconds one backend may spend on one suite before its remaining problems there are skipped (0: no limit).
  double backend_budget = 60.0;
  double progress_every = 5.0;  // seconds between progress lines when stderr is not a terminal (0: none)
  // --shard K/N (empty: the whole run), --resume DIR (empty: a fresh run), --list-jobs.
  std::string shard, resume;
  bool list_jobs = false;
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
                     "paper | families | hard | siconos | scale | tiny | mcp | all | FILE (repeatable; default: "
                     "paper families hard siconos mcp; mcp: the nonlinear MCPs, problem x start, on the backends "
                     "that solve MCPs)");
  bench_->add_option("--solver", f.solvers, "backend (repeatable; default: every registered backend)");
  bench_->add_option("--set", f.sets, "typed backend option BACKEND.OPTION=VALUE (see `smcbench list`)");
  bench_->add_option("--out", f.out, "output folder (default: a fresh ./smcbench-bench-YYYYMMDD-HHMMSS); a folder "
                                     "that already holds results.json is refused unless --overwrite");
  bench_->add_flag("--overwrite", f.overwrite, "let --out name a folder with earlier results (tools/bench.sh "
                                               "passes it for results/bench)");
  bench_->add_option("--siconos-dir", f.siconos_dir, "the Siconos collection (default: $SMCBENCH_SICONOS_DIR, else "
                                                     "share/smcbench/siconos of this installation, else the "
                                                     "checkout's tests/data/siconos)");
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

  bench_->add_option("--shard", f.shard, "run only shard K of N (1 <= K <= N): a deterministic share of the jobs "
                                         "(problem x backend x tolerance x mode), balanced by estimated cost; "
                                         "combine the shards' folders with `smcbench merge`")
      ->type_name("K/N");
  bench_->add_option("--resume", f.resume, "continue the run in DIR (the same command that started it, --out "
                                           "replaced by --resume): run only the jobs missing from "
                                           "DIR/records.jsonl")
      ->type_name("DIR");
  bench_->add_flag("--list-jobs", f.list_jobs, "print the jobs (of --shard's share) with their estimated seconds, "
                                               "run nothing");

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
    const bool known =
        std::find(std::begin(kBenchSuiteNames), std::end(kBenchSuiteNames), name) != std::end(kBenchSuiteNames);
    std::error_code ec;
    if (!known && !fs::is_regular_file(name, ec)) {
      throw InvalidInputError("bench: unknown suite '" + name + "' (known: paper, families, hard, siconos, scale, "
                              "tiny, mcp, all, or a problem-set file)");
    }
    if ((name == "siconos" || name == "hard") && !fs::is_directory(f.siconos_dir, ec)) {
      throw InvalidInputError("bench: suite " + name + " needs the Siconos collection: --siconos-dir '" +
                              f.siconos_dir + "' is not a folder");
    }
  }
  for (const auto& name : f.solvers) CreateSolver(name);  // InvalidInputError listing the known names
  std::vector<std::string> selected = f.solvers;  // none named: every backend
  if (selected.empty()) {
    for (auto n : SolverNames()) selected.emplace_back(n);
  }
  try {
    CheckBackendSettings(f.sets, selected);  // the one --set parser: solvers/registry/backend_settings.h
  } catch (const InvalidInputError& e) {
    throw InvalidInputError(std::string("bench: ") + e.what());
  }
  if (!(f.tol > 0.0) || !(f.time_limit > 0.0) || f.repetitions < 1 || !(f.backend_budget >= 0.0) ||
      !(f.progress_every >= 0.0)) {
    throw InvalidInputError("bench: --tol, --time-limit and --repetitions must be positive, --backend-budget and "
                            "--progress-every at least 0");
  }
  for (const std::string& pattern : f.allow_wrong) {
    if (pattern.empty()) throw InvalidInputError("bench: --allow-wrong needs a non-empty PATTERN");
  }
  if (!f.shard.empty()) ParseShard(f.shard);
  std::error_code ec;
  if (!f.resume.empty()) {
    if (!f.out.empty() || f.overwrite) {
      throw InvalidInputError("bench: --resume DIR continues DIR: give neither --out nor --overwrite with it");
    }
    if (!fs::exists(fs::path(f.resume) / "manifest.json", ec)) {
      throw InvalidInputError("bench: --resume '" + f.resume + "' holds no manifest.json (not a folder bench started)");
    }
    return;
  }
  if (f.list_jobs) return;
  for (const char* file : {"results.json", "manifest.json"}) {
    if (!f.overwrite && !f.out.empty() && fs::exists(fs::path(f.out) / file, ec)) {
      throw InvalidInputError("bench: '" + f.out + "' already holds " + file + ": choose another --out, --resume "
                              "it, or add --overwrite to replace it");
    }
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

// The run at a glance on stdout: per suite and backend the verdict counts and the shifted geometric mean time; a
// backend that solved nothing gets its most common status instead of a time made of failure penalties alone.
void PrintSummaryTable(const BenchResults& results, double time_limit, std::ostream& out) {
  out << "| suite | backend | problems | solved | refused | failed | wrongly claimed | inaccurate | wrongly refused "
         "| SGM time |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const SuiteResults& suite : results.suites) {
    const std::vector<BackendSummary> summary = SummarizeSuite(suite, time_limit);
    for (const BackendSummary& b : summary) {
      out << "| " << suite.suite << " | " << b.solver << " | " << b.problems << " | " << b.solved << " | "
          << b.correctly_refused << " | " << b.failed << " | " << b.wrongly_claimed << " | " << b.inaccurate << " | "
          << b.wrongly_refused << " | "
          << (SolvedNothing(b, summary) ? "solved nothing: " + std::string(ToString(b.failure.status)) + " on " +
                                              std::to_string(b.failure.count)
                                        : FormatDuration(1e9 * b.shifted_geomean))
          << " |\n";
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

// What produced the numbers, with the build's own revision (not the checkout's HEAD at run time) and, when a
// siconos-* backend is among the backends, the Siconos version.
nlohmann::json RunEnvironment(const std::vector<std::string>& solvers) {
  nlohmann::json environment = BenchEnvironment(std::string(GitRevision()));
  environment["version"] = std::string(Version());
  const bool siconos = std::any_of(solvers.begin(), solvers.end(),
                                   [](const std::string& n) { return n.rfind("siconos-", 0) == 0; });
  if (siconos && !SiconosVersion().empty()) environment["libraries"]["siconos_numerics"] = SiconosVersion();
  return environment;
}

// The options that change what a run measures: shards and resumed runs must agree on them (merge refuses others).
nlohmann::json RunOptionsJson(const BenchCommand::Flags& f, const ReplayOptions& options,
                              const std::vector<std::string>& solvers) {
  return {{"solvers", solvers},
          {"settings", f.sets},
          {"tolerance", options.tolerance},
          {"time_limit", options.time_limit_seconds},
          {"repetitions", options.repetitions},
          {"max_seconds_per_pair", options.max_seconds_per_pair},
          {"tolerance_sweep_problems", options.tolerance_sweep_problems},
          {"polish", options.polish},
          {"quick", f.quick},
          {"stepper", !f.no_stepper},
          {"backend_budget", f.backend_budget}};
}

// The suites of a run, built, validated and (with references) certified, one line each on err with the time taken.
std::vector<ProblemSet> BuildBenchSuites(const std::vector<std::string>& names, const SuiteRequest& request,
                                         bool references, std::ostream& err) {
  std::vector<ProblemSet> sets;
  for (const std::string& name : names) {
    if (IsMcpSuiteName(name)) continue;  // BuildBenchMcpSuites
    const auto build_start = std::chrono::steady_clock::now();
    ProblemSet set = BuildSuite(name, request);
    set.Validate();
    if (!references) {
      sets.push_back(std::move(set));
      continue;
    }
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
    sets.push_back(std::move(set));
  }
  return sets;
}

// The MCP suites among names, built (references attached by the suite) and validated, one line each on err.
std::vector<McpProblemSet> BuildBenchMcpSuites(const std::vector<std::string>& names, bool quick, std::ostream& err) {
  std::vector<McpProblemSet> sets;
  for (const std::string& name : names) {
    if (!IsMcpSuiteName(name)) continue;
    const auto build_start = std::chrono::steady_clock::now();
    McpProblemSet set = BuildMcpSuite(quick);
    set.Validate();
    std::size_t instances = 0;
    std::map<std::string, int> certificates;
    for (const McpLibraryProblem& p : set.problems) {
      instances += p.starts.size();
      for (const ReferenceSolution& r : p.references) ++certificates[std::string(ToString(r.certificate))];
      if (p.references.empty()) ++certificates["no reference"];
    }
    std::string certified;
    for (const auto& [certificate, count] : certificates) {
      certified += (certified.empty() ? "" : ", ") + std::to_string(count) + " " + certificate;
    }
    char seconds[64];
    std::snprintf(seconds, sizeof seconds, "built in %.2f s",
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - build_start).count());
    err << "bench: suite " << set.name << " (" << set.problems.size() << " MCPs, " << instances
        << " problem x start, " << seconds << "; references: " << certified << ")\n";
    sets.push_back(std::move(set));
  }
  return sets;
}

// The generic path the report compares against: the same problems with M stored sparse, solved by the semismooth
// Newton backend through UMFPACK (what a general sparse complementarity code does), judged against the same
// certified solutions.
ProblemSet SparseCopy(const ProblemSet& set) {
  ProblemSet sparse;
  sparse.name = set.name;
  sparse.description = set.description;
  for (const LibraryProblem& p : set.problems) {
    const SparseMatrix S = p.problem.dense_matrix().sparseView();
    LibraryProblem copy = MakeLibraryProblem(p.id, p.source, BoxMLCP(S, p.problem.q(), p.problem.l(), p.problem.u()));
    copy.expected = p.expected;
    copy.reference = p.reference;
    sparse.problems.push_back(std::move(copy));
  }
  return sparse;
}

// The run's job list (ListBenchJobs) for these suites and backends.
std::vector<BenchJob> RunJobs(const BenchCommand::Flags& f, const std::vector<ProblemSet>& sets,
                              const std::vector<McpProblemSet>& mcp_sets, const ReplayOptions& options,
                              const std::vector<std::string>& solvers) {
  JobListRequest request;
  request.solvers = solvers;
  for (const std::string& name : solvers) request.iterative.push_back(!CreateSolver(name)->info().exact);
  request.generic_sparse_path =
      f.solvers.empty() || std::find(f.solvers.begin(), f.solvers.end(), "newton") != f.solvers.end();
  request.stepper = !f.no_stepper;
  if (!mcp_sets.empty()) request.mcp_solvers = McpSolverNames(solvers);
  return ListBenchJobs(sets, mcp_sets, options, request);
}

// Runs the jobs of one folder one at a time, each timed, judged and appended to records.jsonl as it finishes. A
// backend past its --backend-budget on a suite (in this process) gets its remaining cold jobs there recorded as
// not run (time limit, a message) and its sweep jobs skipped.
class ShardRunner {
 public:
  ShardRunner(const BenchCommand::Flags& flags, const std::vector<ProblemSet>& sets,
              const std::vector<McpProblemSet>& mcp_sets, const ReplayOptions& options,
              const std::string& records_path, std::ostream& err)
      : flags_(flags), sets_(sets), mcp_sets_(mcp_sets), options_(options), writer_(records_path), err_(err) {}

  JobLine Run(const BenchJob& job) {
    const int before = activity_.Count();
    JobLine line;
    line.job = job.index;
    line.id = job.id;
    line.host = activity_.host();
    if (job.kind == JobKind::kStepper) {
      line.has_stepper = true;
      line.stepper = RunStepper();
    } else if (OverBudget(job)) {
      line.skipped = job.kind == JobKind::kSweep;
      line.has_record = !line.skipped;
      if (line.has_record) line.record = NotRunRecord(job);
      if (line.has_record) ++skipped_[{job.suite, job.solver}];  // problems; skipped sweep rungs are not problems
    } else {
      const auto start = std::chrono::steady_clock::now();
      line.has_record = true;
      line.record = Replay(job);
      spent_[{job.suite, job.solver}] += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    line.concurrent_jobs = std::max(before, activity_.Count());
    if (line.has_record) line.record.host = line.host, line.record.concurrent_jobs = line.concurrent_jobs;
    writer_.Write(line);
    return line;
  }

  // One line per backend that ran out of budget on a suite.
  void ReportSkipped() const {
    for (const auto& [key, count] : skipped_) {
      const bool mcp = key.first >= sets_.size();
      std::size_t problems = 0;
      if (mcp) {
        for (const McpLibraryProblem& p : mcp_sets_[key.first - sets_.size()].problems) problems += p.starts.size();
      } else {
        problems = sets_[key.first].problems.size();
      }
      err_ << "bench: " << key.second << " skipped " << count << " of " << problems
           << (mcp ? " problem x start of suite " : " problems of suite ")
           << (mcp ? mcp_sets_[key.first - sets_.size()].name : sets_[key.first].name)
           << " after spending its budget of "
           << flags_.backend_budget << " s (--backend-budget)\n";
    }
  }

  std::function<void(const std::string&)> stepper_progress;

 private:
  bool OverBudget(const BenchJob& job) const {
    const auto it = spent_.find({job.suite, job.solver});
    return flags_.backend_budget > 0.0 && it != spent_.end() && it->second >= flags_.backend_budget;
  }

  Solver* SolverFor(const std::string& name) {
    auto it = solvers_.find(name);
    if (it == solvers_.end()) {
      if (name == kGenericSparsePath) {  // the baseline the registry defines (CreateGenericSparsePathSolver)
        it = solvers_.emplace(name, CreateGenericSparsePathSolver()).first;
      } else {
        ReplayOptions o = options_;
        std::vector<std::string> names{name};
        o.settings = SettingsReaching(name, options_.settings);  // checked against the whole selection up front
        it = solvers_.emplace(name, std::move(CreateReplaySolvers(o, &names).front())).first;
      }
    }
    return it->second.get();
  }

  ReplayRecord Replay(const BenchJob& job) {
    if (job.kind == JobKind::kMcp) {
      const McpProblemSet& set = mcp_sets_.at(job.suite - sets_.size());
      return ReplayMcpOne(set, set.problems.at(job.problem), job.start, SolverFor(job.solver), job.solver, options_,
                          job.tolerance);
    }
    const ProblemSet& set = sets_[job.suite];
    if (job.kind != JobKind::kGenericSparse) {
      return ReplayOne(set, set.problems[job.problem], SolverFor(job.solver), job.solver, options_,
                       job.kind == JobKind::kSweep ? "sweep" : "cold", job.tolerance);
    }
    auto it = sparse_.find(job.suite);
    if (it == sparse_.end()) it = sparse_.emplace(job.suite, SparseCopy(set)).first;
    return ReplayOne(it->second, it->second.problems[job.problem], SolverFor(job.solver), job.solver, options_,
                     "cold", job.tolerance);
  }

  ReplayRecord NotRunRecord(const BenchJob& job) const {
    if (job.kind == JobKind::kMcp) {
      const McpProblemSet& set = mcp_sets_.at(job.suite - sets_.size());
      char message[160];
      std::snprintf(message, sizeof message, "not run: %s spent its budget of %g s on suite %s (--backend-budget)",
                    job.solver.c_str(), flags_.backend_budget, set.name.c_str());
      return McpNotRunRecord(set, set.problems.at(job.problem), job.start, job.solver, job.tolerance, message);
    }
    const LibraryProblem& p = sets_[job.suite].problems[job.problem];
    ReplayRecord r;
    r.suite = sets_[job.suite].name;
    r.problem = p.id;
    r.solver = job.solver;
    r.size = p.size();
    r.sparse = p.sparse() || job.kind == JobKind::kGenericSparse;
    for (const auto& t : p.tags) r.tags += (r.tags.empty() ? "" : ",") + t;
    r.expected = p.expected;
    r.status = SolveStatus::kTimeLimit;
    char message[160];
    std::snprintf(message, sizeof message, "not run: %s spent its budget of %g s on suite %s (--backend-budget)",
                  job.solver.c_str(), flags_.backend_budget, r.suite.c_str());
    r.message = message;
    r.verdict = Verdict::kFailed;  // not run is no answer, even on a problem with no solution
    r.residual_abs = r.residual_rel = r.residual_scaled = kInf;
    r.certificate = std::string(ToString(p.reference.certificate));
    r.tolerance = job.tolerance;
    return r;
  }

  StepperStudy RunStepper() {
    StepperStudyOptions so;
    so.solvers = flags_.solvers;
    if (so.solvers.empty()) {
      // External adapters run each solve in a child process: along 10⁴-step trajectories that is minutes; they
      // are timed on the replay suites instead (name them with --solver to include them here).
      for (auto n : SolverNames()) {
        if (!IsExternalBackendName(n)) so.solvers.emplace_back(n);
      }
    }
    if (flags_.quick) {
      so.warm_scenes = {"sign", "galias-yu-2007"};
      so.precision_scenes = {"galias-yu-2007"};
      so.refinements = 3;
      so.min_seconds = 0.002;
    }
    so.progress = stepper_progress;
    so.polish = options_.polish;
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
    err_ << "bench: time-stepper studies\n";
    const auto stepper_start = std::chrono::steady_clock::now();
    StepperStudy study = RunStepperStudy(so);
    char line[160];
    std::snprintf(line, sizeof line, "bench: time-stepper studies took %.1f s, of which %.1f s certifying %lld steps",
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - stepper_start).count(),
                  certify_seconds, static_cast<long long>(certified_steps));
    err_ << line << "\n";
    return study;
  }

  const BenchCommand::Flags& flags_;
  const std::vector<ProblemSet>& sets_;
  const std::vector<McpProblemSet>& mcp_sets_;  // BenchJob::suite counts them after sets_
  ReplayOptions options_;
  JobLineWriter writer_;
  std::ostream& err_;
  HostActivity activity_;
  std::map<std::string, std::unique_ptr<Solver>> solvers_;
  std::map<std::size_t, ProblemSet> sparse_;
  std::map<std::pair<std::size_t, std::string>, double> spent_;
  std::map<std::pair<std::size_t, std::string>, int> skipped_;
};

// `bench --list-jobs`: one line per job (of the shard with --shard): index, shard, estimated seconds, kind, id.
void PrintJobs(const std::vector<BenchJob>& jobs, const std::vector<int>& shard, int only_shard, int shards,
               std::ostream& out) {
  double total = 0.0;
  std::size_t listed = 0;
  out << "# job\tshard\test_seconds\tkind\tid\n";
  for (const BenchJob& job : jobs) {
    if (only_shard >= 0 && shard[job.index] != only_shard) continue;
    char cost[32];
    std::snprintf(cost, sizeof cost, "%.3g", job.cost);
    out << job.index + 1 << '\t' << shard[job.index] + 1 << '/' << shards << '\t' << cost << '\t'
        << ToString(job.kind) << '\t' << job.id << '\n';
    total += job.cost;
    ++listed;
  }
  char line[160];
  std::snprintf(line, sizeof line, "# %zu of %zu jobs, estimated %.3g s\n", listed, jobs.size(), total);
  out << line;
}
}  // namespace

int BenchCommand::RunBench(const std::string& command_line, std::ostream& out, std::ostream& err) const {
  const Flags& f = *flags_;
  std::vector<std::string> suites = f.suites;
  if (suites.empty()) suites = {"paper", "families", "hard", "siconos", "mcp"};
  if (std::find(suites.begin(), suites.end(), "all") != suites.end()) {
    suites = {"paper", "families", "hard", "siconos", "scale", "mcp"};
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
  options.polish = !f.no_polish;
  CheckBenchRequest(f, suites);
  const auto [shard, shards] = f.shard.empty() ? std::pair<int, int>{0, 1} : ParseShard(f.shard);
  std::vector<std::string> solvers = f.solvers;
  CreateReplaySolvers(options, &solvers);  // resolves the default (every backend) and checks the settings
  SuiteRequest request;
  request.siconos_dir = f.siconos_dir;
  request.quick = f.quick;
  request.references = false;  // attached by BuildBenchSuites, timed
  if (f.list_jobs) {
    std::ostringstream quiet;
    const std::vector<ProblemSet> sets = BuildBenchSuites(suites, request, false, quiet);
    const std::vector<McpProblemSet> mcp_sets = BuildBenchMcpSuites(suites, f.quick, quiet);
    const std::vector<BenchJob> jobs = RunJobs(f, sets, mcp_sets, options, solvers);
    PrintJobs(jobs, AssignShards(jobs, shards), f.shard.empty() ? -1 : shard, shards, out);
    return 0;
  }
  const std::string out_dir = !f.resume.empty() ? f.resume : f.out.empty() ? DefaultOutputFolder() : f.out;
  {
    std::error_code ec;
    fs::create_directories(out_dir, ec);
    if (ec) throw InvalidInputError("bench: cannot create --out '" + out_dir + "': " + ec.message());
  }
  err << "bench: writing to " << out_dir << "\n";
  const std::vector<ProblemSet> sets = BuildBenchSuites(suites, request, true, err);
  const std::vector<McpProblemSet> mcp_sets = BuildBenchMcpSuites(suites, f.quick, err);
  if (!mcp_sets.empty() && McpSolverNames(solvers).empty()) {
    err << "bench: no chosen backend solves MCPs (`smcbench list` says: accepts nonlinear MCP): the MCP suite is "
           "not run\n";
  }

  RunManifest manifest;
  manifest.command = command_line;
  manifest.environment = RunEnvironment(solvers);
  manifest.options = RunOptionsJson(f, options, solvers);
  for (const ProblemSet& set : sets) {
    SuiteResults suite;
    suite.suite = set.name;
    suite.description = set.description;
    suite.problems = static_cast<int>(set.problems.size());
    suite.checksum = ProblemSetContentChecksum(set);
    manifest.suites.push_back(std::move(suite));
  }
  for (const McpProblemSet& set : mcp_sets) {
    SuiteResults suite;
    suite.suite = set.name;
    suite.description = set.description;
    suite.problems = static_cast<int>(set.problems.size());
    suite.checksum = McpProblemSetChecksum(set);
    manifest.suites.push_back(std::move(suite));
  }
  manifest.jobs = RunJobs(f, sets, mcp_sets, options, solvers);
  manifest.shard = shard;
  manifest.shards = shards;
  manifest.job_shard = AssignShards(manifest.jobs, shards);
  const std::string records_path = (fs::path(out_dir) / "records.jsonl").string();
  std::map<std::size_t, JobLine> done;
  if (!f.resume.empty()) {
    const RunManifest earlier = ReadRunManifest(out_dir);
    std::string why = ManifestMismatch(earlier, manifest);
    if (why.empty() && earlier.shard != shard) {
      why = "another shard (" + std::to_string(earlier.shard + 1) + " vs " + std::to_string(shard + 1) + ")";
    }
    if (!why.empty()) throw InvalidInputError("bench: --resume " + out_dir + ": not the same run: " + why);
    manifest.command = earlier.command;
    manifest.environment = earlier.environment;
    for (JobLine& line : ReadJobLines(records_path, /*truncate_partial=*/true)) done[line.job] = std::move(line);
  } else {
    std::error_code ec;
    fs::remove(records_path, ec);  // --overwrite: a fresh run
    WriteRunManifest(manifest, out_dir);
  }
  std::vector<const BenchJob*> todo;
  for (const BenchJob& job : manifest.jobs) {
    if (manifest.job_shard[job.index] == shard && !done.count(job.index)) todo.push_back(&job);
  }
  if (!f.resume.empty()) {
    err << "bench: resuming " << out_dir << ": " << done.size() << " jobs done, " << todo.size() << " to run\n";
  }
  const bool terminal = &err == &std::cerr && ::isatty(2);
  Progress progress(err, terminal, f.progress_every);
  ShardRunner runner(f, sets, mcp_sets, options, records_path, err);
  runner.stepper_progress = [&](const std::string& what) { progress.Note(what); };
  for (std::size_t k = 0; k < todo.size(); ++k) {
    const BenchJob& job = *todo[k];
    done[job.index] = runner.Run(job);
    const std::string start = job.kind == JobKind::kMcp ? "@" + job.start_label : "";
    progress.Update(k + 1, todo.size(), job.suite_name + " " + job.problem_id + start + " " + job.solver);
  }
  progress.Finish();
  runner.ReportSkipped();

  const BenchResults results = AssembleResults(manifest, done);
  WriteBenchResults(results, out_dir, manifest.environment);
  PrintSummaryTable(results, f.time_limit, out);
  out << "bench: wrote " << (fs::path(out_dir) / "results.json").string() << " and results.csv";
  if (shards > 1) out << " (shard " << shard + 1 << "/" << shards << "; combine the shards with `smcbench merge`)";
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

#include "tools/smcbench/bench_command.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <ostream>
#include <set>

#include "bench/replay/jobs.h"
#include "bench/replay/results_io.h"
#include "bench/replay/warm_track.h"
#include "bench/run/bench_plan.h"
#include "bench/run/run_shard.h"
#include "problems/io/data_dirs.h"
#include "solvers/registry/registry.h"
#include "bench/analysis/report_markdown.h"
#include "tools/smcbench/history_report.h"
#include "tools/smcbench/number_flags.h"
#include "tools/smcbench/solve_report.h"
#include "smcbench/version.h"

namespace smcbench {

namespace fs = std::filesystem;


std::string FormatEta(double elapsed_seconds, double estimated_done, double estimated_total) {
  if (!(estimated_done > 0.0) || !(elapsed_seconds >= 0.0)) return "ETA ?";
  const double left = std::max(0.0, elapsed_seconds * (estimated_total - estimated_done) / estimated_done);
  const long s = std::lround(left);
  char text[48];
  if (s < 60) {
    std::snprintf(text, sizeof text, "ETA %lds", s);
  } else if (s < 3600) {
    std::snprintf(text, sizeof text, "ETA %ldm%02lds", s / 60, s % 60);
  } else {
    std::snprintf(text, sizeof text, "ETA %ldh%02ldm", s / 3600, (s % 3600) / 60);
  }
  return text;
}

// ------------------------------------------------------------------------------------------------------------

struct BenchCommand::Flags {
  std::vector<std::string> suites, solvers, sets, allow_wrong;
  std::vector<std::string> problems;  // --problem GLOB: only the problems whose id matches one (BenchRequest::problems)
  // Empty: a fresh folder ./smcbench-bench-YYYYMMDD-HHMMSS (DefaultOutputFolder), so a run without --out never
  // replaces earlier results, the committed results/bench included.
  std::string out, siconos_dir = DataDirectory(DataFolder::kSiconosCollection), report_dir, history;
  int repetitions = 7;
  double tol = 1e-10, time_limit = 10.0;
  // Seconds one backend may spend on one suite before its remaining problems there are skipped (0: no limit).
  double backend_budget = 60.0;
  double job_budget = kDefaultJobBudgetSeconds, sequence_budget = kDefaultSequenceBudgetSeconds;
  bool full = false;  // no budget at all: the full campaign
  double progress_every = 5.0;  // seconds between progress lines when stderr is not a terminal (0: none)
  // --shard K/N (empty: the whole run), --resume DIR (empty: a fresh run), --list-jobs.
  std::string shard, resume;
  bool list_jobs = false;
  bool overwrite = false, stepper = false, no_stepper = false, quick = false, report = false, no_plots = false,
       report_no_plots = false, no_polish = false, no_warm = false;
};

BenchCommand::BenchCommand(CLI::App* app) : flags_(std::make_unique<Flags>()) {
  Flags& f = *flags_;
  bench_ = app->add_subcommand("bench", "replay problem suites on every backend: status, iterations, both "
                                        "residuals, forward error, verdict, median time and spread → "
                                        "DIR/results.{json,csv}. Exit status 3 when any answer is wrong (wrongly "
                                        "claimed, inaccurate or wrongly refused) on a backend not named by "
                                        "--allow-wrong, after writing the results (and report)");
  bench_->add_option("--suite", f.suites,
                     "paper | families | hard | siconos | scale | tiny | mcp | avi | all | FILE (repeatable; "
                     "default: paper families hard siconos mcp avi; mcp: the nonlinear MCPs, problem x start, on the "
                     "backends that solve MCPs; avi: affine variational inequalities over polytopes, through their "
                     "reduction on every box backend)");
  bench_->add_option("--problem", f.problems,
                     "run only the problems whose id matches GLOB ('*' any characters, '/' included; '?' one), e.g. "
                     "'families/murty/*' or 'mcp/classic/*' (repeatable: a problem runs when it matches any), in "
                     "every suite: box problems, MCPs, AVIs, warm sequences by their id (<suite>/warm/...); a suite "
                     "left with none is left out, no stepper study unless --stepper; a GLOB that matches no problem "
                     "is an error. Recorded in the manifest: --resume and merge need the same")
      ->type_name("GLOB");
  bench_->add_option("--solver", f.solvers, "backend (repeatable; default: every registered backend)");
  bench_->add_option("--set", f.sets, "typed backend option BACKEND.OPTION=VALUE (see `smcbench list`)");
  bench_->add_option("--out", f.out, "output folder (default: a fresh ./smcbench-bench-YYYYMMDD-HHMMSS); a folder "
                                     "that already holds results.json is refused unless --overwrite");
  bench_->add_flag("--overwrite", f.overwrite, "let --out name a folder with earlier results (tools/bench.sh "
                                               "passes it for results/bench)");
  bench_->add_option("--siconos-dir", f.siconos_dir, "the Siconos collection (default: $SMCBENCH_SICONOS_DIR, else "
                                                     "share/smcbench/siconos of this installation, else the "
                                                     "checkout's tests/data/siconos)");
  bench_->add_option("--repetitions", f.repetitions, "timing samples per problem x backend (default 7)")
      ->check(PositiveInteger());
  bench_->add_option("--tol", f.tol, "tolerance on the relative and the row-equilibrated natural residual "
                                     "(default 1e-10)")
      ->check(PositiveNumber());
  bench_->add_option("--time-limit", f.time_limit, "seconds per solve (default 10)")->check(PositiveNumber());
  bench_->add_option("--backend-budget", f.backend_budget,
                     "seconds one backend may spend on one suite (default 60, 0: no limit); past it the backend's "
                     "remaining problems of that suite are skipped and recorded as time limit, with a message")
      ->check(NonNegativeNumber());
  bench_->add_option("--job-budget", f.job_budget,
                     "seconds one cold job (problem x backend, a sweep rung, an MCP or AVI job) may take (default 1, "
                     "0: no limit): its solves run under min(--time-limit, S) and its timed samples stop after S/2; a "
                     "solve stopped by it cuts the job, recorded with mode cut (no verdict: neither solved nor failed)")
      ->check(NonNegativeNumber());
  bench_->add_option("--sequence-budget", f.sequence_budget,
                     "seconds one warm sequence x backend may take (default 1, 0: no limit): its solves run under "
                     "min(--time-limit, S), its untimed pass stops before a step that would pass S and the record "
                     "says 'cut after N of M steps' (mode cut, no verdict); a pass over S/2 is timed once, and "
                     "timed passes run only while they end inside S")
      ->check(NonNegativeNumber());
  bench_->add_flag("--full", f.full, "the full campaign: no budget (--job-budget 0 --sequence-budget 0 "
                                     "--backend-budget 0): every job runs to its time limit, every sequence to its "
                                     "end; tools/bench.sh --full");
  bench_->add_option("--progress-every", f.progress_every, "seconds between progress lines on stderr when it is "
                                                           "not a terminal (default 5, 0: none)")
      ->check(NonNegativeNumber());
  bench_->add_flag("--stepper", f.stepper, "run the time-stepper studies (warm/cold, work-precision on the paper's "
                                           "scenes) whatever the suites (default: only with suite paper or all)");
  bench_->add_flag("--no-stepper", f.no_stepper, "skip the time-stepper studies, even with suite paper or all");
  bench_->add_flag("--no-warm", f.no_warm, "skip the warm track (sequences of one-step problems replayed in order, "
                                           "each backend warm-started from the previous step: suites paper, "
                                           "families and problem-set files)");
  bench_->add_flag("--quick", f.quick, "smaller suites and fewer samples (CI)");
  bench_->add_flag("--report", f.report, "also write DIR/report.md (as `smcbench report DIR`)");
  bench_->add_flag("--no-plots", f.no_plots, "with --report: no PNG plots");
  bench_->add_flag("--no-polish", f.no_polish, "no exact polish of the backends' answers (SolverOptions::polish = "
                                              "false): time a raw algorithm");
  bench_->add_option("--allow-wrong", f.allow_wrong, "glob PATTERN of backends whose wrong answers do not set exit "
                                                     "status 3 (still reported), e.g. 'siconos-*', or `external`: "
                                                     "every adapter to another library (repeatable)")
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
// is seen to move. Short runs stay quiet either way. The runner's messages are lines of their own.
class Progress : public BenchProgress {
 public:
  Progress(std::ostream& err, bool terminal, double every)
      : err_(err), terminal_(terminal), every_(every), start_(Clock::now()), last_line_(start_) {}
  void Update(std::size_t done, std::size_t total, const std::string& what) {
    if (total == 0) return;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    const std::string eta = FormatEta(elapsed, estimated_done_, estimated_total_);
    if (!terminal_) {
      if (!(every_ > 0.0) || std::chrono::duration<double>(Clock::now() - last_line_).count() < every_) return;
      last_line_ = Clock::now();
      char line[260];
      std::snprintf(line, sizeof line, "bench: %zu/%zu (%zu%%) after %.0f s, %s: %.160s", done, total,
                    100 * done / total, elapsed, eta.c_str(), what.c_str());
      err_ << line << "\n" << std::flush;
      return;
    }
    if (elapsed < 2.0 && done < total) return;  // short runs stay quiet
    const int width = 30, filled = static_cast<int>(width * done / total);
    char line[180];
    std::snprintf(line, sizeof line, "\r[%s%s] %3zu%% %.0fs %-12s %-50.50s", std::string(filled, '#').c_str(),
                  std::string(width - filled, '.').c_str(), 100 * done / total, elapsed, eta.c_str(), what.c_str());
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
  void JobFinished(std::size_t finished, std::size_t total, const std::string& what, double estimated_done,
                   double estimated_total) override {
    estimated_done_ = estimated_done;
    estimated_total_ = estimated_total;
    Update(finished, total, what);
  }
  void Phase(const std::string& what) override { Note(what); }
  void Message(const std::string& line) override { err_ << "bench: " << line << "\n"; }

 private:
  using Clock = std::chrono::steady_clock;
  std::ostream& err_;
  bool terminal_;
  double every_;
  Clock::time_point start_, last_line_;
  double estimated_done_ = 0.0, estimated_total_ = 0.0;  // BenchJob::estimate of the jobs run, of all (the ETA)
};

// The --allow-wrong value naming every adapter to another library (siconos-*, bullet-*, dart-*: SolverInfo::external),
// so that the main job need not list the peers' prefixes.
constexpr std::string_view kAllowWrongExternal = "external";

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
        excused += std::any_of(allow_wrong.begin(), allow_wrong.end(), [&](const std::string& pattern) {
          return pattern == kAllowWrongExternal ? IsExternalBackendName(r.solver) : GlobMatch(pattern, r.solver);
        });
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

// The checks of the flags that are the command's own (folders, shards, patterns); the request's own checks are
// CheckBenchRequest's (bench/run/bench_plan.h). Nothing is created here.
void CheckBenchFlags(const BenchCommand::Flags& f) {
  if (f.stepper && f.no_stepper) throw InvalidInputError("bench: give --stepper or --no-stepper, not both");
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

// The engine's request from the flags.
BenchRequest MakeRequest(const BenchCommand::Flags& f) {
  BenchRequest request;
  request.suites = f.suites;
  request.problems = f.problems;
  request.solvers = f.solvers;
  request.settings = f.sets;
  request.siconos_dir = f.siconos_dir;
  request.tolerance = f.tol;
  request.time_limit_seconds = f.time_limit;
  request.repetitions = f.repetitions;
  request.backend_budget_seconds = f.full ? 0.0 : f.backend_budget;
  request.job_budget_seconds = f.full ? 0.0 : f.job_budget;
  request.sequence_budget_seconds = f.full ? 0.0 : f.sequence_budget;
  request.quick = f.quick;
  request.polish = !f.no_polish;
  request.stepper = f.stepper      ? StepperStudyChoice::kAlways
                    : f.no_stepper ? StepperStudyChoice::kNever
                                   : StepperStudyChoice::kIfSceneSuite;
  request.certify = !f.list_jobs;  // the job list does not depend on the references
  request.warm = !f.no_warm;
  return request;
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
  std::size_t cut = 0;
  for (const SuiteResults& full : results.suites) {
    // Records cut by a budget have no verdict: they count in no column (the report lists them).
    SuiteResults suite = full;
    const auto is_cut = [](const ReplayRecord& r) { return r.mode == kCutMode; };
    auto& records = suite.replay.records;
    cut += static_cast<std::size_t>(std::count_if(records.begin(), records.end(), is_cut));
    records.erase(std::remove_if(records.begin(), records.end(), is_cut), records.end());
    for (const WarmRecord& w : suite.warm) cut += is_cut(w.record);
    // A suite run for its warm sequences alone (`--problem 'families/warm/*'`): its warm track's counts.
    if (records.empty() && suite.replay.sweep.empty() && !suite.warm.empty()) {
      suite = WarmTrackAsSuite(suite);
      records.erase(std::remove_if(records.begin(), records.end(), is_cut), records.end());
    }
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
  if (cut > 0) {
    out << cut << " job" << (cut == 1 ? "" : "s") << " cut by a time budget (mode cut: no verdict, in no column "
        << "above; --full runs everything)\n";
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

// `bench --list-jobs`: one line per job (of the shard with --shard): index, shard, estimated seconds, kind, id.
void PrintJobs(const std::vector<BenchJob>& jobs, const std::vector<int>& shard, int only_shard, int shards,
               std::ostream& out) {
  double total = 0.0;
  std::size_t listed = 0;
  out << "# job\tshard\test_seconds\tkind\tid\n";
  for (const BenchJob& job : jobs) {
    if (only_shard >= 0 && shard[job.index] != only_shard) continue;
    char cost[32];
    std::snprintf(cost, sizeof cost, "%.3g", job.estimate);
    out << job.index + 1 << '\t' << shard[job.index] + 1 << '/' << shards << '\t' << cost << '\t'
        << JobKindName(job) << '\t' << job.id << '\n';
    total += job.estimate;
    ++listed;
  }
  char line[240];
  std::snprintf(line, sizeof line, "# %zu of %zu jobs, estimated %.3g s (each backend's job costs measured on this "
                "machine by a probe; building and certifying the suites not included)\n", listed, jobs.size(), total);
  out << line;
}
}  // namespace

int BenchCommand::RunBench(const std::string& command_line, std::ostream& out, std::ostream& err) const {
  const Flags& f = *flags_;
  const BenchRequest request = MakeRequest(f);
  CheckBenchRequest(request);  // a typo fails in a second, before any suite is built
  CheckBenchFlags(f);
  const auto [shard, shards] = f.shard.empty() ? std::pair<int, int>{0, 1} : ParseShard(f.shard);
  if (f.list_jobs) {
    const BenchPlan plan = MakeBenchPlan(request);
    PrintJobs(plan.jobs, AssignShards(plan.jobs, shards), f.shard.empty() ? -1 : shard, shards, out);
    return 0;
  }
  // Every suite is built and certified before the folder is made: a bad problem-set file leaves nothing behind.
  const BenchPlan plan = MakeBenchPlan(request, [&](const std::string& line) { err << "bench: " << line << "\n"; });
  const std::string out_dir = !f.resume.empty() ? f.resume : f.out.empty() ? DefaultOutputFolder() : f.out;

  RunManifest manifest;
  manifest.command = command_line;
  manifest.environment = RunEnvironment(plan.solvers);
  manifest.options = PlanOptionsJson(plan);
  manifest.suites = PlanSuites(plan);
  manifest.jobs = plan.jobs;
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
    fs::create_directories(out_dir, ec);
    if (ec) throw InvalidInputError("bench: cannot create --out '" + out_dir + "': " + ec.message());
    fs::remove(records_path, ec);  // --overwrite: a fresh run
    WriteRunManifest(manifest, out_dir);
  }
  err << "bench: writing to " << out_dir << "\n";
  std::set<std::size_t> finished;
  for (const auto& [index, line] : done) finished.insert(index);
  if (!f.resume.empty()) {
    std::size_t todo = 0;
    for (const BenchJob& job : plan.jobs) todo += manifest.job_shard[job.index] == shard && !finished.count(job.index);
    err << "bench: resuming " << out_dir << ": " << done.size() << " jobs done, " << todo << " to run\n";
  }
  const bool terminal = &err == &std::cerr && ::isatty(2);
  Progress progress(err, terminal, f.progress_every);
  JobLineWriter writer(records_path);
  const ShardSummary summary = RunShard(plan, {shard, shards}, finished, [&](const JobLine& line) {
    writer.Write(line);
    done[line.job] = line;
  }, &progress);
  progress.Finish();
  for (const BudgetSkip& skip : summary.skipped) {
    err << "bench: " << skip.solver << " skipped " << skip.skipped << " of " << skip.problems
        << " " << skip.units << " of suite " << skip.suite
        << " after spending its budget of " << f.backend_budget << " s (--backend-budget; recorded as cut)\n";
  }

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

#include "bench/replay/jobs.h"

#include <signal.h>
#include <sys/types.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <map>
#include <fstream>
#include <numeric>
#include <set>

#include "bench/replay/floor.h"
#include "solvers/core/number_text.h"

namespace smcbench {

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

std::uint64_t Fnv1a64(const std::string& text) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

JobKind JobKindFromText(const std::string& text, const std::string& where) {
  for (JobKind k : {JobKind::kCold, JobKind::kGenericSparse, JobKind::kSweep, JobKind::kStepper, JobKind::kMcp,
                    JobKind::kWarm, JobKind::kAvi, JobKind::kFloor}) {
    if (text == ToString(k)) return k;
  }
  throw InvalidInputError(where + ": unknown job kind '" + text + "'");
}

BackendCost CostOf(const JobListRequest& request, const std::string& solver) {
  const auto it = request.costs.find(solver);
  return it == request.costs.end() ? BackendCost{} : it->second;
}

std::string JobId(const BenchJob& job) {
  if (job.kind == JobKind::kStepper) return "stepper";
  const char* mode = job.kind == JobKind::kSweep   ? "sweep"
                     : job.kind == JobKind::kWarm  ? "warm"
                     : job.kind == JobKind::kFloor ? kFloorSolver
                                                   : "cold";
  if (job.kind == JobKind::kMcp || (job.kind == JobKind::kFloor && !job.start_label.empty())) {
    return job.suite_name + "|" + job.problem_id + "@" + job.start_label + "|" + job.solver + "|" + mode + "|" +
           NumberText(job.tolerance);
  }
  return job.suite_name + "|" + job.problem_id + "|" + job.solver + "|" + mode + "|" + NumberText(job.tolerance);
}

// The backend budget in the estimates, as a single run applies it (run_shard.cc, OverBudget): in job order, a
// backend's jobs on a suite run until their estimates add up to the budget, the rest are not run. The floor and the
// stepper are nobody's budget. Only the estimates change (the shards' costs stay machine-independent).
void ApplyBackendBudget(double budget_seconds, std::vector<BenchJob>* jobs) {
  if (!(budget_seconds > 0.0)) return;
  std::map<std::pair<std::size_t, std::string>, double> spent;
  for (BenchJob& job : *jobs) {
    if (job.kind == JobKind::kFloor || job.kind == JobKind::kStepper) continue;
    double& so_far = spent[{job.suite, job.solver}];
    if (so_far >= budget_seconds) {
      job.estimate = kNotRunJobSeconds;
    } else {
      so_far += job.estimate;
    }
  }
}

}  // namespace

const char* ToString(JobKind kind) {
  switch (kind) {
    case JobKind::kCold: return "cold";
    case JobKind::kGenericSparse: return "generic-sparse";
    case JobKind::kSweep: return "sweep";
    case JobKind::kStepper: return "stepper";
    case JobKind::kMcp: return "mcp";
    case JobKind::kWarm: return "warm";
    case JobKind::kAvi: return "avi";
    case JobKind::kFloor: return "floor";
  }
  return "?";
}

std::string StableHashHex(const std::string& text) {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(Fnv1a64(text)));
  return hex;
}

namespace {

// Seconds of a job whose one solve takes solve seconds: the warm-up (capped by the per-solve limit), then samples
// of at least min_sample_seconds each until repetitions or the sampling cap; a solve that reaches the limit is
// timed once. What a tiny solve's job costs is in job_seconds already, so only the excess over it is added.
double ColdJobSeconds(double solve, const ReplayOptions& options, int repetitions, const BackendCost& cost,
                      const JobBudgets& budgets) {
  const bool budgeted = budgets.job_seconds > 0.0;
  const double limit = budgeted ? std::min(options.time_limit_seconds, budgets.job_seconds)
                                : options.time_limit_seconds;
  const double cap = budgeted ? std::min(options.max_seconds_per_pair, 0.5 * budgets.job_seconds)
                              : options.max_seconds_per_pair;
  const auto job = [&](double t) {
    if (t >= limit) return limit;
    // Sampling stops once past the cap: at most the cap plus the sample running then.
    const double sample = std::max(options.min_sample_seconds, t);
    return t + std::min(repetitions * sample, cap + sample);
  };
  return cost.job_seconds + std::max(0.0, job(solve) - job(0.0));
}

double Units(const LibraryProblem& problem) {
  const double m = problem.size();
  const double nnz = problem.problem.is_sparse() ? static_cast<double>(problem.problem.sparse_matrix().nonZeros())
                                                 : m * m;
  return m * (m + nnz);
}

}  // namespace

double EstimateJobSeconds(const LibraryProblem& problem, const ReplayOptions& options, JobKind kind,
                          const BackendCost& cost, const JobBudgets& budgets) {
  const int repetitions = kind == JobKind::kSweep ? std::min(options.repetitions, 3) : options.repetitions;
  return ColdJobSeconds(cost.seconds_per_unit * Units(problem), options, repetitions, cost, budgets);
}

double EstimateMcpJobSeconds(const McpLibraryProblem& problem, const ReplayOptions& options,
                             const BackendCost& cost, const JobBudgets& budgets) {
  const double n = problem.size();
  const double solve = 20.0 * cost.seconds_per_unit * n * (n + (problem.sparse() ? 10.0 * n : n * n));
  return ColdJobSeconds(solve, options, options.repetitions, cost, budgets);
}

double EstimateAviJobSeconds(const AviLibraryProblem& problem, const ReplayOptions& options,
                             const BackendCost& cost, const JobBudgets& budgets) {
  if (!problem.problem) return 0.0;
  const AffineVI& avi = *problem.problem;
  const double rows = avi.size() + avi.inequality_count() + avi.equality_count();
  const double solve = 2.0 * cost.seconds_per_unit * rows * 2.0 * rows * rows;
  return ColdJobSeconds(solve, options, options.repetitions, cost, budgets);
}

double EstimateWarmJobSeconds(const WarmSequence& sequence, const ReplayOptions& options, const BackendCost& cost,
                              const JobBudgets& budgets) {
  if (sequence.steps.empty()) return 0.0;
  // A step: the cold guess, but at least the ≈ 1 µs fixed cost of a call.
  const double step = std::max(cost.seconds_per_unit * Units(sequence.steps.front()), 1e-6);
  const double pass = static_cast<double>(sequence.steps.size()) * step;
  const double budget = budgets.sequence_seconds;
  if (budget > 0.0 && pass > budget) return cost.job_seconds + budget;     // cut before the step that would pass it
  if (budget > 0.0 && pass > 0.5 * budget) return cost.job_seconds + pass;  // the untimed pass is the sample
  double timed = std::min(options.repetitions * pass, options.max_seconds_per_pair + pass);
  if (budget > 0.0) timed = std::min(timed, std::max(pass, budget - pass));  // passes that end inside the budget
  return cost.job_seconds + pass + timed;
}

std::vector<BenchJob> ListBenchJobs(const std::vector<ProblemSet>& suites, const ReplayOptions& options,
                                    const JobListRequest& request) {
  return ListBenchJobs(suites, {}, options, request);
}

std::vector<BenchJob> ListBenchJobs(const std::vector<ProblemSet>& suites,
                                    const std::vector<McpProblemSet>& mcp_suites,
                                    const ReplayOptions& options, const JobListRequest& request) {
  return ListBenchJobs(suites, mcp_suites, {}, options, request);
}

std::vector<BenchJob> ListBenchJobs(const std::vector<ProblemSet>& suites,
                                    const std::vector<McpProblemSet>& mcp_suites,
                                    const std::vector<AviProblemSet>& avi_suites, const ReplayOptions& options,
                                    const JobListRequest& request) {
  std::vector<BenchJob> jobs;
  const auto add = [&](JobKind kind, std::size_t s, std::size_t p, const std::string& solver, double tolerance) {
    BenchJob job;
    job.index = jobs.size();
    job.kind = kind;
    job.suite = s;
    job.problem = p;
    job.suite_name = suites[s].name;
    job.problem_id = suites[s].problems[p].id;
    job.solver = solver;
    job.tolerance = tolerance;
    job.cost = EstimateJobSeconds(suites[s].problems[p], options, kind, {}, request.budgets);
    job.estimate = EstimateJobSeconds(suites[s].problems[p], options, kind, CostOf(request, solver), request.budgets);
    job.id = JobId(job);
    jobs.push_back(std::move(job));
  };
  for (std::size_t s = 0; s < suites.size(); ++s) {
    const std::size_t n = suites[s].problems.size();
    for (std::size_t p = 0; p < n; ++p) {
      for (const std::string& solver : request.solvers) add(JobKind::kCold, s, p, solver, options.tolerance);
    }
    if (request.floor && !request.solvers.empty()) {
      for (std::size_t p = 0; p < n; ++p) add(JobKind::kFloor, s, p, kFloorSolver, options.tolerance);
    }
    if (request.generic_sparse_path && suites[s].name == "paper") {
      for (std::size_t p = 0; p < n; ++p) add(JobKind::kGenericSparse, s, p, kGenericSparsePath, options.tolerance);
    }
    for (const std::size_t p : SweepProblemIndices(n, options.tolerance_sweep_problems)) {
      for (const std::string& solver : request.solvers) {
        for (const double tol : kSweepTolerances) add(JobKind::kSweep, s, p, solver, tol);
      }
    }
  }
  // The backends of the MCP (AVI) jobs, then the floor when it is asked for and some backend runs there.
  const auto with_floor = [&](std::vector<std::string> names) {
    if (request.floor && !names.empty()) names.push_back(kFloorSolver);
    return names;
  };
  const std::vector<std::string> mcp_jobs = with_floor(request.mcp_solvers), avi_jobs = with_floor(request.avi_solvers);
  for (std::size_t k = 0; k < mcp_suites.size(); ++k) {
    const McpProblemSet& set = mcp_suites[k];
    for (std::size_t p = 0; p < set.problems.size(); ++p) {
      const McpLibraryProblem& problem = set.problems[p];
      for (std::size_t start = 0; start < problem.starts.size(); ++start) {
        for (const std::string& solver : mcp_jobs) {
          BenchJob job;
          job.index = jobs.size();
          job.kind = solver == kFloorSolver ? JobKind::kFloor : JobKind::kMcp;
          job.suite = suites.size() + k;
          job.problem = p;
          job.start = start;
          job.suite_name = set.name;
          job.problem_id = problem.id;
          job.start_label = start < problem.start_labels.size() ? problem.start_labels[start] : "";
          job.solver = solver;
          job.tolerance = options.tolerance;
          job.cost = EstimateMcpJobSeconds(problem, options, {}, request.budgets);
          job.estimate = EstimateMcpJobSeconds(problem, options, CostOf(request, solver), request.budgets);
          job.id = JobId(job);
          jobs.push_back(std::move(job));
        }
      }
    }
  }
  for (std::size_t k = 0; k < avi_suites.size(); ++k) {
    const AviProblemSet& set = avi_suites[k];
    for (std::size_t p = 0; p < set.problems.size(); ++p) {
      for (const std::string& solver : avi_jobs) {
        BenchJob job;
        job.index = jobs.size();
        job.kind = solver == kFloorSolver ? JobKind::kFloor : JobKind::kAvi;
        job.suite = suites.size() + mcp_suites.size() + k;
        job.problem = p;
        job.suite_name = set.name;
        job.problem_id = set.problems[p].id;
        job.solver = solver;
        job.tolerance = options.tolerance;
        job.cost = EstimateAviJobSeconds(set.problems[p], options, {}, request.budgets);
        job.estimate = EstimateAviJobSeconds(set.problems[p], options, CostOf(request, solver), request.budgets);
        job.id = JobId(job);
        jobs.push_back(std::move(job));
      }
    }
  }
  if (request.warm) {
    for (std::size_t s = 0; s < suites.size() && s < request.warm->size(); ++s) {
      const std::vector<WarmSequence>& sequences = (*request.warm)[s];
      for (std::size_t q = 0; q < sequences.size(); ++q) {
        for (const std::string& solver : request.solvers) {
          BenchJob job;
          job.index = jobs.size();
          job.kind = JobKind::kWarm;
          job.suite = s;
          job.problem = q;
          job.suite_name = suites[s].name;
          job.problem_id = sequences[q].id;
          job.solver = solver;
          job.tolerance = options.tolerance;
          job.cost = EstimateWarmJobSeconds(sequences[q], options, {}, request.budgets);
          job.estimate = EstimateWarmJobSeconds(sequences[q], options, CostOf(request, solver), request.budgets);
          job.id = JobId(job);
          jobs.push_back(std::move(job));
        }
      }
    }
  }
  if (request.stepper) {
    BenchJob job;
    job.index = jobs.size();
    job.kind = JobKind::kStepper;
    // Measured (`bench --suite paper`, its line "time-stepper studies took"): 112 s for the full studies (6
    // refinements) on a 2-core Xeon; 29-30 s for 5 refinements under a job budget on a 2-core AMD EPYC (2026-12,
    // with the step verdict's cached path).
    job.cost = options.repetitions <= 3 ? 3.0 : request.budgets.job_seconds > 0.0 ? 30.0 : 120.0;
    job.estimate = job.cost;
    job.id = JobId(job);
    jobs.push_back(std::move(job));
  }
  ApplyBackendBudget(request.budgets.backend_seconds, &jobs);
  return jobs;
}

std::vector<int> AssignShards(const std::vector<BenchJob>& jobs, int shards) {
  std::vector<std::size_t> order(jobs.size());
  std::iota(order.begin(), order.end(), 0);
  std::vector<std::uint64_t> hash(jobs.size());
  for (std::size_t i = 0; i < jobs.size(); ++i) hash[i] = Fnv1a64(jobs[i].id);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (jobs[a].cost != jobs[b].cost) return jobs[a].cost > jobs[b].cost;
    return hash[a] != hash[b] ? hash[a] < hash[b] : a < b;
  });
  std::vector<double> load(std::max(shards, 1), 0.0);
  std::vector<int> shard(jobs.size(), 0);
  for (std::size_t i : order) {
    const int least = static_cast<int>(std::min_element(load.begin(), load.end()) - load.begin());
    shard[i] = least;
    load[least] += jobs[i].cost;
  }
  return shard;
}

std::pair<int, int> ParseShard(const std::string& text) {
  const auto slash = text.find('/');
  int k = 0, n = 0;
  try {
    std::size_t used_k = 0, used_n = 0;
    if (slash == std::string::npos) throw std::invalid_argument("no slash");
    k = std::stoi(text.substr(0, slash), &used_k);
    n = std::stoi(text.substr(slash + 1), &used_n);
    if (used_k != slash || used_n != text.size() - slash - 1) throw std::invalid_argument("trailing text");
  } catch (const std::exception&) {
    throw InvalidInputError("bench: --shard expects K/N with 1 <= K <= N, got '" + text + "'");
  }
  if (n < 1 || k < 1 || k > n) throw InvalidInputError("bench: --shard expects K/N with 1 <= K <= N, got '" + text + "'");
  return {k - 1, n};
}

// ------------------------------------------------------------------------------------------------------------

HostActivity::HostActivity() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) std::snprintf(name, sizeof name, "unknown");
  host_ = name;
  const char* configured = std::getenv("SMCBENCH_ACTIVITY_DIR");
  std::error_code ec;
  dir_ = configured && *configured ? std::string(configured)
                                   : (fs::temp_directory_path(ec) / ("smcbench-activity-" + std::to_string(::getuid())))
                                         .string();
  fs::create_directories(dir_, ec);
  own_file_ = (fs::path(dir_) / std::to_string(::getpid())).string();
  std::ofstream(own_file_) << host_ << "\n";
}

HostActivity::~HostActivity() {
  std::error_code ec;
  fs::remove(own_file_, ec);
}

int HostActivity::Count() const {
  int alive = 0;
  std::error_code ec;
  for (fs::directory_iterator it(dir_, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos) continue;
    const pid_t pid = static_cast<pid_t>(std::stol(name));
    if (::kill(pid, 0) == 0 || errno == EPERM) {
      ++alive;
    } else {
      std::error_code ignored;
      fs::remove(it->path(), ignored);  // a process killed before it could remove its file
    }
  }
  return std::max(alive, 1);  // this process counts even if its file could not be written
}

// ------------------------------------------------------------------------------------------------------------

json JobLineToJson(const JobLine& line) {
  json j = {{"job", line.job}, {"id", line.id}, {"host", line.host}, {"concurrent_jobs", line.concurrent_jobs}};
  if (std::isfinite(line.seconds)) j["seconds"] = line.seconds;
  if (line.skipped) j["skipped"] = true;
  if (line.has_record) j["record"] = ReplayRecordToJson(line.record);
  if (line.has_stepper) j["stepper"] = StepperStudyToJson(line.stepper);
  if (line.has_warm) j["warm_record"] = WarmRecordToJson(line.warm);
  return j;
}

JobLineWriter::JobLineWriter(const std::string& path) : path_(path), file_(std::fopen(path.c_str(), "a")) {
  if (!file_) throw InvalidInputError("bench: cannot append to '" + path + "'");
}

JobLineWriter::~JobLineWriter() {
  if (file_) std::fclose(file_);
}

void JobLineWriter::Write(const JobLine& line) {
  const std::string text = JobLineToJson(line).dump() + "\n";
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size() || std::fflush(file_) != 0) {
    throw InvalidInputError("bench: cannot write '" + path_ + "'");
  }
}

std::vector<JobLine> ReadJobLines(const std::string& path, bool truncate_partial) {
  std::vector<JobLine> lines;
  std::ifstream in(path, std::ios::binary);
  if (!in) return lines;
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  std::size_t start = 0, number = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    if (end == std::string::npos) break;  // a partial last line: its job is not done
    ++number;
    const std::string where = path + " line " + std::to_string(number);
    try {
      const json j = json::parse(text.begin() + static_cast<std::ptrdiff_t>(start),
                                 text.begin() + static_cast<std::ptrdiff_t>(end));
      JobLine line;
      line.job = j.at("job").get<std::size_t>();
      line.id = j.at("id").get<std::string>();
      line.host = j.value("host", std::string());
      line.concurrent_jobs = j.value("concurrent_jobs", 0);
      line.seconds = j.value("seconds", kNaN);
      line.skipped = j.value("skipped", false);
      if (j.contains("record")) line.has_record = true, line.record = ReplayRecordFromJson(j.at("record"));
      if (j.contains("stepper")) line.has_stepper = true, line.stepper = StepperStudyFromJson(j.at("stepper"));
      if (j.contains("warm_record")) line.has_warm = true, line.warm = WarmRecordFromJson(j.at("warm_record"));
      lines.push_back(std::move(line));
    } catch (const json::exception& e) {
      throw InvalidInputError(where + ": malformed job line: " + e.what());
    } catch (const InvalidInputError& e) {
      throw InvalidInputError(where + ": " + e.what());
    }
    start = end + 1;
  }
  if (truncate_partial && start < text.size()) {
    std::error_code ec;
    fs::resize_file(path, start, ec);
    if (ec) throw InvalidInputError("bench: cannot cut the partial last line of '" + path + "': " + ec.message());
  }
  return lines;
}

// ------------------------------------------------------------------------------------------------------------

json RunManifestToJson(const RunManifest& m) {
  json j;
  j["format"] = "smcbench-run/1";
  j["command"] = m.command;
  j["environment"] = m.environment;
  j["options"] = m.options;
  j["suites"] = json::array();
  for (const SuiteResults& s : m.suites) {
    j["suites"].push_back(
        {{"suite", s.suite}, {"description", s.description}, {"problems", s.problems}, {"checksum", s.checksum}});
  }
  j["shard"] = {{"index", m.shard + 1}, {"count", m.shards}};
  j["jobs"] = json::array();
  for (std::size_t i = 0; i < m.jobs.size(); ++i) {
    const BenchJob& b = m.jobs[i];
    j["jobs"].push_back({{"id", b.id}, {"kind", ToString(b.kind)}, {"suite", b.suite}, {"problem", b.problem},
                         {"suite_name", b.suite_name}, {"problem_id", b.problem_id}, {"solver", b.solver},
                         {"tolerance", b.tolerance}, {"cost", b.cost}, {"shard", m.job_shard.at(i) + 1}});
    if (b.kind == JobKind::kMcp || !b.start_label.empty()) j["jobs"].back()["start"] = {{"index", b.start}, {"label", b.start_label}};
  }
  return j;
}

RunManifest RunManifestFromJson(const json& j, const std::string& where) {
  try {
    if (j.value("format", "") != "smcbench-run/1") throw InvalidInputError(where + ": format is not smcbench-run/1");
    RunManifest m;
    m.command = j.at("command").get<std::string>();
    m.environment = j.at("environment");
    m.options = j.at("options");
    for (const json& s : j.at("suites")) {
      SuiteResults suite;
      suite.suite = s.at("suite").get<std::string>();
      suite.description = s.at("description").get<std::string>();
      suite.problems = s.at("problems").get<int>();
      suite.checksum = s.at("checksum").get<std::string>();
      m.suites.push_back(std::move(suite));
    }
    m.shard = j.at("shard").at("index").get<int>() - 1;
    m.shards = j.at("shard").at("count").get<int>();
    for (const json& b : j.at("jobs")) {
      BenchJob job;
      job.index = m.jobs.size();
      job.id = b.at("id").get<std::string>();
      job.kind = JobKindFromText(b.at("kind").get<std::string>(), where);
      job.suite = b.at("suite").get<std::size_t>();
      job.problem = b.at("problem").get<std::size_t>();
      job.suite_name = b.at("suite_name").get<std::string>();
      job.problem_id = b.at("problem_id").get<std::string>();
      job.solver = b.at("solver").get<std::string>();
      job.tolerance = b.at("tolerance").get<double>();
      job.cost = b.at("cost").get<double>();
      job.estimate = job.cost;
      if (job.kind == JobKind::kMcp || b.contains("start")) {  // an MCP job, or an MCP problem's floor job
        job.start = b.at("start").at("index").get<std::size_t>();
        job.start_label = b.at("start").at("label").get<std::string>();
      }
      if (job.kind != JobKind::kStepper && job.suite >= m.suites.size()) {
        throw InvalidInputError(where + ": job " + job.id + " names suite " + std::to_string(job.suite));
      }
      m.job_shard.push_back(b.at("shard").get<int>() - 1);
      m.jobs.push_back(std::move(job));
    }
    return m;
  } catch (const json::exception& e) {
    throw InvalidInputError(where + ": malformed: " + e.what());
  }
}

void WriteRunManifest(const RunManifest& manifest, const std::string& dir) {
  const fs::path path = fs::path(dir) / "manifest.json";
  const fs::path partial = fs::path(dir) / "manifest.json.partial";
  {
    std::ofstream out(partial);
    out << RunManifestToJson(manifest).dump(1) << "\n";
    if (!out) throw InvalidInputError("bench: cannot write " + partial.string());
  }
  std::error_code ec;
  fs::rename(partial, path, ec);
  if (ec) throw InvalidInputError("bench: cannot write " + path.string() + ": " + ec.message());
}

RunManifest ReadRunManifest(const std::string& dir) {
  const fs::path path = fs::path(dir) / "manifest.json";
  std::ifstream in(path);
  if (!in) throw InvalidInputError("cannot read '" + path.string() + "' (not a folder `smcbench bench` wrote)");
  const json j = json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) throw InvalidInputError("'" + path.string() + "' is not valid JSON");
  return RunManifestFromJson(j, path.string());
}

std::string ManifestMismatch(const RunManifest& a, const RunManifest& b) {
  const auto differ = [](const std::string& what, const json& x, const json& y) -> std::string {
    if (x == y) return "";
    if (x.is_object() && y.is_object()) {  // name the first differing field
      for (const auto& [key, value] : x.items()) {
        if (!y.contains(key)) return what + "." + key + ": '" + value.dump() + "' vs none";
        if (y.at(key) != value) return what + "." + key + ": '" + value.dump() + "' vs '" + y.at(key).dump() + "'";
      }
      for (const auto& [key, value] : y.items()) {
        if (!x.contains(key)) return what + "." + key + ": none vs '" + value.dump() + "'";
      }
    }
    return what + ": '" + x.dump() + "' vs '" + y.dump() + "'";
  };
  std::string d = differ("build", BuildIdentity(a.environment), BuildIdentity(b.environment));
  if (!d.empty()) return "another build (" + d + ")";
  d = differ("options", a.options, b.options);
  if (!d.empty()) return "other options (" + d + ")";
  if (a.suites.size() != b.suites.size()) return "other suites (" + std::to_string(a.suites.size()) + " vs " +
                                                 std::to_string(b.suites.size()) + ")";
  for (std::size_t i = 0; i < a.suites.size(); ++i) {
    const SuiteResults &x = a.suites[i], &y = b.suites[i];
    if (x.suite != y.suite) return "other suites ('" + x.suite + "' vs '" + y.suite + "')";
    if (x.checksum != y.checksum || x.problems != y.problems) {
      return "other problems in suite " + x.suite + " (checksum " + x.checksum + " vs " + y.checksum + ")";
    }
  }
  if (a.shards != b.shards) {
    return "another shard count (" + std::to_string(a.shards) + " vs " + std::to_string(b.shards) + ")";
  }
  if (a.jobs.size() != b.jobs.size()) return "other job lists (" + std::to_string(a.jobs.size()) + " vs " +
                                             std::to_string(b.jobs.size()) + " jobs)";
  for (std::size_t i = 0; i < a.jobs.size(); ++i) {
    if (a.jobs[i].id != b.jobs[i].id) return "other job lists (job " + std::to_string(i + 1) + ": " + a.jobs[i].id +
                                             " vs " + b.jobs[i].id + ")";
  }
  return "";
}

BenchResults AssembleResults(const RunManifest& m, const std::map<std::size_t, JobLine>& lines) {
  BenchResults out;
  out.command = m.command;
  out.polish = m.options.value("polish", true);
  out.options = m.options;
  for (const SuiteResults& s : m.suites) {
    SuiteResults suite = s;
    suite.replay = {};
    out.suites.push_back(std::move(suite));
  }
  for (const auto& [index, line] : lines) {
    if (index >= m.jobs.size() || line.id != m.jobs[index].id) continue;
    const BenchJob& job = m.jobs[index];
    if (job.kind == JobKind::kStepper) {
      if (line.has_stepper) out.has_stepper = true, out.stepper = line.stepper;
      continue;
    }
    if (job.kind == JobKind::kWarm) {
      if (line.has_warm) out.suites[job.suite].warm.push_back(line.warm);
      continue;
    }
    if (!line.has_record) continue;
    ReplayResults& replay = out.suites[job.suite].replay;
    (job.kind == JobKind::kSweep   ? replay.sweep
     : job.kind == JobKind::kFloor ? replay.floor
                                   : replay.records)
        .push_back(line.record);
  }
  return out;
}

MergeReport MergeRunFolders(const std::vector<std::string>& dirs) {
  if (dirs.empty()) throw InvalidInputError("merge: give at least one folder");
  MergeReport report;
  RunManifest first;
  std::map<std::size_t, JobLine> lines;
  std::set<std::string> hosts;
  for (std::size_t d = 0; d < dirs.size(); ++d) {
    RunManifest m = ReadRunManifest(dirs[d]);
    if (d == 0) {
      first = m;
      report.environment = m.environment;
    } else if (const std::string why = ManifestMismatch(first, m); !why.empty()) {
      throw InvalidInputError("merge: " + dirs[d] + " is not part of the run in " + dirs[0] + ": " + why);
    }
    for (JobLine& line : ReadJobLines((fs::path(dirs[d]) / "records.jsonl").string(), false)) {
      if (line.job >= first.jobs.size() || line.id != first.jobs[line.job].id) {
        throw InvalidInputError("merge: " + dirs[d] + "/records.jsonl names job " + std::to_string(line.job + 1) +
                                " '" + line.id + "', which is not in the run's job list");
      }
      if (!line.host.empty()) hosts.insert(line.host);
      if (lines.count(line.job)) {
        report.duplicated.push_back(line.id);
        continue;
      }
      lines.emplace(line.job, std::move(line));
    }
  }
  for (const BenchJob& job : first.jobs) {
    if (!lines.count(job.index)) report.missing.push_back(job.id);
  }
  // The merged run is the run of all shards: its command without the shard.
  std::string command = first.command;
  if (const auto at = command.find(" --shard "); at != std::string::npos) {
    const auto next = command.find(' ', at + 9);
    command.erase(at, next == std::string::npos ? std::string::npos : next - at);
  }
  first.command = command;
  report.results = AssembleResults(first, lines);
  report.hosts.assign(hosts.begin(), hosts.end());
  report.environment["hosts"] = report.hosts;
  report.environment["merged_from"] = dirs;
  return report;
}

}  // namespace smcbench

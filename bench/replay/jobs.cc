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

// A manifest's job kind; the names older manifests gave the cold jobs of MCP and AVI suites and of the generic
// sparse path ("mcp", "avi", "generic-sparse") are cold jobs.
JobKind JobKindFromText(const std::string& text, const std::string& where) {
  for (JobKind k : {JobKind::kCold, JobKind::kSweep, JobKind::kStepper, JobKind::kWarm, JobKind::kFloor}) {
    if (text == ToString(k)) return k;
  }
  if (text == "mcp" || text == "avi" || text == "generic-sparse") return JobKind::kCold;
  throw InvalidInputError(where + ": unknown job kind '" + text + "'");
}

}  // namespace

const char* ToString(JobKind kind) {
  switch (kind) {
    case JobKind::kCold: return "cold";
    case JobKind::kSweep: return "sweep";
    case JobKind::kStepper: return "stepper";
    case JobKind::kWarm: return "warm";
    case JobKind::kFloor: return "floor";
  }
  return "?";
}

std::string JobKindName(const BenchJob& job) {
  return job.kind_name.empty() ? std::string(ToString(job.kind)) : job.kind_name;
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
    if (!s.kind.empty()) j["suites"].back()["kind"] = s.kind;  // since recorded
  }
  j["shard"] = {{"index", m.shard + 1}, {"count", m.shards}};
  j["jobs"] = json::array();
  for (std::size_t i = 0; i < m.jobs.size(); ++i) {
    const BenchJob& b = m.jobs[i];
    j["jobs"].push_back({{"id", b.id}, {"kind", JobKindName(b)}, {"suite", b.suite}, {"problem", b.problem},
                         {"suite_name", b.suite_name}, {"problem_id", b.problem_id}, {"solver", b.solver},
                         {"tolerance", b.tolerance}, {"cost", b.cost}, {"shard", m.job_shard.at(i) + 1}});
    if ((b.has_start && b.kind == JobKind::kCold) || !b.start_label.empty()) j["jobs"].back()["start"] = {{"index", b.start}, {"label", b.start_label}};
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
      suite.kind = s.value("kind", std::string());  // older manifests: none
      m.suites.push_back(std::move(suite));
    }
    m.shard = j.at("shard").at("index").get<int>() - 1;
    m.shards = j.at("shard").at("count").get<int>();
    for (const json& b : j.at("jobs")) {
      BenchJob job;
      job.index = m.jobs.size();
      job.id = b.at("id").get<std::string>();
      job.kind_name = b.at("kind").get<std::string>();
      job.kind = JobKindFromText(job.kind_name, where);
      job.suite = b.at("suite").get<std::size_t>();
      job.problem = b.at("problem").get<std::size_t>();
      job.suite_name = b.at("suite_name").get<std::string>();
      job.problem_id = b.at("problem_id").get<std::string>();
      job.solver = b.at("solver").get<std::string>();
      job.tolerance = b.at("tolerance").get<double>();
      job.cost = b.at("cost").get<double>();
      job.estimate = job.cost;
      if (b.contains("start")) {  // a unit problem × start (an MCP's)
        job.has_start = true;
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

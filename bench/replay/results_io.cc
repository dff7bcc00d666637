#include "bench/replay/results_io.h"

#include <sys/utsname.h>
#include <unistd.h>

#include <IpoptConfig.h>
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <suitesparse/umfpack.h>

#include "solvers/core/number_text.h"

#ifndef SMCBENCH_SOURCE_DIR_FOR_GIT
#define SMCBENCH_SOURCE_DIR_FOR_GIT ""
#endif
#ifndef SMCBENCH_CXX_FLAGS
#define SMCBENCH_CXX_FLAGS ""
#endif
#ifndef SMCBENCH_BUILD_TYPE
#define SMCBENCH_BUILD_TYPE ""
#endif

namespace smcbench {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// First line of a command's output, or "" (never throws).
std::string CommandOutput(const std::string& command) {
  std::array<char, 256> buffer{};
  std::string out;
  if (FILE* pipe = ::popen(command.c_str(), "r")) {
    if (std::fgets(buffer.data(), buffer.size(), pipe)) out = buffer.data();
    ::pclose(pipe);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

std::string CpuModel() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(colon + 2);
    }
  }
  return "";
}

json Finite(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
double Number(const json& j) { return j.is_null() ? std::nan("") : j.get<double>(); }
// A number written by a later format revision: NaN when an older results.json does not have it.
double OptionalNumber(const json& record, const char* key) {
  return record.contains(key) ? Number(record.at(key)) : std::nan("");
}

json RecordJson(const ReplayRecord& r) {
  return {{"suite", r.suite},
          {"problem", r.problem},
          {"start", r.start},
          {"solver", r.solver},
          {"size", r.size},
          {"sparse", r.sparse},
          {"tags", r.tags},
          {"expected", std::string(ToString(r.expected))},
          {"status", std::string(ToString(r.status))},
          {"message", r.message},
          {"verdict", std::string(ToString(r.verdict))},
          {"iterations", r.iterations},
          {"residual_abs", Finite(r.residual_abs)},
          {"residual_rel", Finite(r.residual_rel)},
          {"residual_scaled", Finite(r.residual_scaled)},
          {"forward_error", Finite(r.forward_error)},
          {"forward_error_rel", Finite(r.forward_error_rel)},
          {"forward_allowance", Finite(r.forward_allowance)},
          {"certificate", r.certificate},
          {"reference_radius", Finite(r.reference_radius)},
          {"reference_proved_unique", r.reference_proved_unique},
          {"tolerance", r.tolerance},
          {"time_median", r.time_median},
          {"time_min", r.time_min},
          {"time_max", r.time_max},
          {"time_mad", r.time_mad},
          {"samples", r.samples},
          {"solves_per_sample", r.solves_per_sample},
          {"mode", r.mode},
          {"timed_in_worker", r.timed_in_worker},
          {"host", r.host},
          {"concurrent_jobs", r.concurrent_jobs},
          {"backend_code", r.backend_code ? json(*r.backend_code) : json(nullptr)}};
}

template <typename Enum, typename Values>
Enum EnumFromText(const std::string& text, const Values& values, const char* field) {
  for (Enum e : values) {
    if (ToString(e) == text) return e;
  }
  throw InvalidInputError(std::string("results.json: unknown ") + field + " '" + text + "'");
}

ReplayRecord RecordFromJson(const json& j) {
  ReplayRecord r;
  r.suite = j.at("suite").get<std::string>();
  r.problem = j.at("problem").get<std::string>();
  // Written since MCP records (a problem × start); box records and older results have none.
  r.start = j.value("start", std::string());
  r.solver = j.at("solver").get<std::string>();
  r.size = j.at("size").get<int>();
  r.sparse = j.at("sparse").get<bool>();
  r.tags = j.at("tags").get<std::string>();
  r.expected = EnumFromText<ExpectedOutcome>(
      j.at("expected").get<std::string>(),
      std::array{ExpectedOutcome::kUnknown, ExpectedOutcome::kSolvable, ExpectedOutcome::kInfeasible}, "expected");
  const std::string status = j.at("status").get<std::string>();
  const std::optional<SolveStatus> known_status = SolveStatusFromString(status);
  if (!known_status) throw InvalidInputError("results.json: field 'status': unknown status '" + status + "'");
  r.status = *known_status;
  r.message = j.at("message").get<std::string>();
  const std::string verdict = j.at("verdict").get<std::string>();
  const std::optional<Verdict> known_verdict = VerdictFromString(verdict);
  if (!known_verdict) throw InvalidInputError("results.json: field 'verdict': unknown verdict '" + verdict + "'");
  r.verdict = *known_verdict;
  r.iterations = j.at("iterations").get<int>();
  r.residual_abs = Number(j.at("residual_abs"));
  r.residual_rel = Number(j.at("residual_rel"));
  // Optional: results.json files from before the scale-free verdict lack them and read as NaN / "none".
  r.residual_scaled = OptionalNumber(j, "residual_scaled");
  r.forward_error = OptionalNumber(j, "forward_error");
  r.forward_error_rel = OptionalNumber(j, "forward_error_rel");
  r.forward_allowance = OptionalNumber(j, "forward_allowance");
  r.certificate = j.value("certificate", std::string("none"));
  r.reference_radius = OptionalNumber(j, "reference_radius");
  r.reference_proved_unique = j.value("reference_proved_unique", false);
  r.tolerance = j.at("tolerance").get<double>();
  r.time_median = j.at("time_median").get<double>();
  r.time_min = j.at("time_min").get<double>();
  r.time_max = j.at("time_max").get<double>();
  r.time_mad = j.at("time_mad").get<double>();
  r.samples = j.at("samples").get<int>();
  r.solves_per_sample = j.at("solves_per_sample").get<std::int64_t>();
  r.mode = j.at("mode").get<std::string>();
  // Absent from results.json files older than the probe policy (Siconos timed in process after its probe): those
  // timed every siconos-* solve through the isolation worker.
  r.timed_in_worker = j.contains("timed_in_worker") ? j.at("timed_in_worker").get<bool>()
                                                    : r.solver.rfind("siconos-", 0) == 0;
  // Optional: results written before runs recorded their host read as empty / 0.
  r.host = j.value("host", std::string());
  r.concurrent_jobs = j.value("concurrent_jobs", 0);
  // Written since the report's audit of claims; null (or absent, in older results) when there is none.
  if (j.contains("backend_code") && !j.at("backend_code").is_null()) r.backend_code = j.at("backend_code").get<int>();
  return r;
}

std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

json ReplayRecordToJson(const ReplayRecord& record) { return RecordJson(record); }

ReplayRecord ReplayRecordFromJson(const json& record) {
  try {
    return RecordFromJson(record);
  } catch (const json::exception& e) {
    throw InvalidInputError(std::string("record: malformed: ") + e.what());
  }
}

json WarmRecordToJson(const WarmRecord& record) {
  json j = RecordJson(record.record);
  const WarmCounts& c = record.counts;
  j["warm"] = {{"source", ToString(record.source)}, {"steps", c.steps}, {"steps_solved", c.steps_solved},
               {"active_set_changes", c.active_set_changes}, {"iterations", c.iterations}, {"reuse", c.reuse},
               {"reused_steps", c.reused_steps}, {"fallbacks", c.fallbacks}};
  return j;
}

WarmRecord WarmRecordFromJson(const json& j) {
  try {
    WarmRecord out;
    out.record = RecordFromJson(j);
    const json& w = j.at("warm");
    const std::string source = w.at("source").get<std::string>();
    bool known = false;
    for (WarmSource s : {WarmSource::kScene, WarmSource::kTrajectory, WarmSource::kCapture}) {
      if (source == ToString(s)) out.source = s, known = true;
    }
    if (!known) throw InvalidInputError("record: warm.source '" + source + "' is not scene, trajectory or capture");
    WarmCounts& c = out.counts;
    c.steps = w.at("steps").get<int>();
    c.steps_solved = w.at("steps_solved").get<int>();
    c.active_set_changes = w.at("active_set_changes").get<int>();
    c.iterations = w.at("iterations").get<std::int64_t>();
    c.reuse = w.at("reuse").get<bool>();
    c.reused_steps = w.at("reused_steps").get<int>();
    c.fallbacks = w.at("fallbacks").get<int>();
    return out;
  } catch (const json::exception& e) {
    throw InvalidInputError(std::string("record: malformed warm record: ") + e.what());
  }
}

json StepperStudyToJson(const StepperStudy& study) {
  json st;
  st["reference_h_factor"] = study.reference_h_factor;
  st["warm_start"] = json::array();
  for (const auto& r : study.warm_start) {
    st["warm_start"].push_back({{"scene", r.scene}, {"solver", r.solver}, {"mode", r.mode}, {"steps", r.steps},
                                {"seconds_per_step", r.seconds_per_step},
                                {"iterations_per_step", r.iterations_per_step}, {"ok", r.ok}});
  }
  st["work_precision"] = json::array();
  for (const auto& r : study.work_precision) {
    st["work_precision"].push_back({{"scene", r.scene}, {"method", r.method}, {"solver", r.solver}, {"h", r.h},
                                    {"steps", r.steps}, {"seconds", r.seconds}, {"error", Finite(r.error)},
                                    {"s_forward_error", Finite(r.s_forward_error)},
                                    {"s_certified_steps", r.s_certified_steps}, {"ok", r.ok}});
  }
  return st;
}

StepperStudy StepperStudyFromJson(const json& st) {
  StepperStudy out;
  out.reference_h_factor = st.at("reference_h_factor").get<double>();
  for (const json& r : st.at("warm_start")) {
    out.warm_start.push_back({r.at("scene").get<std::string>(), r.at("solver").get<std::string>(),
                              r.at("mode").get<std::string>(), r.at("steps").get<std::int64_t>(),
                              r.at("seconds_per_step").get<double>(), r.at("iterations_per_step").get<double>(),
                              r.at("ok").get<bool>()});
  }
  for (const json& r : st.at("work_precision")) {
    WorkPrecisionRecord w;
    w.scene = r.at("scene").get<std::string>();
    w.method = r.at("method").get<std::string>();
    w.solver = r.at("solver").get<std::string>();
    w.h = r.at("h").get<double>();
    w.steps = r.at("steps").get<std::int64_t>();
    w.seconds = r.at("seconds").get<double>();
    w.error = Number(r.at("error"));
    w.s_forward_error = OptionalNumber(r, "s_forward_error");
    w.s_certified_steps = r.value("s_certified_steps", std::int64_t{0});
    w.ok = r.at("ok").get<bool>();
    out.work_precision.push_back(std::move(w));
  }
  return out;
}

json BuildIdentity(const json& environment) {
  json build = json::object();
  for (const char* key : {"build_revision", "version", "compiler", "cxx_flags", "build_type", "assertions",
                          "libraries"}) {
    if (environment.contains(key)) build[key] = environment.at(key);
  }
  return build;
}

json BenchEnvironment(const std::string& build_revision) {
  json env;
  env["build_revision"] = build_revision;
  env["git_sha"] = CommandOutput(std::string("git -C '") + SMCBENCH_SOURCE_DIR_FOR_GIT + "' rev-parse HEAD 2>/dev/null");
  env["git_dirty"] =
      !CommandOutput(std::string("git -C '") + SMCBENCH_SOURCE_DIR_FOR_GIT + "' status --porcelain 2>/dev/null").empty();
#if defined(__clang__)
  env["compiler"] = std::string("clang ") + __clang_version__;
#elif defined(__GNUC__)
  env["compiler"] = std::string("g++ ") + __VERSION__;
#else
  env["compiler"] = "unknown";
#endif
  env["cxx_flags"] = SMCBENCH_CXX_FLAGS;
  env["build_type"] = SMCBENCH_BUILD_TYPE;
#ifdef NDEBUG
  env["assertions"] = false;
#else
  env["assertions"] = true;
#endif
  struct utsname u {};
  if (::uname(&u) == 0) env["kernel"] = std::string(u.sysname) + " " + u.release + " " + u.machine;
  env["cpu"] = CpuModel();
  env["cores"] = static_cast<int>(::sysconf(_SC_NPROCESSORS_ONLN));
  env["libraries"] = {
      {"eigen", std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) + "." +
                    std::to_string(EIGEN_MINOR_VERSION)},
      {"umfpack", std::to_string(UMFPACK_MAIN_VERSION) + "." + std::to_string(UMFPACK_SUB_VERSION) + "." +
                      std::to_string(UMFPACK_SUBSUB_VERSION)},
      {"ipopt", IPOPT_VERSION},
      {"nlohmann_json", std::to_string(NLOHMANN_JSON_VERSION_MAJOR) + "." + std::to_string(NLOHMANN_JSON_VERSION_MINOR) +
                            "." + std::to_string(NLOHMANN_JSON_VERSION_PATCH)}};
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  env["date"] = date;
  return env;
}

json ToJson(const BenchResults& results, const json& environment) {
  json j;
  j["format"] = "smcbench-bench/1";
  j["command"] = results.command;
  j["polish"] = results.polish;
  if (!results.options.is_null()) j["options"] = results.options;  // since results.json recorded them
  j["environment"] = environment;
  j["suites"] = json::array();
  for (const SuiteResults& s : results.suites) {
    json suite = {{"suite", s.suite}, {"description", s.description}, {"problems", s.problems},
                  {"checksum", s.checksum}};
    if (!s.kind.empty()) suite["kind"] = s.kind;  // since recorded
    suite["records"] = json::array();
    for (const auto& r : s.replay.records) suite["records"].push_back(RecordJson(r));
    suite["sweep"] = json::array();
    for (const auto& r : s.replay.sweep) suite["sweep"].push_back(RecordJson(r));
    if (!s.replay.floor.empty()) {  // since the floor (bench/replay/floor.h); absent: not measured
      suite["floor"] = json::array();
      for (const auto& r : s.replay.floor) suite["floor"].push_back(RecordJson(r));
    }
    if (!s.warm.empty()) {
      suite["warm"] = json::array();
      for (const auto& r : s.warm) suite["warm"].push_back(WarmRecordToJson(r));
    }
    j["suites"].push_back(suite);
  }
  if (results.has_stepper) j["stepper"] = StepperStudyToJson(results.stepper);
  return j;
}

BenchResults BenchResultsFromJson(const json& j) {
  try {
    if (j.value("format", "") != "smcbench-bench/1") {
      throw InvalidInputError("results.json: format is not smcbench-bench/1");
    }
    BenchResults out;
    out.command = j.at("command").get<std::string>();
    out.polish = j.value("polish", false);  // written since the exact polish; before it, answers were raw
    out.options = j.value("options", json());
    for (const json& s : j.at("suites")) {
      SuiteResults suite;
      suite.suite = s.at("suite").get<std::string>();
      suite.description = s.at("description").get<std::string>();
      suite.problems = s.at("problems").get<int>();
      suite.checksum = s.value("checksum", std::string());
      suite.kind = s.value("kind", std::string());  // older results: none
      for (const json& r : s.at("records")) suite.replay.records.push_back(RecordFromJson(r));
      for (const json& r : s.at("sweep")) suite.replay.sweep.push_back(RecordFromJson(r));
      if (s.contains("floor")) {  // written since the floor
        for (const json& r : s.at("floor")) suite.replay.floor.push_back(RecordFromJson(r));
      }
      if (s.contains("warm")) {  // written since the warm track
        for (const json& r : s.at("warm")) suite.warm.push_back(WarmRecordFromJson(r));
      }
      out.suites.push_back(std::move(suite));
    }
    if (j.contains("stepper")) {
      out.has_stepper = true;
      out.stepper = StepperStudyFromJson(j.at("stepper"));
    }
    return out;
  } catch (const json::exception& e) {
    throw InvalidInputError(std::string("results.json: malformed: ") + e.what());
  }
}

void WriteBenchResults(const BenchResults& results, const std::string& dir) {
  WriteBenchResults(results, dir, BenchEnvironment());
}

void WriteBenchResults(const BenchResults& results, const std::string& dir, const json& environment) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir)) throw InvalidInputError("bench: cannot create the output folder '" + dir + "'");
  {
    std::ofstream out(fs::path(dir) / "results.json");
    out << ToJson(results, environment).dump(1) << "\n";
    if (!out) throw InvalidInputError("bench: cannot write " + (fs::path(dir) / "results.json").string());
  }
  // Numbers in shortest round-trip form (NumberText: reads back to the same double; "inf", "nan" when not finite).
  // The columns added later (residual_scaled onwards, then timed_in_worker, host, start, backend_code,
  // reference_radius, reference_proved_unique) come last, so scripts that index the older ones keep working.
  std::ofstream csv(fs::path(dir) / "results.csv");
  csv << "suite,problem,solver,mode,size,sparse,expected,status,verdict,iterations,residual_abs,residual_rel,"
         "tolerance,time_median,time_min,time_max,time_mad,samples,solves_per_sample,residual_scaled,"
         "forward_error,forward_error_rel,forward_allowance,certificate,timed_in_worker,host,concurrent_jobs,start,"
         "backend_code,reference_radius,reference_proved_unique\n";
  for (const SuiteResults& s : results.suites) {
    std::vector<ReplayRecord> warm;  // the warm records' replay part (their counts are in results.json)
    for (const WarmRecord& w : s.warm) warm.push_back(w.record);
    const std::vector<ReplayRecord>* lists[] = {&s.replay.records, &s.replay.sweep, &warm};
    for (const std::vector<ReplayRecord>* records : lists) {
      for (const ReplayRecord& r : *records) {
        csv << CsvField(r.suite) << ',' << CsvField(r.problem) << ',' << CsvField(r.solver) << ',' << r.mode << ','
            << r.size << ',' << (r.sparse ? 1 : 0) << ',' << ToString(r.expected) << ',' << ToString(r.status) << ','
            << ToString(r.verdict) << ',' << r.iterations << ',' << NumberText(r.residual_abs) << ','
            << NumberText(r.residual_rel) << ',' << NumberText(r.tolerance) << ',' << NumberText(r.time_median) << ','
            << NumberText(r.time_min) << ',' << NumberText(r.time_max) << ',' << NumberText(r.time_mad) << ','
            << r.samples << ',' << r.solves_per_sample << ',' << NumberText(r.residual_scaled) << ','
            << NumberText(r.forward_error) << ',' << NumberText(r.forward_error_rel) << ','
            << NumberText(r.forward_allowance) << ',' << CsvField(r.certificate) << ','
            << (r.timed_in_worker ? 1 : 0) << ',' << CsvField(r.host) << ',' << r.concurrent_jobs << ','
            << CsvField(r.start) << ',' << (r.backend_code ? std::to_string(*r.backend_code) : std::string())
            << ',' << NumberText(r.reference_radius) << ',' << (r.reference_proved_unique ? 1 : 0) << '\n';
      }
    }
  }
  if (!csv) throw InvalidInputError("bench: cannot write " + (fs::path(dir) / "results.csv").string());
}

namespace {

// A char iterator over a document that publishes how far the parser has read (*consumed), so that a SAX handler
// knows where in the text the value it was just given ends.
class CountingIterator {
 public:
  using iterator_category = std::forward_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  CountingIterator(const char* at, const char** consumed) : at_(at), consumed_(consumed) {}
  reference operator*() const { return *at_; }
  CountingIterator& operator++() {
    *consumed_ = ++at_;
    return *this;
  }
  CountingIterator operator++(int) {
    CountingIterator before = *this;
    ++*this;
    return before;
  }
  bool operator==(const CountingIterator& other) const { return at_ == other.at_; }
  bool operator!=(const CountingIterator& other) const { return at_ != other.at_; }

 private:
  const char* at_;
  const char** consumed_;
};

// Finds the first record status (suites[i].records[j].status or .sweep[j].status) that is not a SolveStatus name,
// and where its string starts in the text.
class UnknownStatusFinder : public nlohmann::json_sax<json> {
 public:
  UnknownStatusFinder(const char* begin, const char** consumed) : begin_(begin), consumed_(consumed) {}

  bool found() const { return found_; }
  const std::string& name() const { return name_; }
  std::size_t offset() const { return offset_; }

  bool null() override { return Value(); }
  bool boolean(bool) override { return Value(); }
  bool number_integer(number_integer_t) override { return Value(); }
  bool number_unsigned(number_unsigned_t) override { return Value(); }
  bool number_float(number_float_t, const string_t&) override { return Value(); }
  bool binary(binary_t&) override { return Value(); }
  bool string(string_t& value) override {
    if (AtRecordStatus() && !SolveStatusFromString(value)) {
      // The parser has just read the closing quote: step back to the opening one (a quote not escaped).
      const char* end = *consumed_ - 1;
      const char* open = end - 1;
      while (open > begin_ && !(*open == '"' && open[-1] != '\\')) --open;
      found_ = true;
      name_ = value;
      offset_ = static_cast<std::size_t>(open - begin_);
      return false;  // stop parsing
    }
    return Value();
  }
  bool start_object(std::size_t) override { return Open(false); }
  bool key(string_t& name) override {
    frames_.back().key = name;
    return true;
  }
  bool end_object() override { return Close(); }
  bool start_array(std::size_t) override { return Open(true); }
  bool end_array() override { return Close(); }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override { return false; }

 private:
  struct Frame {
    bool array = false;
    std::string key;  // the object's current key
  };
  bool Open(bool array) {
    frames_.push_back({array, {}});
    return true;
  }
  bool Close() {
    frames_.pop_back();
    return true;
  }
  bool Value() { return true; }
  // Document object → "suites" array → suite object → "records"/"sweep" array → record object, at key "status".
  bool AtRecordStatus() const {
    return frames_.size() == 5 && !frames_[0].array && frames_[0].key == "suites" && frames_[1].array &&
           !frames_[2].array && (frames_[2].key == "records" || frames_[2].key == "sweep") && frames_[3].array &&
           !frames_[4].array && frames_[4].key == "status";
  }

  const char* begin_;
  const char** consumed_;
  std::vector<Frame> frames_;
  bool found_ = false;
  std::string name_;
  std::size_t offset_ = 0;
};

// "line:column" (both from 1) of a byte offset in the text.
std::string LineAndColumn(const std::string& text, std::size_t offset) {
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return std::to_string(line) + ":" + std::to_string(column);
}

}  // namespace

BenchResults ReadBenchResults(const std::string& dir, json* environment) {
  const fs::path path = fs::path(dir) / "results.json";
  std::ifstream in(path);
  if (!in) throw InvalidInputError("report: cannot read '" + path.string() + "' (run `smcbench bench --out " + dir + "` first)");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    throw InvalidInputError("report: '" + path.string() + "' is not valid JSON: " + e.what());
  }
  if (environment) *environment = j.value("environment", json::object());
  try {
    return BenchResultsFromJson(j);
  } catch (const InvalidInputError&) {
    // The parsed document has no positions: read the text again, only now, to say where an unknown status is.
    const char* consumed = text.data();
    UnknownStatusFinder finder(text.data(), &consumed);
    json::sax_parse(CountingIterator(text.data(), &consumed), CountingIterator(text.data() + text.size(), &consumed),
                    &finder);
    if (!finder.found()) throw;
    throw InvalidInputError(path.string() + ":" + LineAndColumn(text, finder.offset()) +
                            ": field 'status': unknown status '" + finder.name() + "'");
  }
}

}  // namespace smcbench

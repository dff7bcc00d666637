#include "bench/compare/run_identity.h"

#include <algorithm>
#include <filesystem>
#include <set>

#include "bench/replay/jobs.h"
#include "solvers/core/problem.h"

namespace smcbench {
namespace {

using json = nlohmann::json;

constexpr const char* kMissing = "-";
constexpr std::size_t kShortCommit = 12;

// The environment's fields by part, in the order the table shows them: (key in the environment, row name).
constexpr std::pair<const char*, const char*> kBuildFields[] = {
    {"git_sha", "commit"},   {"git_dirty", "uncommitted changes"}, {"build_revision", "build revision"},
    {"version", "version"},  {"compiler", "compiler"},             {"cxx_flags", "flags"},
    {"build_type", "build type"}, {"assertions", "assertions"}};
constexpr std::pair<const char*, const char*> kMachineFields[] = {
    {"cpu", "cpu"}, {"cores", "cores"}, {"kernel", "kernel"}};

std::string Text(const json& value) {
  if (value.is_null()) return kMissing;
  return value.is_string() ? value.get<std::string>() : value.dump();
}

std::string Field(const json& object, const std::string& key) {
  return object.is_object() && object.contains(key) ? Text(object.at(key)) : kMissing;
}

// The keys of two objects: a's in its order, then those only b has.
std::vector<std::string> KeysOf(const json& a, const json& b) {
  std::vector<std::string> keys;
  for (const json* object : {&a, &b}) {
    if (!object->is_object()) continue;
    for (const auto& [key, value] : object->items()) {
      if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
    }
  }
  return keys;
}

std::string Joined(const std::vector<std::string>& items) {
  if (items.empty()) return kMissing;
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

std::vector<std::string> HostsOf(const BenchResults& results) {
  std::set<std::string> hosts;
  for (const SuiteResults& suite : results.suites) {
    for (const auto* records : {&suite.replay.records, &suite.replay.sweep, &suite.replay.floor}) {
      for (const ReplayRecord& r : *records) {
        if (!r.host.empty()) hosts.insert(r.host);
      }
    }
  }
  return {hosts.begin(), hosts.end()};
}

std::string Shortened(const IdentityRow& row, const std::string& value) {
  return row.name == "commit" && value.size() > kShortCommit ? value.substr(0, kShortCommit) : value;
}

}  // namespace

std::string_view ToString(IdentityPart part) {
  switch (part) {
    case IdentityPart::kSetting: return "setting";
    case IdentityPart::kBuild: return "build";
    case IdentityPart::kMachine: return "machine";
    case IdentityPart::kInfo: return "info";
  }
  return "?";
}

RunIdentity MakeRunIdentity(const BenchResults& results, const json& environment, const json& options) {
  RunIdentity id;
  id.command = results.command;
  id.polish = results.polish;
  id.environment = environment.is_object() ? environment : json::object();
  id.options = options.is_object() ? options : json::object();
  id.hosts = HostsOf(results);
  return id;
}

json ReadRunOptions(const std::string& dir) {
  if (!std::filesystem::exists(std::filesystem::path(dir) / "manifest.json")) return json::object();
  try {
    return ReadRunManifest(dir).options;
  } catch (const InvalidInputError&) {
    return json::object();
  }
}

std::vector<IdentityRow> IdentityRows(const RunIdentity& a, const RunIdentity& b) {
  std::vector<IdentityRow> rows;
  rows.push_back({IdentityPart::kSetting, "polish", json(a.polish).dump(), json(b.polish).dump()});
  for (const std::string& key : KeysOf(a.options, b.options)) {
    if (key == "polish") continue;  // results.json's, above
    rows.push_back({IdentityPart::kSetting, key, Field(a.options, key), Field(b.options, key)});
  }
  for (const auto& [key, name] : kBuildFields) {
    rows.push_back({IdentityPart::kBuild, name, Field(a.environment, key), Field(b.environment, key)});
  }
  const json no_libraries = json::object();
  const json& libraries_a = a.environment.value("libraries", no_libraries);
  const json& libraries_b = b.environment.value("libraries", no_libraries);
  for (const std::string& key : KeysOf(libraries_a, libraries_b)) {
    rows.push_back({IdentityPart::kBuild, key, Field(libraries_a, key), Field(libraries_b, key)});
  }
  rows.push_back({IdentityPart::kMachine, "host", Joined(a.hosts), Joined(b.hosts)});
  for (const auto& [key, name] : kMachineFields) {
    rows.push_back({IdentityPart::kMachine, name, Field(a.environment, key), Field(b.environment, key)});
  }
  rows.push_back({IdentityPart::kInfo, "date", Field(a.environment, "date"), Field(b.environment, "date")});
  rows.push_back({IdentityPart::kInfo, "command", a.command.empty() ? kMissing : a.command,
                  b.command.empty() ? kMissing : b.command});
  return rows;
}

std::string DifferencesLine(const std::vector<IdentityRow>& rows) {
  std::string line;
  for (const IdentityRow& row : rows) {
    if (!row.differs()) continue;
    line += (line.empty() ? "" : "; ") + row.name + " " + Shortened(row, row.a) + " vs " + Shortened(row, row.b);
  }
  return line;
}

bool MachinesDiffer(const std::vector<IdentityRow>& rows) {
  return std::any_of(rows.begin(), rows.end(), [](const IdentityRow& row) {
    return row.part == IdentityPart::kMachine && row.differs() && row.a != kMissing && row.b != kMissing;
  });
}

}  // namespace smcbench

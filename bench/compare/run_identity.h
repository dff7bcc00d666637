// What produced each of two `smcbench bench` runs, side by side: the settings that change what is measured
// (manifest.json's options, results.json's polish), the build (commit, compiler, flags, build type, libraries) and the
// machine (host, CPU, cores, kernel), so that `smcbench compare` can say what differed between A and B before it
// says what changed, and warn when the machines differ (then their times are not comparable).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/replay/results_io.h"

namespace smcbench {

struct RunIdentity {
  std::string command;
  bool polish = true;
  nlohmann::json environment = nlohmann::json::object();  // results.json's "environment" (BenchEnvironment)
  nlohmann::json options = nlohmann::json::object();      // manifest.json's "options"; empty without a manifest
  std::vector<std::string> hosts;                         // the records' hosts, sorted, without repeats
};

// The options manifest.json of the folder records (PlanOptionsJson), or an empty object when it has no readable one
// (older or hand-made folders): the settings are then unknown, the comparison stands.
nlohmann::json ReadRunOptions(const std::string& dir);
// A run's identity from results.json (ReadBenchResults and its environment) and ReadRunOptions.
RunIdentity MakeRunIdentity(const BenchResults& results, const nlohmann::json& environment,
                            const nlohmann::json& options);

enum class IdentityPart : int {  // append-only
  kSetting = 0,  // an option of the run
  kBuild = 1,    // commit, compiler, flags, build type, libraries
  kMachine = 2,  // host, CPU, cores, kernel
  kInfo = 3,     // shown, never a difference: the date, the command line (it names the output folder)
};
std::string_view ToString(IdentityPart part);  // "setting", "build", "machine", "info"

struct IdentityRow {
  IdentityPart part = IdentityPart::kInfo;
  std::string name;  // "tolerance", "commit", "cpu", ...
  std::string a, b;  // the values as text; "-" when the run does not record it
  bool differs() const { return part != IdentityPart::kInfo && a != b; }
};

// Every field either run records, settings first, then build, machine, info; each part in a fixed order.
std::vector<IdentityRow> IdentityRows(const RunIdentity& a, const RunIdentity& b);

// "tolerance 1e-10 vs 1e-08; commit 0123abcd vs 4567ef01" (commits shortened), or "" when nothing differs.
std::string DifferencesLine(const std::vector<IdentityRow>& rows);
// True when a machine field (host, CPU, cores, kernel) both runs record differs: their times are then not comparable.
bool MachinesDiffer(const std::vector<IdentityRow>& rows);

}  // namespace smcbench

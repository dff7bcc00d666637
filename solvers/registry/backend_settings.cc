// `--set BACKEND.OPTION=VALUE`: parse, check against a fresh backend, then apply to the selected ones.
#include "solvers/registry/backend_settings.h"

#include "solvers/auto/auto_solver.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

constexpr std::string_view kListHint = "`smcbench list` shows every backend's options";

// The backends one setting reaches among the selected: those of its name, and auto's instance of it.
std::vector<Solver*> Targets(const BackendSetting& setting, const std::vector<Solver*>& selected) {
  std::vector<Solver*> targets;
  for (Solver* solver : selected) {
    if (solver->info().name == setting.backend) {
      targets.push_back(solver);
    } else if (auto* automatic = dynamic_cast<AutoSolver*>(solver)) {
      const int candidate = AutoCandidateIndex(setting.backend);
      Solver* instance = candidate >= 0 ? automatic->FindCandidate(static_cast<AutoCandidate>(candidate)) : nullptr;
      if (instance != nullptr) targets.push_back(instance);
    }
  }
  return targets;
}

std::string SelectedNames(const std::vector<Solver*>& selected) {
  std::string names;
  for (const Solver* solver : selected) names += (names.empty() ? "'" : ", '") + std::string(solver->info().name) + "'";
  return names.empty() ? "no backend" : names;
}

}  // namespace

BackendSetting ParseBackendSetting(std::string_view text) {
  const auto dot = text.find('.');
  const auto eq = dot == std::string_view::npos ? std::string_view::npos : text.find('=', dot + 1);
  if (dot == std::string_view::npos || eq == std::string_view::npos || dot == 0 || eq == dot + 1) {
    throw InvalidInputError("--set expects BACKEND.OPTION=VALUE, got '" + std::string(text) +
                            "' (e.g. --set psor.omega=1.2; " + std::string(kListHint) + ")");
  }
  return {std::string(text.substr(0, dot)), std::string(text.substr(dot + 1, eq - dot - 1)),
          std::string(text.substr(eq + 1))};
}

void ApplyBackendSettings(const std::vector<std::string>& settings, const std::vector<Solver*>& selected) {
  std::vector<std::pair<BackendSetting, std::vector<Solver*>>> plan;
  for (const std::string& text : settings) {
    BackendSetting setting = ParseBackendSetting(text);
    const std::string quoted = "--set " + text + ": ";
    std::unique_ptr<Solver> probe;
    try {
      probe = CreateSolver(setting.backend);
    } catch (const InvalidInputError& e) {
      throw InvalidInputError(quoted + e.what());
    }
    // The option and its value are checked on a fresh instance, so the error does not depend on the selection.
    std::string error;
    if (!probe->SetOption(setting.option, setting.value, &error)) {
      throw InvalidInputError(quoted + setting.backend + ": " + error + "; " + std::string(kListHint));
    }
    std::vector<Solver*> targets = Targets(setting, selected);
    if (targets.empty()) {
      throw InvalidInputError("--set " + text + " names backend '" + setting.backend +
                              "', which this run does not use (it uses " + SelectedNames(selected) +
                              "); choose it with --solver or drop the setting");
    }
    plan.emplace_back(std::move(setting), std::move(targets));
  }
  for (const auto& [setting, targets] : plan) {
    for (Solver* target : targets) {
      std::string error;
      if (!target->SetOption(setting.option, setting.value, &error)) {  // checked above: cannot fail
        throw InvalidInputError("--set " + setting.backend + "." + setting.option + ": " + error);
      }
    }
  }
}

void ApplyBackendSettings(const std::vector<std::string>& settings,
                          const std::vector<std::unique_ptr<Solver>>& selected) {
  std::vector<Solver*> raw;
  raw.reserve(selected.size());
  for (const auto& solver : selected) raw.push_back(solver.get());
  ApplyBackendSettings(settings, raw);
}

void CheckBackendSettings(const std::vector<std::string>& settings, const std::vector<std::string>& selected_names) {
  std::vector<std::unique_ptr<Solver>> fresh;
  for (const std::string& name : selected_names) fresh.push_back(CreateSolver(name));
  ApplyBackendSettings(settings, fresh);
}

std::vector<std::string> SettingsReaching(std::string_view backend, const std::vector<std::string>& settings) {
  std::vector<std::string> reaching;
  for (const std::string& text : settings) {
    const BackendSetting setting = ParseBackendSetting(text);
    if (setting.backend == backend || (backend == "auto" && AutoCandidateIndex(setting.backend) >= 0)) {
      reaching.push_back(text);
    }
  }
  return reaching;
}

}  // namespace smcbench

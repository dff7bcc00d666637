// The one parser of `--set BACKEND.OPTION=VALUE` (solve, simulate, bench): every command that takes typed backend
// options from text reads and applies them here, so they all accept and refuse the same settings.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "solvers/core/solver.h"

namespace smcbench {

// One parsed `BACKEND.OPTION=VALUE`: split at the first '.' and the first '=' after it.
struct BackendSetting {
  std::string backend;  // a registry name ("psor", "siconos-lcp-lemke", ...)
  std::string option;   // an option of that backend (`smcbench list` shows them)
  std::string value;    // text the option's binder parses (a number, true/false, or a named value)
};

// Parses one setting. Throws InvalidInputError naming the text when it is not BACKEND.OPTION=VALUE (no '.', no '='
// after it, an empty backend or option name). Does not check that the backend or the option exist.
BackendSetting ParseBackendSetting(std::string_view text);

// Applies each setting to the selected backends, in order (a later setting of the same option wins). A setting
// reaches a selected backend of its name and, when `auto` is selected, auto's own instance of that backend (the
// candidates it chooses from). Every check runs before any backend is changed, and each error is one line that
// quotes the setting and says what to do; InvalidInputError is thrown when
//   - the text is not BACKEND.OPTION=VALUE,
//   - the backend is not a registry name (the message lists them),
//   - the backend has no such option or the value does not parse (the message lists the options or the accepted
//     names; `smcbench list` shows every backend's options with their current values),
//   - the backend is registered but not selected, nor a candidate of a selected `auto`: rejected rather than
//     skipped, because a setting that changes nothing is almost always a typo in --solver or a leftover from
//     another run, and skipping it silently would make a run look configured when it is not.
void ApplyBackendSettings(const std::vector<std::string>& settings, const std::vector<Solver*>& selected);
// The same for backends held by unique_ptr (the commands' usual container).
void ApplyBackendSettings(const std::vector<std::string>& settings,
                          const std::vector<std::unique_ptr<Solver>>& selected);
// The same checks for backends selected by name, on fresh instances that are then dropped: for a command that
// checks its settings once up front and creates the backends later, one at a time (a sharded `bench`).
void CheckBackendSettings(const std::vector<std::string>& settings, const std::vector<std::string>& selected_names);
// The settings, in order, that reach a backend of this name when it runs alone: its own, and for "auto" those of
// its candidates. For running the backends of one checked selection separately. Malformed text throws as above.
std::vector<std::string> SettingsReaching(std::string_view backend, const std::vector<std::string>& settings);

}  // namespace smcbench

// Options common to every backend, plus a small binder that maps "key=value" strings onto a backend's typed
// option struct (for the CLI) and rejects unknown names.
#pragma once

#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "solvers/core/types.h"

namespace smcbench {

struct SolverOptions {
  // Solved means: the relative natural residual ‖z − Π(z − F(z))‖∞ / (1 + ‖q‖∞) and the residual of the
  // row-equilibrated problem (Residual::scaled) are both ≤ tolerance.
  double tolerance = 1e-10;
  // Iteration (or pivot) budget; ≤ 0 means "the backend's default" (documented per backend).
  int max_iterations = 0;
  // Starting point. Empty: cold start from Π_[l,u](0). Pivoting methods that cannot use it ignore it.
  Vector warm_start;
  // 0 silent, 1 summary line, 2 per iteration (to stderr).
  int verbosity = 0;
  double time_limit_seconds = kInf;
  // Stamp SolveResult::solve_seconds. Reading the clock twice costs about as much as a whole m ≤ 2 solve,
  // so time-steppers and benchmarks that time many solves externally turn it off.
  bool measure_time = true;
  // Exact polish of the backend's answer (polish.h): identify the active set, solve the reduced system, keep the
  // result when its merit is not worse. Off to time or study a raw algorithm.
  bool polish = true;

  // True if every field is usable; otherwise *why explains which one and why. Inline: runs on every solve.
  bool IsValid(std::string* why) const {
    double probe = 0.0;  // x − x is 0 exactly for finite x, NaN for NaN and ±∞
    for (Eigen::Index i = 0; i < warm_start.size(); ++i) probe += warm_start[i] - warm_start[i];
    return (ScalarsValid() && probe == 0.0) || Explain(why);
  }
  // IsValid without the warm start's finiteness (Solver::Solve checks that while copying it).
  bool ScalarsValid() const {
    return tolerance > 0.0 && tolerance < kInf && time_limit_seconds > 0.0 && verbosity >= 0;
  }
  // The slow half of IsValid: builds the message. Returns IsValid's result.
  bool Explain(std::string* why) const;
};

// One accepted spelling of an enum option: `--set backend.name=NAME` stores value. The first name listed for a
// value is the one ValueText and Help print as the current value.
struct OptionChoice {
  std::string_view name;
  int value;
};

// Binds option names to fields of a typed options struct, so "omega=1.5" can be parsed and checked.
class OptionBinder {
 public:
  void Add(std::string_view name, double* field, std::string_view help);
  void Add(std::string_view name, int* field, std::string_view help);
  void Add(std::string_view name, bool* field, std::string_view help);
  // A named-value (enum) option: only the listed names are accepted.
  template <typename Enum>
  void Add(std::string_view name, Enum* field, std::initializer_list<OptionChoice> choices, std::string_view help) {
    Add(name, field, choices, {}, help);
  }
  // The same for an option that used to be integer-coded: legacy_numbers lists choice names in the order of their
  // old numbers (number i means legacy_numbers[i]), so old command lines keep working. Throws std::logic_error
  // if a legacy name is not one of the choices (a programming error, caught by any test that binds the options).
  template <typename Enum>
  void Add(std::string_view name, Enum* field, std::initializer_list<OptionChoice> choices,
           std::initializer_list<std::string_view> legacy_numbers, std::string_view help) {
    static_assert(std::is_enum_v<Enum>);
    ChoiceField f;
    f.field = field;
    f.get = [](const void* p) { return static_cast<int>(*static_cast<const Enum*>(p)); };
    f.set = [](void* p, int v) { *static_cast<Enum*>(p) = static_cast<Enum>(v); };
    for (const OptionChoice& c : choices) f.choices.emplace_back(std::string(c.name), c.value);
    for (std::string_view legacy : legacy_numbers) f.legacy_values.push_back(f.ValueOf(name, legacy));
    entries_.push_back({std::string(name), std::move(f), std::string(help)});
  }
  // Sets name to value. Returns false with *error naming the problem (unknown key, unparsable value).
  bool Set(std::string_view name, std::string_view value, std::string* error) const;
  // Current value of an option as text that Set() parses back exactly; empty if the name is unknown.
  std::string ValueText(std::string_view name) const;
  // "name (type, now V): help" lines, one per option.
  std::string Help() const;

 private:
  struct ChoiceField {
    void* field = nullptr;
    int (*get)(const void*) = nullptr;
    void (*set)(void*, int) = nullptr;
    std::vector<std::pair<std::string, int>> choices;
    // legacy_values[i]: the value the old number i stands for.
    std::vector<int> legacy_values;
    // The first name listed for the field's current value ("?" if none).
    std::string Current() const;
    // The value of choice `choice` of option `option`; throws std::logic_error if there is no such choice.
    int ValueOf(std::string_view option, std::string_view choice) const;
    // Sets the field from a name or an old number; false with *error listing what is accepted.
    bool Set(const std::string& option, const std::string& text, std::string* error) const;
    // "auto, schur, basic, split, or an old number 0=auto 1=schur 2=basic 3=split".
    std::string Accepted() const;
    // "old number 0=auto 1=schur 2=basic 3=split".
    std::string LegacyNumbers() const;
  };
  struct Entry {
    std::string name;
    std::variant<double*, int*, bool*, ChoiceField> field;
    std::string help;
  };
  std::vector<Entry> entries_;
};

}  // namespace smcbench

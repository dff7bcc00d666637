// Options common to every backend, plus a small binder that maps "key=value" strings onto a backend's typed
// option struct (for the CLI) and rejects unknown names.
#pragma once

#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
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
  // Stamp SolveResult::solve_seconds. Reading the clock twice costs ~40 ns, comparable to a whole m ≤ 2 solve,
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

// Remembers the last value of a backend's options struct that passed its IsValid, byte for byte, so validating
// an unchanged value again (every solve of a time-stepper) costs one fixed-size memcmp instead of every field
// test. A changed value (SetOption, mutable_options(), set_options()) differs in its bytes and is validated
// afresh; equal bytes mean equal fields, hence the same verdict. Not thread-safe, like the Solver that owns it.
template <typename Options>
class OptionsCheckCache {
  static_assert(std::is_trivially_copyable_v<Options>, "compared and copied bytewise");

 public:
  bool Check(const Options& options, std::string* why) const {
    if (valid_ && std::memcmp(&options, &last_, sizeof(Options)) == 0) return true;
    valid_ = false;
    if (!options.IsValid(why)) return false;
    std::memcpy(static_cast<void*>(&last_), &options, sizeof(Options));
    valid_ = true;
    return true;
  }

 private:
  mutable Options last_{};
  mutable bool valid_ = false;
};

// Binds option names to fields of a typed options struct, so "omega=1.5" can be parsed and checked.
class OptionBinder {
 public:
  void Add(std::string_view name, double* field, std::string_view help);
  void Add(std::string_view name, int* field, std::string_view help);
  void Add(std::string_view name, bool* field, std::string_view help);
  // Sets name to value. Returns false with *error naming the problem (unknown key, unparsable value).
  bool Set(std::string_view name, std::string_view value, std::string* error) const;
  // Current value of an option as text that Set() parses back exactly; empty if the name is unknown.
  std::string ValueText(std::string_view name) const;
  // "name (type, now V): help" lines, one per option.
  std::string Help() const;

 private:
  struct Entry {
    std::string name;
    std::variant<double*, int*, bool*> field;
    std::string help;
  };
  std::vector<Entry> entries_;
};

}  // namespace smcbench

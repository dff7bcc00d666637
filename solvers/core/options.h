// Options common to every backend, plus a small binder that maps "key=value" strings onto a backend's typed
// option struct (for the CLI) and rejects unknown names.
#pragma once

#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "solvers/core/types.h"

namespace smcbench {

struct SolverOptions {
  // Solved means: relative natural residual ‖z − Π(z − F(z))‖∞ / scale ≤ tolerance.
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

  // True if every field is usable; otherwise *why explains which one and why.
  bool IsValid(std::string* why) const;
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

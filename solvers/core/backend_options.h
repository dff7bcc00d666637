// Why: every backend with a typed options struct exposes it the same way (read, change in place, replace), and the
// two ways to change it must both tell prepared sessions to check the options again. One template says it once.
#pragma once

#include "solvers/core/solver.h"

namespace smcbench {

// Base of a backend whose typed options are an `Options` struct (LemkeOptions, PsorOptions, ...). The backend
// derives from BackendWithOptions<Options> instead of Solver and reads its options as options_.
template <typename Options>
class BackendWithOptions : public Solver {
 public:
  const Options& options() const { return options_; }
  // The options, to change in place; sessions prepared with this backend check them again on their next call.
  Options& mutable_options() {
    OptionsChanged();
    return options_;
  }
  // Replaces the options; they are validated when the next solve runs (invalid → kInvalidOptions).
  void set_options(const Options& options) {
    options_ = options;
    OptionsChanged();
  }

 protected:
  BackendWithOptions() = default;
  explicit BackendWithOptions(const Options& options) : options_(options) {}

  Options options_;
};

}  // namespace smcbench

// libFuzzer target for typed backend options (Solver::SetOption, what `smcbench solve --set BACKEND.NAME=VALUE`
// calls): every line "name=value" of the input is set on every registered backend, then each built-in backend
// solves a small box-MLCP with the options that were accepted. A rejected option must leave the backend unchanged
// and say why; an accepted one must never make Solve crash, hang or throw (bad combinations are a status).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "solvers/registry/registry.h"
#include "tests/fuzz/fuzz_checks.h"

namespace {

using smcbench::kInf;
using smcbench::Vector;

[[noreturn]] void Finding(std::string_view backend, const std::string& what) {
  std::fprintf(stderr, "FINDING (%.*s): %s\n", static_cast<int>(backend.size()), backend.data(), what.c_str());
  std::abort();
}

// M is a P-matrix, so every backend that applies has a unique solution to find; rows: relay, LCP, free.
smcbench::BoxMLCP SmallProblem() {
  smcbench::DenseMatrix M(3, 3);
  M << 4, 1, 0, 1, 3, 1, 0, 1, 2;
  Vector q(3), l(3), u(3);
  q << -1, 2, -1;
  l << -1, 0, -kInf;
  u << 1, kInf, kInf;
  return smcbench::BoxMLCP(M, q, l, u, "fuzz-small");
}

// The common options a line "solve.NAME=VALUE" may set; the time limit stays short so no input can hang.
// Returns true if it set one.
bool SetCommonOption(std::string_view name, const std::string& value, smcbench::SolverOptions* options) {
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0') return false;
  if (name == "tolerance") {
    options->tolerance = v;
  } else if (name == "max_iterations" && std::abs(v) < 1e9) {
    options->max_iterations = static_cast<int>(v);
  } else if (name == "warm_start") {
    options->warm_start = Vector::Constant(3, v);
  } else {
    return false;
  }
  return true;
}

bool IsExternal(std::string_view name) { return name.rfind("siconos", 0) == 0; }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::vector<std::pair<std::string, std::string>> lines;
  for (std::size_t start = 0; start <= text.size() && lines.size() < 64;) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(start, end - start);
    const std::size_t eq = line.find('=');
    if (eq == std::string_view::npos) {
      lines.emplace_back(std::string(line), std::string());
    } else {
      lines.emplace_back(std::string(line.substr(0, eq)), std::string(line.substr(eq + 1)));
    }
    start = end + 1;
  }

  static const smcbench::BoxMLCP problem = SmallProblem();
  smcbench::SolverOptions options;
  options.time_limit_seconds = 0.1;
  bool common_set = false;
  for (const auto& [name, value] : lines) {
    if (name.rfind("solve.", 0) == 0) common_set |= SetCommonOption(std::string_view(name).substr(6), value, &options);
  }

  // One default-constructed instance per backend, kept between inputs while it stays in its default state (a
  // rejected option must not change it, which is checked), replaced once an option was accepted: creating an
  // Ipopt or Lemke backend under ASan costs far more than checking one input.
  static std::vector<std::unique_ptr<smcbench::Solver>> pool;
  const std::vector<std::string_view> names = smcbench::SolverNames();
  if (pool.empty()) {
    for (std::string_view backend : names) pool.push_back(smcbench::CreateSolver(backend));
  }
  for (std::size_t b = 0; b < names.size(); ++b) {
    const std::string_view backend = names[b];
    smcbench::Solver& solver = *pool[b];
    // Solve never throws for a valid problem, and SetOption reports through its return value.
    smcbench::fuzz::NoExceptionAllowed("(" + std::string(backend) + ") unexpected ", [&] {
      bool changed = common_set;
      for (const auto& [name, value] : lines) {
        const std::string before = solver.OptionsHelp();
        std::string error;
        if (solver.SetOption(name, value, &error)) {
          changed = true;
          continue;
        }
        if (error.empty()) Finding(backend, "SetOption('" + name + "') failed without a message");
        if (solver.OptionsHelp() != before) Finding(backend, "rejected option '" + name + "' changed the backend");
      }
      if (!changed) return;  // default options: solving again would find nothing new
      // Solves fork a worker process for the external backends: too slow to fuzz here, only SetOption is.
      if (!IsExternal(backend)) {
        smcbench::SolveResult result;
        solver.Solve(problem, options, &result);
        if (result.status == smcbench::SolveStatus::kNotRun) Finding(backend, "Solve left the status at not_run");
        if (result.status == smcbench::SolveStatus::kSolved && !(result.residual_rel <= options.tolerance)) {
          Finding(backend, "solved with a residual above the tolerance");
        }
        if (result.status == smcbench::SolveStatus::kInvalidOptions && result.message.empty()) {
          Finding(backend, "invalid options without a message");
        }
      }
      pool[b] = smcbench::CreateSolver(backend);
    });
  }
  return 0;
}

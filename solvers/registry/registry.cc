#include "solvers/registry/registry.h"

#include <functional>
#include <string>
#include <utility>

#include "solvers/enumerative/enumerative_solver.h"
#include "solvers/ipopt/ipopt_qp_solver.h"
#include "solvers/lemke/lemke_solver.h"
#include "solvers/newton/semismooth_newton_solver.h"
#include "solvers/psor/psor_solver.h"

namespace smcbench {
namespace {

using Factory = std::unique_ptr<Solver> (*)();

template <typename T>
std::unique_ptr<Solver> Make() {
  return std::make_unique<T>();
}

// The registry: one line per backend, in the order `smcbench list` prints them.
constexpr std::pair<std::string_view, Factory> kBackends[] = {
    {"lemke", &Make<LemkeSolver>},
    {"psor", &Make<PsorSolver>},
    {"newton", &Make<SemismoothNewtonSolver>},
    {"enum", &Make<EnumerativeSolver>},
    {"ipopt", &Make<IpoptQpSolver>},
};

}  // namespace

std::vector<std::string_view> SolverNames() {
  std::vector<std::string_view> names;
  for (const auto& [name, factory] : kBackends) names.push_back(name);
  return names;
}

std::unique_ptr<Solver> CreateSolver(std::string_view name) {
  for (const auto& [known, factory] : kBackends) {
    if (known == name) return factory();
  }
  std::string list;
  for (const auto& [known, factory] : kBackends) list += (list.empty() ? "" : ", ") + std::string(known);
  throw InvalidInputError("unknown solver '" + std::string(name) + "' (known: " + list + ")");
}

}  // namespace smcbench

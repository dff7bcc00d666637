#include "solvers/registry/registry.h"

#include <functional>
#include <string>
#include <utility>

#include "solvers/auto/auto_solver.h"
#include "solvers/enumerative/enumerative_solver.h"
#include "solvers/ipopt/ipopt_qp_solver.h"
#include "solvers/lemke/lemke_solver.h"
#include "solvers/newton/semismooth_newton_solver.h"
#include "solvers/psor/psor_solver.h"
#include "solvers/siconos/external_backends.h"

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
    // The default of the commands: one of the four above per problem (solvers/auto/auto_solver.h).
    {"auto", &Make<AutoSolver>},
};

// Ours, then the optional external ones that were built in (siconos-*; none without Siconos).
std::vector<std::pair<std::string_view, Factory>> AllBackends() {
  std::vector<std::pair<std::string_view, Factory>> all(std::begin(kBackends), std::end(kBackends));
  std::vector<ExternalBackend> external;
  AppendExternalBackends(&external);
  for (const ExternalBackend& e : external) all.emplace_back(e.name, e.create);
  return all;
}

}  // namespace

std::vector<std::string_view> SolverNames() {
  std::vector<std::string_view> names;
  for (const auto& [name, factory] : AllBackends()) names.push_back(name);
  return names;
}

std::unique_ptr<Solver> CreateSolver(std::string_view name) {
  const auto all = AllBackends();
  for (const auto& [known, factory] : all) {
    if (known == name) return factory();
  }
  std::string list;
  for (const auto& [known, factory] : all) list += (list.empty() ? "" : ", ") + std::string(known);
  throw InvalidInputError("unknown solver '" + std::string(name) + "' (known: " + list + ")");
}

}  // namespace smcbench

// The backend registry: a fixed table of ours, the external adapters built in, and the run-time additions.
#include "solvers/registry/registry.h"

#include <deque>
#include <mutex>
#include <string>
#include <utility>

#include "solvers/auto/auto_solver.h"
#include "solvers/enumerative/enumerative_solver.h"
#include "solvers/ipopt/ipopt_qp_solver.h"
#include "solvers/lemke/lemke_solver.h"
#include "solvers/newton/newton_min_solver.h"
#include "solvers/newton/semismooth_newton_solver.h"
#include "solvers/pivoting/bpp_solver.h"
#include "solvers/psor/psor_solver.h"
#include "solvers/siconos/external_backends.h"

namespace smcbench {
namespace {

template <typename T>
std::unique_ptr<Solver> Make() {
  return std::make_unique<T>();
}

std::unique_ptr<Solver> CreateRegisteredOrNull(std::string_view name);

// auto, with the registry as its lookup for the candidates it does not build itself (its MCP chain).
std::unique_ptr<Solver> MakeAuto() { return std::make_unique<AutoSolver>(AutoOptions{}, &CreateRegisteredOrNull); }

// The registry: one line per backend, in the order `smcbench list` prints them.
constexpr std::pair<std::string_view, std::unique_ptr<Solver> (*)()> kBackends[] = {
    {"lemke", &Make<LemkeSolver>},
    {"psor", &Make<PsorSolver>},
    {"newton", &Make<SemismoothNewtonSolver>},
    {"enum", &Make<EnumerativeSolver>},
    {"ipopt", &Make<IpoptQpSolver>},
    {"newton-min", &Make<NewtonMinSolver>},
    {"bpp", &Make<BppSolver>},
    // The default of the commands: one of the four above per problem (solvers/auto/auto_solver.h).
    {"auto", &MakeAuto},
};

// A backend added with RegisterSolver. The deque never moves its elements, so the string_views SolverNames hands
// out stay valid for the life of the process.
struct RunTimeEntry {
  std::string name;
  SolverFactory create;
};

// The process-wide table of run-time additions (see RegisterSolver for why it is global), behind its mutex.
struct RunTimeTable {
  std::mutex mutex;
  std::deque<RunTimeEntry> entries;
};

RunTimeTable& RunTimeBackends() {
  static RunTimeTable table;  // constructed on first use: safe to call from other static initializers
  return table;
}

// Ours, then the optional external ones that were built in (siconos-*, bullet-*, dart-*; none without their
// libraries), then the run-time additions.
std::vector<std::pair<std::string_view, SolverFactory>> AllBackends() {
  std::vector<std::pair<std::string_view, SolverFactory>> all;
  for (const auto& [name, make] : kBackends) all.emplace_back(name, make);
  std::vector<ExternalBackend> external;
  AppendAllExternalBackends(&external);
  for (const ExternalBackend& e : external) all.emplace_back(e.name, e.create);
  RunTimeTable& table = RunTimeBackends();
  const std::lock_guard<std::mutex> lock(table.mutex);
  for (const RunTimeEntry& e : table.entries) all.emplace_back(e.name, e.create);
  return all;
}

// A fresh backend of a registered name other than auto itself, nullptr if there is none.
std::unique_ptr<Solver> CreateRegisteredOrNull(std::string_view name) {
  if (name == "auto") return nullptr;
  for (const auto& [known, factory] : AllBackends()) {
    if (known == name) return factory();
  }
  return nullptr;
}

std::string KnownNames(const std::vector<std::pair<std::string_view, SolverFactory>>& all) {
  std::string list;
  for (const auto& [known, factory] : all) list += (list.empty() ? "" : ", ") + std::string(known);
  return list;
}

}  // namespace

std::unique_ptr<Solver> CreateGenericSparsePathSolver() {
  NewtonOptions sparse_lu;
  sparse_lu.linear_solver = NewtonOptions::kSparseLinearSolver;
  return std::make_unique<SemismoothNewtonSolver>(sparse_lu);
}

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
  throw InvalidInputError("unknown solver '" + std::string(name) + "' (known: " + KnownNames(all) + ")");
}

void RegisterSolver(std::string name, SolverFactory factory) {
  const std::string what = "RegisterSolver('" + name + "')";
  if (name.empty()) throw InvalidInputError("RegisterSolver: name is empty");
  if (!factory) throw InvalidInputError(what + ": factory is empty");
  const auto all = AllBackends();
  for (const auto& [known, existing] : all) {
    if (known == name) throw InvalidInputError(what + ": name is already registered (known: " + KnownNames(all) + ")");
  }
  // Outside the lock: the factory is user code.
  const std::unique_ptr<Solver> probe = factory();
  if (!probe) throw InvalidInputError(what + ": factory returned no backend");
  if (probe->info().name != name) {
    throw InvalidInputError(what + ": the backend's info().name is '" + std::string(probe->info().name) +
                            "'; it must equal the registered name");
  }
  RunTimeTable& table = RunTimeBackends();
  const std::lock_guard<std::mutex> lock(table.mutex);
  for (const RunTimeEntry& e : table.entries) {  // a concurrent registration of the same name won the race
    if (e.name == name) throw InvalidInputError(what + ": name is already registered");
  }
  table.entries.push_back({std::move(name), std::move(factory)});
}

bool IsExternalBackendName(std::string_view name) {
  for (std::string_view family : {"siconos-", "bullet-", "dart-"}) {
    if (name.substr(0, family.size()) == family) return true;
  }
  return false;
}

bool IsRegisteredAtRunTime(std::string_view name) {
  RunTimeTable& table = RunTimeBackends();
  const std::lock_guard<std::mutex> lock(table.mutex);
  for (const RunTimeEntry& e : table.entries) {
    if (e.name == name) return true;
  }
  return false;
}

}  // namespace smcbench

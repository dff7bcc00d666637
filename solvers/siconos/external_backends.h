// The backends that wrap optional third-party libraries (Siconos Numerics), listed by the registry only when
// the library was found at configure time. CMake compiles exactly one implementation of this header: the
// Siconos adapters (siconos_solver.cc) or the empty list (no_external_backends.cc). No #ifdef anywhere.
#pragma once

#include <memory>
#include <string_view>
#include <vector>

#include "solvers/core/solver.h"

namespace smcbench {

struct ExternalBackend {
  std::string_view name;                // registry name, e.g. "siconos-relay-lemke"
  std::unique_ptr<Solver> (*create)();  // a fresh backend with default options
};

// Appends the external backends built into this binary, in the order `smcbench list` prints them.
void AppendExternalBackends(std::vector<ExternalBackend>* backends);

// True if name is one of them. Cross-backend tests use it: an external backend only takes the problem shapes its
// library can express (kNotApplicable otherwise) and refuses large enumerations (kSizeLimit).
inline bool IsExternalBackend(std::string_view name) {
  std::vector<ExternalBackend> external;
  AppendExternalBackends(&external);
  for (const ExternalBackend& e : external) {
    if (e.name == name) return true;
  }
  return false;
}

}  // namespace smcbench

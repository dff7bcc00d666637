// The backends that wrap optional third-party libraries (Siconos Numerics, Bullet, DART), listed by the registry
// only when the library was found at configure time. For each library CMake compiles exactly one implementation of
// its Append function: the adapters (siconos_solver.cc, bullet/bullet_solver.cc, dart/dart_solver.cc) or the empty
// list (no_external_backends.cc, bullet/no_bullet_backends.cc, dart/no_dart_backends.cc). No #ifdef anywhere.
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

// Appends the Siconos backends built into this binary, in the order `smcbench list` prints them.
void AppendExternalBackends(std::vector<ExternalBackend>* backends);
// The same for the physics engines' box-LCP solvers: bullet-* (solvers/bullet) and dart-* (solvers/dart).
void AppendBulletBackends(std::vector<ExternalBackend>* backends);
void AppendDartBackends(std::vector<ExternalBackend>* backends);
// Every external backend built in: Siconos', then Bullet's, then DART's.
inline void AppendAllExternalBackends(std::vector<ExternalBackend>* backends) {
  AppendExternalBackends(backends);
  AppendBulletBackends(backends);
  AppendDartBackends(backends);
}

// True if name is one of them. Cross-backend tests use it: an external backend only takes the problem shapes its
// library can express (kNotApplicable otherwise) and refuses large enumerations (kSizeLimit).
inline bool IsExternalBackend(std::string_view name) {
  std::vector<ExternalBackend> external;
  AppendAllExternalBackends(&external);
  for (const ExternalBackend& e : external) {
    if (e.name == name) return true;
  }
  return false;
}

}  // namespace smcbench

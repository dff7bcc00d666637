// A sixth backend that only tests register: lemke's pivoting reached through the public Solver::Solve, under its own
// name and with its own capabilities. A test executable that calls RegisterTestBackend before its backend lists are
// built shows that the capability-based suites (conformance, scaling invariance, allocation) pick up a new backend
// registered once, with no list of names to edit.
#pragma once

#include <memory>

#include "solvers/core/solver.h"
#include "solvers/registry/registry.h"

namespace smcbench::test_support {

inline constexpr const char* kTestBackendName = "test-lemke";

class LemkeThroughTheInterface final : public Solver {
 public:
  const SolverInfo& info() const override {
    static const SolverInfo kInfo{
        kTestBackendName,
        "lemke called through Solver::Solve: a backend registered only by tests (tests/support/test_backend.h)",
        "Lemke, Management Science 11 (1965) 681-689, as smcbench's lemke implements it",
        /*dense=*/true,
        /*sparse=*/false,
        /*symmetric_only=*/false,
        /*exact=*/true,
        /*mcp=*/false,
        /*default_size_limit=*/0,
        /*equilibrate=*/true,
        /*delegates=*/false,
        /*external=*/false,
        /*allocation_free=*/true,
        /*solves_every_p_matrix=*/true,
        /*practical_size_limit=*/0};
    return kInfo;
  }

 protected:
  void DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) override {
    lemke_->Solve(problem, options, &inner_);  // inner_ is reused, so repeated solves allocate nothing
    result->z = inner_.z;
    result->iterations = inner_.iterations;
    result->status = inner_.status;
    result->message = inner_.message;
  }

 private:
  std::unique_ptr<Solver> lemke_ = CreateSolver("lemke");
  SolveResult inner_;
};

// Registers the test backend once per process (RegisterSolver refuses a second registration of a name).
inline void RegisterTestBackend() {
  static const bool registered = [] {
    RegisterSolver(kTestBackendName, [] { return std::make_unique<LemkeThroughTheInterface>(); });
    return true;
  }();
  static_cast<void>(registered);
}

}  // namespace smcbench::test_support

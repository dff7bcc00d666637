// Certified references for sets of AVIs (avi_references.h).
#include "problems/avi_library/avi_references.h"

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "solvers/avi/avi_solver.h"
#include "solvers/avi/avi_verdict.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

// ComputeAviReference with the candidate backends created once (AttachAviReferences runs many AVIs through them).
class AviReferenceMaker {
 public:
  explicit AviReferenceMaker(const ReferenceOptions& options) : options_(options) {
    if (!options_.ask_backends) return;
    for (const char* name : kReferenceCandidateBackends) backends_.push_back(CreateSolver(name));
    solve_options_.measure_time = false;  // the backends' timing is not wanted; the rest at its defaults
  }

  AviReference Compute(const AviLibraryProblem& p) {
    if (!p.problem || AviReductionRows(*p.problem) > options_.max_size) return {};
    std::vector<AviSolution> candidates;
    // Every answer, solved or not: a backend's last iterate may sit on the right face, and a second verified
    // answer is what proves non-uniqueness. Wrong ones cost a solve of the reduction.
    for (const std::unique_ptr<Solver>& backend : backends_) {
      AviResult result = SolveAvi(*p.problem, *backend, solve_options_);
      if (result.solution.lambda.size() == p.problem->size() && result.solution.lambda.allFinite()) {
        candidates.push_back(std::move(result.solution));
      }
    }
    CertifyOptions certify;
    certify.max_size = options_.max_size;
    AviReference reference = CertifyAvi(*p.problem, candidates, certify);
    // An AVI stated to have no solution cannot have a verified one: the set's statement is wrong, and every verdict
    // on the AVI with it.
    if (p.expected == ExpectedOutcome::kInfeasible && reference.verified()) {
      throw std::logic_error("AVI '" + QuoteForMessage(p.id) +
                             "' is expected infeasible, but CertifyAvi verified a solution (certificate '" +
                             std::string(ToString(reference.reduced.certificate)) +
                             "'): the set's expected outcome is wrong");
    }
    return reference;
  }

 private:
  ReferenceOptions options_;
  std::vector<std::unique_ptr<Solver>> backends_;
  SolverOptions solve_options_;
};

}  // namespace

int AviReductionRows(const AffineVI& avi) { return avi.size() + avi.inequality_count() + avi.equality_count(); }

AviReference ComputeAviReference(const AviLibraryProblem& problem, const ReferenceOptions& options) {
  return AviReferenceMaker(options).Compute(problem);
}

void AttachAviReferences(AviProblemSet* set, const ReferenceOptions& options) {
  std::optional<AviReferenceMaker> maker;  // created at the first AVI that needs it (backends are not free)
  for (AviLibraryProblem& p : set->problems) {
    if (p.reference.reduced.certificate != Certificate::kNone || !p.problem ||
        AviReductionRows(*p.problem) > options.max_size) {
      continue;
    }
    if (!maker) maker.emplace(options);
    p.reference = maker->Compute(p);
    // Metadata that describes the reference (the avi suite's keys) must not keep describing the old one.
    if (p.metadata.count("certificate")) {
      p.metadata["certificate"] = std::string(ToString(p.reference.reduced.certificate));
    }
    if (p.metadata.count("lambda_unique")) p.metadata["lambda_unique"] = p.reference.lambda_unique ? "yes" : "no";
  }
}

}  // namespace smcbench

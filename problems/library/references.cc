#include "problems/library/references.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "solvers/reference/certify.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

bool HasLabel(const LibraryProblem& p, std::string_view label) {
  return std::find(p.tags.begin(), p.tags.end(), label) != p.tags.end();
}

// ComputeReference with the candidate backends created once (AttachReferences runs many problems through them).
class ReferenceMaker {
 public:
  explicit ReferenceMaker(const ReferenceOptions& options) : options_(options) {
    if (!options_.ask_backends) return;
    for (const char* name : kReferenceCandidateBackends) backends_.push_back(CreateSolver(name));
    // The backends' timing is not wanted; everything else at its defaults (tolerance 1e-10, polish on).
    solve_options_.measure_time = false;
  }

  ReferenceSolution Compute(const LibraryProblem& p) {
    if (p.size() > options_.max_size) return {};
    std::vector<Vector> candidates;
    if (p.solution.size() == p.size()) candidates.push_back(p.solution);
    // Every answer, solved or not: a backend's last iterate may still sit on the right active set, and a second,
    // distinct verified answer is what proves non-uniqueness. Certify checks each one; wrong ones cost a solve.
    for (const std::unique_ptr<Solver>& backend : backends_) {
      backend->Solve(p.problem, solve_options_, &result_);
      if (result_.z.size() == p.size() && result_.z.allFinite()) candidates.push_back(result_.z);
    }
    CertifyOptions certify;
    certify.max_size = options_.max_size;
    if (p.matrix.p_matrix == Tristate::kYes) certify.p_matrix = true;
    if (p.matrix.p_matrix == Tristate::kNo) certify.p_matrix = false;
    ReferenceSolution reference = Certify(p.problem, candidates, certify);
    // A construction that proves several solutions (label "non-unique": a segment of solutions, a ray, two
    // branches) overrides a uniqueness found in the stored bits: rounding M to double can leave exactly one
    // solution (PSD-singular M gets a tiny eigenvalue, μ ≈ 1e17 or an endpoint of the old segment with μ ≈ 10),
    // and judging a backend's forward error against it would call the planted z*, which solves the problem to
    // 1e-16, inaccurate.
    if (reference.verified() && HasLabel(p, kNonUniqueLabel)) reference.certificate = Certificate::kNonUnique;
    // A problem built to have no solution (a certificate row, families.cc) cannot have a verified one: if Certify
    // verifies a point, the construction is wrong, and every verdict on the problem with it.
    if (p.expected == ExpectedOutcome::kInfeasible && reference.verified()) {
      throw std::logic_error("problem '" + QuoteForMessage(p.id) +
                             "' is expected infeasible, but Certify verified a solution (certificate '" +
                             std::string(ToString(reference.certificate)) +
                             "'): the problem's construction is wrong");
    }
    return reference;
  }

 private:
  ReferenceOptions options_;
  std::vector<std::unique_ptr<Solver>> backends_;
  SolverOptions solve_options_;
  SolveResult result_;
};

}  // namespace

ReferenceSolution ComputeReference(const LibraryProblem& problem, const ReferenceOptions& options) {
  return ReferenceMaker(options).Compute(problem);
}

ReferenceSolution ProvedReference(const LibraryProblem& p) {
  ReferenceSolution out = p.reference;
  // A reference read from a file, which does not store the proof: proved again from its z*.
  if (std::isnan(out.proved_radius)) AddProof(p.problem, &out);
  return out;
}

void AttachReferences(ProblemSet* set, const ReferenceOptions& options) {
  std::optional<ReferenceMaker> maker;  // created at the first problem that needs it (backends are not free)
  for (LibraryProblem& p : set->problems) {
    p.reference = ProvedReference(p);
    if (p.reference.certificate != Certificate::kNone || p.size() > options.max_size) continue;
    if (!maker) maker.emplace(options);
    p.reference = maker->Compute(p);
  }
}

}  // namespace smcbench

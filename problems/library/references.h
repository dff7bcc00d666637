// Certified reference solutions for library problems: so that a backend's answer is judged by its
// forward error ‖z − z*‖∞ against a z* proven in extended precision (solvers/reference/certify.h), not only by its
// residual. Suites, captures and `smcbench library --certify` attach them; the .smcps format stores them.
#pragma once

#include <string_view>

#include "problems/library/problem_set.h"

namespace smcbench {

struct ReferenceOptions {
  int max_size = 64;         // larger problems keep Certificate::kNone
  bool ask_backends = true;  // also use the answers of our exact/robust backends (lemke, enum, newton) as candidates
};

// The backends whose answers ComputeReference tries as candidates (with ReferenceOptions::ask_backends): the two
// exact ones (pivoting, enumeration) and the most robust iterative one. Any of them may be wrong: Certify checks.
inline constexpr const char* kReferenceCandidateBackends[] = {"lemke", "enum", "newton"};

// The label (LibraryProblem::tags) of problems whose construction proves several solutions.
inline constexpr std::string_view kNonUniqueLabel = "non-unique";

// The certified reference for one library problem: candidates = its known solution (planted or captured), the
// backends' answers; CertifyOptions::p_matrix from the problem's matrix tags. What the construction proves
// overrides what the stored bits show: a verified z* on a problem labelled kNonUniqueLabel is kNonUnique (rounding
// M to double can make a singular problem's solution unique, with no meaning for the data it stands for). Never
// throws for a valid problem, except std::logic_error naming the id when a solution is verified on a problem
// whose expected outcome is infeasible (the problem's construction is wrong).
ReferenceSolution ComputeReference(const LibraryProblem& problem, const ReferenceOptions& options = {});

// The problem's reference with its proof (ReferenceSolution::proved_radius, proved_unique): as it is when it has
// one or is not verified; else (read from a file, which does not store the proof) proved here from its z*
// (solvers/reference/enclosure.h).
ReferenceSolution ProvedReference(const LibraryProblem& problem);

// Fills LibraryProblem::reference for every problem whose certificate is kNone (and size ≤ max_size), and the
// proved radius (ReferenceSolution::proved_radius, solvers/reference/enclosure.h) of references already verified
// (read from a file, which does not store it). Same exceptions as ComputeReference.
void AttachReferences(ProblemSet* set, const ReferenceOptions& options = {});

}  // namespace smcbench

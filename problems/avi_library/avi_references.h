// Certified references for the AVIs of a set that has none (`smcbench library FILE.smcps --certify OUT` on a set of
// AVIs): the AVI analogue of problems/library/references.h, through CertifyAvi (solvers/avi/avi_verdict.h).
#pragma once

#include "problems/avi_library/avi_library.h"
#include "problems/library/references.h"

namespace smcbench {

// Rows of the reduction CertifyAvi solves (n + m + p): what ReferenceOptions::max_size limits for an AVI, since
// the certifier's cost grows with the reduction, not with n alone.
int AviReductionRows(const AffineVI& avi);

// The certified reference of one AVI: candidates are the answers of kReferenceCandidateBackends on its reduction
// (SolveAvi, solved or not: Certify checks each one); kNone when the reduction has more than options.max_size rows.
// Throws std::logic_error naming the id when a solution is verified on an AVI expected infeasible (the set's
// statement is wrong), as ComputeReference does for a box problem.
AviReference ComputeAviReference(const AviLibraryProblem& problem, const ReferenceOptions& options = {});

// Fills AviLibraryProblem::reference for every AVI whose certificate is kNone and whose reduction has at most
// options.max_size rows; references already there are kept. The metadata keys "certificate" and "lambda_unique",
// where an AVI has them (the avi suite writes them), are updated to say the same as the new reference. Same
// exceptions as ComputeAviReference.
void AttachAviReferences(AviProblemSet* set, const ReferenceOptions& options = {});

}  // namespace smcbench

// Matrix-class tags (symmetric, positive definite, P-matrix) computed from M itself, with a yes/no answer only
// where a test settles it in floating point and "unknown" otherwise: captures and generators tag their problems
// with it, and a benchmark may select or explain results by class.
#pragma once

#include "problems/library/problem_set.h"

namespace smcbench {

struct ClassifyOptions {
  // Eigenvalues of the symmetric part (positive definiteness) for n up to this size (a sparse M is densified).
  int max_eigen_size = 500;
  // All 2ⁿ − 1 principal minors (P-matrix) for n up to this size.
  int max_minors_size = 10;
};

// Every test is one of solvers/core/matrix_class.h:
// symmetric: BoxMLCP::IsSymmetric (within 1e-12·max|M_ij|).
// positive_definite (of H = (M + Mᵀ)/2, DefinitenessTest::kEigenvalues): λ_min(H) > τ → yes, λ_min(H) < −τ → no,
//   else unknown, with τ = 8 n ε max|λ(H)|; unknown above max_eigen_size.
// p_matrix: yes if positive_definite is yes (xᵀMx > 0 makes every principal minor positive); no if a diagonal
//   entry is ≤ 0 (an exact 1×1 minor); for n ≤ max_minors_size (at most 30) every principal minor is computed by
//   LU and judged against 16 k ε times Hadamard's bound ∏‖columns‖₂ of the k×k submatrix
//   (PrincipalMinorTest::kDeterminantVsHadamard): one clearly negative minor → no, all clearly positive → yes,
//   else unknown. Otherwise unknown.
MatrixTags ClassifyMatrix(const BoxMLCP& problem, const ClassifyOptions& options = {});

}  // namespace smcbench

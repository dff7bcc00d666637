// Matrix classes that a backend's guarantee or a problem's tag depends on (symmetric, positive definite, positive
// semidefinite, P-matrix), decided in one place in double precision. Every test states its margin, returns a
// certificate and answers yes, no or "not decided" (too large to test, or too close to call in floating point):
// an untested matrix is never silently "no". solvers/reference/certify.cc keeps its own tests on purpose: they run
// in quad precision, so that a certified reference holds beyond double rounding.
#pragma once

#include <Eigen/Cholesky>
#include <cstdint>
#include <string_view>
#include <vector>

#include "solvers/core/types.h"

namespace smcbench {

enum class MatrixClassAnswer : std::uint8_t { kNotDecided = 0, kNo = 1, kYes = 2 };
std::string_view ToString(MatrixClassAnswer answer);  // "not decided", "no", "yes"

// ---- Symmetry: max_ij |e_i M_ij − e_j M_ji| ≤ relative_tolerance · max_ij |e_i M_ij| (e = 1 unless row weights
// are given: "diag(e) M is symmetric", which is how a row-scaled symmetric M is recognised). Always decided.
struct SymmetryOptions {
  // 1e-12: about 4500 ε, above the rounding of a matrix assembled as a sum of symmetric terms, far below any
  // asymmetry a model means.
  double relative_tolerance = 1e-12;
};

struct SymmetryResult {
  MatrixClassAnswer answer = MatrixClassAnswer::kNotDecided;
  double max_asymmetry = 0.0;  // max |e_i M_ij − e_j M_ji|
  double max_entry = 0.0;      // max |e_i M_ij|
  int row = -1, col = -1;      // the offending pair: where max_asymmetry is reached (−1 if M is symmetric exactly)
};

// Throws InvalidInputError if M is not square, has a non-finite entry, or row_weights is not of size n.
SymmetryResult ClassifySymmetry(const DenseMatrix& M, const SymmetryOptions& options = {},
                                const Vector* row_weights = nullptr);
SymmetryResult ClassifySymmetry(const SparseMatrix& M, const SymmetryOptions& options = {},
                                const Vector* row_weights = nullptr);

// ---- Positive definiteness of the symmetric part H = (M + Mᵀ)/2 (for symmetric M, of M itself): xᵀMx > 0.
enum class DefinitenessTest : std::uint8_t {
  // Cholesky with margin δ = margin · n · ε · ‖H‖∞: yes if H − δI factors (λ_min(H) > δ), no if H + δI does not
  // (λ_min(H) < −δ), otherwise not decided. Default margin 1e3: forming and factoring H rounds by about n·ε·‖H‖,
  // so a thousand times that is not rounding. n³/3 flops.
  kCholesky = 0,
  // Eigenvalues of H with τ = margin · n · ε · max|λ(H)|: λ_min > τ yes, λ_min < −τ no, otherwise not decided;
  // H = 0 is no. Use margin 8 (the backward error of the symmetric QR algorithm is a small multiple of n·ε·‖H‖₂).
  // About 9n³ flops, but it gives λ_min itself.
  kEigenvalues = 1,
};

struct DefinitenessOptions {
  DefinitenessTest test = DefinitenessTest::kCholesky;
  double margin = 1e3;  // see DefinitenessTest
};

struct DefinitenessResult {
  MatrixClassAnswer answer = MatrixClassAnswer::kNotDecided;
  double shift = 0.0;  // δ or τ: the margin in units of M
  // kCholesky: the smallest pivot L_kk² of the factorization that succeeded (of H − δI for yes, of H + δI when not
  // decided; NaN for no). kEigenvalues: λ_min(H).
  double certificate = kNaN;
};

// Throws InvalidInputError if M is not square or has a non-finite entry.
DefinitenessResult ClassifySymmetricPartPositiveDefinite(const DenseMatrix& M, const DefinitenessOptions& options = {});

// ---- Positive semidefiniteness of H = (S + Sᵀ)/2 with a stated tolerance: yes if H + δI factors by Cholesky,
// δ = tolerance · ‖S‖∞ (λ_min(H) ≥ −δ up to rounding), no otherwise; S = 0 is yes. The tolerance is the caller's
// (a backend option): a convex QP on a matrix this close to PSD is still solved to its tolerance.
struct SemidefinitenessResult {
  MatrixClassAnswer answer = MatrixClassAnswer::kNotDecided;
  double shift = 0.0;           // δ
  double smallest_pivot = kNaN;  // min L_kk² of the factorization of H + δI when it succeeded
};

// factor: storage for the dense factorization (reused across calls, so repeated tests do not allocate anew).
// Throws InvalidInputError if S is not square, has a non-finite entry, or tolerance is negative or not finite.
SemidefinitenessResult ClassifySymmetricPartPositiveSemidefinite(const DenseMatrix& S, double tolerance,
                                                                 Eigen::LLT<DenseMatrix>* factor);
SemidefinitenessResult ClassifySymmetricPartPositiveSemidefinite(const SparseMatrix& S, double tolerance);

// ---- How far M is from symmetric: the squared Frobenius norms of its symmetric and skew parts (times two),
// ‖M + Mᵀ‖_F² and ‖M − Mᵀ‖_F², in one pass over the pairs i < j and the diagonal (m²/2 pairs, no allocation). The
// backends that steer by it (auto's skew-dominant rule, bpp's swept first set) each keep their own limit.
struct SymmetricSkewNorms {
  double symmetric_squared = 0.0;  // ‖M + Mᵀ‖_F²
  double skew_squared = 0.0;       // ‖M − Mᵀ‖_F²
  // ‖M − Mᵀ‖_F > ratio · ‖M + Mᵀ‖_F (false for M = 0).
  bool SkewOutweighsSymmetric(double ratio) const { return skew_squared > ratio * ratio * symmetric_squared; }
};

// M square (not checked: the callers' problems are validated); a non-finite entry gives non-finite norms.
SymmetricSkewNorms SymmetricAndSkewPartNorms(const DenseMatrix& M);

// ---- P-matrix: every principal minor positive (the box-MLCP then has exactly one solution for every q, l, u).
// 2ⁿ − 1 minors, so only up to max_size; larger matrices are not decided.
enum class PrincipalMinorTest : std::uint8_t {
  // LU with partial pivoting of each principal submatrix A (k×k); its sign counts when every pivot exceeds
  // margin · k · ε · max|A_ij|. Default margin 1e3 (pivots of that size are not rounding).
  kLuPivots = 0,
  // det(A) by LU against margin · k · ε times Hadamard's bound ∏‖a_j‖₂ (|det A| ≤ that bound, and the rounding
  // of the LU determinant is a small multiple of k·ε times it); 1×1 minors exactly. Use margin 16.
  kDeterminantVsHadamard = 1,
};

struct PMatrixOptions {
  int max_size = 12;  // 2¹² − 1 small factorizations, for a failure path. At most kMaxPMatrixTestSize.
  PrincipalMinorTest test = PrincipalMinorTest::kLuPivots;
  double margin = 1e3;  // see PrincipalMinorTest
};
inline constexpr int kMaxPMatrixTestSize = 30;

struct PMatrixResult {
  MatrixClassAnswer answer = MatrixClassAnswer::kNotDecided;
  bool too_large = false;  // n > max_size: not tested
  // The certificate: for no, a principal minor clearly negative; for yes, the smallest principal minor (by its
  // margin ratio); when not decided on a tested matrix, the first minor too close to zero to call.
  std::vector<int> minor_rows;   // its rows (= columns), ascending
  double minor = kNaN;           // its determinant
};

// Allocates (on the failure paths of backends and for tags only). Throws InvalidInputError if M is not square, has
// a non-finite entry, or max_size lies outside [0, kMaxPMatrixTestSize].
PMatrixResult ClassifyPMatrix(const DenseMatrix& M, const PMatrixOptions& options = {});

}  // namespace smcbench

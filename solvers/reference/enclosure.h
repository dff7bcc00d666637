// A proof, in interval arithmetic, that a box-MLCP has an exact solution within a stated distance of a point: what
// turns a certified reference (certify.h, whose margins are error estimates) into a proved one.
//
// Method (Krawczyk's / Rump's verification of a linear system, applied on the point's active set). The point z
// fixes every row at a bound (z_i = l_i or u_i) or free (l_i < z_i < u_i). On the free rows F the exact solution
// z*_F of M_FF z_F = −(q_F + M_FB z_B) is enclosed: with R ≈ M_FF⁻¹ (double LU), C = I − R M_FF and the residual
// r = −(M z + q)_F, e = z*_F − z_F solves e = R r + C e, so ‖C‖∞ ≤ α < 1 proves M_FF nonsingular and
// |e| ≤ |R||r| + |C| 1 ρ with ρ = ‖ |R||r| ‖∞ / (1 − α). Then (z*_F, z_B) is a solution of the box-MLCP when every
// free row's interval [z_i − e_i, z_i + e_i] lies strictly inside (l_i, u_i) and every bound row's w_i = (M z* + q)_i
// has the sign its bound needs (≥ 0 at l_i, ≤ 0 at u_i) over its whole enclosure. Rows with w_i = 0 at a bound
// (degenerate) cannot be proved this way.
//
// Rounding. No rounding-mode switch: every quantity is computed in round-to-nearest and bounded a priori by the
// standard model of floating-point arithmetic, |fl(Σ a_k b_k) − Σ a_k b_k| ≤ γ_n Σ |a_k b_k| with γ_n = nu/(1 − nu)
// (Higham, Accuracy and Stability of Numerical Algorithms, §3.1; it holds for any summation order and with fused
// multiply-adds), plus a term for gradual underflow; M z + q is accumulated in __float128, where the products of
// doubles are exact. Every bound is then inflated by a few units of rounding, so the enclosure is rigorous, not
// an estimate.
#pragma once

#include <string>

#include "solvers/core/problem.h"

namespace smcbench {

struct SolutionEnclosure {
  bool proved = false;
  // When proved: an exact solution z* of the problem has ‖z* − z‖∞ ≤ radius (0 when no row is free: z itself
  // solves it exactly).
  double radius = 0.0;
  std::string why_not;  // when not proved: the first condition that failed (for messages)
};

// The largest problem EncloseSolution attempts (its work is a dense LU and two n×n products).
inline constexpr int kMaxEnclosureSize = 64;

// Tries to prove that problem has a solution near z (z's active set, see above). Not proved, with the reason, when
// z is not finite, of the wrong size or outside [l, u], when n > kMaxEnclosureSize, when M_FF is not proved
// nonsingular (α ≥ 1: ill-conditioned or singular), or when a row's enclosure crosses what its state needs
// (degenerate rows included). Never throws for a valid problem.
SolutionEnclosure EncloseSolution(const BoxMLCP& problem, const Vector& z);

// A proof that the symmetric part of M is positive definite, which makes M a P-matrix, so that every box-MLCP with
// this M has exactly one solution. Method: an unblocked Cholesky factorization L̃ of fl((M + Mᵀ)/2) − cI in double,
// for a small shift c; when it runs to completion, L̃L̃ᵀ = S − cI + ΔA with |ΔA| ≤ γ_{n+1}|L̃||L̃ᵀ| (Demmel's bound,
// Higham §10.1), so λ_min((M + Mᵀ)/2) ≥ c − γ_{n+1}‖L̃‖_F² − (the rounding of S and of its shifted diagonal),
// and positive definiteness is proved when that is > 0. False for n > kMaxEnclosureSize, non-finite entries, a
// symmetric part that is not (or too nearly not) positive definite.
bool ProveSymmetricPartPositiveDefinite(const DenseMatrix& M);

}  // namespace smcbench

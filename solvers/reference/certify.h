// Certified reference solutions of small box-MLCPs, found and verified in extended precision, so that a backend's
// answer can be judged by its forward error ‖z − z*‖∞ (docs/verdict.md), not only by its residual.
//
// Method. An active set puts every row at its lower bound, at its upper bound or free. For one set, the free block
// of the row-equilibrated problem, (D⁻¹M)_FF z_F = −D⁻¹(q_F + M_FB z_B) (D = BoxMLCP::row_scale(): a positive row
// scaling leaves the solutions unchanged), is solved by Gaussian elimination with complete pivoting (rank-revealing:
// a pivot below 1e-28 times the block's largest entry makes it singular), μ = ‖((D⁻¹M)_FF)⁻¹‖∞ from the inverse,
// and w = M z + q is recomputed. The set is verified when, with the margin δ = 64·n·ε·(1 + μ)·(1 + ‖z‖∞ + ‖D⁻¹q‖∞)
// (ε = 2⁻¹¹², floor 1e-30; an error bound of the solve in units of z), free rows have |w_i/d_i| ≤ δ and lie within
// [l_i − δ(1+|l_i|), u_i + δ(1+|u_i|)], lower rows w_i/d_i ≥ −δ and upper rows w_i/d_i ≤ δ; a row inside a margin of
// the other choice is degenerate. Sets come from the natural map at each candidate point (and, if that set fails,
// from flipping its near-degenerate rows and a few block-principal-pivoting steps), from the cold point Π(0), and,
// when there are at most max_enumerated sets, from all of them. Uniqueness: the caller's p_matrix, a positive
// definite symmetric part (of D⁻¹M or of D^-½ M D^-½, LDLᵀ with a shift), all principal minors positive (n ≤ 12),
// or an exhaustive enumeration that met no singular block and one solution. A singular free block at a verified
// point, or two verified points farther apart than their margins, prove non-uniqueness.
//
// Why __float128: GCC's and clang's quad type (113-bit significand, ≈ 34 digits) needs no new dependency (basic
// arithmetic is in libgcc; nothing here calls libquadmath), unlike Boost.Multiprecision, is fast enough for
// n ≤ 64 (one elimination per set, in software arithmetic), and its 34 digits leave a usable margin for
// condition numbers up to about 1e20, where double has none beyond 1e16.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "solvers/core/solver.h"
#include "solvers/core/verdict.h"

namespace smcbench {

struct CertifyOptions {
  // Larger problems (sparse ones included) are not attempted: certificate kNone.
  int max_size = 64;
  // Exhaustive enumeration of the active sets when their count (3 per row with two finite distinct bounds, 2 per
  // row with one finite bound, 1 for free or fixed rows) is at most this: 3^8, eight relay rows.
  std::int64_t max_enumerated = 6561;
  // The caller's knowledge that M is (true) or is not (false) a P-matrix, e.g. from a generator's construction;
  // nullopt = unknown, tested here. A P-matrix box-MLCP has exactly one solution for every q, l, u.
  std::optional<bool> p_matrix;
};

// What Certify did (for messages and iteration counts).
struct CertifyStats {
  std::int64_t active_sets = 0;     // distinct active sets solved
  double active_sets_total = 0.0;   // the count of all active sets (as a double: 3^64 does not fit an int64)
  bool enumerated = false;          // all of them were solved
  std::int64_t singular_blocks = 0; // sets whose free block was (numerically) singular
  std::int64_t inconclusive = 0;    // nonsingular sets whose margin was too wide to decide (μ beyond ~1e20)
};

// The reference solution of problem: candidates are points to start from (a planted solution, a capture's
// solution, backends' answers); any may be wrong, and those of the wrong size or with non-finite entries are
// ignored. reference.z is z* rounded to double; reference.condition is μ at z*'s active set (the larger over both
// choices for degenerate rows; +∞ when z* was verified only through a singular block; 0 when no row is free).
// reference.proved_radius: EncloseSolution's radius at z* when it proves a solution there, and proved_unique when
// ProveSymmetricPartPositiveDefinite proves it the only one (enclosure.h; dense M).
// Never throws for a valid problem.
ReferenceSolution Certify(const BoxMLCP& problem, const std::vector<Vector>& candidates,
                          const CertifyOptions& options = {}, CertifyStats* stats = nullptr);

// Fills reference->proved_radius and proved_unique when the reference is verified and EncloseSolution proves a
// solution at its z (and ProveSymmetricPartPositiveDefinite, for a dense M, that it is the only one); leaves them
// (NaN, false) otherwise. Certify calls it; so does ProvedReference for references read from files.
void AddProof(const BoxMLCP& problem, ReferenceSolution* reference);

// The backend "reference": Certify from the start point and the warm start, dense n ≤ 64. kSolved with z = z* when
// a solution is verified (iterations = active sets solved, detail "certificate" = the Certificate, read through
// kCertificateDetail, "condition" = μ); else kNumericalFailure saying what was tried (never kInfeasible: finding
// nothing is not a proof).
inline constexpr CodeDetail<Certificate, 6> kCertificateDetail{"certificate"};

class ReferenceSolver final : public Solver {
 public:
  const SolverInfo& info() const override;

 protected:
  void DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) override;
};

}  // namespace smcbench

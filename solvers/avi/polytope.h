// The polytope P = {λ : Hλ ≥ K, Eλ = f} of an affine variational inequality: a point of it (or the proof that the
// linear program finds none) and whether it is bounded, both by a dense phase-1 simplex, and a vertex of it (the
// start of Cao–Ferris' pivotal method). Used once per AffineVI or per direct solve; not on any per-step path.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "solvers/core/types.h"

namespace smcbench {

// Whether P is bounded. Append-only, explicit values (a future file format may store it).
enum class PolytopeBoundedness : std::uint8_t {
  kNotDecided = 0,  // too many unknowns to test (kMaxBoundednessCheckSize)
  kBounded = 1,     // no nonzero direction d with Hd ≥ 0, Ed = 0
  kUnbounded = 2,   // such a direction exists (the AVI may then have no solution)
};
std::string_view ToString(PolytopeBoundedness value);  // "not decided", "bounded", "unbounded"

// Boundedness costs 2n phase-1 simplex solves (one per ±e_j): above this many unknowns it is not decided.
inline constexpr int kMaxBoundednessCheckSize = 100;

// What the phase-1 simplex found. Rows are first divided by their largest coefficient (so the tolerances are in
// units of λ); the infeasibility is max((K_i − H_iλ)⁺/h_i, |E_jλ − f_j|/e_j) at the point, recomputed from the data.
struct PolytopePoint {
  bool found = false;          // a point within the tolerance was found
  Vector point;                // λ (size n) when found
  double infeasibility = kInf; // at point, in units of λ after the row division
  double phase1_objective = kInf;  // the simplex's optimal Σ artificials (> 0 with margin: P is empty)
  int pivots = 0;
  bool pivot_limit = false;    // stopped at the pivot budget (not a proof either way)
};

// Phase-1 simplex with Bland's rule on λ = λ⁺ − λ⁻, Hλ − s = K, Eλ = f, λ±, s ≥ 0, one artificial per row.
// found when the recomputed infeasibility ≤ tolerance·(1 + ‖λ‖∞ + ‖K̃, f̃‖∞), K̃, f̃ the divided right-hand sides.
// H is m×n (m may be 0), E p×n (p may be 0); every row must be nonzero (AffineVI checks it before calling).
PolytopePoint FindPolytopePoint(const DenseMatrix& H, const Vector& K, const DenseMatrix& E, const Vector& f,
                                double tolerance = 1e-9);

// Bounded iff the recession cone {d : Hd ≥ 0, Ed = 0} is {0}: for each j and sign σ, FindPolytopePoint on it with
// the extra row d_j = σ must find nothing. kNotDecided when n > kMaxBoundednessCheckSize.
PolytopeBoundedness ClassifyPolytopeBoundedness(const DenseMatrix& H, const DenseMatrix& E);

// A vertex of P: a point where n linearly independent rows of [H; E] are active (a basic feasible solution of P
// itself, not of the split λ = λ⁺ − λ⁻ of the phase-1 simplex, whose nonbasic λ_j = 0 are no rows of P).
struct PolytopeVertex {
  bool found = false;
  Vector point;           // the vertex (size n): the solution of those n rows as equalities, recomputed from the data
  std::vector<int> rows;  // n indices into [H; E] (i < m: row i of H, m + j: row j of E), every independent row of E
  double infeasibility = kInf;  // at point, in units of λ as PolytopePoint's
  bool contains_line = false;  // not found because P contains a line: it has no vertex at all
  std::string why;        // when not found: P empty, P contains a line, or rounding
};

// From a point of P (start, or FindPolytopePoint's when start is null), moves along a direction in the null space of
// the rows active so far until another row becomes active, n − rank times (at most n steps, each a QR of the
// active rows). A direction that no row of H changes along lies in P's lineality space: rank [H; E] < n and P has
// no vertex (a strip, a half-space, any P with free directions), which is reported, not an error. Rows count as
// active within tolerance·(1 + ‖λ‖∞ + ‖K̃, f̃‖∞) in units of λ; the vertex must satisfy P within the same tolerance.
PolytopeVertex FindPolytopeVertex(const DenseMatrix& H, const Vector& K, const DenseMatrix& E, const Vector& f,
                                  const Vector* start = nullptr, double tolerance = 1e-9);

}  // namespace smcbench

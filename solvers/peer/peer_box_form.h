// Our box-MLCP in the box-LCP convention of the physics engines' solvers (ODE's dSolveLCP, which Bullet's
// btDantzigSolver and DART's DantzigBoxedLcpSolver carry, and which their PGS and Lemke solvers share):
//   A x = b + w, and for each row one of  x = lo, w ≥ 0;  x = hi, w ≤ 0;  lo < x < hi, w = 0;
//   with lo ≤ 0 ≤ hi, the first nub rows unbounded (lo = −∞, hi = +∞), infinite bounds as IEEE ±inf.
// Ours: M z + q = w − v, l ≤ z ≤ u (w ⟂ z − l, v ⟂ u − z), i.e. (Mz + q)_i ≥ 0 at l_i, ≤ 0 at u_i, = 0 inside.
//
// The rewrite (exact in exact arithmetic, both ways), with c = Π_[l,u](0) (so l − c ≤ 0 ≤ u − c):
//   z = c + x  (fixed rows l = u are eliminated: z = l = c),
//   A = M restricted to the kept rows and columns, b = −(q + M c), lo = l − c, hi = u − c,
//   and then their w = A x − b = M z + q: the same sign convention as ours, row by row.
// Row order: the free rows (l = −∞, u = +∞) first, in their original order, so nub = their count; then every other
// kept row in its original order. permutation[k] is our row of peer row k.
// Floating point: c = 0 on every row with l ≤ 0 ≤ u (every LCP, relay and symmetric box), and there the rewrite is
// bitwise exact (b = −q, x = z). On a row shifted by c ≠ 0, b carries the rounding of q + M c and z ↔ x the rounding
// of one subtraction and one addition (|c| ≤ |z| inside the box, so within two ulps of z; exact when z − c is
// representable, e.g. by Sterbenz' lemma for c ≤ z ≤ 2c).
#pragma once

#include <vector>

#include "solvers/core/problem.h"

namespace smcbench {

struct PeerBoxForm {
  DenseMatrix A;  // kept rows × kept columns, in the peer's row order (column-major here; adapters lay it out)
  Vector b, lo, hi;
  int nub = 0;                   // the first nub peer rows are free
  std::vector<int> permutation;  // peer row k → our row
  Vector shift;                  // c per our row (all n rows; a fixed row's z is its c)

  int size() const { return static_cast<int>(b.size()); }
};

// Builds the peer problem of a dense problem (sparse problems: std::logic_error from dense_matrix(); callers
// refuse them first). Reuses *form's storage.
void ToPeerBoxForm(const BoxMLCP& problem, PeerBoxForm* form);
PeerBoxForm ToPeerBoxForm(const BoxMLCP& problem);

// x_k = z_{permutation[k]} − c_{permutation[k]} (a start point, or a known solution of ours).
void ToPeerPoint(const PeerBoxForm& form, const Vector& z, Vector* x);
// The inverse on the peer's answer: z = c, then z_{permutation[k]} = c_{permutation[k]} + x_k. Nothing is clipped.
void FromPeerPoint(const PeerBoxForm& form, const Vector& x, Vector* z);

}  // namespace smcbench

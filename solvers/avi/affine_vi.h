// The affine variational inequality over a polytope (AVI; Siconos' AffineVariationalInequalities, Cao–Ferris 1996):
// find λ ∈ P = {λ : Hλ ≥ K, Eλ = f} with 0 ∈ Mλ + q + N_P(λ), i.e. (x − λ)ᵀ(Mλ + q) ≥ 0 for every x ∈ P.
// The box-MLCP is the case H = [I; −I]; a polytope law of a sliding-mode controller (implicit twisting's
// parallelogram) is the case it cannot state. Solved by every box backend through the exact reduction of
// avi_reduction.h; judged by avi_verdict.h (docs/avi.md).
#pragma once

#include <string>

#include "solvers/avi/polytope.h"
#include "solvers/core/problem.h"
#include "solvers/core/types.h"

namespace smcbench {

// Equalities are a separate block (E, f) rather than flagged rows of H: their multipliers are free, and a block
// keeps H's rows all of one kind. Dense storage. Construction validates everything and throws InvalidInputError
// naming the field: M square n×n (n ≥ 1), q of size n, H m×n and K of size m (m may be 0: P = {Eλ = f}, or all of
// Rⁿ), E p×n and f of size p (p may be 0; an empty 0×0 E means none), every entry finite, no zero row in H or E
// (0 ≥ K_i says nothing about λ), and P non-empty: a phase-1 simplex (polytope.h) must find a point of P within
// 1e-9 in units of λ, else "P is empty". Whether P is bounded is computed and reported (boundedness()), not
// required: on a bounded P the AVI always has a solution (Hartman–Stampacchia), on an unbounded one it may not.
class AffineVI {
 public:
  AffineVI(DenseMatrix M, Vector q, DenseMatrix H, Vector K, DenseMatrix E, Vector f, std::string name = {});
  // No equality rows.
  AffineVI(DenseMatrix M, Vector q, DenseMatrix H, Vector K, std::string name = {});

  int size() const { return static_cast<int>(q_.size()); }              // n, the unknowns λ
  int inequality_count() const { return static_cast<int>(K_.size()); }  // m, the rows of H
  int equality_count() const { return static_cast<int>(f_.size()); }    // p, the rows of E
  const DenseMatrix& M() const { return M_; }
  const Vector& q() const { return q_; }
  const DenseMatrix& H() const { return H_; }
  const Vector& K() const { return K_; }
  const DenseMatrix& E() const { return E_; }  // p×n (0×n when there are no equalities)
  const Vector& f() const { return f_; }
  // Like BoxMLCP's: the id a suite, a file or a report refers to it by.
  const std::string& name() const { return name_; }
  void set_name(std::string name) { name_ = std::move(name); }
  // Replaces q (a time-stepper's new right-hand side): size and finiteness checked like the constructor.
  void set_q(Vector q);

  // The point of P the validation found, and whether P is bounded.
  const Vector& feasible_point() const { return feasible_point_; }
  PolytopeBoundedness boundedness() const { return boundedness_; }

 private:
  void Validate();

  DenseMatrix M_;
  Vector q_;
  DenseMatrix H_;
  Vector K_;
  DenseMatrix E_;
  Vector f_;
  std::string name_;
  Vector feasible_point_;
  PolytopeBoundedness boundedness_ = PolytopeBoundedness::kNotDecided;
};

}  // namespace smcbench

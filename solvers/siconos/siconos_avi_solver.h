// Siconos' Cao–Ferris pivoting as an AVI backend, `siconos-avi-caoferris`: the vertex of P and the change of
// variables are ours, the pivoting is Siconos' avi_caoferris_stage3. Siconos' own avi_caoferris cannot be called in
// the Debian/Ubuntu build of Siconos Numerics 4.4: it finds its vertex with lp_solve, which that build lacks, so
// siconos_find_vertex prints a message and calls exit(1).
//
// The method (Cao & Ferris 1996, Math. Oper. Res. 21(1), "A pivotal method for affine variational inequalities").
// At a vertex of P = {λ : Gλ ≥ b} with n linearly independent active rows A (B = G_A invertible) and the other
// rows I, the slacks s = Gλ − b ≥ 0 and multipliers u ≥ 0 of the KKT system Mλ + q = Gᵀu, u ⟂ s, are related by
// λ = B⁻¹(s_A + b_A) and, eliminating λ and u_A,
//   u_A = B⁻ᵀMB⁻¹ s_A − B⁻ᵀG_Iᵀ u_I + B⁻ᵀ(MB⁻¹b_A + q),   s_I = G_IB⁻¹ s_A + (G_IB⁻¹b_A − b_I),
// an LCP in w = (u_A, s_I) ⟂ z = (u_I, s_A). Its q̄ is ≥ 0 on the I rows (the vertex is in P), so Lemke's method
// needs its covering vector on the A rows only: that is stage 3, Siconos' part. λ and μ = u come back from z and w.
//
// What it takes. An AVI (SolveAvi, as a DirectAviBackend): equalities Eλ = f as the two rows Eλ ≥ f, −Eλ ≥ −f
// (ν = u₊ − u₋); the vertex by FindPolytopeVertex (polytope.h). P without a vertex (rank [H; E] < n: a strip, a
// half-space, free directions) is kNotApplicable. A box-MLCP (Solver::Solve) is the AVI over {l ≤ z ≤ u} (a row
// per finite bound, a fixed row as two): its vertex is at hand (each z_i at a finite bound), so no simplex runs; a
// row with no finite bound leaves the box without a vertex: kNotApplicable. Every row fixed: z = l, no call.
//
// Isolation, options and trust as every siconos-* adapter (siconos_solver.h, solvers/siconos/README.md): stage 3
// runs through a SiconosSolver of method kAviCaoFerrisStage3 (the probe policy, the worker process, quiet stdio,
// details siconos_info, in_process, standard_size = rows of P). Siconos' info 0 is a claim: the box base class
// or SolveAvi's rule judges it; info 1 is a ray (never "infeasible": no certificate) or the pivot budget.
#pragma once

#include <string>
#include <vector>

#include "solvers/avi/avi_solver.h"
#include "solvers/core/backend_options.h"
#include "solvers/core/solver.h"
#include "solvers/siconos/siconos_solver.h"

namespace smcbench {

class SiconosAviSolver final : public BackendWithOptions<SiconosOptions>, public DirectAviBackend {
 public:
  SiconosAviSolver();
  explicit SiconosAviSolver(const SiconosOptions& options);

  const SolverInfo& info() const override;
  void SolveAviDirect(const AffineVI& avi, const SolverOptions& options, AviSolution* solution,
                      SolveResult* result) override;
  // Stage 3 keeps nothing learned between solves.
  WarmStateReset ForgetWarmState() override { return WarmStateReset::kNothingRemembered; }

 protected:
  void DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) override;
  void BindOptions(OptionBinder* binder) override;
  bool ValidateBackendOptions(std::string* why) const override;

 private:
  // The common part: P = {λ : Gλ ≥ b}, vertex_rows the n independent rows of a vertex. Sets result's status,
  // message, iterations and Siconos' details, *lambda (size n) and *multipliers (one per row of G) when Siconos
  // answered.
  void SolveAtVertex(const DenseMatrix& M, const Vector& q, const DenseMatrix& G, const Vector& b,
                     const std::vector<int>& vertex_rows, const SolverOptions& options, Vector* lambda,
                     Vector* multipliers, SolveResult* result);

  SiconosSolver stage3_;
  SolveResult stage3_result_;
};

}  // namespace smcbench

// Generated problem families for the benchmark suites "families" and "scale": seeded, feasible by construction
// (z* and a complementary w* first, then q = w* − M z*), each returned as a LibraryProblem with its id, seed,
// matrix-class tags and expected outcome filled in from the construction (proved in families.cc), never guessed.
// The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "problems/library/problem_set.h"
#include "solvers/generators/random_problems.h"

namespace smcbench {

// Ids are "<suite>/<family>/<parameters>"; every function below uses the suite "families" unless told otherwise.
inline constexpr std::string_view kFamiliesSuite = "families";

// --- Wrappers of solvers/generators (GenerateProblem): SPD, nonsymmetric P-matrix (mildly and strongly
// nonsymmetric), diagonally dominant, column-scaled diagonally dominant. ------------------------------------------
// Id "families/<spd|pmatrix|pmatrix-skew|diagdom|pmatrix-scaled>-<bounds>/m<m>/s<seed>" (plus "-deg<fraction>" when
// degenerate rows are asked for), tags: family, bounds, "degenerate" if any. All are P-matrices: expected
// solvable, z* is the unique solution. PD of the symmetric part: yes for spd, pmatrix and pmatrix-skew (by
// construction), computed for diagdom and pmatrix-scaled.
LibraryProblem RandomFamilyProblem(MatrixFamily family, BoundKind bounds, int m, std::uint64_t seed,
                                   double degenerate_fraction = 0.0);

// --- Symmetric positive semidefinite and singular: non-unique solutions. -------------------------------------
// M = AᵀA with A (m/2 × m) projected so that A d = 0 for a direction d supported on rows where z* is strictly
// inside its bounds: z* + t d solves the problem for every small t. bounds: kLCP or kRelay (m ≥ 2).
// Id "families/psd-singular-<bounds>/m<m>/s<seed>", tags "psd-singular", "non-unique".
LibraryProblem PsdSingularProblem(BoundKind bounds, int m, std::uint64_t seed);

// --- Not a P-matrix, several solutions. ----------------------------------------------------------------------
// M = Pᵀ [[−(I + E), 0], [G, K]] P (E ≥ 0, K a P-matrix, P a permutation): the first block alone has two
// solutions and each extends uniquely through K, so the problem has at least two; z* is one of them.
// bounds: kLCP or kRelay (m ≥ 2). Id "families/nonp-multi-<bounds>/m<m>/s<seed>", tags "non-p", "non-unique".
LibraryProblem NonPMultipleProblem(BoundKind bounds, int m, std::uint64_t seed);

// --- Not a P-matrix, no solution (a certificate row, see families.cc). -----------------------------------------
// bounds: kLCP (every row l = 0, u = ∞) or kMixed (free, LCP, upper-only and finite-box rows). Expected infeasible,
// no solution vector. Id "families/nonp-infeasible-<bounds>/m<m>/s<seed>", tags "non-p", "infeasible".
LibraryProblem NonPInfeasibleProblem(BoundKind bounds, int m, std::uint64_t seed);

// --- The one-step matrix of a scene: W = C S = hC(I − hθE)⁻¹B (eq:TDS3/TDS4), relay bounds [−1, 1]. ------------
// scene: a name of the scene registry (a linear scene; ZOH scenes use the implicit θ-method on their closed loop).
// z* ∈ [−1, 1]: at least one row at a bound with |w*| ∈ [0.1, 1.1] (so q = O(1)), at least one row strictly inside
// when m ≥ 2 (w* = 0 there, so q_i = −(W z*)_i = O(h)). W shrinks with h (O(h³) for "parasitic"): the problem gets
// ill-conditioned as h → 0. Tags "h-sweep", the scene name; metadata scene, h, theta. Matrix tags are computed
// from W (ClassifyMatrix, problems/library/matrix_tags.h). Id "families/h-sweep/<scene>/h<h>/s<seed>".
LibraryProblem SceneStepProblem(std::string_view scene, double h, std::uint64_t seed);
// h = 1e-1, 1e-2, ..., 1e-8: one problem per decade.
std::vector<double> HSweepSteps();

// --- The small-h family: W = h·G as h → 0. ----------------------------------------------------------------------
// Relay bounds [−1, 1]. Planted s*: at least one row strictly inside (w*_i = 0) and at least one at a bound (m ≥ 2),
// the slack of a bound row correctly signed and of order h, w*_i = ±h·c_i with c_i ∈ [0.1, 1.1] (w* > 0 at −1,
// w* < 0 at +1), q = w* − W s*. Every datum is then O(h): the problem is h times a fixed unit problem, on which a
// residual test not scaled by h accepts an error of order tol/h in s. Expected solvable, solution s*, tags
// "small-h", "relay" and the kind below; metadata family, h.
// (a) G = W/h with W = hC(I − hθE)⁻¹B the one-step matrix (eq:TDS3/TDS4) of a linear scene with m ≥ 2 (ZOH scenes:
//     the implicit θ-method on their closed loop), matrix tags computed from W (ClassifyMatrix). Id
//     "families/small-h/<scene>/h<h>/s<seed>". Throws InvalidInputError for m < 2 or a scene that is not linear.
LibraryProblem SmallHSceneProblem(std::string_view scene, double h, std::uint64_t seed);
// (b) G = P(I + K)Pᵀ, P = QΛ^½: Q orthogonal (three Householder reflections of random vectors), Λ = diag(λ_k) with
//     λ_k = 10^(−log10_condition·k/(m−1)) log-spaced in [10^−log10_condition, 1], K skew with ‖K‖_F = 1. The
//     symmetric part of G is QΛQᵀ, positive definite: G (and every positive multiple h·G) is a P-matrix, proved
//     (tags: not symmetric, PD, P). κ₂(G) ∈ [c/2, √2·c], c = 10^log10_condition (families.cc). The same seed gives
//     the same G and s* for every h. Id "families/small-h/pmatrix-m<m>-cond1e<k>/h<h>/s<seed>". m in [2, 64].
LibraryProblem SmallHPMatrixProblem(int m, int log10_condition, double h, std::uint64_t seed);
// h = 1e-2, 1e-4, 1e-6, 1e-8, 1e-10.
std::vector<double> SmallHSteps();

// --- Murty's exponential family for Lemke's method (Murty 1978; Murty 1988, ch. 6). ----------------------------
// M̃(n) lower triangular with 1 on the diagonal and 2 below it, q̂(n)_i = −(2ⁿ + 2ⁿ⁻¹ + ... + 2ⁿ⁻ⁱ⁺¹): Lemke's
// complementary pivot method with covering vector e takes 2ⁿ pivots on the problem as written (Siconos' Lemke does).
// Our backends receive the row-equilibrated problem (solvers/core), for Lemke the covering vector (1, 2, …, 2) in
// these units: our lemke takes 2 pivots (suites_test). Unique solution z* = 2ⁿ e₁ (exact in double).
// n in [2, 40]. Id "families/murty/n<n>", tag "murty". Not random: no seed.
LibraryProblem MurtyProblem(int n);

// --- N coupled sliding-mode subsystems, sparse: the scale family. ----------------------------------------------
// m subsystems x_k' = A_k x_k − B sgn(σ_k), σ_k = c_k x_k1 + x_k2, A_k = [[0, 1], [−a_k, −b_k]] with random
// a_k, b_k, c_k ∈ [0.5, 2], gains α_k ∈ [0.8, 1.2], and weak actuator crosstalk: the sign input of subsystem j
// also drives its neighbours k = j ± 1 with gain ε_kj α_j, ε ∈ [−0.2, 0.2]. Implicit Euler at h gives the exactly
// tridiagonal W = hC(I − hA)⁻¹B, assembled blockwise from the closed-form 2×2 inverses (never a dense inverse):
// O(m) time and memory. Relay bounds; z* rows inside (½) or at a bound (¼ each). W is row diagonally dominant with
// a positive diagonal (a P-matrix); its symmetric part is PD when W is also column dominant (checked, tagged).
// Id "<suite>/coupled-smc/m<m>/s<seed>", tags "sparse", "coupled-smc", "h-<h>". m in [1, 4'000'000], h in (0, 1].
LibraryProblem CoupledSlidingModeProblem(int m, std::uint64_t seed, double h = 1e-2,
                                         std::string_view suite = kFamiliesSuite);

struct FamiliesOptions {
  int seeds = 2;       // seeds 1..seeds for each random (family, bounds, size)
  int max_size = 64;   // problems larger than this are left out
  bool scenes = true;  // include the h-sweep and small-h scene problems (read the scene files of problems/scenes)
  // True if usable; otherwise *why names the field.
  bool IsValid(std::string* why) const;
};

// The "families" suite at small sizes (m ≤ 64 by default, ~180 problems): SPD, P-matrix and diagonally dominant
// (m = 8, 64; LCP, relay, mixed bounds), strongly nonsymmetric and column-scaled P-matrices (m = 8, 64; LCP, relay),
// PSD singular, non-P with several solutions, non-P infeasible
// (m = 8, 32), the h-sweep of five paper scenes (h = 1e-1 … 1e-8), the small-h family (the m ≥ 2 paper scenes and
// five P-matrices of condition 1e1 … 1e6, m = 2 … 8, each at h = 1e-2 … 1e-10: 40 problems), Murty n = 4 … 16,
// coupled sliding-mode subsystems (m = 16, 64). Throws InvalidInputError on invalid options.
ProblemSet FamiliesSuite(const FamiliesOptions& options = {});

struct ScaleOptions {
  int max_size = 100000;  // sizes 10², 10³, 10⁴, 10⁵ up to this
  std::uint64_t seed = 1;
  double h = 1e-2;
  bool IsValid(std::string* why) const;
};

// The "scale" suite: CoupledSlidingModeProblem at m = 10², 10³, 10⁴, 10⁵ (those ≤ max_size).
ProblemSet ScaleSuite(const ScaleOptions& options = {});

}  // namespace smcbench

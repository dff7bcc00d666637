// Lemke's complementary pivoting method (Lemke 1965) with lexicographic degeneracy resolution (Cottle, Pang &
// Stone 1992, ch. 4), applied to a box-MLCP through an exact reduction to a standard LCP.
//
// Reduction of the box-MLCP  z ∈ [l,u], w = Mz + q, (z−l)ᵀw⁺ = 0, (u−z)ᵀw⁻ = 0  to  LCP(N, r): ζ ≥ 0, Nζ + r ≥ 0,
// ζᵀ(Nζ + r) = 0. Every row is classified by its bounds:
//   fixed  (l = u):          z = l, the row is dropped (its w is unconstrained).
//   lower  (l finite, u = ∞): z = l + x, x ≥ 0, row kept:       x ⊥ (Mz + q) ≥ 0.
//   upper  (l = −∞, u finite): z = u − x, x ≥ 0, row negated:   x ⊥ −(Mz + q) ≥ 0  (column and row sign flip).
//   box    (both finite, l < u): z = l + x plus a multiplier y ≥ 0 for the upper bound (the relay → LCP split):
//                               x ⊥ (Mz + q + y) ≥ 0,  y ⊥ (u − l − x) ≥ 0,  so the LCP block is [[M, I], [−I, 0]].
//   free   (both infinite): handled by the first of these that applies (free_row_method = auto):
//     1. Schur complement of the free block A = M_FF (LU with partial pivoting) when Hager's estimate of its
//        reciprocal 1-norm condition number is ≥ free_block_min_rcond. With C the remaining rows:
//        z_F = −A⁻¹(q̂_F + M_FC (z_C − z̄_C)),  M_C ← M_CC − M_CF A⁻¹ M_FC,  q_C ← q̂_C − M_CF A⁻¹ q̂_F.
//     2. Otherwise the free variables stay in the LCP as sign-free variables that must be basic (the MLCP variant
//        of Lemke): before the path starts they are pivoted into the basis in place of their slacks (Gauss-Jordan
//        with partial pivoting); where A is rank deficient, a missing pivot is completed by a 2×2 principal block
//        pivot with a bounded row i ∉ F (z_i basic in place of the free slack, the free z in place of w_i). From
//        this complementary basis B, Lemke runs with the covering direction d = Bê (ê = 1 on sign-constrained
//        rows, 0 on free ones: Lemke from an advanced basis) and free rows never take part in the ratio test.
//     3. If no such basis exists (the free columns are dependent), z_F = x⁺ − x⁻ with x± ≥ 0, x⁺ ⊥ (Mz+q) ≥ 0,
//        x⁻ ⊥ −(Mz+q) ≥ 0: exact, but the LCP matrix only inherits positive semidefiniteness.
// Here q̂ = q + M z̄ with the base point z̄ = l (lower, box, fixed), u (upper), 0 (free). Writing z_C = z̄_C + S x
// with S = diag(±1), the LCP is N = [[S M_C S, E], [−Eᵀ, 0]], r = [S q_C; u_K − l_K] (E: identity columns of the
// box rows K).
// Each LCP solution maps to a box-MLCP solution and back. Classes are preserved: M P-matrix ⇒ Lemke cannot end on a
// secondary ray in exact arithmetic (the augmented problem is the box-MLCP with q + t·d and bounds [l, u + t·d],
// uniquely solvable for every t); M positive semidefinite ⇒ N copositive-plus, for which an exact secondary ray would
// show that no solution exists (Cottle-Pang-Stone ch. 4). A ray computed in floating point proves nothing, so it is
// reported as what it is: kRayTermination ("no solution found by this method"), or kNumericalFailure when the
// problem is known to have a solution (every bound finite; M + Mᵀ positive definite; M a P-matrix, tested by its
// principal minors up to n = 12) — these checks run only on the ray path.
//
// Solver::Solve hands DoSolve the row-equilibrated problem (max_j |M_ij| = 1), so every tolerance below is relative
// to entries of size 1 and every w is in units of z; "solved" inside DoSolve means the merit function of that
// problem passes both of Solver::Finish's tests (relative residual and residual in units of z).
//
// The pivoting works on the revised form: an explicit basis inverse B⁻¹ (p×p, p = LCP size), updated by a rank-one
// Gauss-Jordan step per pivot and recomputed from scratch (reinversion, with one step of iterative refinement of
// B⁻¹r) every refactor_interval pivots. The leaving row is the lexicographic minimum of the rows [B⁻¹r, B⁻¹]_i / c_i
// over the minimum-ratio ties (Cottle-Pang-Stone ch. 4): the row of z₀ in [B⁻¹r, B⁻¹] then decreases strictly in
// the lexicographic order at every pivot, so no basis repeats and the method cannot cycle. Floating point needs
// three safeguards on top:
//   - ties are ratios equal up to the rounding scale of their own rows, max(1e-14, 8pε)·Σ_k |B⁻¹_ik r_k|;
//     a degenerate basic value rounded below zero counts as zero in the ratio test;
//   - z₀ leaves as soon as it ties; and once z₀·‖d‖∞ ≤ tolerance·(1 + ‖q‖∞), the almost-complementary point
//     without z₀ is checked against the merit function and accepted only if it passes both tests, the one in units
//     of z included, so every sign condition holds to tolerance·(1 + ‖z‖∞) (z₀ is then zero up to rounding, and
//     the degenerate pivots that would follow have tiny pivot elements); the relative test alone let a point with
//     a violated sign condition through when one row's q dwarfs the others;
//   - if the final point misses the tolerance, or its residual in units of z is above the rounding level 1e3·n·ε
//     (the pivots carry rounding of order ε·max|β|, and β holds q̂: an ill-conditioned reduction, a base-point shift
//     M·l or a multiplier that dwarfs the rest), the active set of the final basis is solved again in the original
//     variables (LU of M_EE, one refinement step), followed by at most four primal-dual active-set corrections
//     (Hintermüller, Ito & Kunisch 2002); the result is kept only if its residual is smaller.
// Wherever the method stops, a point the merit function accepts is reported solved.
// Warm starts are ignored (Lemke starts from the slack basis, or the free-variable basis above). iterations =
// number of pivots: the z₀ entry and exit and the pivots that bring free variables into the starting basis count,
// reinversions do not.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "solvers/core/backend_options.h"
#include "solvers/core/solver.h"

namespace smcbench {

struct LemkeOptions {
  // The covering vector d of the artificial column z₀ (`--set lemke.covering_vector=NAME`; the old numbers 0 and
  // 1 are still read).
  enum class Covering : int {
    kOnes = 0,       // "ones": d = e, Lemke's choice
    kRowScaled = 1,  // "row-scaled": d_i = ‖N_i·‖∞, so the pivot sequence is invariant to positive row scaling
  };
  // How free rows (l = −∞, u = +∞) enter the LCP (`--set lemke.free_row_method=NAME`; old numbers 0–3 still read).
  enum class FreeRows : int {
    kAutomatic = 0,  // "auto": Schur complement, else free variables kept basic, else the x⁺ − x⁻ split
    kSchur = 1,      // "schur": Schur complement only (kSingular if the free block is singular)
    kBasic = 2,      // "basic": free variables kept basic
    kSplit = 3,      // "split": z_F = x⁺ − x⁻
  };

  // An entry c_i of the entering column B⁻¹a may be a pivot only if c_i > pivot_tolerance · ‖c‖∞.
  double pivot_tolerance = 1e-9;
  // Free variables kept basic use d = Bê whatever this says.
  Covering covering_vector = Covering::kOnes;
  // Recompute B⁻¹ from the basis columns every this many pivots; 0 = automatic, max(64, p).
  int refactor_interval = 0;
  // Free rows are eliminated by a Schur complement only when the reciprocal 1-norm condition estimate of the free
  // block is at least this.
  double free_block_min_rcond = 1e-12;
  FreeRows free_row_method = FreeRows::kAutomatic;

  // True if every field is usable; otherwise *why says which and why.
  bool IsValid(std::string* why) const;
};

// The names `--set` accepts and `smcbench list` prints ("ones", "auto", ...).
std::string_view ToString(LemkeOptions::Covering covering);
std::string_view ToString(LemkeOptions::FreeRows method);
std::optional<LemkeOptions::FreeRows> FreeRowsFromString(std::string_view name);

// Detail "free_row_mode", set when the problem has free rows: the method that handled them (kSchur, kBasic or
// kSplit; under free_row_method = auto the first that applied).
inline constexpr CodeDetail<LemkeOptions::FreeRows, 4> kFreeRowModeDetail{"free_row_mode"};
inline std::optional<LemkeOptions::FreeRows> FreeRowModeOf(const SolveResult& result) {
  return kFreeRowModeDetail.Get(result);
}

// Default pivot budget when SolverOptions::max_iterations ≤ 0: max(2^17, 50·p). 2^17 covers Murty's exponential
// examples (2^n pivots) up to n = 16; 50·p is far beyond the O(p) pivots Lemke usually needs.
inline constexpr int kLemkeDefaultMinPivots = 1 << 17;

namespace lemke_internal {
// Buffers grow to the largest size seen and never shrink, so repeated solves of one size do not allocate.
struct Workspace {
  std::vector<signed char> kind;    // per original row: RowKind (see .cc)
  std::vector<int> core;            // original index of each core row (non-free, non-fixed; + free when split)
  std::vector<int> free_rows;       // original indices of the Schur-eliminated free rows
  std::vector<double> zbar, qhat;   // base point z̄ and q̂ = q + M z̄ (original size)
  // Schur complement of the free block: LU of A (row-major f×f), G = A⁻¹M_FC (row-major f×c), g = A⁻¹q̂_F.
  std::vector<double> lu, G, g, hager_x, hager_y;
  std::vector<int> lu_perm;
  std::vector<double> Mc, qc;       // core matrix (row-major c×c) and vector
  // LCP slots: slot_core[a] = core position, slot_sign[a] = ±1, slot_y[a] = y-slot of a box row or −1,
  // y_owner[y] = the x slot of multiplier y.
  std::vector<int> slot_core, slot_y, y_owner;
  std::vector<double> slot_sign;
  std::vector<char> var_free;       // per LCP variable (w, x, z₀): a sign-free x that must stay basic
  std::vector<double> N;            // LCP matrix, column-major p×p (columns give the pivot columns −a)
  std::vector<double> r, d;         // LCP vector and covering vector
  std::vector<double> binv;         // basis inverse, column-major p×p (its rows are the lexicographic rows)
  std::vector<double> beta;         // basic values B⁻¹r
  std::vector<double> col, tmp;     // entering column B⁻¹a, scratch
  std::vector<int> basis, where, ties, mark;
  std::vector<double> xcore;        // core displacement z_C − z̄_C
  std::vector<double> col2;         // second entering column (2×2 block pivots of the free-variable start)
  // Active-set polish in the original variables: per-row state, the rows E, LU of M_EE, right-hand side.
  std::vector<signed char> active;
  std::vector<int> active_list, active_perm;
  std::vector<double> active_lu, active_res;
  Vector w, z_polish;               // Mz + q for the final check; polished candidate
};
}  // namespace lemke_internal

class LemkeSolver final : public BackendWithOptions<LemkeOptions> {
 public:
  LemkeSolver() = default;
  explicit LemkeSolver(const LemkeOptions& options) : BackendWithOptions(options) {}

  const SolverInfo& info() const override;

 protected:
  void DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) override;
  void BindOptions(OptionBinder* binder) override;
  bool ValidateBackendOptions(std::string* why) const override;

 private:
  lemke_internal::Workspace ws_;
};

}  // namespace smcbench

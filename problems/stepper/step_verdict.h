// A time step's answer judged in the units of the next state, and made exact. The implicit step of a linear scene
// gives x_{k+1} = a − S s (a = R x_k + p_k) and y_{k+1} = −(M s + q), both affine in the answer s of its one-step
// problem (box-MLCP or AVI); a residual relative to 1 + ‖q‖ does not bound the error of x_{k+1} near the origin
// (‖q‖ ≈ ‖x_k‖ → 0), and an ill-conditioned active set turns a residual tol into an error of tol·κ in s.
// So the stepper refines every step the backend calls solved (docs/verdict.md, "The step verdict"):
//   1. the answer's active set: the rows of P = {s : H s ≥ K} (the box [−1, 1]^m is H = [I; −I], K = −1) the
//      natural map projects onto, with multipliers from w = M s + q (box) or the backend's μ (polytope);
//   2. the exact step on it: the KKT system M δ − H_Aᵀ μ_A = −(M s + q), H_A δ = K_A − H_A s solved in long double
//      (complete pivoting; a rank-deficient system, e.g. M = C S of rank one, keeps the pivoted unknowns and must
//      be consistent), s* = s + δ;
//   3. s* must be a solution: H s* ≥ K and μ_A ≥ 0 to rounding (8ε); if it is not, every active set of at most m
//      rows is tried (small P) and the exact step nearest the answer in x kept. Then ‖S δ‖∞ is the backend's
//      forward error in x_{k+1} against that exact step, judged against tol·(‖S‖∞ + ‖x_{k+1}‖∞): ‖S‖∞ is what one
//      unit of s moves x by (the step's input scale h‖B‖), which does not vanish as x → 0.
// The stepper always continues from s* (so a run is exact to rounding whatever the tolerance handed to the
// backend), counts the steps whose answer was off by more than the allowance (Trajectory::refined_steps), and
// reports a step as inaccurate when no exact step is found on the answer's active set (never silently accepted).
// Two paths solve step 2. The cached one, first: consecutive steps mostly share their active set, so the inverse
// of its KKT matrix is kept (long double, verified by its residual I − K X when made; the last 4 active sets, from
// the second step judged since Reset on) and s* = s − X r costs one product, with a rigorous bound on its error (the
// rounding of r and of the product, the data's rounding, the inverse's error). s* is taken only when that bound is
// below ε/4·‖s*‖∞ (so s* is the double the exact step rounds to, but within a quarter ulp of a tie) and s* passes
// step 3's checks with the bound's margin. Otherwise (a singular or ill-conditioned active set, an active set with
// no exact step, a refiner's first step) the factored path above judges the step, unchanged, in long double either
// way: x87 long double costs about the instructions of double, and keeps s* exact to double's rounding (κε would not).
// StepCheck::cached says which path judged.
// Before both, on the box (from the second step judged on, as the cached path), proofs that need no solve. In double:
// a saturated answer (every s_j exactly ±1) is its own exact step when every w_i = (M s + q)_i has the sign
// that keeps row i on its face with a margin above the rounding bound of its m + 1 terms (the products M_ij·(±1) are
// exact, so |fl(w_i) − w_i| ≤ γ_m(|q_i| + Σ_j |M_ij|), Higham 2002, (3.5)); and with m = 1 an answer inside the box
// whose w is far below its slack reads no active row, and s* = −q/M is the division IEEE rounds correctly.
// With m ≥ 2, an answer inside the box reads no active row when every |w̃_i| is below its slack by more than w̃'s
// rounding bound, and its exact step is s − M̃⁻¹w̃: M̃'s inverse is made once at Reset (the cached path's, with its
// residual-verified error bound) and s* is taken on the cached path's terms (exact to a quarter ulp, in the box).
// A mixed answer (m ≥ 2, every s_a exactly ±1 but one s_i inside) reads the set of its saturated rows when each w̃_a
// has its face's sign and |w̃_i| is below its slack, both by more than w̃'s rounding bound; its exact step keeps s_A
// and solves row i alone, s*_i = s_i − w̃_i/M̃_ii (one long double quotient, its error bounded as the cached path's).
// s* is taken on the cached path's terms (a quarter ulp), with s*_i strictly inside the box and the saturated rows'
// multipliers w̃*_a = w̃_a + M̃_ai δ_i of their face's sign, both by more than their error bound. Two or more rows
// inside are left to the cached path. (The saturated w̃_a never enters s*_i: at h → 0, w̃_a = w_a/σ is large, and
// the cached path's bound, which grows with it, sent these steps to the factored solve.)
// StepCheck::proved says so; a proof that fails leaves the step to the paths above, unchanged.
// On a polytope the factored path's s* is projected onto its active faces afterwards (H̃_A s* = K̃_A in long double):
// the solve's rounding grows with its right-hand side w̃ = w/σ, large when M is small (h → 0), and left s* off its
// faces by more than the 8-ulp feasibility test (a correct vertex answer refused; the box fixes s*_j = ±1 instead).
// Allocation-free after Reset (buffers sized to m + rows of P).
#pragma once

#include <cstdint>
#include <vector>

#include "solvers/core/types.h"

namespace smcbench {

// What Refine found.
struct StepCheck {
  bool exact = false;    // s* found and verified on the answer's active set
  double x_error = kNaN;  // ‖S(s − s*)‖∞: the answer's forward error in x_{k+1} (NaN unless exact)
  bool cached = false;    // judged without the factored solve: the cached inverse, or a proof in double (`proved`)
  bool proved = false;    // judged by a proof without a solve (the box: saturated, inside, or one row inside)
};

// The allowance of the step verdict: tol·(‖S‖∞ + ‖x_{k+1}‖∞).
inline double StepAllowance(double tolerance, double input_scale, double x_next_norm) {
  return tolerance * (input_scale + x_next_norm);
}

// P with at most this many rows: when the answer's active set has no exact step, every active set of at most m rows
// is tried (2^rows masks); larger P reports the step instead.
inline constexpr int kMaxEnumeratedRows = 12;

// The cached path keeps this many active sets, for m ≤ kMaxCachedInputs and P with at most 64 rows (a bit mask).
inline constexpr int kCachedActiveSets = 4;
inline constexpr int kMaxCachedInputs = 32;

class StepRefiner {
 public:
  StepRefiner() = default;
  // M = C S (m×m), S (n×m); H (rows×m), K (rows) the polytope law, or H empty for the box [−1, 1]^m. Allocates.
  void Reset(const DenseMatrix& M, const DenseMatrix& S, const DenseMatrix& H, const Vector& K);
  // q: the step's q (m entries). mu: the backend's multipliers of H's rows as stated (M s + q = Hᵀμ), or null (the
  // box: read from w = M s + q). s (m entries): in, the backend's answer; out, s* when exact (unchanged otherwise).
  StepCheck Refine(const double* q, const double* mu, double* s);
  // ‖S‖∞ (max row sum): the x moved by one unit of s.
  double input_scale() const { return input_scale_; }
  bool ready() const { return m_ > 0; }
  // Drops the cached active sets (a run that starts afresh is then judged as the first one was).
  void ForgetActiveSets();

 private:
  // The inverse of the KKT matrix of one active set (scaled units, as SolveOnActiveSet's).
  struct CachedKkt {
    std::uint64_t mask = 0;  // the active rows
    int size = 0;            // N = m + |A|; 0: an empty slot
    bool usable = false;     // false: singular, too many rows, or the inverse failed its residual test
    long double inverse_error = 0.0L;  // β ≥ ‖K⁻¹ − inverse‖∞
    long double gamma = 0.0L;          // γ_N: the rounding of a row of the product inverse · r
    long double matrix_norm = 0.0L;    // ‖K‖∞
    long double delta_rows_norm = 0.0L;  // max over δ's rows of Σ_j |inverse_ij|
    std::vector<int> rows;             // the active rows, in order
    std::vector<long double> inverse;  // N×N row-major
    std::vector<long double> row_norm;  // Σ_j |inverse_ij|
  };
  // The factored path: steps 1-3 above.
  StepCheck RefineFactored(const double* q, const double* mu, double* s);
  // The box's proofs in double; false leaves the step to the cached and factored paths (s untouched).
  bool ProveSaturated(const double* q, double* s, StepCheck* check) const;
  // m = 1: ProveSaturated's proof, or inside the box s* = −q/M.
  bool ProveOneInput(const double* q, double* s, StepCheck* check) const;
  // m ≥ 2, no active row: s* = s − M̃⁻¹ w̃ with the inverse of Reset. kM: m, or 0 (m_ at run time).
  template <int kM>
  bool ProveInside(const double* q, double* s, StepCheck* check);
  // m ≥ 2, a mixed set: every row but one saturated (s_a = ±1 exactly), row i inside, s*_i = s_i − w̃_i/M̃_ii.
  // kM: m, or 0 (m_ at run time).
  template <int kM>
  bool ProveMixed(const double* q, double* s, StepCheck* check);
  // Moves star_ onto the active rows' faces (least-norm correction of H̃_A s* = K̃_A); false if H̃_A H̃_Aᵀ is singular.
  bool ProjectOntoActiveRows(int a);
  // The cached path; false leaves the step to the factored one (s untouched). kM: m, or 0 (m_ at run time).
  template <int kM>
  bool RefineCached(const double* q, const double* mu, double* s, StepCheck* check);
  // The natural map's active set (the factored path's first reading) as a bit mask; fills slack_.
  std::uint64_t ActiveMask(const double* mu, const double* s);
  // The slot of `mask`, made if new (in the next slot, round robin) unless this is the first step judged; or null.
  const CachedKkt* CachedKktFor(std::uint64_t mask);
  // K = [M̃ −H̃_Aᵀ; H̃_A 0] (N = m + a, row-major) of the active rows rows[0..a): both paths' KKT matrix.
  void AssembleKkt(const int* rows, int a, long double* K) const;
  void MakeCachedKkt(std::uint64_t mask, CachedKkt* kkt);
  // Inverts the N×N matrix in a (row-major) in place by Gauss–Jordan with complete pivoting; false if singular.
  bool InvertInPlace(long double* a, int N);
  // H s* ≥ K to the rounding of s* (in star_) to double.
  bool StarIsFeasible(long double star_norm) const;
  // Solves the KKT system on the rows marked in active_, writes s* into star_; false if singular and inconsistent
  // or not a solution.
  bool SolveOnActiveSet(const double* q, const double* s);
  // ‖S(s* − s)‖∞ for the s* in star_.
  long double XError(const double* s) const;

  int n_ = 0, m_ = 0, rows_ = 0;
  bool box_ = true;
  double input_scale_ = 0.0;
  long double sigma_ = 1.0L;           // max |M_ij| (1 when M = 0): M̃ = M/σ, q̃ = q/σ
  std::vector<long double> M_, S_;     // M̃ (row-major m×m), S (row-major n×m)
  std::vector<double> Md_, Mrow_abs_;  // M as given (row-major m×m) and Σ_j |M_ij|: the proofs in double
  std::vector<long double> H_, K_;     // H̃ = H_r/h_r (row-major rows×m), K̃ = K_r/h_r
  std::vector<long double> hscale_;    // h_r = max_j |H_rj|
  std::vector<char> active_;           // rows in the active set
  std::vector<int> active_rows_;
  std::vector<long double> A_, rhs_, sol_, w_, star_, best_, mu_;
  std::vector<int> colp_;
  // The cached path.
  bool cache_on_ = false;
  std::vector<CachedKkt> cache_;
  int next_slot_ = 0;  // the slot the next new active set takes (round robin)
  int last_slot_ = 0;  // the slot the previous step used
  bool judged_before_ = false;  // a step was judged since Reset or ForgetActiveSets
  CachedKkt inside_;            // the box's empty active set (K = M̃), made at Reset: ProveInside's inverse
  long double gamma_r_ = 0.0L;  // γ_{m+3}: the rounding of r (its arithmetic and the data's, to long double)
  std::vector<long double> slack_, r_, z_;
  std::vector<int> pivot_row_, pivot_col_, pivoted_;
};

}  // namespace smcbench

// bpp backend: block principal pivoting on the box (bpp_solver.h states the method, the pivot rule and its
// safeguards).
#include "solvers/pivoting/bpp_solver.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>

#include "solvers/core/matrix_class.h"
#include "solvers/core/polish.h"

namespace smcbench {
namespace {

constexpr auto kLower = static_cast<signed char>(RowState::kLower);
constexpr auto kUpper = static_cast<signed char>(RowState::kUpper);
constexpr auto kFree = static_cast<signed char>(RowState::kFree);

// The set a row moves to when it is infeasible in the solved set: a free row to the bound it crossed, a bound row
// to free.
signed char Flipped(signed char state, double z, double l) {
  if (state != kFree) return kFree;
  return z < l ? kLower : kUpper;
}

// Rows whose state is forced by their bounds: l = u is fixed (kept at l, any w), l = −∞ and u = +∞ always free.
bool FixedRow(double l, double u) { return l == u; }

// Whether the set has a free row (a block to factor): a set with none is exact as placed, and so is its polish.
bool AnyFree(const signed char* state, int n) {
  for (int i = 0; i < n; ++i) {
    if (state[i] == kFree) return true;
  }
  return false;
}

// Below this many rows the sweeps are not run: one or two sets of a few rows cost less than the sweeps, and at
// m = 16 they did not lower the sets (docs/auto.md, "bpp against one factorization of M").
constexpr int kMinSweptRows = 32;
// From this many rows up to kMinSweptRows − 1, the sweeps also choose the first set of a box (every row with a choice
// has both bounds finite) with a positive diagonal whose M is neither symmetric up to the row scaling nor strictly
// diagonally dominant by rows. On a box the projected iterate cannot run off whatever M is, so a poor guess costs
// sets and nothing else; on these matrices the natural map at Π(0) can be far from the answer's set (small-h
// P-matrix relay of condition 1e6 at m = 8: 9 sets from Π(0), 2 from the sweeps; docs/auto.md, "Issue 34: swept
// first sets on small nonsymmetric boxes"). Where M is strictly diagonally dominant the natural map at Π(0) is
// already a contraction's first step and usually the answer's set (diagdom-relay at m = 8: one set either way, the
// sweeps twice its time), and a symmetric box below kMinSweptRows keeps it as measured before (spd-relay at m = 8:
// one set, the sweeps 10 % more instructions). Nor where the skew part of M outweighs its symmetric part
// (‖M − Mᵀ‖_F > kMaxSweptSkewRatio·‖M + Mᵀ‖_F, on the row-scaled M bpp is given): projected Gauss–Seidel does not
// converge there, and its guess sent bpp into Murty's single pivots (the strongly nonsymmetric relay at m = 8, about
// 2.9 by auto's measure on M as stated: auto's bpp handed seed 13 over to lemke; the nonsymmetric P-matrices measure
// about 1.4). Below
// 5 rows enum's fixed-size kernels take every problem auto sends.
constexpr int kMinBoxSweptRows = 5;
constexpr double kMaxSweptSkewRatio = 2.0;

// From this many rows up to UpdatedFreeBlock::kMinRows, a symmetric M's sets are solved by PrefixCholesky and an
// answer the polish would only solve again is not polished. Below, the inline LU of a few rows costs no more than the
// Cholesky, and the classification that skips the polish costs more than it saves (measured by the perf gate: at 5
// rows, solve/families/spd-relay/m8 took 5263 instructions against 4245; at m = 15, relay1.dat, the solve's
// instructions fell from about 118 k to 46 k).
constexpr int kMinPrefixCholeskyRows = 12;
// ... and only from the set after this many (the symmetry test too): the first sets are factored by the inline LU,
// as below 12 rows. A solve of two or three sets, most at these sizes, gains nothing from rows kept between sets,
// and taking the Cholesky path from the first set cost more there (random SPD relays, LCPs and mixed bounds at
// m = 12-15: 4-10 % more time in `bench`, median per class; 1.03-1.41x the instructions through smcbench.solve,
// which tests the symmetry on every call); a solve of many sets (relay1.dat: 7; an SPD relay of condition 1e6:
// 186) keeps rows from the third set on.
constexpr int kLuSetsBeforePrefixCholesky = 2;

template <typename... Args>
void SetMessage(SolveResult* result, const char* format, Args... args) {
  char buffer[400];
  std::snprintf(buffer, sizeof buffer, format, args...);
  result->message.assign(buffer);
}

}  // namespace

bool BppOptions::IsValid(std::string* why) const {
  if (block_steps_without_progress < 0) {
    if (why) *why = "bpp: block_steps_without_progress must be >= 0";
    return false;
  }
  if (!(pivot_tolerance >= 0.0 && pivot_tolerance < 1.0)) {
    if (why) *why = "bpp: pivot_tolerance must lie in [0, 1) (units of the row-equilibrated M, max |M_ij| = 1)";
    return false;
  }
  if (max_single_pivots < -1) {
    if (why) *why = "bpp: max_single_pivots must be >= 0, or -1 for no limit";
    return false;
  }
  if (!(single_pivots_per_row == -1.0 || (single_pivots_per_row > 0.0 && single_pivots_per_row <= 1e6))) {
    if (why) *why = "bpp: single_pivots_per_row must lie in (0, 1e6], or be -1 for no limit";
    return false;
  }
  if (guess_sweeps < 0 || guess_sweeps > 1000) {
    if (why) *why = "bpp: guess_sweeps must lie in [0, 1000]";
    return false;
  }
  return true;
}

const SolverInfo& BppSolver::info() const {
  static const SolverInfo kInfo{
      "bpp",
      "block principal pivoting on the box (each row free / at l / at u, n variables), Murty's least-index single "
      "pivots after non-improving block steps; each free block solved exactly, by LU or a Schur-complement update "
      "of the last one",
      "Judice & Pires, Comput. Oper. Res. 21 (1994); Kostreva, Linear Algebra Appl. 21 (1978); Murty, Opsearch 11 "
      "(1974)",
      /*dense=*/true,
      /*sparse=*/true,
      /*symmetric_only=*/false,
      // Finite on P-matrix LCPs (Murty's least-index fallback), not proven for rows with two finite bounds.
      /*exact=*/false,
      /*mcp=*/false,
      /*default_size_limit=*/0,
      /*equilibrate=*/true,
      /*delegates=*/false,
      /*external=*/false,
      /*allocation_free=*/true,
      /*solves_every_p_matrix=*/true};
  return kInfo;
}

void BppSolver::BindOptions(OptionBinder* binder) {
  binder->Add("block_steps_without_progress", &options_.block_steps_without_progress,
              "block pivots allowed while the infeasible count does not improve (>= 0), then least-index single "
              "pivots");
  binder->Add("pivot_tolerance", &options_.pivot_tolerance,
              "free-block LU pivots at or below this are singular (row-equilibrated M), in [0, 1)");
  binder->Add("max_single_pivots", &options_.max_single_pivots,
              "end as iteration_limit after this many least-index single pivots (-1: no limit; auto sets one)");
  binder->Add("single_pivots_per_row", &options_.single_pivots_per_row,
              "with max_single_pivots -1: end as iteration_limit after max(4, ceil(this * n)) single pivots (-1: no "
              "limit; auto sets 0.25)");
  binder->Add("factor_updates", &options_.factor_updates,
              "dense M: update the last free block's LU by a Schur complement between active sets (false: refactor "
              "every set)");
  binder->Add("cholesky", &options_.cholesky,
              "dense M symmetric up to the row scaling, positive diagonal: factor free blocks by Cholesky (false: "
              "LU only)");
  binder->Add("guess_sweeps", &options_.guess_sweeps,
              "dense M, cold: projected Gauss-Seidel sweeps from the projection of 0 before the first active set is "
              "read off, in [0, 1000]");
}

bool BppSolver::ValidateBackendOptions(std::string* why) const { return options_.IsValid(why); }

void BppSolver::DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) {
  if (problem.is_sparse()) {
    Pivot<true>(problem, options, result);
  } else {
    Pivot<false>(problem, options, result);
  }
}

template <>
bool BppSolver::SolveActiveSet<false>(const BoxMLCP& problem, double* z) {
  const int n = problem.size();
  const ActiveSetScratch s = dense_.For(n);
  const double* m = problem.dense_matrix().data();
  const double *l = problem.l().data(), *u = problem.u().data();
  const int nf = active_set::PlaceBoundRows<0>(n, s.state, l, u, z, s.free_rows);
  if (n >= UpdatedFreeBlock::kMinRows) {
    return updated_.Solve(m, n, problem.q().data(), s.free_rows, nf, options_.pivot_tolerance, z);
  }
  // Below kMinRows no block is ever updated: the set is factored here, inline (a paper problem's whole solve is a
  // few hundred instructions).
  if (nf == 0) return true;
  ++small_factorizations_;
  if (small_cholesky_ && small_factorizations_ == kLuSetsBeforePrefixCholesky + 1) {
    small_cholesky_ = SymmetricUpToRowScaling(problem);  // also checks the positive diagonal
  }
  if (small_cholesky_ && small_factorizations_ > kLuSetsBeforePrefixCholesky) {
    switch (prefix_.Solve(m, n, problem.q().data(), row_ratio_.data(), inv_row_ratio_.data(), s.free_rows, nf,
                          options_.pivot_tolerance, z)) {
      case PrefixCholesky::Outcome::kSolved:
        ++small_cholesky_sets_;
        return true;
      case PrefixCholesky::Outcome::kNonFinite:
        return false;
      case PrefixCholesky::Outcome::kNotPositive:  // the LU judges this set, and solves the rest
        small_cholesky_ = false;
        break;
    }
  }
  active_set::ReducedRhs<0>(m, n, problem.q().data(), z, s.free_rows, nf, s.rhs);
  active_set::GatherFreeBlock(m, n, s.free_rows, nf, s.block, n);
  if (!dense_lu::Factor(s.block, n, nf, s.pivots, options_.pivot_tolerance)) return false;
  dense_lu::Solve(s.block, n, nf, s.pivots, s.rhs);
  return active_set::ScatterFreeRows(s.rhs, s.free_rows, nf, l, u, z) != FreeRowsFit::kNonFinite;
}

bool BppSolver::SymmetricUpToRowScaling(const BoxMLCP& problem) {
  if (symmetry_id_ == problem.matrix_id()) return symmetric_;
  symmetry_id_ = problem.matrix_id();
  symmetric_ = false;
  const int n = problem.size();
  const DenseMatrix& M = problem.dense_matrix();
  for (int i = 0; i < n; ++i) {
    if (!(M(i, i) > 0.0)) return false;
  }
  // M = D S with S symmetric: S_ij = M_ij / d_i = M_ji / d_j, so d_i / d_0 = M_i0 / M_0i from the first row and
  // column (both nonzero, same sign), then every pair is checked to a relative 1e-12.
  if (row_ratio_.size() != n) row_ratio_.resize(n);
  if (inv_row_ratio_.size() != n) inv_row_ratio_.resize(n);
  row_ratio_[0] = inv_row_ratio_[0] = 1.0;
  for (int i = 1; i < n; ++i) {
    const double ratio = M(i, 0) / M(0, i);
    if (!(ratio > 0.0) || !std::isfinite(ratio)) return false;
    row_ratio_[i] = ratio;
    inv_row_ratio_[i] = M(0, i) / M(i, 0);
    if (!(inv_row_ratio_[i] > 0.0) || !std::isfinite(inv_row_ratio_[i])) return false;
  }
  for (int j = 1; j < n; ++j) {
    for (int i = j + 1; i < n; ++i) {
      const double a = M(i, j) / row_ratio_[i], b = M(j, i) / row_ratio_[j];
      if (!(std::abs(a - b) <= 1e-12 * std::max(std::abs(a), std::abs(b)))) return false;
    }
  }
  symmetric_ = true;
  return true;
}

bool BppSolver::BoxWithPositiveDiagonal(const BoxMLCP& problem) const {
  const int n = problem.size();
  const DenseMatrix& M = problem.dense_matrix();
  const double *l = problem.l().data(), *u = problem.u().data();
  for (int i = 0; i < n; ++i) {
    if (FixedRow(l[i], u[i])) continue;
    if (!(M(i, i) > 0.0) || !std::isfinite(l[i]) || !std::isfinite(u[i])) return false;
  }
  return true;
}

bool BppSolver::SweepsChooseTheFirstSet(const BoxMLCP& problem) {
  if (sweep_first_id_ == problem.matrix_id()) return sweep_first_;
  sweep_first_id_ = problem.matrix_id();
  sweep_first_ = false;
  const int n = problem.size();
  const DenseMatrix& M = problem.dense_matrix();
  if (dominance_sums_.size() != n) dominance_sums_.resize(n);
  dominance_sums_.setZero();
  for (int j = 0; j < n; ++j) {  // Σ_j≠i |M_ij| column by column (column-major M)
    const double* column = M.data() + static_cast<std::ptrdiff_t>(j) * n;
    for (int i = 0; i < n; ++i) dominance_sums_[i] += i == j ? 0.0 : std::abs(column[i]);
  }
  bool dominant = true;
  for (int i = 0; i < n && dominant; ++i) dominant = M(i, i) > dominance_sums_[i];
  sweep_first_ = !dominant && !SymmetricAndSkewPartNorms(M).SkewOutweighsSymmetric(kMaxSweptSkewRatio);
  return sweep_first_;
}

bool BppSolver::SweptGuess(const BoxMLCP& problem, const double* z0, signed char* state, bool on_box) {
  const int n = problem.size();
  const DenseMatrix& M = problem.dense_matrix();
  const double *l = problem.l().data(), *u = problem.u().data();
  // On a box the caller checked BoxWithPositiveDiagonal; otherwise symmetric up to the row scaling, which also
  // checks the positive diagonal.
  if (!on_box && !SymmetricUpToRowScaling(problem)) return false;
  if (guess_.size() != n) guess_.resize(n);
  if (z0 != nullptr) {
    std::copy(z0, z0 + n, guess_.data());
  } else {
    for (int i = 0; i < n; ++i) guess_[i] = std::min(std::max(0.0, l[i]), u[i]);  // Π(0)
  }
  double* z = guess_.data();
  double* w = w_.data();
  if (on_box) {
    // w = q + Σ_j z0_j M(:, j) over the nonzero z0_j only: Π(0) is 0 on every row whose box contains 0.
    const double* q = problem.q().data();
    std::copy(q, q + n, w);
    for (int j = 0; j < n; ++j) {
      if (z[j] == 0.0) continue;
      const double* column = M.data() + static_cast<std::ptrdiff_t>(j) * n;
      for (int r = 0; r < n; ++r) w[r] += z[j] * column[r];
    }
  } else {
    w_.noalias() = M * guess_;
    w_ += problem.q();
  }
  for (int sweep = 0; sweep < options_.guess_sweeps; ++sweep) {
    bool moved = false;
    for (int i = 0; i < n; ++i) {
      if (FixedRow(l[i], u[i])) continue;
      const double next = std::min(std::max(z[i] - w[i] / M(i, i), l[i]), u[i]);
      const double delta = next - z[i];
      if (delta == 0.0) continue;
      moved = true;
      z[i] = next;
      const double* column = M.data() + static_cast<std::ptrdiff_t>(i) * n;
      for (int r = 0; r < n; ++r) w[r] += delta * column[r];
    }
    // A sweep that moved nothing is a fixed point: the sweeps left would repeat it (on a box; the symmetric path
    // keeps its sweeps as measured).
    if (on_box && !moved) break;
  }
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(z[i]) || !std::isfinite(w[i])) return false;
  }
  for (int i = 0; i < n; ++i) {
    state[i] = FixedRow(l[i], u[i]) ? kLower
                                    : static_cast<signed char>(ClassifyRow(z[i], w[i] / M(i, i), l[i], u[i]));
  }
  return true;
}

bool BppSolver::PolishWouldRepeat(const BoxMLCP& problem, const double* z, const signed char* state) {
  const int n = problem.size();
  if (n > kMaxPolishDenseSize) return false;  // the base does not polish there
  if (static_cast<int>(polish_state_.size()) != n) polish_state_.assign(n, 0);
  if (polish_w_.size() != n) polish_w_.resize(n);
  ClassifyRowsForPolish<0>(problem, z, polish_state_.data(), polish_w_.data());
  const double *l = problem.l().data(), *u = problem.u().data();
  for (int i = 0; i < n; ++i) {
    if (polish_state_[i] == state[i]) continue;
    // A fixed row (l = u) sits at that value whichever bound the natural map names (it never calls it free).
    if (FixedRow(l[i], u[i]) && polish_state_[i] != kFree) continue;
    return false;
  }
  return true;
}

template <>
bool BppSolver::SolveActiveSet<true>(const BoxMLCP& problem, double* z) {
  const int n = problem.size();
  const ActiveSetScratch s = dense_.For(n);
  if (placed_.size() != n) placed_.resize(n);
  const int nf = active_set::PlaceBoundRows<0>(n, s.state, problem.l().data(), problem.u().data(), placed_.data(),
                                               s.free_rows);
  std::copy(placed_.data(), placed_.data() + n, z);
  if (nf == 0) return true;
  w_.noalias() = problem.sparse_matrix() * placed_;
  w_ += problem.q();
  if (sparse_rhs_.size() != nf) sparse_rhs_.resize(nf);
  for (int k = 0; k < nf; ++k) sparse_rhs_[k] = -w_[s.free_rows[k]];
  if (!sparse_block_.Factor(problem.sparse_matrix(), s.free_rows, nf)) return false;
  if (!sparse_block_.Solve(sparse_rhs_, &sparse_x_)) return false;
  return active_set::ScatterFreeRows(sparse_x_.data(), s.free_rows, nf, problem.l().data(), problem.u().data(), z) !=
         FreeRowsFit::kNonFinite;
}

template <bool Sparse>
void BppSolver::Pivot(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) {
  const int n = problem.size();
  const ActiveSetScratch s = dense_.For(n);
  if (w_.size() != n) w_.resize(n);
  if (static_cast<int>(previous_state_.size()) != n) previous_state_.assign(n, 0);
  if (static_cast<int>(infeasible_.size()) != n) infeasible_.assign(n, 0);
  const double* l = problem.l().data();
  const double* u = problem.u().data();
  double* z = result->z.data();
  const auto multiply = [&] {
    if constexpr (Sparse) {
      w_.noalias() = problem.sparse_matrix() * result->z;
    } else {
      w_.noalias() = problem.dense_matrix() * result->z;
    }
    w_ += problem.q();
  };

  // The first active set: the warm start's own, else the Jacobi-scaled natural map at Π(0) (result->z holds it).
  const bool warm = options.warm_start.size() == n;
  const bool updatable = !Sparse && n >= UpdatedFreeBlock::kMinRows;
  small_factorizations_ = 0;
  small_cholesky_sets_ = 0;
  small_cholesky_ = false;
  if constexpr (!Sparse) {
    // A candidate: SolveActiveSet tests the symmetry when the third set comes (kLuSetsBeforePrefixCholesky).
    if (n < UpdatedFreeBlock::kMinRows && n >= kMinPrefixCholeskyRows && options_.cholesky) {
      small_cholesky_ = true;
      prefix_.Resize(n);
      prefix_.ResetCounts();
    }
  }
  bool cholesky = false;
  if (updatable) {
    updated_.Resize(n);
    updated_.ResetCounts();
    updated_.set_updates(options_.factor_updates);
    if constexpr (!Sparse) {
      cholesky = options_.cholesky && SymmetricUpToRowScaling(problem);
      updated_.set_symmetric_scale(cholesky ? row_ratio_.data() : nullptr,
                                   cholesky ? inv_row_ratio_.data() : nullptr);
    }
  }
  bool swept = false;
  if constexpr (!Sparse) {
    // Symmetric up to the row scaling from kMinSweptRows rows; from kMinBoxSweptRows, a box whose M is neither
    // symmetric up to the row scaling nor strictly diagonally dominant nor skew-dominant.
    if (!warm && options_.guess_sweeps > 0 && n >= kMinBoxSweptRows) {
      const bool on_box = n < kMinSweptRows && !SymmetricUpToRowScaling(problem) &&
                          BoxWithPositiveDiagonal(problem) && SweepsChooseTheFirstSet(problem);
      swept = (on_box || n >= kMinSweptRows) && SweptGuess(problem, z, s.state, on_box);
    }
  }
  if (!warm && !swept) multiply();
  for (int i = 0; i < n && !swept; ++i) {
    signed char state = kFree;
    if (FixedRow(l[i], u[i])) {
      state = kLower;
    } else if (warm) {
      state = z[i] <= l[i] ? kLower : (z[i] >= u[i] ? kUpper : kFree);
    } else {
      double diagonal = 1.0;
      if constexpr (Sparse) {
        diagonal = problem.sparse_matrix().coeff(i, i);
      } else {
        diagonal = problem.dense_matrix()(i, i);
      }
      const double step = diagonal > 0.0 ? w_[i] / diagonal : w_[i];
      state = static_cast<signed char>(ClassifyRow(z[i], step, l[i], u[i]));
    }
    s.state[i] = state;
  }

  const double q_norm = problem.residual_scale() - 1.0;
  const int budget = IterationBudget(options, std::max(kBppDefaultMinIterations, 20 * n));
  int best_count = n + 1;       // fewest infeasible rows seen
  int credit = options_.block_steps_without_progress;
  bool last_was_block = false;  // the current set came from a block pivot (a singular block steps back)
  bool force_single = false;    // stepped back from a singular block: the next pivot is a single one
  int iterations = 0, block_pivots = 0, single_pivots = 0, singular_blocks = 0, refactored_answers = 0;
  int final_cholesky = 0;  // answers from an update factored afresh by Cholesky in place of the polish
  // The work safeguard (max_single_pivots, else single_pivots_per_row): −1 for none.
  const int single_pivot_limit =
      options_.max_single_pivots >= 0 ? options_.max_single_pivots
      : options_.single_pivots_per_row > 0.0
          ? std::max(4, static_cast<int>(std::min(1e9, std::ceil(options_.single_pivots_per_row * n))))
          : -1;
  // On the Cholesky path, when the base will polish (n ≤ kMaxPolishDenseSize), a set reached by a block pivot is
  // factored afresh: a Cholesky costs half an LU, and an answer from an update would be factored again anyway (the
  // final re-solve below), so the update loses (measured: docs/auto.md); single pivots (one row) are still updated.
  const bool fresh_block_sets = updatable && cholesky && options.polish && n <= kMaxPolishDenseSize;
  const auto finish = [&](SolveStatus status) {
    result->status = status;
    result->iterations = iterations;
    result->SetDetail("block_pivots", block_pivots);
    result->SetDetail("single_pivots", single_pivots);
    result->SetDetail("singular_blocks", singular_blocks);
    if constexpr (!Sparse) {
      result->SetDetail("factorizations", updatable ? updated_.factorizations() : small_factorizations_);
      result->SetDetail("updated_sets", updatable ? updated_.updates() : 0);
      if (updatable && updated_.cholesky_factorizations() > 0) {
        result->SetDetail("cholesky_factorizations", updated_.cholesky_factorizations());
      }
      if (!updatable && small_cholesky_sets_ > 0) {
        result->SetDetail("cholesky_factorizations", small_cholesky_sets_);
        result->SetDetail("reused_cholesky_rows", prefix_.reused_rows());
      }
      if (refactored_answers > 0) result->SetDetail("refactored_answers", refactored_answers);
      if (final_cholesky > 0) result->SetDetail("final_cholesky", final_cholesky);
      if (swept) result->SetDetail("swept_guess", 1);
    }
    if (options.verbosity > 0) {
      std::fprintf(stderr, "bpp: %s after %d active sets (%d block, %d single pivots, %d singular blocks)\n",
                   std::string(ToString(status)).c_str(), iterations, block_pivots, single_pivots, singular_blocks);
    }
  };

  for (;;) {
    if (iterations >= budget) {
      SetMessage(result, "bpp: iteration budget of %d active sets exhausted (best infeasible count %d)", budget,
                 best_count);
      finish(SolveStatus::kIterationLimit);
      return;
    }
    if (options.time_limit_seconds < kInf && TimeLimitReached()) {
      SetMessage(result, "bpp: time limit reached after %d active sets", iterations);
      finish(SolveStatus::kTimeLimit);
      return;
    }
    ++iterations;
    if (fresh_block_sets && last_was_block) updated_.Invalidate();
    if (!SolveActiveSet<Sparse>(problem, z)) {
      ++singular_blocks;
      if (last_was_block) {
        // Step back to the set before the block pivot and change one row only (Murty's rule) from there.
        std::copy(previous_state_.begin(), previous_state_.end(), s.state);
        last_was_block = false;
        force_single = true;
        continue;
      }
      if (iterations == 1) {
        // The guessed first set is singular: start again from every row at a bound (Júdice–Pires' F = ∅), free
        // only where no bound is finite.
        for (int i = 0; i < n; ++i) {
          s.state[i] = l[i] > -kInf ? kLower : (u[i] < kInf ? kUpper : kFree);
        }
        continue;
      }
      SetMessage(result,
                 "bpp: the free block of active set %d is singular or its solution not finite (pivot tolerance %g); "
                 "M is not a P-matrix",
                 iterations, options_.pivot_tolerance);
      finish(SolveStatus::kSingular);
      return;
    }
    multiply();
    double z_norm = 0.0;
    for (int i = 0; i < n; ++i) z_norm = std::max(z_norm, std::abs(z[i]));
    const double margin = 0.5 * options.tolerance * (1.0 + std::min(z_norm, q_norm));
    int count = 0;
    for (int i = 0; i < n; ++i) {
      const signed char state = s.state[i];
      const bool bad = state == kFree ? (z[i] < l[i] - margin || z[i] > u[i] + margin)
                                      : (!FixedRow(l[i], u[i]) &&
                                         (state == kLower ? w_[i] < -margin : w_[i] > margin));
      if (bad) infeasible_[count++] = i;
    }
    if constexpr (!Sparse) {
      if (count == 0 && updatable && updated_.last_path() == UpdatedFreeBlock::Path::kUpdated) {
        // The answer came from an update: its free rows' w must vanish to the margin, else the set is factored
        // afresh and solved again (an update that lost accuracy never makes the answer).
        double free_w = 0.0;
        for (int i = 0; i < n; ++i) {
          if (s.state[i] == kFree) free_w = std::max(free_w, std::abs(w_[i]));
        }
        if (!(free_w <= margin)) {
          updated_.Invalidate();
          ++refactored_answers;
          continue;
        }
        if (options.polish && n <= kMaxPolishDenseSize && iterations < budget &&
            updated_.reference_is_cholesky()) {
          // The base's polish would factor the answer's block by LU (2/3·nf³); a Cholesky of it costs half, and
          // the set's exact answer from it needs no polish (PolishWouldRepeat below).
          updated_.Invalidate();
          ++final_cholesky;
          --iterations;  // the same set once more, not a new one (iterations counts active sets)
          continue;
        }
      }
    }
    if (count == 0) {
      bool clipped = false;
      for (int i = 0; i < n; ++i) {
        const double clip = std::min(std::max(z[i], l[i]), u[i]);
        clipped |= clip != z[i];
        z[i] = clip;
      }
      if constexpr (!Sparse) {
        // The answer's block was factored afresh (an update's answer is left to the polish) and is exact: when the
        // polish would read the same set off z, it would only factor the block again. Below kMinRows every set is
        // factored inline; there the test runs on the Cholesky path and after swept sets with a free row (small-h
        // P-matrix relay at m = 8: the polish was 4.8 k of 12.7 k instructions per solve). Not on every small set:
        // where the answer's residual is exactly 0 the base does not polish, and the test is pure cost (spd-relay
        // at m = 8: +22 % instructions in the perf gate).
        if (options.polish && !clipped &&
            (updatable ? updated_.last_path() == UpdatedFreeBlock::Path::kFactored
                       : (small_cholesky_sets_ > 0 || (swept && AnyFree(s.state, n)))) &&
            PolishWouldRepeat(problem, z, s.state)) {
          NotePolishRedundant();
        }
      }
      finish(SolveStatus::kSolved);
      return;
    }
    if (options.verbosity > 1) {
      std::fprintf(stderr, "bpp: set %d  infeasible %d (best %d)\n", iterations, count, best_count);
    }
    std::copy(s.state, s.state + n, previous_state_.begin());
    bool block = false;
    if (!force_single) {
      if (count < best_count) {
        best_count = count;
        credit = options_.block_steps_without_progress;
        block = true;
      } else if (credit > 0) {
        --credit;
        block = true;
      }
    }
    force_single = false;
    if (block) {
      for (int k = 0; k < count; ++k) {
        const int i = infeasible_[k];
        s.state[i] = Flipped(s.state[i], z[i], l[i]);
      }
      ++block_pivots;
    } else {
      if (single_pivot_limit >= 0 && single_pivots >= single_pivot_limit) {
        SetMessage(result,
                   "bpp: handed over after %d single pivots (%s), %d active sets, best infeasible count %d",
                   single_pivots, options_.max_single_pivots >= 0 ? "max_single_pivots" : "single_pivots_per_row",
                   iterations, best_count);
        finish(SolveStatus::kIterationLimit);
        return;
      }
      const int i = infeasible_[0];  // least index: rows were collected in increasing order
      s.state[i] = Flipped(s.state[i], z[i], l[i]);
      ++single_pivots;
    }
    last_was_block = block;
  }
}

}  // namespace smcbench

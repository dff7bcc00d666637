#include "problems/stepper/step_verdict.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace smcbench {

namespace {

constexpr long double kEps = std::numeric_limits<double>::epsilon();
// Rounding allowance of the verification (s* is rounded to double before it is checked).
constexpr long double kVerifyUlps = 8.0L;
// A pivot below this times the largest entry of the KKT matrix counts as 0 (rank deficiency).
constexpr long double kRankThreshold = 1e-12L;

}  // namespace

void StepRefiner::Reset(const DenseMatrix& M, const DenseMatrix& S, const DenseMatrix& H, const Vector& K) {
  m_ = static_cast<int>(M.rows());
  n_ = static_cast<int>(S.rows());
  box_ = H.rows() == 0;
  rows_ = box_ ? 2 * m_ : static_cast<int>(H.rows());
  const double max_m = M.size() > 0 ? M.cwiseAbs().maxCoeff() : 0.0;
  sigma_ = max_m > 0.0 ? static_cast<long double>(max_m) : 1.0L;
  M_.assign(static_cast<std::size_t>(m_) * m_, 0.0L);
  for (int i = 0; i < m_; ++i) {
    for (int j = 0; j < m_; ++j) M_[static_cast<std::size_t>(i * m_ + j)] = static_cast<long double>(M(i, j)) / sigma_;
  }
  S_.assign(static_cast<std::size_t>(n_) * m_, 0.0L);
  input_scale_ = 0.0;
  for (int i = 0; i < n_; ++i) {
    double row = 0.0;
    for (int j = 0; j < m_; ++j) {
      S_[static_cast<std::size_t>(i * m_ + j)] = S(i, j);
      row += std::abs(S(i, j));
    }
    input_scale_ = std::max(input_scale_, row);
  }
  H_.assign(static_cast<std::size_t>(rows_) * m_, 0.0L);
  K_.assign(static_cast<std::size_t>(rows_), -1.0L);
  hscale_.assign(static_cast<std::size_t>(rows_), 1.0L);
  if (box_) {
    for (int i = 0; i < m_; ++i) {  // row i: s_i ≥ −1; row m + i: −s_i ≥ −1
      H_[static_cast<std::size_t>(i * m_ + i)] = 1.0L;
      H_[static_cast<std::size_t>((m_ + i) * m_ + i)] = -1.0L;
    }
  } else {
    for (int r = 0; r < rows_; ++r) {
      const double hr = H.row(r).cwiseAbs().maxCoeff();
      const long double scale = hr > 0.0 ? static_cast<long double>(hr) : 1.0L;
      hscale_[static_cast<std::size_t>(r)] = scale;
      for (int j = 0; j < m_; ++j) H_[static_cast<std::size_t>(r * m_ + j)] = static_cast<long double>(H(r, j)) / scale;
      K_[static_cast<std::size_t>(r)] = static_cast<long double>(K[r]) / scale;
    }
  }
  const std::size_t cap = static_cast<std::size_t>(m_ + rows_);
  active_.assign(static_cast<std::size_t>(rows_), 0);
  active_rows_.assign(static_cast<std::size_t>(rows_), 0);
  A_.assign(cap * cap, 0.0L);
  rhs_.assign(cap, 0.0L);
  sol_.assign(cap, 0.0L);
  colp_.assign(cap, 0);
  w_.assign(static_cast<std::size_t>(m_), 0.0L);
  star_.assign(static_cast<std::size_t>(m_), 0.0L);
  best_.assign(static_cast<std::size_t>(m_), 0.0L);
  mu_.assign(static_cast<std::size_t>(rows_), 0.0L);
}

StepCheck StepRefiner::Refine(const double* q, const double* mu, double* s) {
  StepCheck check;
  // w̃ = M̃ s + q̃, and the multipliers in units of s: μ̃_r = μ_r h_r/σ (the box: w̃'s positive and negative parts).
  long double s_norm = 0.0L;
  for (int i = 0; i < m_; ++i) {
    long double wi = static_cast<long double>(q[i]) / sigma_;
    for (int j = 0; j < m_; ++j) wi += M_[static_cast<std::size_t>(i * m_ + j)] * s[j];
    w_[static_cast<std::size_t>(i)] = wi;
    s_norm = std::max(s_norm, std::abs(static_cast<long double>(s[i])));
  }
  for (int r = 0; r < rows_; ++r) {
    long double mr = 0.0L;
    if (box_) {
      const long double wi = w_[static_cast<std::size_t>(r % m_)];
      mr = r < m_ ? std::max(wi, 0.0L) : std::max(-wi, 0.0L);
    } else if (mu != nullptr) {
      mr = static_cast<long double>(mu[r]) * hscale_[static_cast<std::size_t>(r)] / sigma_;
    }
    mu_[static_cast<std::size_t>(r)] = mr;
  }
  // Two readings of the active set: the natural map's (row r active when μ̃_r > its slack, what the projection
  // Π(μ̃ − slack) keeps), then every row within 1e-9 of its face (a backend whose multipliers are not its own).
  for (int attempt = 0; attempt < 2 && !check.exact; ++attempt) {
    for (int r = 0; r < rows_; ++r) {
      long double slack = -K_[static_cast<std::size_t>(r)];
      for (int j = 0; j < m_; ++j) slack += H_[static_cast<std::size_t>(r * m_ + j)] * s[j];
      active_[static_cast<std::size_t>(r)] =
          attempt == 0 ? mu_[static_cast<std::size_t>(r)] > slack : slack <= 1e-9L * (1.0L + s_norm);
    }
    check.exact = SolveOnActiveSet(q, s);
  }
  if (check.exact) {
    check.x_error = static_cast<double>(XError(s));
  } else if (rows_ <= kMaxEnumeratedRows) {
    // The answer's active set has no exact step: near a face where w is of the order of the state (near the origin)
    // the sign of a multiplier decides between faces whose steps give almost the same x (M = C S of rank one: λ
    // is far from unique, x is not). Every active set of at most m rows is tried, and the exact step nearest the
    // answer in x is kept.
    long double best = std::numeric_limits<long double>::infinity();
    for (unsigned mask = 0; mask < (1u << rows_); ++mask) {
      int count = 0;
      for (int r = 0; r < rows_; ++r) count += (mask >> r) & 1u;
      if (count > m_) continue;
      for (int r = 0; r < rows_; ++r) active_[static_cast<std::size_t>(r)] = (mask >> r) & 1u;
      if (!SolveOnActiveSet(q, s)) continue;
      const long double error = XError(s);
      if (error < best) {
        best = error;
        best_ = star_;  // same size: no allocation
      }
    }
    if (best < std::numeric_limits<long double>::infinity()) {
      check.exact = true;
      check.x_error = static_cast<double>(best);
      star_ = best_;
    }
  }
  if (!check.exact) return check;
  for (int j = 0; j < m_; ++j) s[j] = static_cast<double>(star_[static_cast<std::size_t>(j)]);
  return check;
}

long double StepRefiner::XError(const double* s) const {
  long double x_error = 0.0L;
  for (int i = 0; i < n_; ++i) {
    long double dx = 0.0L;
    for (int j = 0; j < m_; ++j) {
      dx += S_[static_cast<std::size_t>(i * m_ + j)] * (star_[static_cast<std::size_t>(j)] - s[j]);
    }
    x_error = std::max(x_error, std::abs(dx));
  }
  return x_error;
}

bool StepRefiner::SolveOnActiveSet(const double* q, const double* s) {
  int a = 0;
  for (int r = 0; r < rows_; ++r) {
    if (active_[static_cast<std::size_t>(r)]) active_rows_[static_cast<std::size_t>(a++)] = r;
  }
  const int N = m_ + a;
  const auto at = [&](int i, int j) -> long double& { return A_[static_cast<std::size_t>(i * N + j)]; };
  // [M̃  −H̃_Aᵀ] [δ  ]   [−w̃          ]
  // [H̃_A   0  ] [μ̃_A] = [K̃_A − H̃_A s ]
  long double amax = 0.0L;
  for (int i = 0; i < m_; ++i) {
    for (int j = 0; j < m_; ++j) at(i, j) = M_[static_cast<std::size_t>(i * m_ + j)];
    for (int c = 0; c < a; ++c) {
      at(i, m_ + c) = -H_[static_cast<std::size_t>(active_rows_[static_cast<std::size_t>(c)] * m_ + i)];
    }
    rhs_[static_cast<std::size_t>(i)] = -w_[static_cast<std::size_t>(i)];
  }
  for (int c = 0; c < a; ++c) {
    const int r = active_rows_[static_cast<std::size_t>(c)];
    long double b = K_[static_cast<std::size_t>(r)];
    for (int j = 0; j < m_; ++j) {
      at(m_ + c, j) = H_[static_cast<std::size_t>(r * m_ + j)];
      b -= H_[static_cast<std::size_t>(r * m_ + j)] * s[j];
    }
    for (int j = 0; j < a; ++j) at(m_ + c, m_ + j) = 0.0L;
    rhs_[static_cast<std::size_t>(m_ + c)] = b;
  }
  long double data_scale = 1.0L;  // 1 + ‖q̃‖∞ + ‖K̃_A‖∞ + ‖M̃‖‖s‖: what the consistency test is relative to
  for (int i = 0; i < m_; ++i) {
    data_scale += std::abs(static_cast<long double>(q[i])) / sigma_ + std::abs(static_cast<long double>(s[i]));
  }
  for (int i = 0; i < N; ++i) {
    colp_[static_cast<std::size_t>(i)] = i;
    for (int j = 0; j < N; ++j) amax = std::max(amax, std::abs(at(i, j)));
  }
  // Gaussian elimination with complete pivoting; the unknowns past the rank are 0.
  int rank = 0;
  for (int k = 0; k < N; ++k) {
    int pi = k, pj = k;
    long double best = -1.0L;
    for (int i = k; i < N; ++i) {
      for (int j = k; j < N; ++j) {
        if (std::abs(at(i, j)) > best) best = std::abs(at(i, j)), pi = i, pj = j;
      }
    }
    if (!(best > kRankThreshold * amax)) break;
    if (pi != k) {
      for (int j = 0; j < N; ++j) std::swap(at(k, j), at(pi, j));
      std::swap(rhs_[static_cast<std::size_t>(k)], rhs_[static_cast<std::size_t>(pi)]);
    }
    if (pj != k) {
      for (int i = 0; i < N; ++i) std::swap(at(i, k), at(i, pj));
      std::swap(colp_[static_cast<std::size_t>(k)], colp_[static_cast<std::size_t>(pj)]);
    }
    for (int i = k + 1; i < N; ++i) {
      const long double f = at(i, k) / at(k, k);
      if (f == 0.0L) continue;
      for (int j = k; j < N; ++j) at(i, j) -= f * at(k, j);
      rhs_[static_cast<std::size_t>(i)] -= f * rhs_[static_cast<std::size_t>(k)];
    }
    ++rank;
  }
  // A rank-deficient system must be consistent: the rest of the right-hand side is rounding of the data.
  for (int i = rank; i < N; ++i) {
    if (!(std::abs(rhs_[static_cast<std::size_t>(i)]) <= 64.0L * kEps * data_scale)) return false;
  }
  for (int i = N - 1; i >= 0; --i) {
    long double v = 0.0L;
    if (i < rank) {
      v = rhs_[static_cast<std::size_t>(i)];
      for (int j = i + 1; j < rank; ++j) v -= at(i, j) * sol_[static_cast<std::size_t>(j)];
      v /= at(i, i);
    }
    sol_[static_cast<std::size_t>(i)] = v;
  }
  // Unpermute: δ (first m unknowns) and μ̃_A.
  long double star_norm = 0.0L, mu_norm = 0.0L;
  for (int j = 0; j < N; ++j) {
    const int c = colp_[static_cast<std::size_t>(j)];
    if (c < m_) {
      star_[static_cast<std::size_t>(c)] = static_cast<long double>(s[c]) + sol_[static_cast<std::size_t>(j)];
    } else {
      rhs_[static_cast<std::size_t>(c)] = sol_[static_cast<std::size_t>(j)];  // μ̃ of active row c − m
    }
  }
  for (int j = 0; j < m_; ++j) {
    if (!std::isfinite(static_cast<double>(star_[static_cast<std::size_t>(j)]))) return false;
    star_norm = std::max(star_norm, std::abs(star_[static_cast<std::size_t>(j)]));
  }
  for (int c = 0; c < a; ++c) mu_norm = std::max(mu_norm, std::abs(rhs_[static_cast<std::size_t>(m_ + c)]));
  // s* must solve the step: inside P and μ̃_A ≥ 0, to the rounding of s* to double.
  for (int c = 0; c < a; ++c) {
    if (rhs_[static_cast<std::size_t>(m_ + c)] < -kVerifyUlps * kEps * (1.0L + mu_norm)) return false;
  }
  for (int r = 0; r < rows_; ++r) {
    long double slack = -K_[static_cast<std::size_t>(r)];
    for (int j = 0; j < m_; ++j) {
      slack += H_[static_cast<std::size_t>(r * m_ + j)] *
               static_cast<long double>(static_cast<double>(star_[static_cast<std::size_t>(j)]));
    }
    if (slack < -kVerifyUlps * kEps * (1.0L + star_norm)) return false;
  }
  return true;
}

}  // namespace smcbench

// Ipopt on a nonlinear MCP: find z ∈ [l,u] with −F(z) ∈ N_[l,u](z).
//
// The program (the box backend's complementarity-gap NLP with F in place of Mz + q). Variables y = z / c in the
// problem's units c (MCP::variable_scale, 1 by default), and per row i the multipliers its bounds need:
//   l_i finite, l_i < u_i:  w_k ≥ 0 (lower bound);   u_i finite, l_i < u_i:  v_k ≥ 0 (upper bound);
//   l_i = u_i (fixed row):  one free multiplier y_k (z_i is then fixed by its bounds, Ipopt makes it a parameter);
//   l_i = −∞, u_i = +∞ (free row): no multiplier, so its constraint is the equation F_i(z) = 0.
//     min  G = Σ (y_i − l_i/c_i) w_k + Σ (u_i/c_i − y_i) v_k                (finite bounds only)
//     s.t. F_i(c∘y) / d_i − w_k + v_k − y_k = 0   (i = 1..n, the terms row i has),   l/c ≤ y ≤ u/c,  w, v ≥ 0,
// with d_i = max_j |∂F_i/∂z_j|·c_j at the starting point (McpRowScales): in these units the program's constraint
// residual and the verdict's scaled residual (McpScaledResidual) measure the same thing, so Ipopt's stopping test
// does not change when F's rows or the variables' units are scaled. G ≥ 0 on the feasible set and G = 0 exactly at
// the MCP's solutions; a stationary point with G > 0 is a failure (kStalled, G in the message).
//
// Derivatives. The constraints' Jacobian is exact: ∂g_i/∂y_j = J_ij c_j / d_i from the MCP's Jacobian (dense: every
// entry; sparse: the pattern of J at the starting point, kept for the whole run since Ipopt needs a fixed
// structure; an entry outside it later is a kNumericalFailure naming it). The Hessian of the Lagrangian is
// ∇²G + Σ λ_i ∇²F_i / d_i, and F's second derivatives are not available. Two choices (IpoptOptions::mcp_hessian):
//   gap (default): ∇²G only, constant (+1 at (w_k, y_i), −1 at (v_k, y_i)). Exact when F is affine, so a box-MLCP
//     posed as an MCP gets the box backend's Newton steps; for a nonlinear F the dropped curvature slows
//     Ipopt's convergence (badly where the multipliers are large, below), and the Newton refinement takes over near
//     a solution (quadratic where J is nonsingular on the active set). Cheap and with the sparsity of the problem.
//   limited-memory: Ipopt's L-BFGS approximation of the whole Lagrangian ("hessian_approximation limited-memory"),
//     which learns F's curvature from gradient differences but not the exact bilinear part.
//   Neither dominates (ipopt_mcp_test.cc): gap converges where F is affine or mildly nonlinear and from a start at a
//   critical point of F (Billups' example from x = 1, which limited-memory calls locally infeasible); where a
//   stationary point of the program has a nonzero multiplier on a curved F, gap misses the curvature and may not
//   converge to it, which limited-memory reaches in a few iterations (with the refinement both end at the solution
//   there, gap after far more iterations). Gap is the default: exact for affine F (a box-MLCP posed as an MCP), and
//   with the refinement it solved every test problem limited-memory solved, and Billups' from x = 1.
//
// Refinement (the MCP counterpart of the box backend's active-set polish). From a point z: clip to [l,u]; then up to
// mcp_newton_steps times: identify the active set from the scaled natural map p_i = z_i − c_i F_i / d_i (d: row
// scales of J at z), L = {p_i ≤ l_i}, U = {p_i ≥ u_i}, F the rest; set z_L = l_L, z_U = u_U and take the Newton
// step of F_F = 0 linearized at z: J_FF δ_F = −F_F − J_{F,L∪U} δ_{L∪U} (dense LU, or sparse LU). This is a
// semismooth Newton step on the min function without a line search; the best point seen (by the verdict's scaled
// residual, J evaluated there) is the result, kept only if better than the point it started from. It stops at 1 % of
// the tolerance, not at the tolerance: a step more at most (quadratic convergence), and the answer keeps a margin.
//   With polish (on by default) it runs on Ipopt's final point (also when an Ipopt iterate already met the
//   tolerance: then for the margin); with early_polish also at iterates whose scaled
//   residual is below early_polish_threshold (and whose active set changed), stopping Ipopt when it succeeds; with
//   polish_warm_start on a warm start before Ipopt.
//
// Stopping and verdict: the scale-free residual McpScaledResidual with McpRowScales of J at the point, ≤ the
// tolerance. Ipopt is also stopped as soon as one of its iterates meets it.
//
// Status (as for the box): solved iff the measure holds at the returned z; else Ipopt's status is mapped:
// iteration limit → kIterationLimit, time → kTimeLimit, converged with G > 0 → kStalled, converged otherwise →
// kInaccurate, tiny step → kStalled, diverging → kDiverged, infeasible constraints → kNumericalFailure (local
// infeasibility of a nonlinear system proves nothing), restoration / step computation failure / NaN → 
// kNumericalFailure, invalid option → kInvalidOptions. F not finite at the start, or a Jacobian of the wrong size,
// is kNumericalFailure before Ipopt runs, with the entry or the size in the message.
//
// Details: ipopt_status (Ipopt's ApplicationReturnStatus), ipopt_residual and refined_residual (scaled residual at
// Ipopt's point and after the refinement, NaN if not computed), refine_accepted (1/0), objective (G at Ipopt's
// point), and the codes early_stop and mcp_hessian (ipopt_details.h).
//
// An exception from F or J is not a status: it reaches the caller (Ipopt would swallow it; it is kept and rethrown
// once Ipopt returned).
//
// Allocation: Ipopt allocates on every solve; our buffers are members reused while the size stays.
#include "solvers/ipopt/ipopt_mcp.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/LU>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseLU>

#include <IpIpoptApplication.hpp>
#include <IpTNLP.hpp>

#include "solvers/ipopt/gap_program.h"
#include "solvers/ipopt/ipopt_details.h"
#include "solvers/ipopt/ipopt_names.h"
#include "solvers/ipopt/ipopt_qp_solver.h"
#include "solvers/ipopt/ipopt_runner.h"

namespace smcbench {
namespace {

using Ipopt::Index;
using Ipopt::Number;

constexpr double kIpoptInf = 2e19;  // beyond Ipopt's nlp_lower/upper_bound_inf: "no bound"

double IpoptBound(double b) { return std::isfinite(b) ? b : (b > 0 ? kIpoptInf : -kIpoptInf); }

enum StopReason { kNotStopped, kStopMerit, kStopRefined, kStopTime };
constexpr double kRefineMargin = 1e-2;  // the refinement's goal, relative to the tolerance

}  // namespace

struct IpoptMcpSession::Impl {
  explicit Impl(std::function<bool()> time_up) : time_up_(std::move(time_up)) {}

  void Solve(const MCP& p, const SolverOptions& options, const IpoptOptions& o, SolveResult* result);

  // F at z into *F; false if an entry is not finite (first such index in *bad).
  bool EvaluateF(const Vector& z, Vector* F, int* bad = nullptr) const {
    problem_->Evaluate(z, F);
    for (int i = 0; i < n_; ++i) {
      if (!std::isfinite((*F)[i])) {
        if (bad) *bad = i;
        return false;
      }
    }
    return true;
  }
  // J at z into Jd_ or Js_ (the MCP's kind); false (with jacobian_error_) on a wrong size.
  bool EvaluateJ(const Vector& z) {
    if (sparse_) {
      problem_->JacobianSparse(z, &Js_);
      if (Js_.rows() != n_ || Js_.cols() != n_) return WrongSize(Js_.rows(), Js_.cols());
      Js_.makeCompressed();
    } else {
      if (Jd_.rows() != n_ || Jd_.cols() != n_) Jd_.resize(n_, n_);
      problem_->JacobianDense(z, &Jd_);
      if (Jd_.rows() != n_ || Jd_.cols() != n_) return WrongSize(Jd_.rows(), Jd_.cols());
    }
    return true;
  }
  bool WrongSize(Eigen::Index rows, Eigen::Index cols) {
    std::ostringstream s;
    s << "the MCP Jacobian has the wrong size: " << rows << "x" << cols << ", expected " << n_ << "x" << n_;
    jacobian_error_ = s.str();
    return false;
  }
  // Row scales of the current J into *d.
  void RowScales(Vector* d) const {
    if (sparse_) {
      McpRowScales(Js_, problem_->variable_scale(), d);
    } else {
      McpRowScales(Jd_, problem_->variable_scale(), d);
    }
  }
  // The verdict's measure at z: F into *F, J evaluated at z, row scales into merit_d_. +∞ if F or J fails.
  double Merit(const Vector& z, Vector* F) {
    if (!EvaluateF(z, F) || !EvaluateJ(z)) return kInf;
    RowScales(&merit_d_);
    return McpScaledResidual(z, *F, problem_->l(), problem_->u(), merit_d_, problem_->variable_scale());
  }
  // The Newton refinement (header comment) from z; the best point into *out, its measure returned.
  double Refine(const Vector& z, Vector* out);
  // The iterate check Ipopt's callback runs: false stops Ipopt.
  bool OnIteration(Ipopt::AlgorithmMode mode, Index iter);

  void SetUpProgram();
  Ipopt::ApplicationReturnStatus RunIpopt(const SolverOptions& options, const IpoptOptions& o);
  void ExplainFailure(Ipopt::ApplicationReturnStatus status, double ipopt_residual, double refined_residual,
                      SolveResult* result);

  // The program's z from Ipopt's y.
  void ToZ(const Number* y, Vector* z) const {
    for (int i = 0; i < n_; ++i) (*z)[i] = c_[i] * y[i];
  }

  std::function<bool()> time_up_;
  std::unique_ptr<IpoptRunner> runner_;  // made at the first solve that reaches Ipopt
  Ipopt::SmartPtr<Ipopt::TNLP> tnlp_;

  // Per solve.
  const MCP* problem_ = nullptr;
  const IpoptOptions* o_ = nullptr;
  int n_ = 0;
  bool sparse_ = false;
  double target_ = 0.0;
  Vector c_;      // units (1 when the problem states none)
  Vector d_;      // the program's row scales, from J at the start
  Vector start_;  // z at the start
  Vector F_, z_;  // scratch for the TNLP's evaluations
  DenseMatrix Jd_;
  SparseMatrix Js_;
  std::string jacobian_error_;
  // An exception from F or J inside Ipopt's callbacks (Ipopt would swallow it): rethrown once Ipopt returned, so it
  // reaches the caller as from every backend.
  std::exception_ptr callback_error_;
  GapMultipliers mult_;  // the gap program's multipliers (gap_program.h), in the program's variables y = z / c
  // Sparse: the Jacobian's pattern at the start (column-major), Ipopt's fixed structure.
  std::vector<int> pattern_outer_, pattern_inner_;
  int objective_gap_hessian_ = 0;
  int iterations_ = 0;
  double objective_ = kNaN;
  StopReason stop_ = kNotStopped;
  Vector last_x_;
  bool have_last_x_ = false;
  Vector ipopt_x_;
  bool have_ipopt_x_ = false;
  Vector iter_z_, iter_F_, early_z_, early_ipopt_z_;
  double early_ipopt_residual_ = kInf, early_refined_residual_ = kNaN;
  std::vector<signed char> tried_state_, state_;
  Vector merit_d_;

  // Refinement workspace.
  Vector ref_z_, ref_F_, ref_d_, ref_rhs_, ref_delta_, ref_best_;
  std::vector<int> free_idx_, pos_;
  DenseMatrix block_;
  Eigen::PartialPivLU<DenseMatrix> lu_;
  SparseMatrix sparse_block_;
  std::vector<Eigen::Triplet<double, int>> triplets_;
  Eigen::SparseLU<SparseMatrix, Eigen::COLAMDOrdering<int>> slu_;
};

namespace {

// The gap program of the header comment as Ipopt's TNLP, a thin adapter over the session.
class McpGapTnlp final : public Ipopt::TNLP {
 public:
  explicit McpGapTnlp(IpoptMcpSession::Impl* s) : s_(s) {}

  // Runs a callback that calls the caller's F or J: an exception is kept for the session and stops Ipopt.
  template <typename Body>
  bool Guarded(Body&& body) {
    if (s_->callback_error_) return false;
    try {
      return body();
    } catch (...) {
      s_->callback_error_ = std::current_exception();
      return false;
    }
  }

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag, IndexStyleEnum& style) override {
    n = s_->n_ + static_cast<Index>(s_->mult_.count());
    m = s_->n_;
    nnz_jac_g = JacobianEntries() + static_cast<Index>(s_->mult_.count());
    nnz_h_lag = s_->objective_gap_hessian_;
    style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index, Number* x_l, Number* x_u, Index m, Number* g_l, Number* g_u) override {
    const MCP& p = *s_->problem_;
    for (Index i = 0; i < m; ++i) {
      x_l[i] = IpoptBound(p.l()[i] / s_->c_[i]);
      x_u[i] = IpoptBound(p.u()[i] / s_->c_[i]);
      g_l[i] = g_u[i] = 0.0;
    }
    s_->mult_.Bounds(m, kIpoptInf, x_l, x_u);
    return true;
  }

  // y from the start; multipliers from the sign split of F/d there (Ipopt pushes them into the interior).
  bool get_starting_point(Index n, bool init_x, Number* x, bool init_z, Number* z_l, Number* z_u, Index m,
                          bool init_lambda, Number* lambda) override {
    return Guarded([&] { return StartingPoint(n, init_x, x, init_z, z_l, z_u, m, init_lambda, lambda); });
  }
  bool StartingPoint(Index n, bool init_x, Number* x, bool init_z, Number* z_l, Number* z_u, Index m,
                     bool init_lambda, Number* lambda) {
    if (init_x) {
      for (Index i = 0; i < m; ++i) x[i] = s_->start_[i] / s_->c_[i];
      s_->EvaluateF(s_->start_, &s_->F_);
      s_->mult_.Start([this](int i) { return s_->F_[i] / s_->d_[i]; }, x + m);
    }
    GapMultipliers::StartDuals(n, init_z, z_l, z_u, m, init_lambda, lambda);
    return true;
  }

  bool eval_f(Index, const Number* x, bool, Number& f) override {
    f = s_->mult_.Gap(x, s_->n_);
    return std::isfinite(f);
  }

  bool eval_grad_f(Index nx, const Number* x, bool, Number* grad) override {
    s_->mult_.Gradient(x, s_->n_, grad);
    if (s_->last_x_.size() != nx) s_->last_x_.resize(nx);
    std::copy(x, x + nx, s_->last_x_.data());
    s_->have_last_x_ = true;
    return true;
  }

  // g_i = F_i(c∘y)/d_i − w + v − y_fixed.
  bool eval_g(Index n, const Number* x, bool new_x, Index m, Number* g) override {
    return Guarded([&] { return Constraints(n, x, new_x, m, g); });
  }
  bool Constraints(Index, const Number* x, bool, Index m, Number* g) {
    s_->ToZ(x, &s_->z_);
    if (!s_->EvaluateF(s_->z_, &s_->F_)) return false;  // Ipopt then shortens the step
    for (Index i = 0; i < m; ++i) g[i] = s_->F_[i] / s_->d_[i];
    s_->mult_.AddToConstraints(x, m, g);
    return true;
  }

  bool eval_jac_g(Index nx, const Number* x, bool new_x, Index m, Index nele, Index* row, Index* col,
                  Number* values) override {
    return Guarded([&] { return ConstraintJacobian(nx, x, new_x, m, nele, row, col, values); });
  }
  bool ConstraintJacobian(Index, const Number* x, bool, Index m, Index, Index* row, Index* col, Number* values) {
    const int n = s_->n_;
    const Index entries = JacobianEntries();
    const int count = s_->mult_.count();
    if (values == nullptr) {
      Index e = 0;
      if (s_->sparse_) {
        for (int j = 0; j < n; ++j) {
          for (int k = s_->pattern_outer_[j]; k < s_->pattern_outer_[j + 1]; ++k, ++e) {
            row[e] = s_->pattern_inner_[k];
            col[e] = j;
          }
        }
      } else {
        for (int j = 0; j < n; ++j) {
          for (int i = 0; i < n; ++i, ++e) {
            row[e] = i;
            col[e] = j;
          }
        }
      }
      for (int k = 0; k < count; ++k) {
        row[entries + k] = s_->mult_.row[k];
        col[entries + k] = m + k;
      }
      return true;
    }
    s_->ToZ(x, &s_->z_);
    if (!s_->EvaluateJ(s_->z_)) return false;
    const Vector& c = s_->c_;
    const Vector& d = s_->d_;
    if (s_->sparse_) {
      if (!ScatterSparse(values)) return false;
    } else {
      const double* J = s_->Jd_.data();
      Index e = 0;
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i, ++e) values[e] = J[e] * c[j] / d[i];
      }
    }
    for (int k = 0; k < count; ++k) values[entries + k] = s_->mult_.ConstraintEntry(k);
    for (Index e = 0; e < entries + count; ++e) {
      if (!std::isfinite(values[e])) return false;
    }
    return true;
  }

  bool eval_h(Index, const Number*, bool, Number obj_factor, Index, const Number*, bool, Index, Index* row,
              Index* col, Number* values) override {
    // The constant Hessian of G (gap mode): (w_k or v_k, y_i) = ±1, lower triangle (n + k > i).
    const int n = s_->n_;
    Index e = 0;
    for (int k = 0; k < s_->mult_.count(); ++k) {
      if (s_->mult_.kind[k] == kFixedMult) continue;
      if (values == nullptr) {
        row[e] = n + k;
        col[e] = s_->mult_.row[k];
      } else {
        values[e] = obj_factor * s_->mult_.HessianEntry(k);
      }
      ++e;
    }
    return true;
  }

  void finalize_solution(Ipopt::SolverReturn, Index n, const Number* x, const Number*, const Number*, Index,
                         const Number*, const Number*, Number obj, const Ipopt::IpoptData*,
                         Ipopt::IpoptCalculatedQuantities*) override {
    s_->ipopt_x_.resize(s_->n_);
    s_->ToZ(x, &s_->ipopt_x_);
    (void)n;
    s_->have_ipopt_x_ = true;
    s_->objective_ = obj;
  }

  bool intermediate_callback(Ipopt::AlgorithmMode mode, Index iter, Number, Number, Number, Number, Number, Number,
                             Number, Number, Index, const Ipopt::IpoptData*,
                             Ipopt::IpoptCalculatedQuantities*) override {
    return Guarded([&] { return s_->OnIteration(mode, iter); });
  }

 private:
  Index JacobianEntries() const {
    return s_->sparse_ ? static_cast<Index>(s_->pattern_inner_.size())
                       : static_cast<Index>(s_->n_) * static_cast<Index>(s_->n_);
  }

  // Js_ into the fixed pattern, scaled to ∂g_i/∂y_j = J_ij c_j / d_i; false (with the entry named) when J has a
  // nonzero outside the pattern.
  bool ScatterSparse(Number* values) const {
    const SparseMatrix& J = s_->Js_;
    const int n = s_->n_;
    const Index entries = JacobianEntries();
    std::fill(values, values + entries, 0.0);
    for (int j = 0; j < n; ++j) {
      const int begin = s_->pattern_outer_[j], end = s_->pattern_outer_[j + 1];
      int at = begin;
      for (SparseMatrix::InnerIterator it(J, j); it; ++it) {
        const int i = static_cast<int>(it.row());
        while (at < end && s_->pattern_inner_[at] < i) ++at;
        if (at == end || s_->pattern_inner_[at] != i) {
          if (it.value() == 0.0) continue;
          std::ostringstream msg;
          msg << "the MCP's sparse Jacobian has an entry (" << i << ", " << j
              << ") outside its pattern at the starting point (Ipopt needs a fixed structure: store it there, "
                 "even as 0)";
          s_->jacobian_error_ = msg.str();
          return false;
        }
        values[at] = it.value() * s_->c_[j] / s_->d_[i];
      }
    }
    return true;
  }

  IpoptMcpSession::Impl* s_;
};

}  // namespace

void IpoptMcpSession::Impl::SetUpProgram() {
  const MCP& p = *problem_;
  mult_.Build(p.l(), p.u(), &c_);
  objective_gap_hessian_ = mult_.bounded;
  if (o_->mcp_hessian == IpoptOptions::kLimitedMemory) objective_gap_hessian_ = 0;
  if (sparse_) {
    // J was evaluated at the start (Solve): its pattern is the structure Ipopt keeps.
    pattern_outer_.assign(Js_.outerIndexPtr(), Js_.outerIndexPtr() + n_ + 1);
    pattern_inner_.assign(Js_.innerIndexPtr(), Js_.innerIndexPtr() + Js_.nonZeros());
  }
}

bool IpoptMcpSession::Impl::OnIteration(Ipopt::AlgorithmMode mode, Index iter) {
  iterations_ = std::max(iterations_, static_cast<int>(iter));
  if (time_up_()) {
    stop_ = kStopTime;
    return false;
  }
  if (mode != Ipopt::RegularMode || !have_last_x_) return true;
  iter_z_.resize(n_);
  ToZ(last_x_.data(), &iter_z_);
  const double res = Merit(iter_z_, &iter_F_);
  if (res <= target_) {
    early_z_ = iter_z_;
    early_ipopt_z_ = iter_z_;
    early_ipopt_residual_ = res;
    stop_ = kStopMerit;
    return false;
  }
  const IpoptOptions& o = *o_;
  if (o.polish && o.early_polish && o.mcp_newton_steps > 0 && res <= o.early_polish_threshold) {
    // Try the refinement once per active set (of the scaled natural map at the iterate).
    state_.resize(n_);
    for (int i = 0; i < n_; ++i) {
      const double pi = iter_z_[i] - c_[i] * iter_F_[i] / merit_d_[i];
      state_[i] = pi <= problem_->l()[i] ? 1 : (pi >= problem_->u()[i] ? 2 : 0);
    }
    if (state_ != tried_state_) {
      tried_state_ = state_;
      const double refined = Refine(iter_z_, &early_z_);
      if (refined <= target_) {
        early_ipopt_z_ = iter_z_;
        early_ipopt_residual_ = res;
        early_refined_residual_ = refined;
        stop_ = kStopRefined;
        return false;
      }
    }
  }
  return true;
}

double IpoptMcpSession::Impl::Refine(const Vector& z, Vector* out) {
  const MCP& p = *problem_;
  const Vector& l = p.l();
  const Vector& u = p.u();
  ref_z_ = z.cwiseMax(l).cwiseMin(u);
  *out = ref_z_;
  double best = Merit(ref_z_, &ref_F_);
  if (!std::isfinite(best)) return kInf;
  pos_.assign(n_, -1);
  // Aim below the tolerance: Newton converges quadratically there, so the margin costs a step at most and keeps
  // the answer solved under any reasonable variant of the measure (J at a slightly different point).
  const double goal = kRefineMargin * target_;
  for (int step = 0; step < o_->mcp_newton_steps && best > goal; ++step) {
    if (time_up_()) break;
    // ref_F_, J and merit_d_ are those of ref_z_ (Merit just ran there).
    RowScales(&ref_d_);
    free_idx_.clear();
    ref_delta_.setZero(n_);
    for (int i = 0; i < n_; ++i) {
      const double pi = ref_z_[i] - c_[i] * ref_F_[i] / ref_d_[i];
      if (l[i] == u[i] || pi <= l[i]) {
        ref_delta_[i] = l[i] - ref_z_[i];
      } else if (pi >= u[i]) {
        ref_delta_[i] = u[i] - ref_z_[i];
      } else {
        pos_[i] = static_cast<int>(free_idx_.size());
        free_idx_.push_back(i);
        continue;
      }
      pos_[i] = -1;
    }
    const int nf = static_cast<int>(free_idx_.size());
    if (nf > 0) {
      // rhs = −F_F − J_{F,A} δ_A.
      ref_rhs_.resize(nf);
      for (int a = 0; a < nf; ++a) ref_rhs_[a] = -ref_F_[free_idx_[a]];
      if (sparse_) {
        triplets_.clear();
        for (int j = 0; j < n_; ++j) {
          for (SparseMatrix::InnerIterator it(Js_, j); it; ++it) {
            const int i = static_cast<int>(it.row());
            if (pos_[i] < 0) continue;
            if (pos_[j] >= 0) {
              triplets_.emplace_back(pos_[i], pos_[j], it.value());
            } else {
              ref_rhs_[pos_[i]] -= it.value() * ref_delta_[j];
            }
          }
        }
        sparse_block_.resize(nf, nf);
        sparse_block_.setFromTriplets(triplets_.begin(), triplets_.end());
        sparse_block_.makeCompressed();
        slu_.compute(sparse_block_);
        if (slu_.info() != Eigen::Success) break;
        Vector solved = slu_.solve(ref_rhs_);
        if (slu_.info() != Eigen::Success) break;
        for (int a = 0; a < nf; ++a) ref_delta_[free_idx_[a]] = solved[a];
      } else {
        block_.resize(nf, nf);
        for (int b = 0; b < nf; ++b) {
          for (int a = 0; a < nf; ++a) block_(a, b) = Jd_(free_idx_[a], free_idx_[b]);
        }
        for (int j = 0; j < n_; ++j) {
          if (pos_[j] >= 0 || ref_delta_[j] == 0.0) continue;
          for (int a = 0; a < nf; ++a) ref_rhs_[a] -= Jd_(free_idx_[a], j) * ref_delta_[j];
        }
        lu_.compute(block_);
        ref_rhs_ = lu_.solve(ref_rhs_);
        for (int a = 0; a < nf; ++a) ref_delta_[free_idx_[a]] = ref_rhs_[a];
      }
    }
    if (!ref_delta_.allFinite()) break;
    ref_z_ += ref_delta_;
    // A free row's Newton step may leave the box: the next step's active set takes it back to the bound.
    ref_z_ = ref_z_.cwiseMax(l).cwiseMin(u);
    const double r = Merit(ref_z_, &ref_F_);
    if (!std::isfinite(r)) break;
    if (r < best) {
      best = r;
      *out = ref_z_;
    }
  }
  return best;
}

Ipopt::ApplicationReturnStatus IpoptMcpSession::Impl::RunIpopt(const SolverOptions& options,
                                                              const IpoptOptions& o) {
  return runner_->Run(tnlp_, options, o, [&o](Ipopt::OptionsList& list) {
    bool ok = list.SetStringValue("mu_strategy", o.mu_strategy == IpoptOptions::kAdaptive ? "adaptive" : "monotone");
    if (o.mcp_hessian == IpoptOptions::kLimitedMemory) {
      ok &= list.SetStringValue("hessian_approximation", "limited-memory");
    } else {
      ok &= list.SetStringValue("hessian_constant", "yes");
    }
    return ok;
  });
}

void IpoptMcpSession::Impl::Solve(const MCP& p, const SolverOptions& options, const IpoptOptions& o,
                                  SolveResult* result) {
  problem_ = &p;
  o_ = &o;
  n_ = p.size();
  sparse_ = p.jacobian_kind() == MCP::JacobianKind::kSparse;
  target_ = options.tolerance;
  c_ = p.variable_scale().size() == n_ ? p.variable_scale() : Vector::Ones(n_);
  start_ = result->z;
  F_.resize(n_);
  z_.resize(n_);
  iter_F_.resize(n_);
  ref_F_.resize(n_);
  jacobian_error_.clear();
  iterations_ = 0;
  objective_ = kNaN;
  stop_ = kNotStopped;
  have_last_x_ = have_ipopt_x_ = false;
  early_ipopt_residual_ = kInf;
  early_refined_residual_ = kNaN;
  tried_state_.clear();
  result->iterations = 0;
  kIpoptMcpHessianDetail.Set(result, o.mcp_hessian);

  // F and J at the start: a failure there is a status before Ipopt runs.
  int bad = -1;
  if (!EvaluateF(start_, &F_, &bad)) {
    std::ostringstream msg;
    msg << "F is NaN or Inf at the starting point: F[" << bad << "] = " << F_[bad];
    result->status = SolveStatus::kNumericalFailure;
    result->message = msg.str();
    return;
  }
  if (!EvaluateJ(start_)) {
    result->status = SolveStatus::kNumericalFailure;
    result->message = jacobian_error_;
    return;
  }
  RowScales(&d_);
  if (!d_.allFinite()) {
    result->status = SolveStatus::kNumericalFailure;
    result->message = "the MCP Jacobian has a NaN or Inf entry at the starting point";
    return;
  }
  const double at_start = McpScaledResidual(start_, F_, p.l(), p.u(), d_, p.variable_scale());
  if (at_start <= target_) {
    result->status = SolveStatus::kSolved;
    kIpoptMcpEarlyStopDetail.Set(result, IpoptMcpEarlyStop::kSolvedAtStart);
    return;
  }
  if (o.polish && o.polish_warm_start && o.mcp_newton_steps > 0 && options.warm_start.size() == n_) {
    const double refined = Refine(start_, &ref_best_);
    if (refined <= target_) {
      result->z = ref_best_;
      result->status = SolveStatus::kSolved;
      result->SetDetail("refined_residual", refined);
      kIpoptMcpEarlyStopDetail.Set(result, IpoptMcpEarlyStop::kRefinedWarmStart);
      return;
    }
    EvaluateJ(start_);  // the program's pattern is J's at the start
  }
  SetUpProgram();
  if (runner_ == nullptr) {
    runner_ = std::make_unique<IpoptRunner>();
    tnlp_ = new McpGapTnlp(this);
  }
  callback_error_ = nullptr;
  const Ipopt::ApplicationReturnStatus status = RunIpopt(options, o);
  if (callback_error_) std::rethrow_exception(std::exchange(callback_error_, nullptr));
  result->SetDetail("ipopt_status", static_cast<double>(status));
  result->iterations = iterations_;
  result->SetDetail("objective", objective_);

  // Ipopt's point: the iterate that met the measure or fed a successful refinement, else its final x.
  double ipopt_residual = kNaN, refined_residual = kNaN;
  bool accepted = false;
  if (stop_ == kStopRefined) {
    ipopt_residual = early_ipopt_residual_;
    result->z = early_z_;
    refined_residual = early_refined_residual_;
    accepted = true;
    kIpoptMcpEarlyStopDetail.Set(result, IpoptMcpEarlyStop::kRefinedIterate);
  } else {
    if (stop_ == kStopMerit) kIpoptMcpEarlyStopDetail.Set(result, IpoptMcpEarlyStop::kMeritAtIterate);
    bool have = true;
    if (stop_ == kStopMerit) {
      result->z = early_z_;
    } else if (have_ipopt_x_) {
      result->z = ipopt_x_;
    } else if (have_last_x_) {
      ToZ(last_x_.data(), &result->z);
    } else {
      have = false;  // Ipopt stopped before evaluating anything: keep the start
    }
    if (have) ipopt_residual = Merit(result->z, &iter_F_);
    if (o.polish && o.mcp_newton_steps > 0 && !(ipopt_residual <= kRefineMargin * target_) && !time_up_()) {
      refined_residual = Refine(result->z, &ref_best_);
      if (refined_residual < ipopt_residual || (std::isnan(ipopt_residual) && refined_residual < kInf)) {
        accepted = true;
        result->z = ref_best_;
      }
    }
  }
  result->SetDetail("ipopt_residual", ipopt_residual);
  if (o.polish) {
    result->SetDetail("refined_residual", refined_residual);
    result->SetDetail("refine_accepted", accepted ? 1.0 : 0.0);
  }
  const double final_residual = accepted ? refined_residual : ipopt_residual;
  if (options.verbosity > 0) {
    std::fprintf(stderr, "ipopt (MCP): Ipopt %s (%d) after %d iterations, scaled residual %.3e, refined %.3e%s\n",
                 IpoptStatusName(status), static_cast<int>(status), iterations_, ipopt_residual, refined_residual,
                 accepted ? " (kept)" : "");
  }
  if (final_residual <= target_) {
    result->status = SolveStatus::kSolved;
    return;
  }
  ExplainFailure(status, ipopt_residual, refined_residual, result);
}

void IpoptMcpSession::Impl::ExplainFailure(Ipopt::ApplicationReturnStatus status, double ipopt_residual,
                                           double refined_residual, SolveResult* result) {
  std::ostringstream msg;
  msg.precision(3);
  if (!jacobian_error_.empty()) {
    result->status = SolveStatus::kNumericalFailure;
    msg << jacobian_error_;
  } else {
    switch (status) {
      case Ipopt::Solve_Succeeded:
      case Ipopt::Solved_To_Acceptable_Level:
      case Ipopt::Feasible_Point_Found:
        if (objective_ > target_) {
          result->status = SolveStatus::kStalled;
          msg << "Ipopt converged to a stationary point of the gap program with complementarity gap G = "
              << objective_ << " > 0 (a local minimizer, not a solution of the MCP)";
        } else {
          result->status = SolveStatus::kInaccurate;
          msg << "Ipopt converged (" << IpoptStatusName(status) << ") but not to the requested accuracy";
        }
        break;
      case Ipopt::Infeasible_Problem_Detected:
        result->status = SolveStatus::kNumericalFailure;
        msg << "Ipopt found F(z) = w - v, z in [l,u], w, v >= 0 locally infeasible: for a nonlinear F not a proof "
               "that the MCP has no solution";
        break;
      case Ipopt::Diverging_Iterates:
        result->status = SolveStatus::kDiverged;
        msg << "Ipopt's iterates diverged";
        break;
      case Ipopt::Invalid_Number_Detected:
        result->status = SolveStatus::kNumericalFailure;
        msg << "NaN or Inf in F or its Jacobian during Ipopt's iterations";
        break;
      default:  // what any program's Ipopt run would mean
        result->status = IpoptFailureStatus(status, o_->linear_solver, stop_ == kStopTime, msg);
        break;
    }
  }
  msg << "; Ipopt status " << static_cast<int>(status) << ", " << iterations_
      << " iterations, scaled residual " << ipopt_residual;
  if (o_->polish) msg << " (refined " << refined_residual << ")";
  msg << " > tolerance " << target_;
  result->message = msg.str();
}

IpoptMcpSession::IpoptMcpSession(std::function<bool()> time_up)
    : impl_(std::make_unique<Impl>(std::move(time_up))) {}
IpoptMcpSession::~IpoptMcpSession() = default;

void IpoptMcpSession::Solve(const MCP& problem, const SolverOptions& options, const IpoptOptions& ipopt,
                            SolveResult* result) {
  impl_->Solve(problem, options, ipopt, result);
}

}  // namespace smcbench

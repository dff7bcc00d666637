// Ipopt backend for the box-MLCP: find z in [l,u], w, v >= 0 with M z + q = w - v, (z-l)'w = 0, (u-z)'v = 0.
// Ipopt (Wächter & Biegler 2006, Math. Prog. 106:25-57) is a primal-dual interior-point filter line-search
// method; we give it exact first and second derivatives through its C++ TNLP interface.
//
// The problem arrives row-equilibrated (Solver's base divides row i of M and q by d_i = max_j |M_ij|), so a
// symmetric M reaches this backend as D^-1 M, which is not symmetric. It is symmetrizable: diag(e) D^-1 M is
// symmetric for e = c d. Classify recovers such weights e > 0 from the matrix alone (a maximum spanning tree of
// the entries, e_j = e_i M_ij / M_ji along it, each connected block normalized to max e = 1, then every entry
// checked) and poses the QP below with S = diag(e) M, r = diag(e) q: scaling row i of the MLCP by e_i leaves its
// solutions unchanged. So a symmetric problem keeps the convex QP whatever its row scaling, including rows
// scaled by the user (R M with M symmetric is symmetrizable as well).
//
// Formulation 1 — convex QP (S = diag(e) M symmetric positive semidefinite; detail formulation = 1):
//     min 1/2 z'Sz + r'z   s.t.  l <= z <= u.
//   With bound multipliers w (lower) and v (upper) its KKT conditions are S z + r = w - v, w, v >= 0,
//   (z-l)'w = 0, (u-z)'v = 0: the box-MLCP with row i scaled by e_i > 0. For PSD S a KKT point is a global
//   minimizer, so the MLCP has a solution iff the QP has a minimizer; Ipopt's "diverging iterates" then means the
//   QP looks unbounded below (not a certificate: the status is kDiverged, never kInfeasible).
//   Hessian = (S + S')/2 (constant; lower triangle, exact zeros of a dense M dropped from the structure).
//   With formulation = kQp the same QP is used for symmetrizable indefinite M (detail formulation = 3): every
//   KKT point of it, which is what Ipopt converges to, still solves the MLCP.
//   Symmetry: |S_ij - S_ji| <= symmetry_tolerance * max|S|. PSD: Cholesky of (S+S')/2 + delta I succeeds with
//   delta = psd_tolerance * ||S||_inf, i.e. lambda_min > -delta (both tests from solvers/core/matrix_class.h).
//   The test is cached for repeated solves with the same M (compared entry by entry, O(nnz), against the O(n^3)
//   factorization).
//
// Formulation 2 — complementarity-gap NLP (any other M; detail formulation = 2):
//     variables  z (n), w_i for rows with finite l_i < u_i, v_i for rows with finite u_i > l_i,
//                y_i for rows with l_i = u_i (a free multiplier);  multipliers on infinite bounds are fixed
//                to zero, i.e. not created.
//     min  G = sum_i (z_i - l_i) w_i + sum_i (u_i - z_i) v_i      (finite bounds only)
//     s.t. M z + q - w + v - y = 0,   l <= z <= u,   w, v >= 0.
//   G >= 0 on the feasible set, and G = 0 exactly at solutions of the MLCP. This is a nonconvex bilinear
//   program; since the constraints are linear the Hessian of the Lagrangian is that of G, constant, with
//   entries +1 (w_i, z_i) and -1 (v_i, z_i). A stationary point with G > 0 is a failure (kStalled, "complementarity
//   gap G > 0"). For an LCP with row-sufficient M (P-matrices included) every KKT point of
//   min z'(Mz+q) s.t. z, Mz+q >= 0 solves the LCP (Cottle, Pang & Stone 1992, §3.5), so for those problems a
//   stationary point is a solution. If Ipopt reports the (linear) constraints infeasible, the MLCP has no
//   solution only if a Farkas certificate from Ipopt's final point holds with a margin (CertifyInfeasible):
//   Ipopt's own test is in floating point, and a claim of no solution is a verdict like "solved".
//
// Residual: the base's verdict on the (equilibrated) problem: its natural residual r, in units of z, relative to
// 1 + min(||z||_inf, ||q||_inf), so that r <= tol means both r <= tol (1 + ||z||) (Residual::scaled) and
// r <= tol (1 + ||q||) (Residual::rel, which keeps a runaway z from passing); it decides when Ipopt is stopped
// early and whether a point is a solution.
//
// Polish (after OSQP's solution polishing, Stellato et al. 2020, Math. Prog. Comp. 12, §4): interior-point
// iterates are accurate only to about Ipopt's tolerance, while our merit function asks for 1e-10.
//   1. Active set from the natural map at z, w = Mz+q, p = z - w: i in L if p_i <= l_i (or l_i = u_i),
//      i in U if p_i >= u_i, else i in F.
//   2. z_L = l_L, z_U = u_U, and z_F solves M_FF z_F = -(q + M_{F,L+U} z_{L+U}), computed as a correction
//      M_FF d = -(Mz+q)_F from the snapped point plus one step of iterative refinement. M_FF is gathered and
//      factored by the active-set kernel's RobustFreeBlock: dense, partial-pivoting LU, or the minimum-norm
//      complete orthogonal decomposition when M_FF is numerically singular (PSD singular M: any solution of the
//      consistent system will do, the nearest stays inside the box best); sparse, SparseLU, falling back to
//      SparseQR.
//   3. Verify: the natural residual at the polished point is zero iff l_F <= z_F <= u_F, w_L >= 0, w_U <= 0.
//      If not, re-identify the active set at the polished point and repeat (polish_rounds times at most).
//   The polished z is kept only if its natural residual is smaller than that of Ipopt's z; both are reported.
//   With early_polish the same step is tried at Ipopt iterates whose residual is below early_polish_threshold
//   and whose active set changed since the last try; Ipopt is stopped as soon as a polished point is a
//   solution. Independently, Ipopt is stopped once an iterate itself meets the merit function.
//
// Status: solved iff the merit function holds at the returned z (whatever Ipopt said; detail ipopt_status keeps
// Ipopt's raw ApplicationReturnStatus). Otherwise Ipopt's status is mapped: iteration limit -> kIterationLimit,
// infeasible -> kInfeasible with a checked certificate (else kNumericalFailure), restoration failure / step
// computation error / invalid number -> kNumericalFailure, CPU or wall time -> kTimeLimit, diverging -> kDiverged,
// tiny step -> kStalled, converged with G > 0 -> kStalled, converged otherwise -> kInaccurate, invalid option ->
// kInvalidOptions.
//
// Details: the codes formulation and early_stop (ipopt_details.h), symmetric_psd (1/0: S above), ipopt_status
// (Ipopt's own return code), ipopt_residual and polished_residual (the residual above, NaN if not computed),
// polish_accepted (1/0), objective (QP objective or gap G at Ipopt's point).
//
// Allocation: Ipopt allocates internally on every solve (accepted for this backend); our own buffers are
// members reused across solves, resized only when sizes change.
#include "solvers/ipopt/ipopt_qp_solver.h"

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <queue>
#include <sstream>
#include <vector>

#include <Eigen/Cholesky>

#include <IpIpoptApplication.hpp>
#include <IpTNLP.hpp>

#include "solvers/core/active_set.h"
#include "solvers/core/matrix_class.h"
#include "solvers/ipopt/gap_program.h"
#include "solvers/ipopt/ipopt_details.h"
#include "solvers/ipopt/ipopt_names.h"
#include "solvers/ipopt/ipopt_runner.h"

namespace smcbench {
namespace {

using Ipopt::Index;
using Ipopt::Number;
using ConstMap = Eigen::Map<const Vector>;
using MutMap = Eigen::Map<Vector>;

// Beyond Ipopt's default nlp_lower/upper_bound_inf (-+1e19): "no bound".
constexpr double kIpoptInf = 2e19;

double IpoptBound(double b) { return std::isfinite(b) ? b : (b > 0 ? kIpoptInf : -kIpoptInf); }

enum StopReason { kNotStopped, kStopMerit, kStopPolished, kStopTime };

// True if dlopen finds the library (then closed again): Ipopt's run-time loaded linear solvers.
bool RuntimeLibraryLoadable(const char* name) {
  void* handle = ::dlopen(name, RTLD_LAZY | RTLD_LOCAL);
  if (!handle) return false;
  ::dlclose(handle);
  return true;
}

// y = M x for dense or sparse M; x, y may be Eigen maps over Ipopt's arrays.
template <typename In, typename Out>
void MultiplyM(const BoxMLCP& p, const In& x, Out& y) {
  if (p.is_sparse()) {
    y.noalias() = p.sparse_matrix() * x;
  } else {
    y.noalias() = p.dense_matrix() * x;
  }
}

template <typename In, typename Out>
void MultiplyMt(const BoxMLCP& p, const In& x, Out& y) {
  if (p.is_sparse()) {
    y.noalias() = p.sparse_matrix().transpose() * x;
  } else {
    y.noalias() = p.dense_matrix().transpose() * x;
  }
}

class QpTnlp;
class GapTnlp;

// Everything one IpoptQpSolver owns: the Ipopt application, both TNLPs, the per-solve state they share, the
// matrix-class cache and the polish workspace. The TNLPs are thin adapters over this object.
class Session {
 public:
  Session();
  virtual ~Session() = default;
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  // The phases, in order: reset the per-solve state, accept the start (or its polish) if it already solves the
  // problem, choose and set up the formulation, run Ipopt, take its point (polished), and explain a failure.
  void Solve(const BoxMLCP& problem, const SolverOptions& options, const IpoptOptions& ipopt, SolveResult* result);

 private:
  void ResetForSolve(const BoxMLCP& p, const SolverOptions& options, const IpoptOptions& o, const Vector& start);
  bool SolvedAtStart(const SolverOptions& options, const IpoptOptions& o, SolveResult* result);
  // kConvexQp, kForcedQp or kGapNlp, with its TNLP set up; nullopt (result kNotApplicable) for qp on a
  // nonsymmetric M.
  std::optional<IpoptFormulation> ChooseFormulation(const BoxMLCP& p, const IpoptOptions& o, SolveResult* result);
  Ipopt::ApplicationReturnStatus RunIpopt(const SolverOptions& options, const IpoptOptions& o,
                                          IpoptFormulation formulation);
  // Ipopt's point, polished when that helps, into result->z; its residual, and the polish's.
  struct Answer {
    double ipopt_residual = kInf;
    double polished_residual = kNaN;
    bool accepted = false;  // the polished point replaced Ipopt's
  };
  Answer TakeIpoptPoint(const IpoptOptions& o, SolveResult* result);
  // Status and message of an answer above the tolerance: what Ipopt's status means for this problem.
  void ExplainFailure(const BoxMLCP& p, const IpoptOptions& o, Ipopt::ApplicationReturnStatus status, bool gap,
                      const Answer& answer, SolveResult* result);

 public:

  // Called by the TNLPs.
  bool OnIteration(Ipopt::AlgorithmMode mode, Index iter);
  void RecordGradientPoint(const Number* x, Index count);
  // x has `count` entries: z first (the QP's only variables), then the gap NLP's multipliers.
  void RecordSolution(const Number* x, Index count, Number objective);

  // Per-solve problem data, read by the TNLPs.
  const BoxMLCP* problem_ = nullptr;
  int n_ = 0;
  bool exact_symmetric_ = false;  // S = M exactly (weights all 1, M symmetric to the bit)
  Vector weights_;                // e: S = diag(e) M symmetric (Classify); all 1 for a symmetric M
  Vector weighted_q_;             // r = diag(e) q, per solve (the QP's linear term)
  Vector start_;    // starting z
  Vector product_;  // M x scratch for the TNLP evaluations
  Vector product_t_;
  // Lower triangle of the Hessian (QP: (M+M')/2; gap: the +-1 couplings), triplets.
  std::vector<Index> hess_row_, hess_col_;
  std::vector<Number> hess_val_;
  // Gap NLP: its multipliers (gap_program.h); Jacobian triplets of the rows.
  GapMultipliers mult_;
  std::vector<Index> jac_row_, jac_col_;
  std::vector<Number> jac_val_;

 protected:
  virtual bool TimeUp() const = 0;

 private:
  void Classify(const BoxMLCP& p, const IpoptOptions& o);
  // Weights e > 0 with diag(e) M symmetric, if the maximum-spanning-tree construction finds candidates (Classify
  // then checks every entry). False when some tree edge has entries of different signs.
  bool SymmetrizingWeights(const BoxMLCP& p);
  bool SameMatrixAsCache(const BoxMLCP& p) const;
  void SetupQp(const BoxMLCP& p);
  void SetupGap(const BoxMLCP& p);
  // Natural residual at z relative to 1 + min(||z||_inf, ||q||_inf) (file comment); *w receives M z + q.
  double RelResidual(const Vector& z, Vector* w) const;
  double Relative(double residual, const Vector& z) const {
    return residual / std::min(1.0 + z.cwiseAbs().maxCoeff(), problem_->residual_scale());
  }
  void ActiveSet(const Vector& z, const Vector& w, std::vector<signed char>* state) const;
  // Polish from z_in (see the file comment). Returns the smallest residual (RelResidual's) found and writes that
  // point to *z_out; returns +inf (z_out untouched) if no candidate could be computed.
  double Polish(const Vector& z_in, Vector* z_out);
  // After Infeasible_Problem_Detected on the gap NLP: a Farkas certificate for its linear constraints, checked
  // here with a margin (see the definition). False if none of the candidates holds.
  bool CertifyInfeasible(const BoxMLCP& p) const;
  bool FarkasCertificateHolds(const BoxMLCP& p, const Vector& y) const;

  // Ipopt.
  IpoptRunner runner_;
  QpTnlp* qp_ = nullptr;  // owned by qp_holder_
  GapTnlp* gap_ = nullptr;
  Ipopt::SmartPtr<Ipopt::TNLP> qp_holder_, gap_holder_;

  // Per-solve options and Ipopt outcome.
  const IpoptOptions* ipopt_options_ = nullptr;
  double target_ = 0.0;  // SolverOptions::tolerance
  Vector last_x_;        // x of the last gradient evaluation: the current iterate when the callback runs
  bool have_last_x_ = false;
  Vector ipopt_x_;       // Ipopt's final x (z part)
  Vector ipopt_full_x_;  // all of Ipopt's final x (gap NLP: z, then the multipliers)
  bool have_ipopt_x_ = false;
  double objective_ = kNaN;
  int iterations_ = 0;
  StopReason stop_ = kNotStopped;
  Vector iter_z_, iter_w_;   // the iterate examined in the callback
  Vector early_z_;           // point that met the merit function during the iterations
  Vector early_ipopt_z_;     // the Ipopt iterate it came from
  double early_ipopt_residual_ = kInf;
  double early_polished_residual_ = kNaN;

  // Matrix-class cache.
  bool cache_valid_ = false;
  bool cache_sparse_ = false;
  double cache_sym_tol_ = -1.0, cache_psd_tol_ = -1.0;
  DenseMatrix cached_dense_;
  SparseMatrix cached_sparse_;
  bool symmetric_ = false;
  bool psd_ = false;
  Eigen::LLT<DenseMatrix> llt_;  // storage of the PSD test's factorization, kept across matrices

  // Polish workspace.
  Vector pol_z_, pol_r_, pol_w_, pol_rhs_, pol_delta_, pol_best_;
  std::vector<signed char> state_, prev_state_, tried_state_;
  std::vector<int> free_idx_;
  RobustFreeBlock free_block_;  // M_FF's factors, with a least-squares fallback for a singular block
};

// What both formulations share: the Hessian's pattern and values from the session (hess_row_/col_/val_, set up by
// the formulation before the solve), the solution and the per-iteration callback handed back to the session.
class SessionTnlp : public Ipopt::TNLP {
 public:
  explicit SessionTnlp(Session* s) : s_(s) {}

  bool eval_h(Index, const Number*, bool, Number obj_factor, Index, const Number*, bool, Index nele, Index* row,
              Index* col, Number* values) override {
    if (values == nullptr) {
      std::copy(s_->hess_row_.begin(), s_->hess_row_.end(), row);
      std::copy(s_->hess_col_.begin(), s_->hess_col_.end(), col);
    } else {
      for (Index k = 0; k < nele; ++k) values[k] = obj_factor * s_->hess_val_[k];
    }
    return true;
  }

  void finalize_solution(Ipopt::SolverReturn, Index n, const Number* x, const Number*, const Number*, Index,
                         const Number*, const Number*, Number obj, const Ipopt::IpoptData*,
                         Ipopt::IpoptCalculatedQuantities*) override {
    s_->RecordSolution(x, n, obj);
  }

  bool intermediate_callback(Ipopt::AlgorithmMode mode, Index iter, Number, Number, Number, Number, Number, Number,
                             Number, Number, Index, const Ipopt::IpoptData*,
                             Ipopt::IpoptCalculatedQuantities*) override {
    return s_->OnIteration(mode, iter);
  }

 protected:
  Session* s_;
};

// Formulation 1: min 1/2 z'Mz + q'z on the box, no constraints.
class QpTnlp final : public SessionTnlp {
 public:
  explicit QpTnlp(Session* s) : SessionTnlp(s) {}

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag, IndexStyleEnum& style) override {
    n = s_->n_;
    m = 0;
    nnz_jac_g = 0;
    nnz_h_lag = static_cast<Index>(s_->hess_row_.size());
    style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index, Number*, Number*) override {
    const BoxMLCP& p = *s_->problem_;
    for (Index i = 0; i < n; ++i) {
      x_l[i] = IpoptBound(p.l()[i]);
      x_u[i] = IpoptBound(p.u()[i]);
    }
    return true;
  }

  bool get_starting_point(Index n, bool init_x, Number* x, bool init_z, Number* z_l, Number* z_u, Index,
                          bool, Number*) override {
    if (init_x) MutMap(x, n) = s_->start_;
    if (init_z) {
      std::fill(z_l, z_l + n, 1.0);
      std::fill(z_u, z_u + n, 1.0);
    }
    return true;
  }

  // x'Sx = x'((S+S')/2)x and S x = e .* (M x), so the objective needs only M.
  bool eval_f(Index n, const Number* x, bool, Number& f) override {
    const ConstMap xm(x, n);
    MultiplyM(*s_->problem_, xm, s_->product_);
    f = 0.5 * xm.dot(s_->weights_.cwiseProduct(s_->product_)) + xm.dot(s_->weighted_q_);
    return std::isfinite(f);
  }

  // (S + S')/2 x + r with S x = e .* (M x) and S' x = M' (e .* x).
  bool eval_grad_f(Index n, const Number* x, bool, Number* grad) override {
    const ConstMap xm(x, n);
    MutMap g(grad, n);
    MultiplyM(*s_->problem_, xm, g);
    if (!s_->exact_symmetric_) {
      s_->product_ = s_->weights_.cwiseProduct(xm);
      MultiplyMt(*s_->problem_, s_->product_, s_->product_t_);
      g = 0.5 * (s_->weights_.cwiseProduct(g) + s_->product_t_);
    }
    g += s_->weighted_q_;
    s_->RecordGradientPoint(x, n);
    return true;
  }

  bool eval_g(Index, const Number*, bool, Index, Number*) override { return true; }
  bool eval_jac_g(Index, const Number*, bool, Index, Index, Index*, Index*, Number*) override { return true; }
};

// Formulation 2: the complementarity-gap NLP in x = (z, multipliers).
class GapTnlp final : public SessionTnlp {
 public:
  explicit GapTnlp(Session* s) : SessionTnlp(s) {}

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag, IndexStyleEnum& style) override {
    n = s_->n_ + static_cast<Index>(s_->mult_.count());
    m = s_->n_;
    nnz_jac_g = static_cast<Index>(s_->jac_row_.size());
    nnz_h_lag = static_cast<Index>(s_->hess_row_.size());
    style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index, Number* x_l, Number* x_u, Index m, Number* g_l, Number* g_u) override {
    const BoxMLCP& p = *s_->problem_;
    for (Index i = 0; i < m; ++i) {
      x_l[i] = IpoptBound(p.l()[i]);
      x_u[i] = IpoptBound(p.u()[i]);
      g_l[i] = g_u[i] = -p.q()[i];
    }
    s_->mult_.Bounds(m, kIpoptInf, x_l, x_u);
    return true;
  }

  // z from the start; multipliers from the sign split of M z + q (Ipopt pushes them into the interior).
  bool get_starting_point(Index n, bool init_x, Number* x, bool init_z, Number* z_l, Number* z_u, Index m,
                          bool init_lambda, Number* lambda) override {
    if (init_x) {
      const BoxMLCP& p = *s_->problem_;
      MutMap(x, m) = s_->start_;
      p.Affine(s_->start_, &s_->product_);
      s_->mult_.Start([this](int i) { return s_->product_[i]; }, x + m);
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
    s_->RecordGradientPoint(x, nx);
    return true;
  }

  // g = M z - w + v - y (bounds -q).
  bool eval_g(Index, const Number* x, bool, Index m, Number* g) override {
    MutMap gm(g, m);
    MultiplyM(*s_->problem_, ConstMap(x, m), gm);
    s_->mult_.AddToConstraints(x, m, g);
    return true;
  }

  bool eval_jac_g(Index, const Number*, bool, Index, Index, Index* row, Index* col, Number* values) override {
    if (values == nullptr) {
      std::copy(s_->jac_row_.begin(), s_->jac_row_.end(), row);
      std::copy(s_->jac_col_.begin(), s_->jac_col_.end(), col);
    } else {
      std::copy(s_->jac_val_.begin(), s_->jac_val_.end(), values);
    }
    return true;
  }
};

Session::Session() {
  qp_ = new QpTnlp(this);
  qp_holder_ = qp_;
  gap_ = new GapTnlp(this);
  gap_holder_ = gap_;
}

void Session::RecordGradientPoint(const Number* x, Index count) {
  if (last_x_.size() != count) last_x_.resize(count);
  last_x_ = ConstMap(x, count);
  have_last_x_ = true;
}

void Session::RecordSolution(const Number* x, Index count, Number objective) {
  ipopt_full_x_ = ConstMap(x, count);
  ipopt_x_ = ConstMap(x, n_);
  have_ipopt_x_ = true;
  objective_ = objective;
}

double Session::RelResidual(const Vector& z, Vector* w) const {
  if (w->size() != z.size()) w->resize(z.size());  // Affine writes into a pre-sized vector
  problem_->Affine(z, w);
  return Relative(NaturalResidualNorm(z, *w, problem_->l(), problem_->u()), z);
}

bool Session::OnIteration(Ipopt::AlgorithmMode mode, Index iter) {
  iterations_ = std::max(iterations_, static_cast<int>(iter));
  if (TimeUp()) {
    stop_ = kStopTime;
    return false;
  }
  if (mode != Ipopt::RegularMode || !have_last_x_) return true;
  iter_z_ = last_x_.head(n_);
  const double res = RelResidual(iter_z_, &iter_w_);
  if (res <= target_) {
    early_z_ = iter_z_;
    early_ipopt_z_ = iter_z_;
    early_ipopt_residual_ = res;
    stop_ = kStopMerit;
    return false;
  }
  const IpoptOptions& o = *ipopt_options_;
  if (o.polish && o.early_polish && res <= o.early_polish_threshold) {
    ActiveSet(iter_z_, iter_w_, &state_);
    if (state_ != tried_state_) {
      tried_state_ = state_;
      const double polished = Polish(iter_z_, &early_z_);
      if (polished <= target_) {
        early_ipopt_z_ = iter_z_;
        early_ipopt_residual_ = res;
        early_polished_residual_ = polished;
        stop_ = kStopPolished;
        return false;
      }
    }
  }
  return true;
}

bool Session::SameMatrixAsCache(const BoxMLCP& p) const {
  if (!cache_valid_ || cache_sparse_ != p.is_sparse()) return false;
  if (!p.is_sparse()) {
    const DenseMatrix& M = p.dense_matrix();
    return cached_dense_.rows() == M.rows() && cached_dense_ == M;
  }
  const SparseMatrix& M = p.sparse_matrix();
  const SparseMatrix& C = cached_sparse_;
  if (C.rows() != M.rows() || C.nonZeros() != M.nonZeros()) return false;
  const int nnz = static_cast<int>(M.nonZeros());
  return std::equal(M.outerIndexPtr(), M.outerIndexPtr() + M.outerSize() + 1, C.outerIndexPtr()) &&
         std::equal(M.innerIndexPtr(), M.innerIndexPtr() + nnz, C.innerIndexPtr()) &&
         std::equal(M.valuePtr(), M.valuePtr() + nnz, C.valuePtr());
}

bool Session::SymmetrizingWeights(const BoxMLCP& p) {
  const int n = p.size();
  // Prim's maximum spanning tree on the edges {i, j} with M_ij and M_ji both nonzero, weighted by the smaller of
  // |M_ij|, |M_ji| (the problem is row-equilibrated, so entries are comparable): strong entries set the ratios,
  // and a tiny entry that may be rounding noise is only checked, never used. Lazy deletion in a heap.
  weights_.setZero(n);  // 0 = not reached yet
  Vector best = Vector::Zero(n);
  std::vector<int> component(n, -1);
  std::vector<double> component_max;
  struct Edge {
    double strength;
    int to, from;
    bool operator<(const Edge& other) const { return strength < other.strength; }
  };
  std::priority_queue<Edge> heap;
  const auto entry = [&p](int i, int j) {
    return p.is_sparse() ? p.sparse_matrix().coeff(i, j) : p.dense_matrix()(i, j);
  };
  const auto offer = [&](int i, int j) {  // edge from reached i to j
    if (j == i || weights_[j] != 0.0) return;
    const double a = entry(i, j), b = entry(j, i);
    const double strength = std::min(std::abs(a), std::abs(b));
    if (strength > best[j]) {
      best[j] = strength;
      heap.push({strength, j, i});
    }
  };
  const auto reach = [&](int i) {
    if (p.is_sparse()) {
      for (SparseMatrix::InnerIterator it(p.sparse_matrix(), i); it; ++it) offer(i, static_cast<int>(it.row()));
    } else {
      for (int j = 0; j < n; ++j) offer(i, j);
    }
  };
  for (int root = 0; root < n; ++root) {
    if (weights_[root] != 0.0) continue;
    const int id = static_cast<int>(component_max.size());
    weights_[root] = 1.0;
    component[root] = id;
    component_max.push_back(1.0);
    reach(root);
    while (!heap.empty()) {
      const Edge e = heap.top();
      heap.pop();
      if (weights_[e.to] != 0.0) continue;
      const double a = entry(e.from, e.to), b = entry(e.to, e.from);
      if ((a > 0.0) != (b > 0.0)) return false;  // e_i a = e_j b has no positive solution
      // e_from M(from, to) = e_to M(to, from).
      const double weight = weights_[e.from] * (a / b);
      if (!(weight > 0.0) || !std::isfinite(weight)) return false;
      weights_[e.to] = weight;
      component[e.to] = id;
      component_max[id] = std::max(component_max[id], weight);
      reach(e.to);
    }
  }
  for (int i = 0; i < n; ++i) weights_[i] /= component_max[component[i]];
  return true;
}

void Session::Classify(const BoxMLCP& p, const IpoptOptions& o) {
  if (cache_sym_tol_ == o.symmetry_tolerance && cache_psd_tol_ == o.psd_tolerance && SameMatrixAsCache(p)) return;
  const int n = p.size();
  // S = diag(e) M with e from SymmetrizingWeights, then the same symmetry test on S as on any matrix.
  const bool have_weights = SymmetrizingWeights(p);
  if (!have_weights) weights_.setOnes(n);
  const bool unweighted = (weights_.array() == 1.0).all();
  const SymmetryOptions symmetry{o.symmetry_tolerance};
  const SymmetryResult asymmetry = p.is_sparse() ? ClassifySymmetry(p.sparse_matrix(), symmetry, &weights_)
                                                 : ClassifySymmetry(p.dense_matrix(), symmetry, &weights_);
  exact_symmetric_ = have_weights && unweighted && asymmetry.max_asymmetry == 0.0;
  symmetric_ = have_weights && asymmetry.answer == MatrixClassAnswer::kYes;
  psd_ = false;
  if (symmetric_) {
    // (S + S')/2 + delta I by Cholesky, delta = psd_tolerance ||S||_inf, S = diag(e) M.
    if (!p.is_sparse()) {
      const DenseMatrix S = weights_.asDiagonal() * p.dense_matrix();
      psd_ = ClassifySymmetricPartPositiveSemidefinite(S, o.psd_tolerance, &llt_).answer == MatrixClassAnswer::kYes;
    } else {
      const SparseMatrix W = weights_.asDiagonal() * p.sparse_matrix();
      psd_ = ClassifySymmetricPartPositiveSemidefinite(W, o.psd_tolerance).answer == MatrixClassAnswer::kYes;
    }
  }
  cache_sparse_ = p.is_sparse();
  if (cache_sparse_) {
    cached_sparse_ = p.sparse_matrix();
  } else {
    cached_dense_ = p.dense_matrix();
  }
  cache_sym_tol_ = o.symmetry_tolerance;
  cache_psd_tol_ = o.psd_tolerance;
  cache_valid_ = true;
}

void Session::SetupQp(const BoxMLCP& p) {
  hess_row_.clear();
  hess_col_.clear();
  hess_val_.clear();
  const int n = p.size();
  if (!p.is_sparse()) {
    const DenseMatrix& M = p.dense_matrix();
    for (int j = 0; j < n; ++j) {
      for (int i = j; i < n; ++i) {
        const double value = exact_symmetric_ ? M(i, j) : 0.5 * (weights_[i] * M(i, j) + weights_[j] * M(j, i));
        if (value == 0.0) continue;
        hess_row_.push_back(i);
        hess_col_.push_back(j);
        hess_val_.push_back(value);
      }
    }
    return;
  }
  const SparseMatrix& M = p.sparse_matrix();
  const auto add_lower = [&](const SparseMatrix& S) {
    for (int j = 0; j < S.outerSize(); ++j) {
      for (SparseMatrix::InnerIterator it(S, j); it; ++it) {
        if (it.row() < j || it.value() == 0.0) continue;
        hess_row_.push_back(static_cast<Index>(it.row()));
        hess_col_.push_back(j);
        hess_val_.push_back(it.value());
      }
    }
  };
  if (exact_symmetric_) {
    add_lower(M);
  } else {
    const SparseMatrix W = weights_.asDiagonal() * M;
    add_lower(SparseMatrix(0.5 * (W + SparseMatrix(W.transpose()))));
  }
}

void Session::SetupGap(const BoxMLCP& p) {
  const int n = p.size();
  mult_.Build(p.l(), p.u(), nullptr);
  jac_row_.clear();
  jac_col_.clear();
  jac_val_.clear();
  const auto add = [&](Index row, Index col, double value) {
    jac_row_.push_back(row);
    jac_col_.push_back(col);
    jac_val_.push_back(value);
  };
  if (!p.is_sparse()) {
    const DenseMatrix& M = p.dense_matrix();
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        if (M(i, j) != 0.0) add(i, j, M(i, j));
      }
    }
  } else {
    const SparseMatrix& M = p.sparse_matrix();
    for (int j = 0; j < M.outerSize(); ++j) {
      for (SparseMatrix::InnerIterator it(M, j); it; ++it) {
        if (it.value() != 0.0) add(static_cast<Index>(it.row()), j, it.value());
      }
    }
  }
  hess_row_.clear();
  hess_col_.clear();
  hess_val_.clear();
  for (int k = 0; k < mult_.count(); ++k) {
    add(mult_.row[k], n + k, mult_.ConstraintEntry(k));
    if (mult_.kind[k] == kFixedMult) continue;
    hess_row_.push_back(n + k);  // row n + k > column i: the lower triangle
    hess_col_.push_back(mult_.row[k]);
    hess_val_.push_back(mult_.HessianEntry(k));
  }
}

void Session::ActiveSet(const Vector& z, const Vector& w, std::vector<signed char>* state) const {
  const Vector& l = problem_->l();
  const Vector& u = problem_->u();
  state->resize(n_);
  for (int i = 0; i < n_; ++i) {
    const RowState s = l[i] == u[i] ? RowState::kFixed : ClassifyRow(z[i], w[i], l[i], u[i]);
    (*state)[i] = static_cast<signed char>(s);
  }
}

double Session::Polish(const Vector& z_in, Vector* z_out) {
  const Vector& l = problem_->l();
  const Vector& u = problem_->u();
  const int rounds = ipopt_options_->polish_rounds;
  pol_z_ = z_in;
  problem_->Affine(pol_z_, &pol_w_);
  double best = kInf;
  for (int round = 0; round < rounds; ++round) {
    ActiveSet(pol_z_, pol_w_, &state_);
    if (round > 0 && state_ == prev_state_) break;  // the same active set gives the same point
    prev_state_ = state_;
    free_idx_.clear();
    for (int i = 0; i < n_; ++i) {
      const auto s = static_cast<RowState>(state_[i]);
      if (s == RowState::kFree) {
        free_idx_.push_back(i);  // keeps its value: the solve below is a correction from the snapped point
      } else {
        pol_z_[i] = PlacedValue(s, l[i], u[i]);
      }
    }
    problem_->Affine(pol_z_, &pol_r_);
    const int k = static_cast<int>(free_idx_.size());
    if (k > 0) {
      if (!free_block_.Factor(*problem_, free_idx_.data(), k)) break;
      if (pol_rhs_.size() != k) pol_rhs_.resize(k);
      if (pol_delta_.size() != k) pol_delta_.resize(k);
      bool finite = true;
      // Correction from the snapped point, then one step of iterative refinement with the same factors.
      for (int step = 0; step < 2 && finite; ++step) {
        for (int a = 0; a < k; ++a) pol_rhs_[a] = -pol_r_[free_idx_[a]];
        free_block_.Solve(pol_rhs_, &pol_delta_);
        finite = pol_delta_.allFinite();
        if (!finite) break;
        for (int a = 0; a < k; ++a) pol_z_[free_idx_[a]] += pol_delta_[a];
        problem_->Affine(pol_z_, &pol_r_);
      }
      if (!finite) break;
    }
    const double res = Relative(NaturalResidualNorm(pol_z_, pol_r_, l, u), pol_z_);
    if (res < best) {
      best = res;
      *z_out = pol_z_;
    }
    if (res <= target_) break;
    pol_w_ = pol_r_;
  }
  return best;
}

// The gap NLP's constraints c(x) = M z + q - w + v - y = 0 over the bounds (z in [l, u], w, v >= 0, y free) have
// no solution if some vector g has g'c(x) > 0 for every x within the bounds: then c(x) = 0 is impossible, so the
// MLCP has no solution. The infimum of g'c(x) is finite only if g_i <= 0 on rows with a lower multiplier w only,
// g_i >= 0 on rows with an upper one v only, g_i = 0 on rows with both or with a fixed-row y; then it is
// g'q + sum_j min over z_j in [l_j, u_j] of (M'g)_j z_j (infinite when (M'g)_j pushes z_j to an infinite bound).
// It must exceed 1e3 n eps times the sum of the magnitudes that make it up, a margin for rounding. Candidates:
// c at Ipopt's final (least-infeasible) point, which is such a g for the least-squares infeasibility measure
// (g'c(x) >= |c|^2 for every x in the bounds), and its sign vector (for Ipopt's l1 measure); each is first made
// to satisfy the sign conditions (a vector that then works is a certificate whatever it came from).
bool Session::FarkasCertificateHolds(const BoxMLCP& p, const Vector& y) const {
  const int n = p.size();
  Vector g = y;
  for (int i = 0; i < n; ++i) {
    const double l = p.l()[i], u = p.u()[i];
    const bool lower = std::isfinite(l), upper = std::isfinite(u);
    if (l == u || (lower && upper)) {
      g[i] = 0.0;
    } else if (lower) {
      g[i] = std::min(g[i], 0.0);
    } else if (upper) {
      g[i] = std::max(g[i], 0.0);
    }
  }
  Vector mt_g(n);
  MultiplyMt(p, g, mt_g);
  double value = g.dot(p.q()), size = g.cwiseAbs().dot(p.q().cwiseAbs());
  Vector vertex(n);
  for (int j = 0; j < n; ++j) {
    const double c = mt_g[j];
    vertex[j] = c > 0.0 ? p.l()[j] : (c < 0.0 ? p.u()[j] : 0.0);
    if (c != 0.0 && !std::isfinite(vertex[j])) return false;
    value += c * vertex[j];
  }
  Vector m_vertex(n);
  const Vector abs_vertex = vertex.cwiseAbs();
  if (p.is_sparse()) {
    m_vertex.noalias() = p.sparse_matrix().cwiseAbs() * abs_vertex;
  } else {
    m_vertex.noalias() = p.dense_matrix().cwiseAbs() * abs_vertex;
  }
  size += g.cwiseAbs().dot(m_vertex);
  return value > 1e3 * n * std::numeric_limits<double>::epsilon() * size && size > 0.0;
}

bool Session::CertifyInfeasible(const BoxMLCP& p) const {
  if (!have_ipopt_x_ || ipopt_full_x_.size() != n_ + mult_.count() || !ipopt_full_x_.allFinite()) return false;
  Vector c(n_);
  MultiplyM(p, ipopt_full_x_.head(n_), c);
  c += p.q();
  mult_.AddToConstraints(ipopt_full_x_.data(), n_, c.data());
  const Vector sign = c.array().sign().matrix();
  return FarkasCertificateHolds(p, c) || FarkasCertificateHolds(p, sign);
}

void Session::ResetForSolve(const BoxMLCP& p, const SolverOptions& options, const IpoptOptions& o,
                            const Vector& start) {
  problem_ = &p;
  n_ = p.size();
  ipopt_options_ = &o;
  target_ = options.tolerance;
  stop_ = kNotStopped;
  have_last_x_ = have_ipopt_x_ = false;
  objective_ = kNaN;
  iterations_ = 0;
  early_ipopt_residual_ = kInf;
  early_polished_residual_ = kNaN;
  tried_state_.clear();
  if (product_.size() != n_) product_.resize(n_);
  if (product_t_.size() != n_) product_t_.resize(n_);
  start_ = start;
}

// The starting point may already be a solution (re-solve from a previous result, or all rows fixed), or its polish.
bool Session::SolvedAtStart(const SolverOptions& options, const IpoptOptions& o, SolveResult* result) {
  const double start_residual = RelResidual(start_, &iter_w_);
  if (start_residual <= target_) {
    result->status = SolveStatus::kSolved;
    kIpoptFormulationDetail.Set(result, IpoptFormulation::kNone);
    return true;
  }
  if (o.polish && o.polish_warm_start && options.warm_start.size() == n_) {
    const double polished = Polish(start_, &pol_best_);
    if (polished <= target_) {
      result->z = pol_best_;
      result->status = SolveStatus::kSolved;
      kIpoptFormulationDetail.Set(result, IpoptFormulation::kNone);
      result->SetDetail("polished_residual", polished);
      result->SetDetail("polish_accepted", 1.0);
      kIpoptEarlyStopDetail.Set(result, IpoptEarlyStop::kWarmPolish);
      return true;
    }
  }
  return false;
}

std::optional<IpoptFormulation> Session::ChooseFormulation(const BoxMLCP& p, const IpoptOptions& o, SolveResult* result) {
  Classify(p, o);
  IpoptFormulation formulation;
  if (o.formulation == IpoptOptions::kGap) {
    formulation = IpoptFormulation::kGapNlp;
  } else if (o.formulation == IpoptOptions::kQp) {
    if (!symmetric_) {
      result->status = SolveStatus::kNotApplicable;
      result->message =
          "formulation=qp needs a symmetric M, up to a positive row scaling (the QP's KKT system uses (S+S')/2)";
      return std::nullopt;
    }
    formulation = psd_ ? IpoptFormulation::kConvexQp : IpoptFormulation::kForcedQp;
  } else {
    formulation = (symmetric_ && psd_) ? IpoptFormulation::kConvexQp : IpoptFormulation::kGapNlp;
  }
  kIpoptFormulationDetail.Set(result, formulation);
  result->SetDetail("symmetric_psd", (symmetric_ && psd_) ? 1.0 : 0.0);
  if (formulation == IpoptFormulation::kGapNlp) {
    SetupGap(p);
  } else {
    SetupQp(p);
    weighted_q_ = weights_.cwiseProduct(p.q());
  }
  return formulation;
}

// Ipopt never throws through here: its exceptions become statuses.
Ipopt::ApplicationReturnStatus Session::RunIpopt(const SolverOptions& options, const IpoptOptions& o,
                                                 IpoptFormulation formulation) {
  const bool convex_qp = formulation == IpoptFormulation::kConvexQp;
  return runner_.Run(formulation == IpoptFormulation::kGapNlp ? gap_holder_ : qp_holder_, options, o,
                     [&o, convex_qp](Ipopt::OptionsList& list) {
                       bool ok = true;
                       // mehrotra_algorithm chooses its own mu strategy; Ipopt asks not to set it as well.
                       if (convex_qp && o.mehrotra) {
                         ok &= list.SetStringValue("mehrotra_algorithm", "yes");
                       } else {
                         ok &= list.SetStringValue("mu_strategy",
                                                   o.mu_strategy == IpoptOptions::kAdaptive ? "adaptive" : "monotone");
                       }
                       // Both formulations have a constant Hessian and linear (or no) constraints.
                       ok &= list.SetStringValue("hessian_constant", "yes");
                       ok &= list.SetStringValue("jac_c_constant", "yes");
                       ok &= list.SetStringValue("jac_d_constant", "yes");
                       return ok;
                     });
}

Session::Answer Session::TakeIpoptPoint(const IpoptOptions& o, SolveResult* result) {
  // Ipopt's point: the iterate that met the merit function or fed a successful early polish, else its final x.
  Answer answer;
  const Vector* ipopt_z = nullptr;
  if (stop_ == kStopMerit || stop_ == kStopPolished) {
    ipopt_z = &early_ipopt_z_;
    answer.ipopt_residual = early_ipopt_residual_;
  } else if (have_ipopt_x_) {
    ipopt_z = &ipopt_x_;
  } else if (have_last_x_) {
    ipopt_x_ = last_x_.head(n_);
    ipopt_z = &ipopt_x_;
  }
  if (ipopt_z != nullptr && stop_ != kStopMerit && stop_ != kStopPolished) {
    answer.ipopt_residual = RelResidual(*ipopt_z, &iter_w_);
  }
  if (ipopt_z != nullptr) result->SetDetail("ipopt_residual", answer.ipopt_residual);
  // Ipopt's objective at its final point (finalize_solution runs on early stops too): QP value or gap G.
  result->SetDetail("objective", objective_);

  if (stop_ == kStopPolished) {
    answer.polished_residual = early_polished_residual_;
    answer.accepted = true;
    result->z = early_z_;
    kIpoptEarlyStopDetail.Set(result, IpoptEarlyStop::kEarlyPolish);
  } else if (ipopt_z != nullptr) {
    result->z = *ipopt_z;
    if (stop_ == kStopMerit) kIpoptEarlyStopDetail.Set(result, IpoptEarlyStop::kMeritAtIterate);
    if (o.polish && answer.ipopt_residual > target_) {
      answer.polished_residual = Polish(*ipopt_z, &pol_best_);
      if (answer.polished_residual < answer.ipopt_residual) {
        answer.accepted = true;
        result->z = pol_best_;
      }
    }
  }
  if (o.polish) {
    result->SetDetail("polished_residual", answer.polished_residual);
    result->SetDetail("polish_accepted", answer.accepted ? 1.0 : 0.0);
  }
  return answer;
}

void Session::Solve(const BoxMLCP& p, const SolverOptions& options, const IpoptOptions& o, SolveResult* result) {
  ResetForSolve(p, options, o, result->z);
  if (SolvedAtStart(options, o, result)) return;
  const std::optional<IpoptFormulation> formulation = ChooseFormulation(p, o, result);
  if (!formulation) return;
  const Ipopt::ApplicationReturnStatus status = RunIpopt(options, o, *formulation);
  result->SetDetail("ipopt_status", static_cast<double>(status));
  result->iterations = iterations_;
  const Answer answer = TakeIpoptPoint(o, result);
  if (options.verbosity > 0) {
    const std::string formulation_name(ToString(*formulation));
    std::fprintf(stderr, "ipopt: formulation %s, Ipopt %s (%d) after %d iterations, residual %.3e, polished %.3e%s\n",
                 formulation_name.c_str(), IpoptStatusName(status), static_cast<int>(status), iterations_,
                 answer.ipopt_residual, answer.polished_residual, answer.accepted ? " (kept)" : "");
  }
  const double final_residual = answer.accepted ? answer.polished_residual : answer.ipopt_residual;
  if (final_residual <= target_) {
    result->status = SolveStatus::kSolved;
    return;
  }
  ExplainFailure(p, o, status, *formulation == IpoptFormulation::kGapNlp, answer, result);
}

void Session::ExplainFailure(const BoxMLCP& p, const IpoptOptions& o, Ipopt::ApplicationReturnStatus status, bool gap,
                             const Answer& answer, SolveResult* result) {
  std::ostringstream msg;
  msg.precision(3);
  const double scaled_gap = objective_ / p.residual_scale();
  switch (status) {
    case Ipopt::Solve_Succeeded:
    case Ipopt::Solved_To_Acceptable_Level:
    case Ipopt::Feasible_Point_Found:
      if (gap && scaled_gap > target_) {
        result->status = SolveStatus::kStalled;
        msg << "Ipopt converged to a stationary point of the gap program with complementarity gap G = "
            << objective_ << " > 0 (a local minimizer of a nonconvex bilinear program, not a solution)";
      } else {
        result->status = SolveStatus::kInaccurate;
        msg << "Ipopt converged (" << IpoptStatusName(status) << ") but not to the requested accuracy";
      }
      break;
    case Ipopt::Infeasible_Problem_Detected:
      // A claim of no solution is a verdict too: only with a certificate checked here.
      if (gap && CertifyInfeasible(p)) {
        result->status = SolveStatus::kInfeasible;
        msg << "M z + q = w - v, l <= z <= u, w, v >= 0 has no solution: Ipopt's least-infeasible point gives a "
               "Farkas certificate, checked with a margin in the row-equilibrated problem";
      } else {
        result->status = SolveStatus::kNumericalFailure;
        msg << "Ipopt reported the constraints infeasible, but its point gives no Farkas certificate that holds "
               "with a margin: not a proof that the MLCP has no solution";
      }
      break;
    case Ipopt::Diverging_Iterates:
      result->status = SolveStatus::kDiverged;
      msg << (gap ? "Ipopt's iterates diverged"
                  : "Ipopt's iterates diverged: the QP looks unbounded below (for a PSD M an unbounded QP would "
                    "mean that the MLCP has no solution; diverging iterates are not a proof of it)");
      break;
    case Ipopt::Invalid_Number_Detected:
      result->status = SolveStatus::kNumericalFailure;
      msg << "NaN or Inf appeared in Ipopt's evaluations";
      break;
    default:  // what any program's Ipopt run would mean
      result->status = IpoptFailureStatus(status, o.linear_solver, stop_ == kStopTime, msg);
      break;
  }
  msg << "; Ipopt status " << static_cast<int>(status) << ", " << iterations_ << " iterations, relative natural "
      << "residual " << answer.ipopt_residual;
  if (o.polish) {
    msg << " (polished " << answer.polished_residual << (answer.accepted ? ", kept" : ", rejected") << ")";
  }
  msg << " > tolerance " << target_;
  result->message = msg.str();
}

}  // namespace

bool IpoptOptions::IsValid(std::string* why) const {
  std::ostringstream s;
  if (formulation < kAuto || formulation > kGap) {
    s << "formulation must be auto, qp or gap, got the code " << static_cast<int>(formulation);
  } else if (!(tol > 0.0) || !std::isfinite(tol)) {
    s << "tol must be a positive finite number, got " << tol;
  } else if (max_iter < 1) {
    s << "max_iter must be >= 1, got " << max_iter;
  } else if (mu_strategy != kMonotone && mu_strategy != kAdaptive) {
    s << "mu_strategy must be monotone or adaptive, got the code " << static_cast<int>(mu_strategy);
  } else if (linear_solver < kMumps || linear_solver > kPardiso) {
    s << "linear_solver must be mumps, ma27, ma57, ma77, ma86, ma97 or pardiso, got the code "
      << static_cast<int>(linear_solver);
  } else if (const char* library = linear_solver == kPardiso ? "libpardiso.so" : "libhsl.so";
             linear_solver != kMumps && !RuntimeLibraryLoadable(library)) {
    // Checked here, not left to Ipopt: Ipopt 3.11 loads these at run time and, for some of them (ma97), calls
    // exit() when the library is missing, which would end the whole program.
    s << "linear_solver " << LinearSolverName(linear_solver) << " needs " << library
      << ", which cannot be loaded here (Debian's Ipopt ships MUMPS only: use mumps)";
  } else if (print_level < 0 || print_level > 12) {
    s << "print_level must be in 0..12, got " << print_level;
  } else if (!(symmetry_tolerance >= 0.0) || !std::isfinite(symmetry_tolerance)) {
    s << "symmetry_tolerance must be a finite number >= 0, got " << symmetry_tolerance;
  } else if (!(psd_tolerance >= 0.0) || !std::isfinite(psd_tolerance)) {
    s << "psd_tolerance must be a finite number >= 0, got " << psd_tolerance;
  } else if (polish_rounds < 1 || polish_rounds > 100) {
    s << "polish_rounds must be in 1..100, got " << polish_rounds;
  } else if (!(early_polish_threshold > 0.0)) {
    s << "early_polish_threshold must be positive, got " << early_polish_threshold;
  } else if (mcp_hessian != kGapHessian && mcp_hessian != kLimitedMemory) {
    s << "mcp_hessian must be gap or limited-memory, got the code " << static_cast<int>(mcp_hessian);
  } else if (mcp_newton_steps < 0 || mcp_newton_steps > 1000) {
    s << "mcp_newton_steps must be in 0..1000, got " << mcp_newton_steps;
  }
  if (s.tellp() == 0) return true;
  if (why) *why = s.str();
  return false;
}

struct IpoptQpSolver::Impl final : Session {
  explicit Impl(const IpoptQpSolver* owner) : owner_(owner) {}
  bool TimeUp() const override { return owner_->Expired(); }
  const IpoptQpSolver* owner_;
};

IpoptQpSolver::IpoptQpSolver() : impl_(std::make_unique<Impl>(this)) {}
IpoptQpSolver::~IpoptQpSolver() = default;

const SolverInfo& IpoptQpSolver::info() const {
  static const SolverInfo kInfo{
      "ipopt",
      "Ipopt interior point on the convex QP (symmetric PSD M) or the complementarity-gap NLP, then active-set "
      "polish; nonlinear MCPs: the gap NLP with F's exact Jacobian, then a Newton refinement on the active set",
      "Wächter & Biegler, Math. Prog. 106 (2006) 25-57; polish after Stellato et al., OSQP (2020)",
      /*dense=*/true,
      /*sparse=*/true,
      /*symmetric_only=*/false,
      /*exact=*/false,
      /*mcp=*/true,
      /*default_size_limit=*/0,
      /*equilibrate=*/true,
      /*delegates=*/false,
      /*external=*/false,
      /*allocation_free=*/false,  // Ipopt's internals allocate on every solve
      /*solves_every_p_matrix=*/true,
      /*practical_size_limit=*/256};
  return kInfo;
}

void IpoptQpSolver::DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) {
  impl_->Solve(problem, options, options_, result);
}

void IpoptQpSolver::DoSolveMCP(const MCP& problem, const SolverOptions& options, SolveResult* result) {
  if (!mcp_) mcp_ = std::make_unique<IpoptMcpSession>([this] { return Expired(); });
  mcp_->Solve(problem, options, options_, result);
}

void IpoptQpSolver::BindOptions(OptionBinder* binder) {
  // The choice options were integer-coded: their old numbers are still read (the name lists after the choices).
  binder->Add("formulation", &options_.formulation,
              {{"auto", IpoptOptions::kAuto}, {"qp", IpoptOptions::kQp}, {"gap", IpoptOptions::kGap}},
              {"auto", "qp", "gap"}, "auto (QP if M symmetric PSD, else gap NLP), qp, gap");
  binder->Add("tol", &options_.tol, "Ipopt tol (scaled NLP error)");
  binder->Add("max_iter", &options_.max_iter, "Ipopt max_iter when max_iterations <= 0");
  binder->Add("mu_strategy", &options_.mu_strategy,
              {{"monotone", IpoptOptions::kMonotone}, {"adaptive", IpoptOptions::kAdaptive}},
              {"monotone", "adaptive"}, "Ipopt mu_strategy: monotone or adaptive");
  binder->Add("mehrotra", &options_.mehrotra, "Mehrotra predictor-corrector for the convex QP");
  binder->Add("linear_solver", &options_.linear_solver,
              {{"mumps", IpoptOptions::kMumps}, {"ma27", IpoptOptions::kMa27}, {"ma57", IpoptOptions::kMa57},
               {"ma77", IpoptOptions::kMa77}, {"ma86", IpoptOptions::kMa86}, {"ma97", IpoptOptions::kMa97},
               {"pardiso", IpoptOptions::kPardiso}},
              {"mumps", "ma27", "ma57", "ma77", "ma86", "ma97", "pardiso"},
              "Ipopt linear_solver: mumps (Debian's), or ma27/ma57/ma77/ma86/ma97 (libhsl.so), pardiso "
              "(libpardiso.so)");
  binder->Add("print_level", &options_.print_level, "Ipopt print_level (0..12) when verbosity >= 2");
  binder->Add("symmetry_tolerance", &options_.symmetry_tolerance, "relative asymmetry still called symmetric");
  binder->Add("psd_tolerance", &options_.psd_tolerance, "PSD if lambda_min > -psd_tolerance*||M||_inf");
  binder->Add("polish", &options_.polish, "active-set polish of Ipopt's solution");
  binder->Add("polish_rounds", &options_.polish_rounds, "active-set re-identifications in one polish");
  binder->Add("early_polish", &options_.early_polish, "try the polish at Ipopt iterates and stop when it solves");
  binder->Add("early_polish_threshold", &options_.early_polish_threshold,
              "relative residual below which iterates are polished");
  binder->Add("polish_warm_start", &options_.polish_warm_start, "polish the warm start before running Ipopt");
  binder->Add("mcp_hessian", &options_.mcp_hessian,
              {{"gap", IpoptOptions::kGapHessian}, {"limited-memory", IpoptOptions::kLimitedMemory}},
              {"gap", "limited-memory"},
              "MCP gap program: Hessian of the gap only (exact for affine F), or Ipopt's limited-memory quasi-Newton");
  binder->Add("mcp_newton_steps", &options_.mcp_newton_steps, "Newton steps of one MCP refinement (0: none)");
}

bool IpoptQpSolver::ValidateBackendOptions(std::string* why) const { return options_.IsValid(why); }

}  // namespace smcbench

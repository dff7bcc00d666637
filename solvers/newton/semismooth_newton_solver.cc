// Semismooth Newton method for box-MLCPs and nonlinear MCPs.
//
// Reformulation: Phi(z) = 0 with Billups' box Fischer–Burmeister function (fischer_burmeister.h; Billups 1995,
// Facchinei–Pang 2003 §9.4). Merit Psi = ½‖Phi‖², C¹ with ∇Psi = Hᵀ Phi for any H in ∂Phi.
// Iteration (De Luca–Facchinei–Kanzow 1996, Algorithm 3.1; Munson–Facchinei–Ferris–Fischer–Kanzow 2001):
//   H = Da + Db ∇F with the DFK element at kinks. Directions are tried in this order, each only if it passes
//   its descent test and then its Armijo (optionally Grippo–Lampariello–Lucidi non-monotone) line search:
//   1. Newton, H d = −Phi, with the DFK test ∇Psiᵀd ≤ −ρ‖d‖^p;
//   2. regularized Newton, (Da + Db(∇F + μI)) d = −Phi with μ = regularization·min(1, ‖Phi‖): the Newton step
//      of the proximal subproblem centred at z. It exists for monotone/P0 problems whose Newton matrix is
//      singular (non-isolated solutions) and keeps fast local convergence because μ → 0 with ‖Phi‖
//      (Levenberg–Marquardt-type choice; Yamashita–Fukushima 2001). On random monotone LCPs with rank-deficient
//      M it replaces the crawling gradient steps on which some of them otherwise fail;
//   3. the steepest-descent direction −∇Psi.
//   Stopping test: the natural residual the base class reports (never Psi). A box-MLCP arrives row-equilibrated
//   (Solver's base), and the test is the base's verdict on that problem: its residual r, in units of z, at most
//   tol·(1 + ‖z‖∞) (Residual::scaled) and tol·(1 + ‖q‖∞) (Residual::rel), i.e. r ≤ tol·(1 + min(‖z‖∞, ‖q‖∞)).
//   1 + ‖q‖∞ alone would let a problem with small M (W = O(h)) stop at errors of order tol/h in z, 1 + ‖z‖∞ alone
//   a runaway z. A nonlinear MCP stops on the base's own verdict: the scale-free residual McpScaledResidual (rows
//   divided by the row scales of ∇F at the iterate, variables in their units c) ≤ tol. ∇F at the iterate is what the
//   next Newton step needs anyway, so it is evaluated before the test and reused by the step: the test costs no
//   evaluation of F or ∇F except ∇F at the final point (and at its projection onto the box, when the iterate lies
//   outside). Newton therefore neither stops at a point the base would downgrade nor runs on past one it accepts.
// Units of an MCP: the FB function, its merit, the descent tests, the regularization and the proximal term all
//   depend on the scaling of F's rows and on the units of z, which a verdict must not. So a nonlinear MCP is solved
//   in y = z/c (c = MCP::variable_scale, default 1) as G(y) = D⁻¹F(c∘y), D = diag(d) the row scales of ∇F (in units
//   c) at the starting point: G's Jacobian D⁻¹∇F C has rows of largest entry 1 there, and every quantity above is
//   the same, up to rounding, for any positive scaling of F's rows and any change of units stated through c.
//   (The scale-free residual of the problem in y is the problem's own, so the stopping test is unchanged by it.)
// Safeguard (Billups 1995, ch. 3, "proximal perturbation"): Psi can have local minimizers that are not
// solutions. Billups' example F(x) = (x − 1)² − 1.01, x ≥ 0, from x = 0 ends at x ≈ 1 − √1.01 ≈ −0.005, a
// minimizer of Psi outside the box. When the line search fails or Psi stagnates, the solver solves the
// perturbed problem F(z) + λ(z − z̄) with z̄ the current point (for λ ≥ ‖∇F‖ the perturbed Jacobian is
// diagonally dominant with a nonnegative diagonal, where the FB method behaves well), takes its solution as
// the next z̄, and restarts the unperturbed method from there. This follows the proximal-point path
// z' ∈ z − (F(z') + N(z'))/λ instead of −∇Psi, so it walks out of merit-function basins. It is a simplified
// variant of Billups' strategy: λ starts at proximal_lambda·max(1, ‖∇F‖∞), is halved after each successful
// round and multiplied by 10 after a failed one; the number of rounds is bounded.
//
// Linear algebra. Dense: the rows with Db_i = 0 (to reduction_threshold relative to Da_i) are trivially
// active: their step is −Phi_i/Da_i, and the remaining rows R solve
//     (∇F_RR + diag(Da_R/Db_R) + (λ + μ)I) d_R = −Phi_R/Db_R − ∇F_RT d_T       (Da/Db ≥ 0 by the sign convention)
// which is exact when those Db_i are exactly 0 and an inexact Newton step of relative error ≤ threshold
// otherwise. Near a strictly complementary solution Db_i → 0 quadratically on the active rows, so the
// factorization only sees the rows that are inactive or degenerate; at a cold start z = 0 of an LCP every row
// with q_i > 0 drops out. The factorization cost is what limits dense speed (O(|R|³) against the O(n²) of the
// rest of an iteration), so this is where the time goes and where the reduction pays.
// For a symmetric M the reduced matrix is symmetric positive (semi)definite when M is, and Cholesky is tried
// first (half the flops). Both kernels are Eigen's blocked in-place routines run on a preallocated n×n buffer
// with a preallocated transposition array: Eigen's PartialPivLU/LLT objects would reallocate whenever |R|
// changes. (Eigen's level-3 kernels use a stack buffer up to 128 KiB and malloc beyond it, so reduced systems
// larger than about 300 do call malloc inside the factorization; none of that goes through operator new.)
// Sparse: the full H = Da + Db ∇F + shift on the fixed pattern of ∇F ∪ diag, factorized by UMFPACK through
// Eigen's UmfPackLU: analyzePattern once per pattern (kept across solves), factorize every iteration, no
// iterative refinement.
#include "solvers/newton/semismooth_newton_solver.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <vector>

#include "solvers/newton/fischer_burmeister.h"
#include "solvers/newton/newton_globalization.h"
#include "solvers/newton/newton_jacobian.h"

namespace smcbench {
namespace {

using newton::Exit;
using newton::IsHardFailure;
using newton::SufficientDescent;
constexpr int kMaxStagnationWindow = newton::MeritWindow::kMaxWindow;
static_assert(NewtonOptions::kMaxNonmonotoneMemory == newton::NonmonotoneReference::kMaxMemory,
              "the GLL memory's bound is the shared line search's");

// Symmetric to rounding (|a_ij − a_ji| ≤ 1e-13·(|a_ij| + |a_ji|)); exits at the first asymmetric pair, so a
// nonsymmetric matrix costs almost nothing. Block-wise so both triangles are read cache-friendly.
bool IsNumericallySymmetric(const DenseMatrix& M) {
  const Eigen::Index n = M.rows();
  constexpr Eigen::Index kBlock = 32;
  for (Eigen::Index jb = 0; jb < n; jb += kBlock) {
    for (Eigen::Index ib = jb; ib < n; ib += kBlock) {
      const Eigen::Index jend = std::min(jb + kBlock, n), iend = std::min(ib + kBlock, n);
      for (Eigen::Index j = jb; j < jend; ++j) {
        for (Eigen::Index i = std::max(ib, j + 1); i < iend; ++i) {
          const double a = M(i, j), b = M(j, i);
          if (!(std::abs(a - b) <= 1e-13 * (std::abs(a) + std::abs(b)))) return false;
        }
      }
    }
  }
  return true;
}

}  // namespace

bool NewtonOptions::IsValid(std::string* why) const {
  // Checked without building any string on the success path (this runs at every Solve()).
  const auto fail = [why](const auto&... parts) {
    if (why) {
      std::ostringstream s;
      (s << ... << parts);
      *why = s.str();
    }
    return false;
  };
  if (!newton::ValidArmijoRule(newton::ArmijoRule{armijo_sigma, backtrack_factor, max_backtracks}, why)) return false;
  if (nonmonotone_memory < 1 || nonmonotone_memory > kMaxNonmonotoneMemory)
    return fail("nonmonotone_memory must be in [1, ", kMaxNonmonotoneMemory, "], got ", nonmonotone_memory);
  if (mcp_nonmonotone_memory < 1 || mcp_nonmonotone_memory > kMaxNonmonotoneMemory)
    return fail("mcp_nonmonotone_memory must be in [1, ", kMaxNonmonotoneMemory, "], got ", mcp_nonmonotone_memory);
  if (mcp_stagnation_window < 1 || mcp_stagnation_window > kMaxStagnationWindow)
    return fail("mcp_stagnation_window must be in [1, ", kMaxStagnationWindow, "], got ", mcp_stagnation_window);
  if (!(mcp_proximal_lambda > 0.0) || !std::isfinite(mcp_proximal_lambda))
    return fail("mcp_proximal_lambda must be a positive finite number, got ", mcp_proximal_lambda);
  if (crash_steps < 0 || crash_steps > 1000) return fail("crash_steps must be in [0, 1000], got ", crash_steps);
  if (!newton::ValidDescentTest(descent_rho, descent_power, why)) return false;
  if (linear_solver < kAutoLinearSolver || linear_solver > kSparseLinearSolver)
    return fail("linear_solver must be auto, dense or sparse, got the code ", static_cast<int>(linear_solver));
  if (dense_max_size < 0) return fail("dense_max_size must be >= 0, got ", dense_max_size);
  if (!(reduction_threshold >= 0.0 && reduction_threshold <= 1e-2))
    return fail("reduction_threshold must be in [0, 1e-2], got ", reduction_threshold);
  if (!(regularization >= 0.0) || !std::isfinite(regularization))
    return fail("regularization must be a finite number >= 0, got ", regularization);
  if (max_proximal_rounds < 0) return fail("max_proximal_rounds must be >= 0, got ", max_proximal_rounds);
  if (!(proximal_lambda > 0.0) || !std::isfinite(proximal_lambda))
    return fail("proximal_lambda must be a positive finite number, got ", proximal_lambda);
  if (!newton::ValidStagnation(stagnation_window, stagnation_ratio, why)) return false;
  if (proximal_inner_iterations < 1)
    return fail("proximal_inner_iterations must be >= 1, got ", proximal_inner_iterations);
  return true;
}

// Everything a solve touches, sized once per problem size. Holds the problem view for the current solve.
// ∇F, its copies and the sparse system's pattern live in the shared JacobianStore (newton_jacobian.h).
struct SemismoothNewtonSolver::Workspace : newton::JacobianStore {
  // ---- Problem view (set per solve) ----
  const SemismoothNewtonSolver* owner = nullptr;
  const NewtonOptions* opt = nullptr;
  const BoxMLCP* lcp = nullptr;
  const MCP* mcp = nullptr;
  const Vector* l = nullptr;
  const Vector* u = nullptr;
  int n = 0;
  bool symmetric_jacobian = false;   // dense LCP with symmetric M: Cholesky on the reduced system
  double scale = 1.0;                // relative-residual scale: 1 + ‖q‖∞, or 1 + ‖F(Π(0))‖∞ for an MCP
  bool z_relative = false;           // box-MLCP: residuals relative to 1 + min(‖z‖∞, ‖q‖∞) (file comment)
  double tolerance = 1e-10;
  int verbosity = 0;
  int budget = 0;
  double lambda = 0.0;            // proximal perturbation F + λ(z − zbar); 0 = the original problem
  double shift = 0.0;             // λ + μ on the Jacobian's diagonal in the current linear system
  bool F_is_incremental = false;  // LCP: F was updated as F + t·M d and not yet recomputed

  // ---- Iterate and work vectors (size n) ----
  Vector z, F, Phi, Da, Db, g, d, Md, zt, Ft, v, w, e, Je, zbar, rhs;
  Vector row_scale;             // s_i: Phi_i uses s_i·F_i (see ComputeRowScaling)
  Vector jac_row_max;           // max_j |∂F_i/∂z_j| at the start (row equilibration of the dense LU)
  Vector row_eq;                // equilibration factors of the current reduced rows
  newton::BestIterate best;     // by the stopping measure (Relative, or the MCP's scale-free residual)
  Vector mcp_row_scales;        // MCP: McpRowScales of ∇G at the point last measured (StopMeasure)
  // MCP: Newton runs on y = z/c with G(y) = D⁻¹F(c∘y) (the file comment): the units c, 1/d of the row scales d of
  // ∇F at the start, the bounds l/c, u/c, and c∘y (mutable: EvalF is const).
  bool mcp_units = false;  // c was declared (else c = 1 and y = z)
  Vector mcp_c, mcp_inv_d, mcp_l, mcp_u;
  mutable Vector mcp_z;
  bool jacobian_current = false;     // MCP: Jd/Js hold ∇G at z (UpdateJacobian need not evaluate it again)
  bool projection_verified = false;  // MCP: the last Loop returned converged with Π(z) checked (zt, Ft hold it)

  // ---- Dense linear algebra ----
  DenseMatrix A;         // n×n LU buffer; the leading |R|×|R| block is used
  Eigen::VectorXi perm;  // row transpositions of the LU
  Eigen::VectorXi ridx;  // the rows R kept in the reduced system
  // ---- Sparse linear algebra (H, its pattern and UMFPACK in JacobianStore) ----
  std::vector<int> h_map;   // ∇F nonzero k → position in H's value array
  std::vector<int> h_diag;  // row i → position of H(i, i)

  // ---- Line search, its memory and the stagnation window ----
  newton::ArmijoRule armijo;
  newton::NonmonotoneReference reference;
  int memory = 1;      // the GLL memory of this solve (nonmonotone_memory, or mcp_nonmonotone_memory for an MCP)
  int crash_left = 0;  // crash steps still allowed (Loop's first run on an MCP only)
  int stagnation_window = 10;    // stagnation_window, or mcp_stagnation_window for an MCP
  double proximal_lambda = 1.0;  // proximal_lambda, or mcp_proximal_lambda for an MCP
  newton::MeritWindow psi_window;

  // ---- Counters ----
  int iterations = 0, backtracks = 0, gradient_steps = 0, factorizations = 0, max_system = 0;
  int crash_steps = 0, nonmonotone_steps = 0, row_rescalings = 0;
  static constexpr int kMaxRowRescalings = 8;
  int proximal_rounds = 0;
  int regularized_steps = 0;
  bool safeguard_failed = false;  // proximal rounds ran and did not recover (for the message)
  int last_system = 0;            // size of the last linear system (verbose output)
  int polish_left = 0;            // extra iterations allowed to make the projected point meet the tolerance
  const char* failure_detail = "";

  void Resize(int size) {
    if (n == size && z.size() == size) return;
    n = size;
    for (Vector* x : {&z, &F, &Phi, &Da, &Db,   &g,     &d,   &Md,        &zt,          &Ft,
                      &v, &w, &e,   &Je, &zbar, &best.z, &rhs, &row_scale, &jac_row_max, &row_eq,
                      &mcp_row_scales, &mcp_c, &mcp_inv_d, &mcp_l, &mcp_u, &mcp_z}) {
      x->resize(n);
    }
    perm.resize(n);
    ridx.resize(n);
    A.resize(0, 0);  // allocated on first dense use
    ResetStorage();
  }

  // ---------------------------------------------------------------- model: F and its Jacobian
  // F(x) of the original problem into *out; false if an entry is NaN or ±∞.
  bool EvalF(const Vector& x, Vector* out) const {
    if (lcp) {
      lcp->Affine(x, out);
    } else {
      // G(y) = D⁻¹F(c∘y).
      if (mcp_units) {
        mcp_z = mcp_c.cwiseProduct(x);
        mcp->Evaluate(mcp_z, out);
      } else {
        mcp->Evaluate(x, out);
      }
      out->array() *= mcp_inv_d.array();
    }
    return out->allFinite();
  }

  // Refreshes Jd/Js at z for an MCP (an LCP's Jacobian is M, fixed at setup), unless they already hold ∇G(z).
  // False on a malformed Jacobian.
  bool UpdateJacobian() {
    if (lcp || jacobian_current) return true;
    jacobian_current = JacobianAt(z);
    return jacobian_current;
  }
  // Jd/Js ← ∇G(y) = D⁻¹ ∇F(c∘y) C of the MCP at y = x. False on a malformed Jacobian.
  bool JacobianAt(const Vector& x) {
    const Vector* at = &x;
    if (mcp_units) {
      mcp_z = mcp_c.cwiseProduct(x);
      at = &mcp_z;
    }
    if (!native_sparse) {
      if (J_dense.rows() != n || J_dense.cols() != n) J_dense.resize(n, n);
      mcp->JacobianDense(*at, &J_dense);
      if (J_dense.rows() != n || J_dense.cols() != n) return false;
      if (mcp_units) J_dense *= mcp_c.asDiagonal();
      J_dense.array().colwise() *= mcp_inv_d.array();
      Jd = &J_dense;
      if (!dense_la) {
        J_sparse = J_dense.sparseView();  // forced sparse LA on dense data: converted every iteration
        Js = &J_sparse;
      }
    } else {
      mcp->JacobianSparse(*at, &J_sparse);
      if (J_sparse.rows() != n || J_sparse.cols() != n) return false;
      J_sparse.makeCompressed();
      for (int k = 0; k < J_sparse.outerSize(); ++k) {
        const double c = mcp_units ? mcp_c[k] : 1.0;
        for (SparseMatrix::InnerIterator it(J_sparse, k); it; ++it) it.valueRef() *= mcp_inv_d[it.row()] * c;
      }
      Js = &J_sparse;
      if (dense_la) {
        CopySparseToDense(J_sparse);
        Jd = &J_dense;
      }
    }
    return true;
  }

  double JacobianInfNorm() const {
    if (native_sparse) {
      Vector& sums = const_cast<Vector&>(v);
      sums.setZero();
      for (int k = 0; k < Js->outerSize(); ++k) {
        for (SparseMatrix::InnerIterator it(*Js, k); it; ++it) sums[it.row()] += std::abs(it.value());
      }
      return sums.maxCoeff();
    }
    return Jd->cwiseAbs().rowwise().sum().maxCoeff();
  }

  // Row scaling s_i = 1/max(1, ‖∇F_i‖∞) from the Jacobian at the starting point. The FB function is not
  // invariant under scaling F, and on data whose rows are far larger than the box (siconos relay1.dat:
  // entries ~1e7, box [−0.1, 0.1]) the unscaled Psi is so ill-shaped that the line search crawls with
  // t ~ 1e-4. Scaling the rows of F leaves the solution set unchanged; rows of norm ≤ 1 are not touched, nor
  // are free rows (there Phi_i = F_i has no kink and scaling only reweights Psi, which hurt the ill-conditioned
  // siconos deltasigma MLCPs). Stopping tests always use the unscaled natural residual.
  void ComputeRowScaling(bool enabled) {
    Vector& m = jac_row_max;
    m.setZero();
    if (native_sparse) {
      for (int k = 0; k < Js->outerSize(); ++k) {
        for (SparseMatrix::InnerIterator it(*Js, k); it; ++it)
          m[it.row()] = std::max(m[it.row()], std::abs(it.value()));
      }
    } else {
      for (int j = 0; j < n; ++j) m = m.cwiseMax(Jd->col(j).cwiseAbs());
    }
    for (int i = 0; i < n; ++i) {
      if (!std::isfinite(m[i])) m[i] = 0.0;
      const bool free_row = !fb::HasLower((*l)[i]) && !fb::HasUpper((*u)[i]);
      row_scale[i] = enabled && !free_row ? 1.0 / std::max(1.0, m[i]) : 1.0;
    }
  }

  // ---------------------------------------------------------------- merit and residuals
  // F of the problem being solved (perturbed when λ > 0).
  double Fp(int i, const Vector& x, const Vector& Fx) const {
    return lambda > 0.0 ? Fx[i] + lambda * (x[i] - zbar[i]) : Fx[i];
  }

  double Merit(const Vector& x, const Vector& Fx) const {
    double s = 0.0;
    for (int i = 0; i < n; ++i) {
      const double p = fb::BoxPhi(x[i], row_scale[i] * Fp(i, x, Fx), (*l)[i], (*u)[i]);
      s += p * p;
    }
    return 0.5 * s;  // NaN propagates
  }

  // Natural residual ‖x − Π(x − F)‖∞ of the problem being solved.
  double ResidualOfCurrent(const Vector& x, const Vector& Fx) const {
    if (lambda == 0.0) return NaturalResidualNorm(x, Fx, *l, *u);
    double r = 0.0;
    for (int i = 0; i < n; ++i) {
      const double p = std::min(std::max(x[i] - Fp(i, x, Fx), (*l)[i]), (*u)[i]);
      const double ei = std::abs(x[i] - p);
      if (std::isnan(ei)) return kInf;
      r = std::max(r, ei);
    }
    return r;
  }

  // The stopping measure of a natural residual r at x: r / (1 + min(‖x‖∞, ‖q‖∞)) for a box-MLCP, r / scale
  // for an MCP.
  double Relative(double r, const Vector& x) const {
    return z_relative ? r / std::min(1.0 + x.cwiseAbs().maxCoeff(), scale) : r / scale;
  }
  // The MCP's stopping measure at (y, G(y)) with Jd/Js = ∇G(y): the base's verdict McpScaledResidual at z = c∘y,
  // computed in y (where the units are 1 and the row scales of ∇F at z are d∘those of ∇G: the same number up to
  // rounding).
  double StopMeasure(const Vector& x, const Vector& Fx) {
    if (native_sparse) {
      McpRowScales(*Js, Vector(), &mcp_row_scales);
    } else {
      McpRowScales(*Jd, Vector(), &mcp_row_scales);
    }
    return McpScaledResidual(x, Fx, *l, *u, mcp_row_scales, Vector());
  }
  // Loop's MCP stopping test, out of line so that the box-MLCP loop compiles as it did: ∇G(z), which the step
  // needs anyway, first, then the base's verdict at z. A perturbed solve (λ > 0) that meets the original problem's
  // test ends too (Run then accepts it at once). 1: converged, 0: not, −1: malformed Jacobian.
  [[gnu::noinline]] int McpConvergence(double r, double target_abs, double* measure) {
    if (!UpdateJacobian()) return -1;
    *measure = StopMeasure(z, F);
    best.Track(*measure, z);
    return *measure <= tolerance || (lambda > 0.0 && r <= target_abs) ? 1 : 0;
  }
  // ProjectionConverged for an MCP whose z lies outside the box (zt = Π(z)), out of line like McpConvergence. ∇G at
  // Π(z) replaces ∇G(z) in Jd/Js: the next UpdateJacobian evaluates it at z again.
  [[gnu::noinline]] bool McpProjectionConverged() {
    jacobian_current = false;
    return EvalF(zt, &Ft) && JacobianAt(zt) && StopMeasure(zt, Ft) <= tolerance;
  }
  // True when the row scales of ∇G at z (mcp_row_scales, just computed by StopMeasure) are far from 1: G's rows are
  // scaled by ∇F's at a point where ∇F differs from the current one by more than a factor 100 in some row. At most
  // kMaxRowRescalings times per solve (a refresh that cycles would otherwise reset the memory forever).
  bool RowScalesStale() const {
    if (mcp == nullptr || !opt->row_scale_refresh || row_rescalings >= kMaxRowRescalings) return false;
    for (int i = 0; i < n; ++i) {
      const double s = mcp_row_scales[i];
      if (s > 0.0 && s < kInf && (s < 1e-2 || s > 1e2)) return true;
    }
    return false;
  }
  // G ← G / s row by row with s = mcp_row_scales (D ← D∘s), then F, ∇G and the FB row scaling at z again.
  bool RefreshRowScales() {
    ++row_rescalings;
    for (int i = 0; i < n; ++i) {
      const double s = mcp_row_scales[i];
      if (s > 0.0 && s < kInf) mcp_inv_d[i] /= s;
    }
    if (!ResetF() || !UpdateJacobian()) return false;
    ComputeRowScaling(opt->row_scaling);
    return true;
  }

  // ---------------------------------------------------------------- generalized Jacobian and gradient
  // Phi, Da, Db at z (DFK rule at kinks), then g = ∇Psi = Da∘Phi + (∇F + λI)ᵀ(Db∘Phi). Phi_i is evaluated
  // at the scaled s_i·F_i, so Db_i includes the factor s_i.
  void ComputeDerivatives() {
    bool any_kink = false;
    fb::RowDerivative rd;
    for (int i = 0; i < n; ++i) {
      double value;
      const bool kink = fb::BoxPhiDerivative(z[i], row_scale[i] * Fp(i, z, F), (*l)[i], (*u)[i], 1.0, 0.0, &value, &rd);
      Phi[i] = value;
      Da[i] = rd.da;
      Db[i] = row_scale[i] * rd.db;
      e[i] = kink ? 1.0 : 0.0;
      any_kink |= kink;
    }
    if (any_kink) {
      // DFK 1996: the limit of gradients along z + t e_β, β = kink rows, needs (∇F + λI) e_β.
      ApplyJ(e, &Je);
      for (int i = 0; i < n; ++i) {
        if (e[i] == 0.0) continue;
        double value;
        fb::BoxPhiDerivative(z[i], row_scale[i] * Fp(i, z, F), (*l)[i], (*u)[i], 1.0, row_scale[i] * (Je[i] + lambda),
                             &value, &rd);
        Da[i] = rd.da;
        Db[i] = row_scale[i] * rd.db;
      }
    }
    v.array() = Db.array() * Phi.array();
    ApplyJt(v, &g);
    g.array() += Da.array() * Phi.array() + lambda * v.array();
  }

  // ---------------------------------------------------------------- Newton system H d = −Phi
  // H_μ d = −Phi with H_μ = Da + Db(∇F + (λ + μ)I): μ = 0 is the Newton step of the problem being solved,
  // μ > 0 the regularized retry (see Loop).
  bool SolveNewtonSystem(double mu) {
    shift = lambda + mu;
    return dense_la ? SolveDense() : SolveSparse();
  }

  bool SolveDense() {
    const double threshold = opt->reduction_threshold;
    int nr = 0;
    bool any_trivial = false;
    for (int i = 0; i < n; ++i) {
      if (std::abs(Db[i]) <= threshold * std::abs(Da[i])) {
        // Trivially active row: Da_i d_i = −Phi_i (Db_i dropped; exact when Db_i == 0).
        d[i] = -Phi[i] / (Da[i] + shift * Db[i]);
        w[i] = d[i];
        any_trivial = true;
      } else {
        ridx[nr++] = i;
        w[i] = 0.0;
      }
    }
    max_system = std::max(max_system, nr);
    last_system = nr;
    if (nr == 0) return d.allFinite();
    // Right-hand side −Phi_R/Db_R − ∇F_RT d_T (the λI term has no off-diagonal part).
    if (any_trivial) ApplyJ(w, &Md);
    for (int k = 0; k < nr; ++k) {
      const int i = ridx[k];
      rhs[k] = -Phi[i] / Db[i] - (any_trivial ? Md[i] : 0.0);
    }
    if (A.rows() != n) A.resize(n, n);
    Eigen::Map<DenseMatrix, 0, Eigen::OuterStride<>> a(A.data(), nr, nr, Eigen::OuterStride<>(A.outerStride()));
    auto x = rhs.head(nr);
    ++factorizations;
    // Symmetric ∇F: ∇F_RR + diag(Da/Db) + λI is symmetric with a nonnegative diagonal shift, positive
    // definite whenever ∇F is; Cholesky costs half an LU. Not positive definite → LU below.
    if (symmetric_jacobian) {
      GatherReduced(nr, /*lower_only=*/true, /*equilibrate=*/false);
      if (Eigen::internal::llt_inplace<double, Eigen::Lower>::blocked(a) < 0) {
        a.triangularView<Eigen::Lower>().solveInPlace(x);
        a.triangularView<Eigen::Lower>().transpose().solveInPlace(x);
        for (int k = 0; k < nr; ++k) d[ridx[k]] = x[k];
        return d.allFinite();
      }
    }
    // Row equilibration before partial pivoting: a row close to active carries Da/Db up to
    // 1/reduction_threshold (or far more with threshold 0) on its diagonal. If such a row were picked as pivot
    // for another column, its huge entry would be spread over the trailing rows and cancel there, losing
    // |Da/Db|·ε of accuracy (this made the exact variant crawl). Dividing row i by ‖∇F_i‖∞ + |Da_i/Db_i + shift|
    // keeps every row O(1); it changes nothing mathematically.
    for (int k = 0; k < nr; ++k) {
      const int i = ridx[k];
      const double norm = jac_row_max[i] + std::abs(Da[i] / Db[i] + shift);
      row_eq[k] = norm > 0.0 && std::isfinite(norm) ? 1.0 / norm : 1.0;
      rhs[k] *= row_eq[k];
    }
    GatherReduced(nr, /*lower_only=*/false, /*equilibrate=*/true);
    int transpositions = 0;
    const Eigen::Index zero_pivot = Eigen::internal::partial_lu_impl<double, Eigen::ColMajor, int>::blocked_lu(
        nr, nr, A.data(), A.outerStride(), perm.data(), transpositions);
    // An exactly zero pivot is singular. A nearly singular system is not rejected here: its direction is
    // large and fails the DFK descent test instead (a pivot floor relative to max|A| would misfire, since
    // rows close to active carry Da/Db up to 1/reduction_threshold on the diagonal).
    if (zero_pivot >= 0) return false;
    for (int k = 0; k < nr; ++k) {
      if (perm[k] != k) std::swap(rhs[k], rhs[perm[k]]);
    }
    a.triangularView<Eigen::UnitLower>().solveInPlace(x);
    a.triangularView<Eigen::Upper>().solveInPlace(x);
    for (int k = 0; k < nr; ++k) d[ridx[k]] = x[k];
    return d.allFinite();
  }

  // A(0:nr, 0:nr) = ∇F_RR + diag(Da_R/Db_R) + shift·I (only the lower triangle if lower_only), with row k
  // multiplied by row_eq[k] if equilibrate.
  void GatherReduced(int nr, bool lower_only, bool equilibrate) {
    const DenseMatrix& J = *Jd;
    for (int jj = 0; jj < nr; ++jj) {
      const int j = ridx[jj];
      const double* col = J.col(j).data();
      double* a = A.col(jj).data();
      if (equilibrate) {
        for (int ii = lower_only ? jj : 0; ii < nr; ++ii) a[ii] = col[ridx[ii]] * row_eq[ii];
        a[jj] += (Da[j] / Db[j] + shift) * row_eq[jj];
      } else {
        for (int ii = lower_only ? jj : 0; ii < nr; ++ii) a[ii] = col[ridx[ii]];
        a[jj] += Da[j] / Db[j] + shift;
      }
    }
  }

  // H's pattern (∇F ∪ diag, JacobianStore) and the value maps when the pattern of ∇F changed (allocates then only).
  void EnsureSparseMaps(const SparseMatrix& J) {
    if (!EnsureSparsePattern(J)) return;
    const int nnz = static_cast<int>(J.nonZeros());
    const auto position = [&](int row, int col) {
      const int* begin = H.innerIndexPtr() + H.outerIndexPtr()[col];
      const int* end = H.innerIndexPtr() + H.outerIndexPtr()[col + 1];
      return static_cast<int>(std::lower_bound(begin, end, row) - H.innerIndexPtr());
    };
    h_map.resize(nnz);
    for (int j = 0; j < n; ++j) {
      for (int k = J.outerIndexPtr()[j]; k < J.outerIndexPtr()[j + 1]; ++k) {
        h_map[k] = position(J.innerIndexPtr()[k], j);
      }
    }
    h_diag.resize(n);
    for (int i = 0; i < n; ++i) h_diag[i] = position(i, i);
  }

  bool SolveSparse() {
    const SparseMatrix& J = *Js;
    EnsureSparseMaps(J);
    double* hv = H.valuePtr();
    std::fill(hv, hv + H.nonZeros(), 0.0);
    const double* jv = J.valuePtr();
    const int* inner = J.innerIndexPtr();
    const int nnz = static_cast<int>(J.nonZeros());
    for (int k = 0; k < nnz; ++k) hv[h_map[k]] += Db[inner[k]] * jv[k];
    for (int i = 0; i < n; ++i) hv[h_diag[i]] += Da[i] + shift * Db[i];
    max_system = std::max(max_system, n);
    if (!umf_analyzed) {
      // No iterative refinement: an inexact solve only perturbs the Newton step, which the next iteration
      // corrects, and each refinement step costs a solve plus a product with H.
      umf.umfpackControl()(UMFPACK_IRSTEP) = 0;
      umf.analyzePattern(H);
      if (umf.info() != Eigen::Success) return false;
      umf_analyzed = true;
    }
    umf.factorize(H);
    ++factorizations;
    if (umf.info() != Eigen::Success) return false;  // includes UMFPACK's "singular matrix" warning
    rhs = -Phi;
    d = umf.solve(rhs);
    return umf.info() == Eigen::Success && d.allFinite();
  }

  // ---------------------------------------------------------------- crash phase (MCP, dense)
  // One min-map Newton step from z (Jd = ∇G(z), λ = 0): rows whose natural map z_i − G_i lies at or beyond a bound
  // go to that bound, the others R solve their linearization G_R + ∇G_R Δ = 0, i.e.
  //     ∇G_RR Δ_R = −G_R − ∇G_RA Δ_A,
  // and the step is projected onto the box. Accepted (zt, Ft, *psi_new hold the point) when Psi there is at most
  // half of psi; false otherwise (a singular system, NaN F, too little decrease), z untouched.
  bool CrashStep(double psi, double* psi_new) {
    const DenseMatrix& J = *Jd;
    int nr = 0;
    bool any_active = false;
    for (int i = 0; i < n; ++i) {
      const double t = z[i] - F[i];
      if (t <= (*l)[i]) {
        w[i] = (*l)[i] - z[i];
        any_active = true;
      } else if (t >= (*u)[i]) {
        w[i] = (*u)[i] - z[i];
        any_active = true;
      } else {
        w[i] = 0.0;
        ridx[nr++] = i;
      }
    }
    d = w;
    last_system = nr;
    if (nr > 0) {
      if (any_active) ApplyJ(w, &Md);
      for (int k = 0; k < nr; ++k) {
        const int i = ridx[k];
        rhs[k] = -F[i] - (any_active ? Md[i] : 0.0);
      }
      if (A.rows() != n) A.resize(n, n);
      for (int jj = 0; jj < nr; ++jj) {
        const double* col = J.col(ridx[jj]).data();
        double* a = A.col(jj).data();
        for (int ii = 0; ii < nr; ++ii) a[ii] = col[ridx[ii]];
      }
      ++factorizations;
      max_system = std::max(max_system, nr);
      int transpositions = 0;
      if (Eigen::internal::partial_lu_impl<double, Eigen::ColMajor, int>::blocked_lu(
              nr, nr, A.data(), A.outerStride(), perm.data(), transpositions) >= 0) {
        return false;
      }
      Eigen::Map<DenseMatrix, 0, Eigen::OuterStride<>> a(A.data(), nr, nr, Eigen::OuterStride<>(A.outerStride()));
      auto x = rhs.head(nr);
      for (int k = 0; k < nr; ++k) {
        if (perm[k] != k) std::swap(rhs[k], rhs[perm[k]]);
      }
      a.triangularView<Eigen::UnitLower>().solveInPlace(x);
      a.triangularView<Eigen::Upper>().solveInPlace(x);
      for (int k = 0; k < nr; ++k) d[ridx[k]] = x[k];
    }
    for (int i = 0; i < n; ++i) zt[i] = std::min(std::max(z[i] + d[i], (*l)[i]), (*u)[i]);
    if (!zt.allFinite() || !EvalF(zt, &Ft)) return false;
    *psi_new = Merit(zt, Ft);
    return *psi_new <= 0.5 * psi;
  }

  // ---------------------------------------------------------------- line search
  // Armijo backtracking from t = 1 along d until Psi(z + t d) ≤ psi_ref + σ t gd. On success zt/Ft hold the accepted
  // point and *psi_out its merit. *all_nan reports that every trial had a non-finite F (MCP).
  bool LineSearch(double psi_ref, double gd, double* psi_out, double* t_out, bool* all_nan) {
    if (lcp) ApplyJ(d, &Md);  // F is affine: F(z + t d) = F + t M d, no product per trial
    const auto merit_at = [this](double t, double* psi) {
      zt = z + t * d;
      bool finite = true;
      if (lcp) {
        Ft = F + t * Md;
      } else {
        finite = EvalF(zt, &Ft);
      }
      if (finite) *psi = Merit(zt, Ft);
      return finite;
    };
    return newton::ArmijoBacktrack(armijo, psi_ref, gd, merit_at, psi_out, t_out, all_nan, &backtracks);
  }

  void ResetMemory(double psi) { reference.Reset(memory, psi); }
  void PushMemory(double psi) { reference.Push(psi); }
  double ReferenceMerit() const { return reference.Reference(); }

  // ---------------------------------------------------------------- the Newton loop
  // Runs on the problem F + λ(z − zbar) (λ = this->lambda) from z (F = F(z) of the original problem, finite).
  // Converged: λ = 0 ⇒ relative natural residual ≤ tolerance; λ > 0 ⇒ perturbed residual ≤ target_abs.
  Exit Loop(double target_abs, int local_budget, bool detect_stagnation) {
    const NewtonOptions& o = *opt;
    double psi = Merit(z, F);
    ResetMemory(psi);
    double psi_best = psi;
    int since_best = 0;
    psi_window.SetWindow(stagnation_window);
    for (int k = 0;; ++k) {
      // The stagnation test compares reference merits (max of the GLL memory) so that a non-monotone
      // line search is not mistaken for stagnation; with memory 1 this is Psi itself.
      psi_window.Record(k, ReferenceMerit());
      double r = ResidualOfCurrent(z, F);
      bool converged;
      double measure = 0.0;  // MCP: the stopping measure of the original problem at z
      if (mcp != nullptr) {
        const int test = McpConvergence(r, target_abs, &measure);
        if (test < 0) {
          failure_detail = "the MCP Jacobian has the wrong size";
          return Exit::kNumericalFailure;
        }
        converged = test > 0;
        if (!converged && lambda == 0.0 && RowScalesStale()) {
          // The merit function is measured in the row scales of ∇F at the start; where they no longer describe
          // ∇F (an economy's price leaving its floor: ∂F/∂p falls by orders of magnitude), Psi decreases while the
          // verdict's residual grows. Rescale G to ∇F's rows here and restart the line-search memory.
          if (!RefreshRowScales()) {
            failure_detail = "F is NaN/Inf or the Jacobian malformed after a row-scale refresh";
            return Exit::kNumericalFailure;
          }
          psi = Merit(z, F);
          ResetMemory(psi);
          psi_best = psi;
          since_best = 0;
          psi_window.Fill(kInf);
        }
      } else {
        const double r_original = lambda == 0.0 ? r : NaturalResidualNorm(z, F, *l, *u);
        best.Track(Relative(r_original, z), z);
        converged = lambda == 0.0 ? Relative(r, z) <= tolerance : r <= target_abs;
      }
      if (converged && F_is_incremental) {
        // The accumulated F + t M d may differ from M z + q by rounding: confirm on a fresh product.
        EvalF(z, &F);
        F_is_incremental = false;
        r = ResidualOfCurrent(z, F);
        converged = lambda == 0.0 ? Relative(r, z) <= tolerance : r <= target_abs;
        psi = Merit(z, F);
      }
      // FB iterates may sit outside [l, u] by up to the tolerance; the returned point is projected onto the
      // box (Conclude). If the projection would break the tolerance, polish with a few more Newton steps,
      // which near the solution shrink the infeasibility quadratically.
      if (converged && (lambda > 0.0 || polish_left <= 0 || ProjectionConverged())) {
        if (mcp != nullptr) projection_verified = lambda == 0.0 && polish_left > 0;
        return Exit::kConverged;
      }
      if (converged) --polish_left;
      if (k >= local_budget || iterations >= budget) return Exit::kBudget;
      if (owner->TimeLimitReached()) return Exit::kTimeLimit;
      ++iterations;

      if (!UpdateJacobian()) {
        failure_detail = "the MCP Jacobian has the wrong size";
        return Exit::kNumericalFailure;
      }
      if (crash_left > 0) {
        double psi_crash = psi;
        if (CrashStep(psi, &psi_crash)) {
          --crash_left;
          ++crash_steps;
          if (verbosity >= 2) {
            std::fprintf(stderr, "newton %4d crash  psi %.3e -> %.3e res %.3e system %d\n", iterations, psi,
                         psi_crash, measure, last_system);
          }
          z.swap(zt);
          F.swap(Ft);
          jacobian_current = false;
          psi = psi_crash;
          ResetMemory(psi);
          psi_best = std::min(psi_best, psi);
          since_best = 0;
          continue;
        }
        crash_left = 0;  // the first step that does not halve Psi ends the crash phase
      }
      ComputeDerivatives();
      if (!g.allFinite()) {
        failure_detail = "the merit-function gradient is NaN/Inf (Jacobian not finite?)";
        return Exit::kNumericalFailure;
      }
      // Directions in order: Newton; regularized Newton; −∇Psi. A direction is used if it passes its descent
      // test and its line search succeeds; otherwise the next one is tried.
      const double psi_ref = ReferenceMerit();
      double psi_new = psi, t = 0.0, gd = 0.0;
      bool all_nan = false, accepted = false, regularized = false, gradient = false, any_direction = false;
      if (SolveNewtonSystem(0.0)) {
        gd = g.dot(d);
        // DFK 1996 sufficient-descent test.
        if (SufficientDescent(gd, d.norm(), o.descent_rho, o.descent_power)) {
          any_direction = true;
          accepted = LineSearch(psi_ref, gd, &psi_new, &t, &all_nan);
        }
      }
      if (!accepted && o.regularization > 0.0) {
        // Singular Newton system, or a step the line search rejects (typical near non-isolated solutions of
        // monotone problems): retry with ∇F + μI, μ = regularization·min(1, ‖Phi‖), i.e. the Newton step of
        // the proximal subproblem centred at z. μ → 0 with ‖Phi‖, which keeps fast local convergence under
        // a local error bound (Levenberg–Marquardt-type choice, cf. Yamashita–Fukushima 2001).
        ++regularized_steps;
        regularized = true;
        if (SolveNewtonSystem(o.regularization * std::min(1.0, std::sqrt(2.0 * psi)))) {
          gd = g.dot(d);
          // The DFK test ρ‖d‖^p is absolute: near a non-isolated solution set this step has O(1) components
          // along the null space while ∇Psiᵀd = O(‖Phi‖²). Accept also the scale-free angle condition
          // ∇Psiᵀd ≤ −10⁻⁶‖∇Psi‖‖d‖ (gradient-relatedness is what the Armijo convergence argument needs).
          const double norm_d = d.norm();
          if (SufficientDescent(gd, norm_d, o.descent_rho, o.descent_power) ||
              (gd < 0.0 && gd <= -1e-6 * g.norm() * norm_d)) {
            any_direction = true;
            accepted = LineSearch(psi_ref, gd, &psi_new, &t, &all_nan);
          }
        }
      }
      if (!accepted) {
        if (!o.gradient_fallback) {
          failure_detail = any_direction ? "the line search failed along the Newton direction"
                                         : "the Newton system is singular or its direction is not a descent direction";
          return any_direction ? Exit::kStalled : Exit::kSingular;
        }
        d = -g;
        gd = -g.squaredNorm();
        ++gradient_steps;
        gradient = true;
        if (!(gd < 0.0)) {
          if (any_direction) {
            failure_detail = "the line search failed and the merit-function gradient is zero";
            return Exit::kStalled;
          }
          failure_detail = "the Newton system is singular and the merit-function gradient is zero";
          return Exit::kSingular;
        }
        accepted = LineSearch(psi_ref, gd, &psi_new, &t, &all_nan);
      }
      if (verbosity >= 2) {
        std::fprintf(stderr, "newton %4d%s psi %.3e res %.3e step %s t %.2e system %d\n", iterations,
                     lambda > 0.0 ? " (prox)" : "", psi, mcp != nullptr ? measure : Relative(r, z),
                     gradient      ? "grad  "
                     : regularized ? "reg   "
                                   : "newton",
                     t, dense_la ? last_system : n);
      }
      if (!accepted) {
        if (all_nan) {
          failure_detail = "F is NaN/Inf at every trial point of the line search";
          return Exit::kNumericalFailure;
        }
        failure_detail = "the line search failed along the Newton and the gradient direction";
        return Exit::kStalled;
      }
      // Step collapse: the accepted point equals z to rounding.
      if (!newton::StepMoved(z, zt)) {
        failure_detail = "the step length collapsed to rounding level";
        return Exit::kStalled;
      }
      if (psi_new > psi) ++nonmonotone_steps;
      z.swap(zt);
      F.swap(Ft);
      F_is_incremental = lcp != nullptr;
      jacobian_current = false;
      psi = psi_new;
      PushMemory(psi);
      // Watchdog for the non-monotone search: if the memory window passed without a new best merit value,
      // restart the memory so that the next step must decrease Psi from here (monotone Armijo).
      if (psi < psi_best) {
        psi_best = psi;
        since_best = 0;
      } else if (++since_best >= memory && memory > 1) {
        ResetMemory(psi);
        since_best = 0;
      }
      if (!newton::IterateBounded(z.cwiseAbs().maxCoeff())) {
        failure_detail = "the iterates grew without bound";
        return Exit::kDiverged;
      }
      // The reference merit after iteration k + 1 against the one recorded at iteration k − window.
      if (detect_stagnation && psi_window.Stagnated(k, ReferenceMerit(), o.stagnation_ratio)) {
        failure_detail = "the merit function stagnated at a point that is not a solution";
        return Exit::kStagnated;
      }
    }
  }

  // Recomputes F at z (after z was reset). False if not finite.
  bool ResetF() {
    F_is_incremental = false;
    jacobian_current = false;
    return EvalF(z, &F);
  }

  // ---------------------------------------------------------------- driver
  Exit Run() {
    const NewtonOptions& o = *opt;
    lambda = 0.0;
    best.Reset();
    if (!ResetF()) {
      failure_detail = "F is NaN/Inf at the starting point";
      return Exit::kNumericalFailure;
    }
    if (!UpdateJacobian()) {
      failure_detail = "the MCP Jacobian has the wrong size";
      return Exit::kNumericalFailure;
    }
    ComputeRowScaling(o.row_scaling);
    polish_left = 3;
    crash_left = mcp != nullptr && dense_la ? o.crash_steps : 0;
    Exit exit = Loop(0.0, budget, o.proximal_safeguard);
    crash_left = 0;
    // Why the unperturbed method failed; reported if the safeguard does not recover.
    const Exit first_exit = exit;
    const char* first_detail = failure_detail;
    // Proximal perturbation rounds (see the file comment). psi_stuck is the merit level at which the
    // unperturbed method last stalled: a later Newton run that ends clearly below it has left that basin.
    double lambda_round = -1.0;
    double psi_stuck = Merit(z, F);
    while (o.proximal_safeguard && !IsHardFailure(exit) && exit != Exit::kConverged &&
           proximal_rounds < o.max_proximal_rounds && iterations < budget) {
      ++proximal_rounds;
      if (lambda_round < 0.0) {
        if (!UpdateJacobian()) break;
        const double norm = JacobianInfNorm();
        lambda_round = proximal_lambda * std::max(1.0, std::isfinite(norm) ? norm : 1.0);
      }
      zbar = z;
      const double r0 = NaturalResidualNorm(z, F, *l, *u);
      lambda = lambda_round;
      // Relative's unit; an MCP's perturbed solves aim at tol·(1 + ‖z‖∞), the base's scale-free unit.
      const double unit = z_relative ? std::min(1.0 + z.cwiseAbs().maxCoeff(), scale)
                                     : (mcp != nullptr ? 1.0 + z.cwiseAbs().maxCoeff() : scale);
      const Exit inner = Loop(std::max(0.5 * tolerance * unit, 0.1 * r0), o.proximal_inner_iterations, true);
      lambda = 0.0;
      if (verbosity >= 2) {
        std::fprintf(stderr, "newton proximal round %d: lambda %.3e, perturbed solve %s\n", proximal_rounds,
                     lambda_round, inner == Exit::kConverged ? "converged" : "failed");
      }
      if (IsHardFailure(inner)) {
        exit = inner;
        break;
      }
      if (inner == Exit::kConverged) {
        // The perturbed solution is the next proximal point: restart the unperturbed method from it.
        lambda_round *= 0.5;
        zbar = z;
        if (!ResetF()) {
          failure_detail = "F is NaN/Inf at a proximal point";
          exit = Exit::kNumericalFailure;
          break;
        }
        exit = Loop(0.0, budget, true);
        if (exit == Exit::kConverged || IsHardFailure(exit)) break;
        const double psi_now = Merit(z, F);
        if (psi_now < o.stagnation_ratio * psi_stuck) {  // escaped: the next round starts where it stopped
          psi_stuck = psi_now;
          continue;
        }
      } else {
        lambda_round *= 10.0;  // the perturbed problem was still too hard: perturb more
      }
      // Newton fell back into the same basin (or the perturbed solve failed): continue the proximal sequence
      // from its last centre.
      z = zbar;
      if (!ResetF()) {
        failure_detail = "F is NaN/Inf at a proximal point";
        exit = Exit::kNumericalFailure;
        break;
      }
    }
    if (proximal_rounds > 0 && exit != Exit::kConverged && !IsHardFailure(exit)) {
      exit = first_exit;
      failure_detail = first_detail;
      safeguard_failed = true;
    }
    return exit;
  }

  // True if Π_[l,u](z) meets the tolerance (zt, Ft receive Π(z) and F there). True if z is inside the box.
  bool ProjectionConverged() {
    bool outside = false;
    for (int i = 0; i < n; ++i) {
      zt[i] = std::min(std::max(z[i], (*l)[i]), (*u)[i]);
      outside |= zt[i] != z[i];
    }
    if (mcp != nullptr && outside) return McpProjectionConverged();
    return !outside || (EvalF(zt, &Ft) && Relative(NaturalResidualNorm(zt, Ft, *l, *u), zt) <= tolerance);
  }

  // Writes the returned point, status, message and details. A solved point outside [l, u] (FB iterates need
  // not be feasible) is replaced by its projection when that still meets the tolerance.
  void Conclude(Exit exit, SolveResult* result) {
    if (exit == Exit::kConverged) {
      // An MCP whose Loop already checked Π(z) is not evaluated there a second time.
      if ((mcp != nullptr && projection_verified) || ProjectionConverged()) z.swap(zt);  // else z passes, outside
    } else if (best.residual < kInf) {
      z = best.z;
    }
    result->z = z;
    result->iterations = iterations;
    newton::ReportExit(exit, failure_detail, iterations, budget, safeguard_failed ? proximal_rounds : 0,
                       mcp != nullptr ? "scale-free residual" : "relative natural residual", best.residual, result);
    result->SetDetail("backtracks", backtracks);
    result->SetDetail("gradient_steps", gradient_steps);
    result->SetDetail("proximal_rounds", proximal_rounds);
    result->SetDetail("regularized_steps", regularized_steps);
    result->SetDetail("factorizations", factorizations);
    result->SetDetail("max_system_size", max_system);
    if (mcp != nullptr) {
      result->SetDetail("crash_steps", crash_steps);
      result->SetDetail("nonmonotone_steps", nonmonotone_steps);
      result->SetDetail("row_rescalings", row_rescalings);
    }
    if (verbosity >= 1) {
      std::fprintf(stderr, "newton: %s after %d iterations (%d gradient steps, %d backtracks, %d proximal rounds)\n",
                   exit == Exit::kConverged ? "solved" : "not solved", iterations, gradient_steps, backtracks,
                   proximal_rounds);
    }
  }
};

SemismoothNewtonSolver::SemismoothNewtonSolver() : ws_(std::make_unique<Workspace>()) {}
SemismoothNewtonSolver::SemismoothNewtonSolver(const NewtonOptions& options)
    : BackendWithOptions(options), ws_(std::make_unique<Workspace>()) {}
SemismoothNewtonSolver::~SemismoothNewtonSolver() = default;

const SolverInfo& SemismoothNewtonSolver::info() const {
  static const SolverInfo kInfo{
      "newton",
      "semismooth Newton on Billups' box Fischer-Burmeister function, Armijo/GLL line search, gradient "
      "fallback, proximal-perturbation safeguard; dense reduced LU or UMFPACK",
      "De Luca, Facchinei, Kanzow 1996 (Math. Prog. 75); Billups 1995 (PhD thesis, UW-Madison); Munson, "
      "Facchinei, Ferris, Fischer, Kanzow 2001 (INFORMS J. Comput. 13)",
      /*dense=*/true,
      /*sparse=*/true,
      /*symmetric_only=*/false,
      /*exact=*/false,
      /*mcp=*/true,
      /*default_size_limit=*/0};
  return kInfo;
}

bool SemismoothNewtonSolver::ValidateBackendOptions(std::string* why) const { return options_.IsValid(why); }

void SemismoothNewtonSolver::BindOptions(OptionBinder* b) {
  NewtonOptions& o = options_;
  b->Add("armijo_sigma", &o.armijo_sigma, "Armijo constant sigma in (0, 0.5)");
  b->Add("backtrack_factor", &o.backtrack_factor, "step-length reduction factor in (0, 1)");
  b->Add("max_backtracks", &o.max_backtracks, "trial steps per line search");
  b->Add("nonmonotone_memory", &o.nonmonotone_memory, "GLL memory (1 = monotone Armijo, max 32)");
  b->Add("mcp_nonmonotone_memory", &o.mcp_nonmonotone_memory, "GLL memory for nonlinear MCPs (1 = monotone)");
  b->Add("crash_steps", &o.crash_steps, "MCP, dense: min-map Newton steps first, each kept if it halves Psi");
  b->Add("mcp_stagnation_window", &o.mcp_stagnation_window, "stagnation_window for nonlinear MCPs");
  b->Add("mcp_proximal_lambda", &o.mcp_proximal_lambda, "proximal_lambda for nonlinear MCPs");
  b->Add("row_scale_refresh", &o.row_scale_refresh, "MCP: rescale F's rows where the start's row scales are stale");
  b->Add("descent_rho", &o.descent_rho, "DFK descent test grad'd <= -rho ||d||^p: rho");
  b->Add("descent_power", &o.descent_power, "DFK descent test: p (> 2)");
  b->Add("gradient_fallback", &o.gradient_fallback, "use -grad Psi when the Newton direction fails");
  b->Add("linear_solver", &o.linear_solver,
         {{"auto", NewtonOptions::kAutoLinearSolver}, {"dense", NewtonOptions::kDenseLinearSolver},
          {"sparse", NewtonOptions::kSparseLinearSolver}},
         {"auto", "dense", "sparse"},  // its old numbers 0-2, still read
         "auto (dense LU for dense and small sparse data, else UMFPACK), dense (reduced LU), sparse (UMFPACK)");
  b->Add("dense_max_size", &o.dense_max_size, "auto: sparse data up to this size are factorized densely");
  b->Add("reduction_threshold", &o.reduction_threshold,
         "dense: rows with |Db| <= threshold |Da| leave the LU (0 = exact zeros only)");
  b->Add("use_cholesky", &o.use_cholesky, "dense LCP with symmetric M: Cholesky on the reduced system");
  b->Add("row_scaling", &o.row_scaling, "FB on s_i F_i with s_i = 1/max(1, max_j |J_ij|) at the start");
  b->Add("regularization", &o.regularization,
         "retry a failed Newton system with J + mu I, mu = this * min(1, ||Phi||) (0 = off)");
  b->Add("proximal_safeguard", &o.proximal_safeguard, "proximal-perturbation rounds when Psi stalls");
  b->Add("max_proximal_rounds", &o.max_proximal_rounds, "limit on proximal-perturbation rounds");
  b->Add("proximal_lambda", &o.proximal_lambda, "initial lambda = this * max(1, ||J||_inf)");
  b->Add("stagnation_window", &o.stagnation_window, "iterations over which Psi must decrease");
  b->Add("stagnation_ratio", &o.stagnation_ratio, "required decrease factor of Psi over the window");
  b->Add("proximal_inner_iterations", &o.proximal_inner_iterations,
         "Newton iterations per perturbed (proximal) solve");
}

// What a box-MLCP solve and an MCP solve set up alike: the sizes, the bounds, and dense or sparse linear algebra
// (native_sparse: ∇F arrives sparse).
void SemismoothNewtonSolver::SetUpSolve(int n, const Vector& l, const Vector& u, bool native_sparse) {
  Workspace& ws = *ws_;
  ws.Resize(n);
  ws.owner = this;
  ws.opt = &options_;
  ws.l = &l;
  ws.u = &u;
  ws.ChooseAlgebra(options_.linear_solver, options_.dense_max_size, n, native_sparse);
}

// The other half they share: the stopping test and budget, zeroed counters, the start in result->z; then Newton.
void SemismoothNewtonSolver::RunAndConclude(const SolverOptions& options, SolveResult* result) {
  Workspace& ws = *ws_;
  ws.tolerance = options.tolerance;
  ws.verbosity = options.verbosity;
  ws.budget = IterationBudget(options, kDefaultMaxIterations);
  ws.iterations = ws.backtracks = ws.gradient_steps = ws.factorizations = ws.max_system = 0;
  ws.proximal_rounds = ws.regularized_steps = 0;
  ws.crash_steps = ws.nonmonotone_steps = ws.row_rescalings = 0;
  const bool mcp = ws.mcp != nullptr;
  ws.memory = mcp ? options_.mcp_nonmonotone_memory : options_.nonmonotone_memory;
  ws.armijo = newton::ArmijoRule{options_.armijo_sigma, options_.backtrack_factor, options_.max_backtracks};
  ws.stagnation_window = mcp ? options_.mcp_stagnation_window : options_.stagnation_window;
  ws.proximal_lambda = mcp ? options_.mcp_proximal_lambda : options_.proximal_lambda;
  ws.safeguard_failed = false;
  ws.failure_detail = "";
  ws.jacobian_current = false;
  ws.projection_verified = false;
  ws.z = result->z;
  ws.Conclude(ws.Run(), result);
}

void SemismoothNewtonSolver::DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) {
  SetUpSolve(problem.size(), problem.l(), problem.u(), problem.is_sparse());
  Workspace& ws = *ws_;
  ws.lcp = &problem;
  ws.mcp = nullptr;
  ws.BindBoxMatrix(problem);
  ws.symmetric_jacobian = ws.dense_la && options_.use_cholesky && IsNumericallySymmetric(*ws.Jd);
  ws.scale = problem.residual_scale();
  ws.z_relative = true;
  RunAndConclude(options, result);
}

void SemismoothNewtonSolver::DoSolveMCP(const MCP& problem, const SolverOptions& options, SolveResult* result) {
  const int n = problem.size();
  SetUpSolve(n, problem.l(), problem.u(), problem.jacobian_kind() == MCP::JacobianKind::kSparse);
  Workspace& ws = *ws_;
  ws.lcp = nullptr;
  ws.mcp = &problem;
  ws.symmetric_jacobian = false;  // an MCP Jacobian is not assumed symmetric
  ws.scale = 1.0;                 // unused: an MCP stops on the scale-free residual (StopMeasure)
  ws.z_relative = false;
  // Units and row scales (the file comment): y = z/c, G(y) = D⁻¹F(c∘y), d = McpRowScales of ∇F at the start, so
  // that Newton's iterates do not depend on the scaling of F's rows or on the stated units of z.
  const Vector& c = problem.variable_scale();
  ws.mcp_units = c.size() == n;
  if (ws.mcp_units) {
    ws.mcp_c = c;
  } else {
    ws.mcp_c.setOnes();
  }
  ws.mcp_l = problem.l().cwiseQuotient(ws.mcp_c);
  ws.mcp_u = problem.u().cwiseQuotient(ws.mcp_c);
  ws.l = &ws.mcp_l;
  ws.u = &ws.mcp_u;
  ws.mcp_inv_d.setOnes();
  if (ws.native_sparse) {
    problem.JacobianSparse(result->z, &ws.J_sparse);
    if (ws.J_sparse.rows() == n && ws.J_sparse.cols() == n) McpRowScales(ws.J_sparse, c, &ws.mcp_row_scales);
  } else {
    if (ws.J_dense.rows() != n || ws.J_dense.cols() != n) ws.J_dense.resize(n, n);
    problem.JacobianDense(result->z, &ws.J_dense);
    if (ws.J_dense.rows() == n && ws.J_dense.cols() == n) McpRowScales(ws.J_dense, c, &ws.mcp_row_scales);
  }
  // A malformed Jacobian is reported by Run; a non-finite row leaves that row unscaled.
  const bool scaled = ws.native_sparse ? ws.J_sparse.rows() == n && ws.J_sparse.cols() == n
                                       : ws.J_dense.rows() == n && ws.J_dense.cols() == n;
  for (int i = 0; scaled && i < n; ++i) {
    const double d = ws.mcp_row_scales[i];
    ws.mcp_inv_d[i] = d > 0.0 && d < kInf ? 1.0 / d : 1.0;
  }
  if (ws.mcp_units) result->z.array() /= ws.mcp_c.array();
  RunAndConclude(options, result);
  if (ws.mcp_units) {
    // Back to z = c∘y; a y on its bound l/c or u/c maps onto l or u exactly.
    for (int i = 0; i < n; ++i) {
      const double y = result->z[i];
      double& z = result->z[i];
      if (y == ws.mcp_l[i]) {
        z = problem.l()[i];
      } else if (y == ws.mcp_u[i]) {
        z = problem.u()[i];
      } else if (y > ws.mcp_l[i] && y < ws.mcp_u[i]) {
        z = std::min(std::max(c[i] * y, problem.l()[i]), problem.u()[i]);  // inside stays inside despite rounding
      } else {
        z = c[i] * y;
      }
    }
  }
}

}  // namespace smcbench

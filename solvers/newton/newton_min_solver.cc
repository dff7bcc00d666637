// Semismooth Newton on the min function with a Fischer–Burmeister line search (newton_min_solver.h).
//
// Units. G(z) = c∘F(z)/d (d = McpRowScales(J(z₀), c) fixed for the solve, or d = 1 with merit_scaling none; c the
// variables' units) is F in units of z; the min function is Phi_i = (z_i − Π_[l_i,u_i](z_i − G_i))/c_i. Every
// quantity the iteration compares is measured in the units c, as if it ran on y = z/c (`newton` does so explicitly):
// a step's norm is ‖d/c‖, the steepest descent is the gradient in y, −c∘c∘∇Psi, the Newton systems are solved for
// d/c, and the divergence test bounds z/c. So the iterates are the same, up to rounding, after any positive scaling
// of F's rows and any change of units stated through c.
// Iteration (Pang 1990; Qi 1993; Facchinei–Pang 2003 §9.1 and §9.3; Siconos' min_FBLSA):
//   1. the active set of the natural map: z_i − G_i ≤ l_i → row at its lower bound, ≥ u_i → at its upper bound
//      (ties count as active: either choice is an element of ∂_B Phi), otherwise free;
//   2. the min-Newton step Δ, an element of ∂_B Phi applied: Δ_i = bound_i − z_i on the active rows, and on the free
//      rows R the linearization F_R + J_R Δ = 0, i.e. J_RR Δ_R = −F_R − J_RA Δ_A (row scales cancel);
//   3. globalization (fb-line-search): Phi is not differentiable, so the step is judged on the C¹ merit
//      Psi = ½‖Phi_FB(z, G)/c‖² with Billups' box FB function; Δ is used when ∇Psiᵀ Δ ≤ −ρ‖Δ/c‖^p (DFK 1996) and its
//      Armijo search succeeds, else FB's own Newton step under the same test, else the steepest descent.
//      Near a strictly complementary solution the two functions pick the same active set and full min-Newton steps
//      are accepted (local quadratic convergence).
// Stopping test: the verdict's scale-free residual with the row scales of J at the current z (problem.h).
// Linear algebra. Both Newton systems have rows α_i d_i + β_i J_i d = r_i. Dense: rows with β_i = 0 are solved
// directly and the others form the block (J_RR + diag(α/β)_R) C_R, rows equilibrated, Eigen's blocked in-place LU on a
// preallocated buffer (newton's choice: Eigen's PartialPivLU object would reallocate whenever |R| changes); a pivot
// below |R|·ε after row equilibration counts as singular. Sparse: the full n×n system (diag(α) + diag(β) J) C on
// the pattern J ∪ diag, so the pattern is fixed and UMFPACK's symbolic analysis is done once per pattern.
#include "solvers/newton/newton_min_solver.h"

#include <Eigen/LU>
#include <algorithm>
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

constexpr double kEps = std::numeric_limits<double>::epsilon();

using newton::Exit;
static_assert(NewtonMinOptions::kMaxStagnationWindow == newton::MeritWindow::kMaxWindow,
              "the stagnation window's bound is the shared one's");

}  // namespace

bool NewtonMinOptions::IsValid(std::string* why) const {
  const auto fail = [why](const auto&... parts) {
    if (why) {
      std::ostringstream s;
      (s << ... << parts);
      *why = s.str();
    }
    return false;
  };
  if (globalization != kFischerBurmeisterLineSearch && globalization != kNoGlobalization)
    return fail("globalization must be fb-line-search or none, got the code ", static_cast<int>(globalization));
  if (merit_scaling != kJacobianRowScaling && merit_scaling != kNoRowScaling)
    return fail("merit_scaling must be jacobian-rows or none, got the code ", static_cast<int>(merit_scaling));
  if (!newton::ValidArmijoRule(newton::ArmijoRule{armijo_sigma, backtrack_factor, max_backtracks}, why) ||
      !newton::ValidDescentTest(descent_rho, descent_power, why)) {
    return false;
  }
  if (linear_solver < NewtonOptions::kAutoLinearSolver || linear_solver > NewtonOptions::kSparseLinearSolver)
    return fail("linear_solver must be auto, dense or sparse, got the code ", static_cast<int>(linear_solver));
  if (dense_max_size < 0) return fail("dense_max_size must be >= 0, got ", dense_max_size);
  return newton::ValidStagnation(stagnation_window, stagnation_ratio, why);
}

// J, its copies and the sparse system's pattern live in the shared JacobianStore (newton_jacobian.h).
struct NewtonMinSolver::Workspace : newton::JacobianStore {
  // ---- Problem view (set per solve) ----
  const NewtonMinSolver* owner = nullptr;
  const NewtonMinOptions* opt = nullptr;
  const BoxMLCP* box = nullptr;  // F = M z + q (M fixed), or
  const MCP* mcp = nullptr;      // a nonlinear F with its Jacobian
  const Vector* l = nullptr;
  const Vector* u = nullptr;
  int n = 0;
  double tolerance = 1e-10;
  int budget = 0;
  int verbosity = 0;

  // ---- Iterate and work vectors (size n) ----
  Vector z, F, zt, Ft, dir, g, w, Jw, phi, weight_z, weight_F, rhs;
  Vector units;           // c: the variables' units (ones when the problem states none)
  Vector in_units;        // a step or gradient measured in the units c (the norms the tests compare)
  Vector reform_rows;     // d₀: the row scales of the reformulation, fixed for the solve
  Vector stop_rows;       // the row scales of J at z, for the stopping test
  Vector row_eq;          // equilibration of the reduced dense rows
  Vector alpha, beta, r;  // the rows of the Newton system being solved: α_i d_i + β_i J_i d = r_i
  newton::BestIterate best;  // by the scale-free residual

  // ---- Dense linear algebra ----
  DenseMatrix A;         // n×n buffer; the leading |R|×|R| block is used
  Eigen::VectorXi perm;  // row transpositions of the LU
  Eigen::VectorXi ridx;  // the rows R with β ≠ 0 (the free rows of the min-Newton system)

  // ---- The Armijo rule, and Psi at the last stagnation_window + 1 iterations (MeritStagnated) ----
  newton::ArmijoRule armijo;
  newton::MeritWindow psi_history;

  // ---- Counters and the reason of a failure ----
  int iterations = 0, newton_steps = 0, fb_newton_steps = 0, gradient_steps = 0, backtracks = 0, factorizations = 0;
  int max_system = 0;
  const char* failure_detail = "";

  void Resize(int size) {
    if (n == size && z.size() == size) return;
    n = size;
    for (Vector* x : {&z, &F, &zt, &Ft, &dir, &g, &w, &Jw, &phi, &weight_z, &weight_F, &rhs, &best.z, &units,
                      &in_units, &reform_rows, &stop_rows, &row_eq, &alpha, &beta, &r}) {
      x->resize(n);
    }
    perm.resize(n);
    ridx.resize(n);
    A.resize(0, 0);  // allocated on first dense use
    ResetStorage();
  }

  // ---------------------------------------------------------------- F and J
  bool EvalF(const Vector& x, Vector* out) const {
    if (box) {
      box->Affine(x, out);
    } else {
      mcp->Evaluate(x, out);
    }
    return out->allFinite();
  }

  // J at z for an MCP (a box-MLCP's J = M is set up once). False with failure_detail on a Jacobian of the wrong size
  // or with NaN/Inf entries.
  bool UpdateJacobian() {
    if (box) return true;
    if (!native_sparse) {
      if (J_dense.rows() != n || J_dense.cols() != n) J_dense.resize(n, n);
      mcp->JacobianDense(z, &J_dense);
      if (J_dense.rows() != n || J_dense.cols() != n) return Fail("the MCP Jacobian has the wrong size");
      if (!J_dense.allFinite()) return Fail("the MCP Jacobian is NaN/Inf");
      Jd = &J_dense;
      if (!dense_la) {
        J_sparse = J_dense.sparseView();  // forced sparse LA on dense data: converted every iteration
        Js = &J_sparse;
      }
      return true;
    }
    mcp->JacobianSparse(z, &J_sparse);
    if (J_sparse.rows() != n || J_sparse.cols() != n) return Fail("the MCP Jacobian has the wrong size");
    J_sparse.makeCompressed();
    const double* values = J_sparse.valuePtr();
    for (Eigen::Index k = 0; k < J_sparse.nonZeros(); ++k) {
      if (!std::isfinite(values[k])) return Fail("the MCP Jacobian is NaN/Inf");
    }
    Js = &J_sparse;
    if (dense_la) {
      CopySparseToDense(J_sparse);
      Jd = &J_dense;
    }
    return true;
  }

  bool Fail(const char* detail) {
    failure_detail = detail;
    return false;
  }
  Exit Stop(Exit exit, const char* detail) {
    failure_detail = detail;
    return exit;
  }

  void RowScalesOfJ(Vector* d) const {
    const Vector no_units;  // empty: no allocation
    const Vector& c = mcp ? mcp->variable_scale() : no_units;
    if (native_sparse) {
      McpRowScales(*Js, c, d);
    } else {
      McpRowScales(*Jd, c, d);
    }
  }

  // ---------------------------------------------------------------- stopping test
  // The verdict's scale-free residual at (z, F) with the row scales of J at z (stop_rows, refreshed by the caller);
  // a box-MLCP also needs its natural residual ≤ tolerance·(1 + ‖q‖∞), so the value returned is the larger of the
  // two measures.
  double StoppingResidual(const Vector& x, const Vector& Fx) const {
    const Vector no_units;
    const double scaled = McpScaledResidual(x, Fx, *l, *u, stop_rows, mcp ? mcp->variable_scale() : no_units);
    if (!box) return scaled;
    return std::max(scaled, NaturalResidualNorm(x, Fx, *l, *u) / box->residual_scale());
  }

  // ---------------------------------------------------------------- Newton systems α_i d_i + β_i J_i d = r_i
  // Both steps have this row form: the min function's (SetMinNewtonRows) and FB's (SetFischerBurmeisterRows).
  // Rows with β_i = 0 fix d_i = r_i/α_i; the others, divided by β_i, give (J_RR + diag(α/β)_R) d_R = r_R/β_R − J_RT
  // d_T.

  // The min function's active set by the natural map, and its Newton rows: at a bound d_i = bound − z_i
  // (α = 1, β = 0), free F_i + J_i d = 0 (α = 0, β = 1).
  void SetMinNewtonRows() {
    for (int i = 0; i < n; ++i) {
      const double trial = z[i] - units[i] * F[i] / reform_rows[i];
      const double bound = trial <= (*l)[i] ? (*l)[i] : trial >= (*u)[i] ? (*u)[i] : kNaN;
      const bool active = !std::isnan(bound);
      alpha[i] = active ? 1.0 : 0.0;
      beta[i] = active ? 0.0 : 1.0;
      r[i] = active ? bound - z[i] : -F[i];
    }
  }

  // FB's Newton rows ∂phi_i d = −phi_i from MeritGradient's derivatives (De Luca–Facchinei–Kanzow 1996).
  void SetFischerBurmeisterRows() {
    alpha = weight_z;
    beta = weight_F;
    r = -phi;
  }

  // dir = the solution of the system the rows describe. False if it is singular.
  bool SolveNewtonSystem() {
    ++factorizations;
    return dense_la ? SolveDense() : SolveSparse();
  }

  bool SolveDense() {
    int nr = 0;
    bool any_fixed = false;
    for (int i = 0; i < n; ++i) {
      if (beta[i] == 0.0) {
        if (!(alpha[i] != 0.0)) return false;  // an empty row
        dir[i] = r[i] / alpha[i];
        w[i] = dir[i];
        any_fixed = true;
      } else {
        ridx[nr++] = i;
        w[i] = 0.0;
      }
    }
    max_system = std::max(max_system, nr);
    if (nr == 0) return dir.allFinite();
    if (any_fixed) ApplyJ(w, &Jw);  // J_RT d_T (w is zero on R)
    if (A.rows() != n) A.resize(n, n);
    const DenseMatrix& J = *Jd;
    for (int k = 0; k < nr; ++k) row_eq[k] = 0.0;
    // Unknowns d_R/c_R: the block is (J_RR + diag(α/β)_R) C_R, so pivoting and the pivot test see the same
    // matrix whatever the variables' units.
    for (int jj = 0; jj < nr; ++jj) {
      const int j = ridx[jj];
      const double cj = units[j];
      const double* col = J.col(j).data();
      double* a = A.col(jj).data();
      for (int ii = 0; ii < nr; ++ii) a[ii] = col[ridx[ii]] * cj;
      a[jj] += alpha[j] / beta[j] * cj;
      for (int ii = 0; ii < nr; ++ii) row_eq[ii] = std::max(row_eq[ii], std::abs(a[ii]));
    }
    // Rows scaled to max 1 before partial pivoting (a row's scale says nothing about its pivot quality).
    for (int k = 0; k < nr; ++k) {
      if (!(row_eq[k] > 0.0) || !std::isfinite(row_eq[k])) return false;  // a zero row: singular
      row_eq[k] = 1.0 / row_eq[k];
      const int i = ridx[k];
      rhs[k] = (r[i] / beta[i] - (any_fixed ? Jw[i] : 0.0)) * row_eq[k];
    }
    for (int jj = 0; jj < nr; ++jj) A.col(jj).head(nr).array() *= row_eq.head(nr).array();
    int transpositions = 0;
    const Eigen::Index zero_pivot = Eigen::internal::partial_lu_impl<double, Eigen::ColMajor, int>::blocked_lu(
        nr, nr, A.data(), A.outerStride(), perm.data(), transpositions);
    if (zero_pivot >= 0) return false;
    // Rows of max 1: a pivot below |R|·ε is rounding noise on a singular block.
    for (int k = 0; k < nr; ++k) {
      if (!(std::abs(A(k, k)) > nr * kEps)) return false;
    }
    for (int k = 0; k < nr; ++k) {
      if (perm[k] != k) std::swap(rhs[k], rhs[perm[k]]);
    }
    Eigen::Map<DenseMatrix, 0, Eigen::OuterStride<>> a(A.data(), nr, nr, Eigen::OuterStride<>(A.outerStride()));
    auto x = rhs.head(nr);
    a.triangularView<Eigen::UnitLower>().solveInPlace(x);
    a.triangularView<Eigen::Upper>().solveInPlace(x);
    for (int k = 0; k < nr; ++k) dir[ridx[k]] = x[k] * units[ridx[k]];
    return dir.allFinite();
  }

  // The full system H = (diag(α) + diag(β) J) C on the pattern J ∪ diag, for the unknowns d/c: UMFPACK's scaling
  // and pivoting then see the same matrix whatever the variables' units. J's entries are a subset of H's in every
  // column (both with sorted row indices), so one merged pass per column fills H.
  bool SolveSparse() {
    const SparseMatrix& J = *Js;
    EnsureSparsePattern(J);
    double* hv = H.valuePtr();
    const int* h_inner = H.innerIndexPtr();
    const int* h_outer = H.outerIndexPtr();
    const double* jv = J.valuePtr();
    const int* j_inner = J.innerIndexPtr();
    const int* j_outer = J.outerIndexPtr();
    for (int col = 0; col < n; ++col) {
      int k = j_outer[col];
      for (int p = h_outer[col]; p < h_outer[col + 1]; ++p) {
        const int row = h_inner[p];
        double value = 0.0;
        if (k < j_outer[col + 1] && j_inner[k] == row) value = jv[k++];
        hv[p] = (beta[row] * value + (row == col ? alpha[row] : 0.0)) * units[col];
      }
    }
    rhs = r;
    max_system = std::max(max_system, n);
    if (!umf_analyzed) {
      umf.umfpackControl()(UMFPACK_IRSTEP) = 0;  // an inexact step is corrected by the next iteration
      umf.analyzePattern(H);
      if (umf.info() != Eigen::Success) return false;
      umf_analyzed = true;
    }
    umf.factorize(H);
    if (umf.info() != Eigen::Success) return false;  // includes UMFPACK's "singular matrix" warning
    dir = umf.solve(rhs);
    dir.array() *= units.array();
    return umf.info() == Eigen::Success && dir.allFinite();
  }

  // ---------------------------------------------------------------- the Fischer–Burmeister merit
  // Psi(x) = ½ Σ (Phi_FB(x_i, c_i F_i/d_i)/c_i)² (FB is positively homogeneous: this is FB in the units c).
  double Merit(const Vector& x, const Vector& Fx) const {
    double s = 0.0;
    for (int i = 0; i < n; ++i) {
      const double p = fb::BoxPhi(x[i], units[i] * Fx[i] / reform_rows[i], (*l)[i], (*u)[i]) / units[i];
      s += p * p;
    }
    return 0.5 * s;  // NaN propagates
  }

  // g = ∇Psi(z) = (Da/c)∘phi + Jᵀ((Db/d)∘phi), phi the scaled FB values. Psi is C¹ (its kinks are zeros of
  // Phi_FB), so any element of ∂_B Phi_FB gives the same gradient.
  void MeritGradient() {
    fb::RowDerivative rd;
    for (int i = 0; i < n; ++i) {
      double value;
      fb::BoxPhiDerivative(z[i], units[i] * F[i] / reform_rows[i], (*l)[i], (*u)[i], 1.0, 0.0, &value, &rd);
      phi[i] = value / units[i];
      weight_z[i] = rd.da / units[i];
      weight_F[i] = rd.db / reform_rows[i];
    }
    w.array() = weight_F.array() * phi.array();
    ApplyJt(w, &g);
    g.array() += weight_z.array() * phi.array();
  }

  // Armijo backtracking from t = 1 along dir. On success zt, Ft hold the accepted point and *psi_out its merit.
  bool LineSearch(double psi, double gd, double* psi_out, bool* all_nan) {
    if (box) box->Multiply(dir, &Jw);  // F(z + t d) = F + t M d: no product per trial
    const auto merit_at = [this](double t, double* psi_t) {
      zt = z + t * dir;
      bool finite = true;
      if (box) {
        Ft = F + t * Jw;
      } else {
        finite = EvalF(zt, &Ft);
      }
      if (finite) *psi_t = Merit(zt, Ft);
      return finite;
    };
    double t = 0.0;
    return newton::ArmijoBacktrack(armijo, psi, gd, merit_at, psi_out, &t, all_nan, &backtracks);
  }

  // Records Psi after `iterations` steps; true if it is above stagnation_ratio × its value stagnation_window steps
  // earlier (the iterates crawl towards a minimizer of Psi that is not a solution, or cycle).
  bool MeritStagnated(double psi) {
    psi_history.Record(iterations, psi);
    return psi_history.Stagnated(iterations, psi, opt->stagnation_ratio);
  }

  // dir if it passes the DFK sufficient-descent test and its Armijo search (then zt, Ft, *psi_new are the new point).
  // ∇Psiᵀd does not depend on the units; ‖d‖ is measured in them (‖d/c‖).
  bool TryDirection(double psi, double* psi_new, bool* all_nan) {
    const double gd = g.dot(dir);
    in_units.array() = dir.array() / units.array();
    return newton::SufficientDescent(gd, in_units.norm(), opt->descent_rho, opt->descent_power) &&
           LineSearch(psi, gd, psi_new, all_nan);
  }

  // ---------------------------------------------------------------- the iteration
  Exit Run() {
    const NewtonMinOptions& o = *opt;
    const bool globalized = o.globalization == NewtonMinOptions::kFischerBurmeisterLineSearch;
    if (!EvalF(z, &F)) return Stop(Exit::kNumericalFailure, "F is NaN/Inf at the starting point");
    if (!UpdateJacobian()) return Exit::kNumericalFailure;
    if (o.merit_scaling == NewtonMinOptions::kJacobianRowScaling) {
      RowScalesOfJ(&reform_rows);
    } else {
      reform_rows.setOnes();
    }
    if (!reform_rows.allFinite()) return Stop(Exit::kNumericalFailure, "the Jacobian's row scales are not finite");
    double psi = globalized ? Merit(z, F) : 0.0;
    for (;;) {
      if (box == nullptr || iterations == 0) RowScalesOfJ(&stop_rows);  // a box-MLCP's J = M never changes
      const double residual = StoppingResidual(z, F);
      best.Track(residual, z);
      if (residual <= tolerance) return Exit::kConverged;
      if (iterations >= budget) return Exit::kBudget;
      if (owner->TimeLimitReached()) return Exit::kTimeLimit;
      if (globalized && MeritStagnated(psi)) {
        return Stop(Exit::kStalled, "the merit function stagnated at a point that is not a solution");
      }
      ++iterations;

      SetMinNewtonRows();
      const bool min_ok = SolveNewtonSystem();
      const char* step = "min-newton";
      if (!globalized) {
        if (!min_ok) return Stop(Exit::kSingular, "the min-Newton system is singular");
        zt = z + dir;
        if (!EvalF(zt, &Ft)) return Stop(Exit::kNumericalFailure, "F is NaN/Inf at the full min-Newton step");
        ++newton_steps;
      } else {
        MeritGradient();
        if (!g.allFinite()) return Stop(Exit::kNumericalFailure, "the merit-function gradient is NaN/Inf");
        // Directions in order, each used if it passes the DFK descent test and its Armijo search: the min-Newton
        // step; FB's Newton step (where the two functions disagree on the active set, e.g. a free row whose
        // Newton system has no nearby solution); the steepest descent −∇Psi.
        double psi_new = psi;
        bool all_nan = false, any_system = min_ok;
        bool accepted = min_ok && TryDirection(psi, &psi_new, &all_nan);
        newton_steps += accepted;
        if (!accepted && o.fischer_burmeister_step) {
          step = "fb-newton";
          SetFischerBurmeisterRows();
          const bool fb_ok = SolveNewtonSystem();
          any_system |= fb_ok;
          accepted = fb_ok && TryDirection(psi, &psi_new, &all_nan);
          fb_newton_steps += accepted;
        }
        if (!accepted) {
          step = "gradient";
          ++gradient_steps;
          // Steepest descent in the units c: ∇Psi with respect to z/c is c∘g, so d = −c∘(c∘g), ∇Psiᵀd = −‖c∘g‖².
          in_units.array() = units.array() * g.array();
          dir.array() = -(units.array() * in_units.array());
          const double gd = -in_units.squaredNorm();
          if (!(gd < 0.0)) {
            return any_system
                       ? Stop(Exit::kStalled, "the merit function is stationary at a point that is not a solution")
                       : Stop(Exit::kSingular,
                              "the Newton systems are singular and the merit-function gradient is zero");
          }
          if (!LineSearch(psi, gd, &psi_new, &all_nan)) {
            if (all_nan) return Stop(Exit::kNumericalFailure, "F is NaN/Inf at every trial point of the line search");
            return Stop(Exit::kStalled, "the line search failed along every direction");
          }
        }
        if (box) box->Affine(zt, &Ft);  // exact F at the accepted point (the search used F + t M d)
        psi = psi_new;
      }
      if (verbosity >= 2) {
        std::fprintf(stderr, "newton-min %4d residual %.3e psi %.3e step %s\n", iterations, residual, psi, step);
      }
      if (!newton::StepMoved(z, zt)) return Stop(Exit::kStalled, "the step length collapsed to rounding level");
      z.swap(zt);
      F.swap(Ft);
      if (!newton::IterateBounded((z.array() / units.array()).abs().maxCoeff())) {
        return Stop(Exit::kDiverged, "the iterates grew without bound");
      }
      if (!UpdateJacobian()) return Exit::kNumericalFailure;
    }
  }

  // A converged z may lie outside [l, u] (free rows are not clamped): keep its projection when it still passes.
  void ProjectIfItPasses() {
    bool outside = false;
    for (int i = 0; i < n; ++i) {
      zt[i] = std::min(std::max(z[i], (*l)[i]), (*u)[i]);
      outside |= zt[i] != z[i];
    }
    if (outside && EvalF(zt, &Ft) && StoppingResidual(zt, Ft) <= tolerance) z.swap(zt);
  }

  void Conclude(Exit exit, SolveResult* result) {
    if (exit == Exit::kConverged) {
      ProjectIfItPasses();
    } else if (best.residual < kInf) {
      z = best.z;
    }
    result->z = z;
    result->iterations = iterations;
    newton::ReportExit(exit, failure_detail, iterations, budget, /*rounds=*/0, "scale-free residual", best.residual,
                       result);
    result->SetDetail("newton_steps", newton_steps);
    result->SetDetail("fb_newton_steps", fb_newton_steps);
    result->SetDetail("gradient_steps", gradient_steps);
    result->SetDetail("backtracks", backtracks);
    result->SetDetail("factorizations", factorizations);
    result->SetDetail("max_system_size", max_system);
    if (verbosity >= 1) {
      std::fprintf(stderr, "newton-min: %s after %d iterations (%d min-Newton, %d FB-Newton, %d gradient steps)\n",
                   exit == Exit::kConverged ? "solved" : "not solved", iterations, newton_steps, fb_newton_steps,
                   gradient_steps);
    }
  }
};

NewtonMinSolver::NewtonMinSolver() : ws_(std::make_unique<Workspace>()) {}
NewtonMinSolver::NewtonMinSolver(const NewtonMinOptions& options)
    : BackendWithOptions(options), ws_(std::make_unique<Workspace>()) {}
NewtonMinSolver::~NewtonMinSolver() = default;

const SolverInfo& NewtonMinSolver::info() const {
  static const SolverInfo kInfo{
      "newton-min",
      "semismooth Newton on the min (natural-map) function: active-set Newton steps checked by an Armijo line "
      "search on the Fischer-Burmeister merit, FB-Newton then gradient fallback; dense reduced LU or UMFPACK",
      "Pang 1990 (Math. Oper. Res. 15); Qi 1993 (Math. Oper. Res. 18); Facchinei, Pang 2003 (ch. 9); "
      "De Luca, Facchinei, Kanzow 1996 (Math. Prog. 75)",
      /*dense=*/true,
      /*sparse=*/true,
      /*symmetric_only=*/false,
      /*exact=*/false,
      /*mcp=*/true,
      /*default_size_limit=*/0};
  return kInfo;
}

bool NewtonMinSolver::ValidateBackendOptions(std::string* why) const { return options_.IsValid(why); }

void NewtonMinSolver::BindOptions(OptionBinder* b) {
  NewtonMinOptions& o = options_;
  b->Add("globalization", &o.globalization,
         {{"fb-line-search", NewtonMinOptions::kFischerBurmeisterLineSearch},
          {"none", NewtonMinOptions::kNoGlobalization}},
         "fb-line-search (Armijo on the Fischer-Burmeister merit, gradient fallback) or none (full min-Newton steps)");
  b->Add("merit_scaling", &o.merit_scaling,
         {{"jacobian-rows", NewtonMinOptions::kJacobianRowScaling}, {"none", NewtonMinOptions::kNoRowScaling}},
         "jacobian-rows (F_i / max_j |J_ij| c_j at the start: invariant under row scaling) or none (F as given)");
  b->Add("armijo_sigma", &o.armijo_sigma, "Armijo constant sigma in (0, 0.5)");
  b->Add("backtrack_factor", &o.backtrack_factor, "step-length reduction factor in (0, 1)");
  b->Add("max_backtracks", &o.max_backtracks, "trial steps per line search");
  b->Add("fischer_burmeister_step", &o.fischer_burmeister_step,
         "try FB's Newton step when the min-Newton step is rejected, before the gradient step");
  b->Add("descent_rho", &o.descent_rho, "DFK descent test grad'd <= -rho ||d||^p: rho");
  b->Add("descent_power", &o.descent_power, "DFK descent test: p (> 2)");
  b->Add("stagnation_window", &o.stagnation_window, "iterations over which the merit must fall (max 64)");
  b->Add("stagnation_ratio", &o.stagnation_ratio, "required decrease factor of the merit over the window");
  b->Add("linear_solver", &o.linear_solver,
         {{"auto", NewtonOptions::kAutoLinearSolver},
          {"dense", NewtonOptions::kDenseLinearSolver},
          {"sparse", NewtonOptions::kSparseLinearSolver}},
         "auto (dense LU for dense and small sparse data), dense (LU of the free rows), sparse (UMFPACK)");
  b->Add("dense_max_size", &o.dense_max_size, "auto: sparse data up to this size are factorized densely");
}

void NewtonMinSolver::SetUpSolve(int n, const Vector& l, const Vector& u, bool native_sparse) {
  Workspace& ws = *ws_;
  ws.Resize(n);
  ws.owner = this;
  ws.opt = &options_;
  ws.l = &l;
  ws.u = &u;
  ws.ChooseAlgebra(options_.linear_solver, options_.dense_max_size, n, native_sparse);
}

void NewtonMinSolver::RunAndConclude(const SolverOptions& options, SolveResult* result) {
  Workspace& ws = *ws_;
  ws.tolerance = options.tolerance;
  ws.verbosity = options.verbosity;
  ws.budget = IterationBudget(options, kDefaultMaxIterations);
  ws.iterations = ws.newton_steps = ws.fb_newton_steps = ws.gradient_steps = ws.backtracks = 0;
  ws.factorizations = ws.max_system = 0;
  ws.best.Reset();
  ws.psi_history.SetWindow(options_.stagnation_window);
  ws.armijo = newton::ArmijoRule{options_.armijo_sigma, options_.backtrack_factor, options_.max_backtracks};
  ws.failure_detail = "";
  ws.z = result->z;
  ws.Conclude(ws.Run(), result);
}

void NewtonMinSolver::DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) {
  SetUpSolve(problem.size(), problem.l(), problem.u(), problem.is_sparse());
  Workspace& ws = *ws_;
  ws.box = &problem;
  ws.mcp = nullptr;
  ws.units.setOnes();
  ws.BindBoxMatrix(problem);
  RunAndConclude(options, result);
}

void NewtonMinSolver::DoSolveMCP(const MCP& problem, const SolverOptions& options, SolveResult* result) {
  SetUpSolve(problem.size(), problem.l(), problem.u(), problem.jacobian_kind() == MCP::JacobianKind::kSparse);
  Workspace& ws = *ws_;
  ws.box = nullptr;
  ws.mcp = &problem;
  if (problem.variable_scale().size() == problem.size()) {
    ws.units = problem.variable_scale();
  } else {
    ws.units.setOnes();
  }
  RunAndConclude(options, result);
}

}  // namespace smcbench

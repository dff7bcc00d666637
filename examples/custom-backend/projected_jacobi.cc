// Projected Jacobi (projected_jacobi.h): the iteration, its safeguards and its options.
#include "projected_jacobi.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace example {
namespace {

using smcbench::BoxMLCP;
using smcbench::SolveResult;
using smcbench::SolveStatus;
using smcbench::Vector;

// diag(M) and the row sums of |M|, for dense or sparse M.
void DiagonalAndRowSums(const BoxMLCP& problem, Vector* diagonal, Vector* row_sums) {
  if (problem.is_sparse()) {
    const smcbench::SparseMatrix& M = problem.sparse_matrix();
    *diagonal = Vector::Zero(problem.size());
    *row_sums = Vector::Zero(problem.size());
    for (int j = 0; j < M.outerSize(); ++j) {
      for (smcbench::SparseMatrix::InnerIterator it(M, j); it; ++it) {
        if (it.row() == j) (*diagonal)[j] += it.value();
        (*row_sums)[it.row()] += std::abs(it.value());
      }
    }
  } else {
    const smcbench::DenseMatrix& M = problem.dense_matrix();
    *diagonal = M.diagonal();
    *row_sums = M.cwiseAbs().rowwise().sum();
  }
}

double NaturalResidual(const Vector& z, const Vector& w, const Vector& l, const Vector& u) {
  return (z - (z - w).cwiseMax(l).cwiseMin(u)).lpNorm<Eigen::Infinity>();
}

}  // namespace

bool ProjectedJacobiOptions::IsValid(std::string* why) const {
  if (!(omega == 0.0 || (omega > 0.0 && omega < 2.0))) {
    *why = "pjacobi: omega must be 0 (automatic) or lie in (0, 2)";
    return false;
  }
  if (stall_iterations < 0) {
    *why = "pjacobi: stall_iterations must be >= 0 (0 disables the stall test)";
    return false;
  }
  if (!(divergence_threshold > 1.0)) {
    *why = "pjacobi: divergence_threshold must be > 1";
    return false;
  }
  return true;
}

const smcbench::SolverInfo& ProjectedJacobiSolver::info() const {
  static const smcbench::SolverInfo kInfo{
      kName,
      "projected damped Jacobi z <- P(z - omega D^-1 (Mz+q)); SPD or diagonally dominant M (example backend)",
      "Cottle, Pang, Stone: The Linear Complementarity Problem (1992), sec. 5.2 (projected splitting methods)",
      /*dense=*/true,
      /*sparse=*/true};
  return kInfo;
}

void ProjectedJacobiSolver::BindOptions(smcbench::OptionBinder* binder) {
  binder->Add("omega", &options_.omega, "relaxation in (0,2); 0 = automatic 1/|D^-1 M|inf");
  binder->Add("stall_iterations", &options_.stall_iterations,
              "stalled if the best residual does not halve within this many iterations (0: off)");
  binder->Add("divergence_threshold", &options_.divergence_threshold,
              "diverged once |z|inf > this * (1 + |z0|inf + |q|inf / min M_ii)");
}

bool ProjectedJacobiSolver::ValidateBackendOptions(std::string* why) const { return options_.IsValid(why); }

void ProjectedJacobiSolver::DoSolve(const BoxMLCP& problem, const smcbench::SolverOptions& options,
                                    SolveResult* result) {
  const int n = problem.size();
  const Vector& l = problem.l();
  const Vector& u = problem.u();
  Vector diagonal, row_sums;
  DiagonalAndRowSums(problem, &diagonal, &row_sums);

  // Rows that can move need a positive diagonal; ‖D⁻¹M‖∞ over them gives the automatic ω.
  double bound = 0.0, min_diagonal = smcbench::kInf;
  step_.resize(n);
  for (int i = 0; i < n; ++i) {
    if (l[i] == u[i]) continue;
    if (!(diagonal[i] > 0.0)) {
      result->status = SolveStatus::kNotApplicable;
      result->message = "pjacobi: M(" + std::to_string(i) + "," + std::to_string(i) + ") = " +
                        std::to_string(diagonal[i]) + " is not positive";
      return;
    }
    bound = std::max(bound, row_sums[i] / diagonal[i]);
    min_diagonal = std::min(min_diagonal, diagonal[i]);
  }
  const double omega = options_.omega > 0.0 ? options_.omega : (bound > 0.0 ? 1.0 / bound : 1.0);
  for (int i = 0; i < n; ++i) step_[i] = l[i] == u[i] ? 0.0 : omega / diagonal[i];
  result->SetDetail("omega", omega);

  Vector& z = result->z;  // the base put the starting point here
  const double q_norm = problem.q().lpNorm<Eigen::Infinity>();
  const double divergence = options_.divergence_threshold *
                            (1.0 + z.lpNorm<Eigen::Infinity>() + (n > 0 ? q_norm / min_diagonal : 0.0));
  const int budget = IterationBudget(options, kDefaultMaxIterations);
  double best = smcbench::kInf;
  int best_at = 0;
  for (int k = 0;; ++k) {
    problem.Affine(z, &w_);
    const double residual = NaturalResidual(z, w_, l, u);
    const double z_norm = z.lpNorm<Eigen::Infinity>();
    result->iterations = k;
    if (!std::isfinite(residual) || !std::isfinite(z_norm)) {
      result->status = SolveStatus::kNumericalFailure;
      result->message = "pjacobi: the iterate is not finite after " + std::to_string(k) + " iterations";
      return;
    }
    if (residual <= options.tolerance * (1.0 + std::min(z_norm, q_norm))) {
      result->status = SolveStatus::kSolved;
      return;
    }
    if (z_norm > divergence) {
      result->status = SolveStatus::kDiverged;
      result->message = "pjacobi: |z|inf = " + std::to_string(z_norm) + " after " + std::to_string(k) +
                        " iterations (omega " + std::to_string(omega) + ")";
      return;
    }
    if (residual < 0.5 * best) {
      best = residual;
      best_at = k;
    } else if (options_.stall_iterations > 0 && k - best_at >= options_.stall_iterations) {
      result->status = SolveStatus::kStalled;
      result->message = "pjacobi: the residual did not halve in " + std::to_string(options_.stall_iterations) +
                        " iterations (best " + std::to_string(best) + ")";
      return;
    }
    if (k >= budget) {
      result->status = SolveStatus::kIterationLimit;
      result->message = "pjacobi: " + std::to_string(budget) + " iterations, residual " + std::to_string(residual);
      return;
    }
    if (TimeLimitReached()) {
      result->status = SolveStatus::kTimeLimit;
      result->message = "pjacobi: time limit after " + std::to_string(k) + " iterations";
      return;
    }
    z = (z - step_.cwiseProduct(w_)).cwiseMax(l).cwiseMin(u);
  }
}

}  // namespace example

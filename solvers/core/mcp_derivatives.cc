#include "solvers/core/mcp_derivatives.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "solvers/core/number_text.h"

namespace smcbench {

void CentralDifferenceJacobian(const MCP& problem, const Vector& z, DenseMatrix* J) {
  const int n = problem.size();
  if (z.size() != n) {
    throw InvalidInputError("central differences: z has size " + std::to_string(z.size()) + ", the MCP has " +
                            std::to_string(n) + " unknowns");
  }
  const double eps = std::numeric_limits<double>::epsilon();
  const double central = std::cbrt(eps), one_sided = std::sqrt(eps);
  J->resize(n, n);
  Vector zp = z, zm = z, Fp(n), Fm(n);
  for (int j = 0; j < n; ++j) {
    const double scale = std::max(1.0, std::abs(z[j]));
    const double h = central * scale, h1 = one_sided * scale;
    const double lo = problem.l()[j], hi = problem.u()[j];
    // The two points; one-sided inward (step ε^{1/2} scale, that difference's balance) when one would leave
    // [l_j, u_j] and the box has room.
    double plus = z[j] + h, minus = z[j] - h;
    if (minus < lo && z[j] + h1 <= hi) {
      minus = z[j];
      plus = z[j] + h1;
    } else if (plus > hi && z[j] - h1 >= lo) {
      plus = z[j];
      minus = z[j] - h1;
    }
    zp[j] = plus;
    zm[j] = minus;
    problem.Evaluate(zp, &Fp);
    problem.Evaluate(zm, &Fm);
    J->col(j) = (Fp - Fm) / (zp[j] - zm[j]);  // the realised step: exact in binary
    zp[j] = z[j];
    zm[j] = z[j];
  }
}

JacobianCheck CheckMcpJacobian(const MCP& problem, const Vector& z, const JacobianCheckOptions& options) {
  if (!(options.tolerance > 0.0)) {
    throw InvalidInputError("derivative check: tolerance must be > 0, got " + NumberText(options.tolerance));
  }
  if (z.size() != problem.size()) {
    throw InvalidInputError("derivative check: z has size " + std::to_string(z.size()) + ", the MCP has " +
                            std::to_string(problem.size()) + " unknowns");
  }
  if (!z.allFinite()) throw InvalidInputError("derivative check: z is not finite");
  const int n = problem.size();
  DenseMatrix analytic(n, n), difference;
  if (problem.jacobian_kind() == MCP::JacobianKind::kSparse) {
    SparseMatrix sparse(n, n);
    problem.JacobianSparse(z, &sparse);
    analytic = DenseMatrix(sparse);
  } else {
    problem.JacobianDense(z, &analytic);
  }
  CentralDifferenceJacobian(problem, z, &difference);

  JacobianCheck check;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double a = analytic(i, j), d = difference(i, j);
      double error = std::abs(a - d) / std::max(1.0, std::abs(d));
      if (std::isnan(error)) error = std::numeric_limits<double>::infinity();
      if (error > options.tolerance) ++check.wrong_entries;
      if (error > check.max_error) {
        check.max_error = error;
        check.row = i;
        check.col = j;
        check.analytic = a;
        check.finite_difference = d;
      }
    }
  }
  check.ok = check.wrong_entries == 0;
  if (!check.ok) {
    check.message = "derivative check: J[" + std::to_string(check.row) + ", " + std::to_string(check.col) +
                    "] = " + NumberText(check.analytic) + " but central differences give " +
                    NumberText(check.finite_difference) + " (relative error " + NumberText(check.max_error) +
                    " > " + NumberText(options.tolerance) + "; " + std::to_string(check.wrong_entries) + " of " +
                    std::to_string(n * n) + " entries differ)";
  }
  return check;
}

}  // namespace smcbench

// The MCP's merit function, one home for Solver::Solve and JudgeMCP (verdict.h): internal (not installed), since
// its workspace is storage a caller keeps between solves, not API.
#pragma once

#include <string>

#include "solvers/core/problem.h"
#include "solvers/core/types.h"

namespace smcbench::internal {

// The storage of McpMerit, kept so that repeated MCP solves of one size do not allocate.
struct McpMeritWorkspace {
  Vector scale_point;            // Π(0)
  DenseMatrix jacobian_dense;    // the Jacobian at z, of the kind the problem provides
  SparseMatrix jacobian_sparse;
  Vector row_scale;              // McpRowScales of it
};

// The MCP's merit function at z. Into *r: abs = ‖z − Π(z − F)‖∞, rel = abs / (1 + ‖F(Π(0))‖∞) (information only: not
// invariant under row scaling) and scaled = McpScaledResidual with the row scales of the Jacobian at z, the one that
// decides "solved". *F receives F(z). False with *why when F or the Jacobian throws (std::runtime_error,
// std::logic_error; other exceptions propagate, as in Solver::Solve), the Jacobian has the wrong size, or z has the
// wrong size (the entries of *r not computed stay +∞). A z or F(z) with NaN/Inf has r = +∞ and returns true; no
// Jacobian is asked for there.
bool McpMerit(const MCP& problem, const Vector& z, Vector* F, McpMeritWorkspace* workspace, Residual* r,
              std::string* why);

}  // namespace smcbench::internal

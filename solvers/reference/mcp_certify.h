// Certified reference solutions of small nonlinear MCPs, refined and verified in __float128, so that an MCP
// backend's answer is judged by its forward error as a box-MLCP's is (solvers/reference/certify.h for the box).
//
// Method. For each candidate point (a backend's answer, a published solution), projected onto the box: its active
// set is read off the scale-free natural map (row scales d_i = max_j |J_ij| c_j at the point, McpRowScales; a row
// is at its lower bound when z_i − c_i F_i/d_i ≤ l_i, at its upper when ≥ u_i, else free); Newton's method in quad
// solves the reduced system (bound rows fixed at their bounds, F_F(z) = 0), with complete-pivoting LU and step
// halving when F is NaN or the residual grows. At the limit z*, with A = D_F⁻¹ J_FF C_F (C = diag(c), c the
// variable units) and μ = ‖A⁻¹‖∞, the margin δ = 64 n ε (1 + μ)(1 + ‖C⁻¹z*‖∞) + 4 μ ‖D_F⁻¹F_F(z*)‖∞ (ε = 2⁻¹¹²;
// the rounding of the evaluation plus the forward error of the remaining reduced residual, in units of z) must
// separate every
// condition from failure: free rows inside [l, u] within δ, bound rows with c_i F_i/d_i of the right sign within δ,
// A nonsingular (no pivot below 1e-28 of the largest entry) and δ ≤ 1e-10 (1 + ‖C⁻¹z*‖∞). A violated condition
// moves the row to the other state and the set is tried again (at most max_set_changes times per candidate).
// Sparse problems above max_size take a banded path: the same steps with A in band storage, factored without
// pivoting, μ = ‖A⁻¹e‖∞ when A is a Z-matrix and A⁻¹e > 0 (then A is an M-matrix and A⁻¹ ≥ 0); otherwise no
// certificate.
//
// Certificates (solvers/core/verdict.h). Several distinct verified points: each kNonUnique. One point: kUnique when
// the problem declares a property implying uniqueness (ExtendedPrecisionMCP::solution_set_property; a P-function is
// checked at z* through the principal minors of J for n ≤ 10, strong monotonicity through the symmetric part of
// J) and z* is strictly complementary; kDegenerate when declared but some row is within δ of the other state;
// kIsolated without such a declaration when z* is strictly complementary, or degenerate with A nonsingular for the
// degenerate rows both at their bounds and free (locally unique, as the box certifier decides); kNoneFound
// otherwise. condition = μ at z* (the larger of the two choices for degenerate rows): the verdict's forward-error
// allowance uses it.
#pragma once

#include <vector>

#include "solvers/core/extended_precision_mcp.h"
#include "solvers/core/verdict.h"

namespace smcbench {

struct McpCertifyOptions {
  int max_size = 64;               // dense path up to this n
  // Larger problems with jacobian_kind() kSparse up to this n take the banded path (reduced Jacobian in band
  // storage, LU without pivoting; certified only when it is an M-matrix, which bounds μ by one solve); others, and
  // bands wider than max_bandwidth, are not attempted or not certified (kNone / kNoneFound).
  int max_banded_size = 10000;
  int max_bandwidth = 128;
  int max_newton_iterations = 80;  // per active set
  int max_set_changes = 16;        // active-set corrections per candidate
};

// One verified solution.
struct McpCertifiedSolution {
  ReferenceSolution reference;  // certificate, z* rounded to double, condition μ
  std::vector<Quad> z;          // z* in quad
  double margin = 0.0;          // δ, in units of z (variable_scale)
  bool degenerate = false;      // some row within δ of the other state
  int newton_iterations = 0;    // of the set that verified it
};

// Every distinct solution verified from the candidates, in the order found (candidates of the wrong size or with
// non-finite entries are skipped). A point that meets every condition but cannot be certified (degenerate, no
// declared property, a singular alternative block) is listed with kNoneFound and an empty reference.z. Empty when
// none verifies or the problem is not attempted. Never throws for a valid problem.
std::vector<McpCertifiedSolution> CertifyMCPSolutions(const ExtendedPrecisionMCP& problem,
                                                      const std::vector<Vector>& candidates,
                                                      const McpCertifyOptions& options = {});

// The reference of problem: the first solution CertifyMCPSolutions verifies (kNonUnique when it found several),
// kNoneFound when it found none, kNone when the problem is not attempted (size limits above).
ReferenceSolution CertifyMCP(const ExtendedPrecisionMCP& problem, const std::vector<Vector>& candidates,
                             const McpCertifyOptions& options = {});

}  // namespace smcbench

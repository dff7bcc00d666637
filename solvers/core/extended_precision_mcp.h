// MCPs whose F and Jacobian can also be evaluated in GCC's/clang's __float128 (113-bit significand), so that a
// reference solution is refined and verified in extended precision (solvers/reference/mcp_certify.h), as the
// box-MLCP's references are (solvers/reference/certify.h).
#pragma once

#include <string_view>
#include <vector>

#include "solvers/core/problem.h"

namespace smcbench {

// The extended-precision scalar: +, −, ×, ÷ and comparisons come from libgcc; no libquadmath call is needed.
using Quad = __float128;

// What the problem's author knows about its solution set; the certifier trusts it (and checks it at the answer
// where that is cheap). Append-only, explicit values.
enum class SolutionSetProperty : int {
  kNone = 0,              // nothing known: at best a locally unique (isolated) solution is certified
  kPFunction = 1,         // F is a P-function on the box (e.g. ∇F a P-matrix on the whole box, Moré–Rheinboldt
                          // 1973): at most one solution
  kStronglyMonotone = 2,  // (F(x) − F(y))ᵀ(x − y) ≥ c‖x − y‖² on the box: exactly one solution
  kUniqueByProof = 3,     // uniqueness proved for this instance (the proof is in the problem's comment)
};
std::string_view ToString(SolutionSetProperty value);  // "none", "P-function", "strongly monotone", "unique by proof"

// One Jacobian entry ∂F_row/∂z_col in quad.
struct QuadEntry {
  int row = 0;
  int col = 0;
  Quad value = 0;
};

class ExtendedPrecisionMCP : public MCP {
 public:
  using MCP::MCP;

  // F(z) in quad; z and F have size() entries. NaN where F is undefined (outside the box, for some problems).
  virtual void EvaluateQuad(const Quad* z, Quad* F) const = 0;
  // ∂F/∂z at z in quad, dense column-major size()×size() (every entry written).
  virtual void JacobianQuad(const Quad* z, Quad* J) const = 0;
  // The same Jacobian as entries (an (i, j) listed twice is summed), for problems too large for the dense n×n of
  // JacobianQuad (the certifier's banded path). Default: the nonzeros of JacobianQuad (an n² workspace).
  virtual void JacobianQuadEntries(const Quad* z, std::vector<QuadEntry>* entries) const {
    const int n = size();
    std::vector<Quad> J(static_cast<std::size_t>(n) * n);
    JacobianQuad(z, J.data());
    entries->clear();
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const Quad v = J[static_cast<std::size_t>(j) * n + i];
        if (v != 0) entries->push_back({i, j, v});
      }
    }
  }
  // What is known about the solution set (the certifier's `unique` needs more than kNone).
  virtual SolutionSetProperty solution_set_property() const { return SolutionSetProperty::kNone; }
};

inline std::string_view ToString(SolutionSetProperty value) {
  switch (value) {
    case SolutionSetProperty::kNone: return "none";
    case SolutionSetProperty::kPFunction: return "P-function";
    case SolutionSetProperty::kStronglyMonotone: return "strongly monotone";
    case SolutionSetProperty::kUniqueByProof: return "unique by proof";
  }
  return "unknown";
}

}  // namespace smcbench

// Small nonlinear MCPs of the literature that the backends' tests share, as FunctionMCPs (the built-in library's
// templated versions, problems/mcp, are above the solvers' layer).
#pragma once

#include <cmath>

#include "solvers/core/problem.h"

namespace smcbench {

// Josephy's NCP (MCPLIB "josephy"; Kojima–Shindo's companion problem), z ≥ 0: the unique nondegenerate solution is
// JosephySolution() = (√6/2, 0, 0, 1/2); MCPLIB's first starts are 0 and (1, 1, 1, 1).
inline FunctionMCP JosephyMcp() {
  return FunctionMCP(
      Vector::Zero(4), Vector::Constant(4, kInf),
      [](const Vector& x, Vector* F) {
        (*F)[0] = 3 * x[0] * x[0] + 2 * x[0] * x[1] + 2 * x[1] * x[1] + x[2] + 3 * x[3] - 6;
        (*F)[1] = 2 * x[0] * x[0] + x[0] + x[1] * x[1] + 3 * x[2] + 2 * x[3] - 2;
        (*F)[2] = 3 * x[0] * x[0] + x[0] * x[1] + 2 * x[1] * x[1] + 2 * x[2] + 3 * x[3] - 1;
        (*F)[3] = x[0] * x[0] + 3 * x[1] * x[1] + 2 * x[2] + 3 * x[3] - 3;
      },
      [](const Vector& x, DenseMatrix* J) {
        *J << 6 * x[0] + 2 * x[1], 2 * x[0] + 4 * x[1], 1, 3,  //
            4 * x[0] + 1, 2 * x[1], 3, 2,                      //
            6 * x[0] + x[1], x[0] + 4 * x[1], 2, 3,            //
            2 * x[0], 6 * x[1], 2, 3;
      },
      "josephy");
}

inline Vector JosephySolution() {
  Vector z(4);
  z << std::sqrt(6.0) / 2, 0, 0, 0.5;
  return z;
}

// Kojima–Shindo's NCP (Kojima, Shindo 1986, J. Oper. Res. Soc. Japan 29; MCPLIB `kojshin`): it differs from Josephy's
// in F2 (10 x3) and F3 (9 x4 − 9), and has two solutions, (1, 0, 3, 0) and (√6/2, 0, 0, 1/2).
inline FunctionMCP KojimaShindoMcp() {
  return FunctionMCP(
      Vector::Zero(4), Vector::Constant(4, kInf),
      [](const Vector& x, Vector* F) {
        (*F)[0] = 3 * x[0] * x[0] + 2 * x[0] * x[1] + 2 * x[1] * x[1] + x[2] + 3 * x[3] - 6;
        (*F)[1] = 2 * x[0] * x[0] + x[0] + x[1] * x[1] + 10 * x[2] + 2 * x[3] - 2;
        (*F)[2] = 3 * x[0] * x[0] + x[0] * x[1] + 2 * x[1] * x[1] + 2 * x[2] + 9 * x[3] - 9;
        (*F)[3] = x[0] * x[0] + 3 * x[1] * x[1] + 2 * x[2] + 3 * x[3] - 3;
      },
      [](const Vector& x, DenseMatrix* J) {
        *J << 6 * x[0] + 2 * x[1], 2 * x[0] + 4 * x[1], 1, 3,  //
            4 * x[0] + 1, 2 * x[1], 10, 2,                     //
            6 * x[0] + x[1], x[0] + 4 * x[1], 2, 9,            //
            2 * x[0], 6 * x[1], 2, 3;
      },
      "kojshin");
}

// Billups' example (thesis 1995): F(x) = (x − 1)² − 1.01, x ≥ 0; the solution is 1 + √1.01. From x = 0 (F = −0.01)
// a Newton step on the Fischer–Burmeister function leaves the box towards the infeasible root 1 − √1.01 of F, where
// the merit function has a local minimizer that is not a solution.
inline FunctionMCP BillupsMcp() {
  return FunctionMCP(
      Vector::Zero(1), Vector::Constant(1, kInf),
      [](const Vector& x, Vector* F) { (*F)[0] = (x[0] - 1.0) * (x[0] - 1.0) - 1.01; },
      [](const Vector& x, DenseMatrix* J) { (*J)(0, 0) = 2.0 * (x[0] - 1.0); }, "billups");
}

}  // namespace smcbench

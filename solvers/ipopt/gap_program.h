// The complementarity-gap program both Ipopt adapters give Ipopt (the box-MLCP's for a matrix that is not
// symmetric PSD, the MCP's always): one multiplier per bound a row can sit at, the constraints
// r(z) − w + v = 0 (r = M z + q, or F(z) scaled by rows), and the gap Σ (z_i − l_i) w_k + (u_i − z_i) v_k as the
// objective, zero exactly at a solution. A fixed row (l = u) gets one free multiplier. This is the multipliers' part
// of that program, shared by ipopt_qp_solver.cc and ipopt_mcp.cc; the residual's part is each adapter's own.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "solvers/core/problem.h"

namespace smcbench {

enum MultiplierKind : signed char { kLowerMult = 0, kUpperMult = 1, kFixedMult = 2 };

struct GapMultipliers {
  std::vector<int> row;                 // multiplier k sits in row row[k]
  std::vector<signed char> kind;        // its MultiplierKind
  std::vector<double> bound;            // l_i (lower) or u_i (upper) in the program's variables; 0 for fixed rows
  int bounded = 0;                      // multipliers of a lower or upper bound (the gap's Hessian entries)

  int count() const { return static_cast<int>(row.size()); }

  // The multipliers of the box [l, u]; the program's variable i is z_i / scale[i] (scale null: z itself).
  void Build(const Vector& l, const Vector& u, const Vector* scale) {
    row.clear(), kind.clear(), bound.clear();
    bounded = 0;
    const int n = static_cast<int>(l.size());
    const auto add = [&](int i, MultiplierKind k, double b) {
      row.push_back(i), kind.push_back(k), bound.push_back(b);
    };
    for (int i = 0; i < n; ++i) {
      if (l[i] == u[i]) {
        add(i, kFixedMult, 0.0);
        continue;
      }
      if (std::isfinite(l[i])) add(i, kLowerMult, scale == nullptr ? l[i] : l[i] / (*scale)[i]), ++bounded;
      if (std::isfinite(u[i])) add(i, kUpperMult, scale == nullptr ? u[i] : u[i] / (*scale)[i]), ++bounded;
    }
  }

  // Starting multipliers from the residual at the start (residual(i) of row i): its positive part for a lower
  // bound, its negative part for an upper one, itself for a fixed row.
  template <typename Residual>
  void Start(Residual&& residual, double* mult) const {
    for (int k = 0; k < count(); ++k) {
      const double r = residual(row[k]);
      switch (kind[k]) {
        case kLowerMult: mult[k] = std::max(r, 0.0); break;
        case kUpperMult: mult[k] = std::max(-r, 0.0); break;
        default: mult[k] = r; break;
      }
    }
  }

  // The multipliers' bounds in the program's variables m, m + 1, …: a fixed row's multiplier is free, every other
  // one nonnegative (inf: Ipopt's infinity).
  void Bounds(int m, double inf, double* x_l, double* x_u) const {
    for (int k = 0; k < count(); ++k) {
      x_l[m + k] = kind[k] == kFixedMult ? -inf : 0.0;
      x_u[m + k] = inf;
    }
  }

  // The duals Ipopt may ask a start for: 1 for every bound's (Ipopt pushes them into the interior), 0 for the m
  // constraints'.
  static void StartDuals(int n, bool init_z, double* z_l, double* z_u, int m, bool init_lambda, double* lambda) {
    if (init_z) {
      std::fill(z_l, z_l + n, 1.0);
      std::fill(z_u, z_u + n, 1.0);
    }
    if (init_lambda) std::fill(lambda, lambda + m, 0.0);
  }

  // The gap at x = (z of size n, multipliers).
  double Gap(const double* x, int n) const {
    double gap = 0.0;
    for (int k = 0; k < count(); ++k) {
      const int i = row[k];
      if (kind[k] == kLowerMult) gap += (x[i] - bound[k]) * x[n + k];
      if (kind[k] == kUpperMult) gap += (bound[k] - x[i]) * x[n + k];
    }
    return gap;
  }

  // Its gradient (grad of size n + count()).
  void Gradient(const double* x, int n, double* grad) const {
    std::fill(grad, grad + n, 0.0);
    for (int k = 0; k < count(); ++k) {
      const int i = row[k];
      switch (kind[k]) {
        case kLowerMult:
          grad[i] += x[n + k];
          grad[n + k] = x[i] - bound[k];
          break;
        case kUpperMult:
          grad[i] -= x[n + k];
          grad[n + k] = bound[k] - x[i];
          break;
        default: grad[n + k] = 0.0; break;
      }
    }
  }

  // ∂g_row/∂mult_k: −1 for w (lower, fixed), +1 for v (upper).
  double ConstraintEntry(int k) const { return kind[k] == kUpperMult ? 1.0 : -1.0; }
  // g_i −= w_k, += v_k for every multiplier of row i (x: z of size m, then the multipliers).
  void AddToConstraints(const double* x, int m, double* g) const {
    for (int k = 0; k < count(); ++k) g[row[k]] += ConstraintEntry(k) * x[m + k];
  }
  // ∂²gap/∂mult_k∂z_i for a bounded multiplier: +1 for (z_i − l_i) w_k, −1 for (u_i − z_i) v_k.
  double HessianEntry(int k) const { return kind[k] == kLowerMult ? 1.0 : -1.0; }
};

}  // namespace smcbench

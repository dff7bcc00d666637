// The Fischer–Burmeister NCP function and Billups' extension to box constraints, with an element of the
// B-subdifferential chosen at kinks. Header-only so tests can check values and derivatives directly.
//
// Sign convention: phi(a, b) = sqrt(a² + b²) − a − b (Fischer 1992), which is zero iff a ≥ 0, b ≥ 0, ab = 0.
// Billups (1995 thesis, ch. 2; Facchinei–Pang 2003 §9.4) writes the box function with the opposite sign,
// φ_B = −phi, as φ_B(z − l, −φ_B(u − z, −F)). Rewritten in our sign that is
//     Phi_i = phi(z_i − l_i, phi(u_i − z_i, −F_i))          both bounds finite,
// because phi(u − z, −F) ≈ F far from the upper bound, so it plays the role of F in the lower-bound phi.
// (Writing −phi(...) for the inner term would mix the two conventions and break the zero set.)
//     Phi_i = phi(z_i − l_i, F_i)        lower bound only,
//     Phi_i = −phi(u_i − z_i, −F_i)      upper bound only,
//     Phi_i = F_i                        free.
// With this choice every bounded row has ∂Phi/∂z ≤ 0 and ∂Phi/∂F ≤ 0 (free rows: 0 and 1), which the
// reduced Newton system in semismooth_newton_solver.cc relies on (Da/Db ≥ 0).
#pragma once

#include <cmath>

namespace smcbench {
namespace fb {

// Value and partial derivatives of one row: Phi_i and the diagonal entries Da_i = ∂Phi_i/∂z_i (explicit
// dependence), Db_i = ∂Phi_i/∂F_i, so a generalized Jacobian row is Da_i e_iᵀ + Db_i ∇F_i(z)ᵀ.
struct RowDerivative {
  double da = 0.0;
  double db = 0.0;
};

// Euclidean norm of (a, b); falls back to hypot only where squaring would overflow.
inline double Norm2(double a, double b) {
  if (std::abs(a) > 1e150 || std::abs(b) > 1e150) return std::hypot(a, b);
  return std::sqrt(a * a + b * b);
}

// phi(a, b) without cancellation: for a + b > 0, phi = −2ab / (r + a + b) (multiply by the conjugate).
inline double Phi(double a, double b) {
  const double r = Norm2(a, b);
  const double s = a + b;
  return s > 0.0 ? -2.0 * a * b / (r + s) : r - s;
}

// Gradient (pa, pb) of phi at (a, b). At the kink a = b = 0 the limiting gradient along the direction
// (da, db) is returned, an element of the B-subdifferential (De Luca–Facchinei–Kanzow 1996, Prop. 3.1 and
// the rule of their §3). The stable forms a/r − 1 = −b²/(r(r + a)) (a > 0) keep tiny derivatives accurate,
// which matters when deciding that a row is trivially active. Returns true if (a, b) is the kink.
inline bool PhiGradient(double a, double b, double da, double db, double* pa, double* pb) {
  double r = Norm2(a, b);
  bool kink = false;
  if (!(r > 0.0)) {
    kink = true;
    a = da;
    b = db;
    r = Norm2(a, b);
    if (!(r > 0.0)) {  // no usable direction: any point of the unit circle is a valid limit
      a = b = 1.0;
      r = std::sqrt(2.0);
    }
  }
  *pa = a > 0.0 ? -(b * b) / (r * (r + a)) : a / r - 1.0;
  *pb = b > 0.0 ? -(a * a) / (r * (r + b)) : b / r - 1.0;
  return kink;
}

inline bool HasLower(double l) { return l > -HUGE_VAL; }
inline bool HasUpper(double u) { return u < HUGE_VAL; }

// Phi_i(z, F) for the bounds (l, u) (see the header comment for the four cases).
inline double BoxPhi(double z, double F, double l, double u) {
  const bool lower = HasLower(l);
  const bool upper = HasUpper(u);
  if (lower && upper) return Phi(z - l, Phi(u - z, -F));
  if (lower) return Phi(z - l, F);
  if (upper) return -Phi(u - z, -F);
  return F;
}

// Value and derivatives of Phi_i. (dz, dF) is the direction used only at kinks: the DFK rule takes the path
// z + t·e_β with e_β the indicator of the kink rows, i.e. dz = 1 and dF = (∇F e_β)_i. The directional
// derivative of the inner phi feeds the outer one, so the pair is the limit of gradients along one path and
// H = Da + Db ∇F is an element of ∂_B Phi. Returns true if any kink was met (the caller then computes ∇F e_β
// and calls again with the direction).
inline bool BoxPhiDerivative(double z, double F, double l, double u, double dz, double dF, double* value,
                             RowDerivative* out) {
  const bool lower = HasLower(l);
  const bool upper = HasUpper(u);
  double pa, pb;
  if (lower && upper) {
    // Inner g = phi(u − z, −F): ∂g/∂z = −qa, ∂g/∂F = −qb.
    double qa, qb;
    const double b = u - z;
    const bool inner_kink = PhiGradient(b, -F, -dz, -dF, &qa, &qb);
    const double g = Phi(b, -F);
    const double dg = -qa * dz - qb * dF;  // directional derivative of g along (dz, dF)
    const bool outer_kink = PhiGradient(z - l, g, dz, dg, &pa, &pb);
    *value = Phi(z - l, g);
    out->da = pa - pb * qa;
    out->db = -pb * qb;
    return inner_kink || outer_kink;
  }
  if (lower) {
    const bool kink = PhiGradient(z - l, F, dz, dF, &pa, &pb);
    *value = Phi(z - l, F);
    out->da = pa;
    out->db = pb;
    return kink;
  }
  if (upper) {
    // Phi = −phi(u − z, −F): ∂/∂z = −pa·(−1) = pa, ∂/∂F = −pb·(−1) = pb.
    const bool kink = PhiGradient(u - z, -F, -dz, -dF, &pa, &pb);
    *value = -Phi(u - z, -F);
    out->da = pa;
    out->db = pb;
    return kink;
  }
  *value = F;
  out->da = 0.0;
  out->db = 1.0;
  return false;
}

}  // namespace fb
}  // namespace smcbench

// The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.
#include "problems/stepper/nonlinear_scenes.h"

#include <cmath>

namespace smcbench {

NonlinearScene HypomonotoneScene(double rho) {
  NonlinearScene scene;
  scene.name = "hypomonotone";
  scene.title = "S9: x' in -(x+1) sgn(x), class (3), hypomonotone (Lemma youpi)";
  AffineGainSignSystem s;
  s.A = {DenseMatrix::Constant(1, 1, 1.0)};
  s.B = DenseMatrix::Constant(1, 1, 1.0);
  s.C = DenseMatrix::Constant(1, 1, 1.0);
  scene.system = ToNonlinear(s);
  scene.system.description = "x' in -(x+1) sgn(x)";
  scene.scheme.h = 0.1;
  scene.scheme.theta = 1.0;
  scene.scheme.gamma = 1.0;
  scene.scheme.rho = rho;
  scene.scheme.Validate();
  scene.x0 = Vector::Constant(1, 1.5);
  scene.T = 2.0;
  scene.exact = [](const Vector& x0) { return HypomonotoneExact(x0[0]); };
  return scene;
}

ExactSolution HypomonotoneExact(double x0) {
  // t* = ∓ln(1 + x0): the time at which (x0 + 1)e^{∓t} − 1 reaches 0 (never when x0 ≤ −1).
  const double sign = x0 > 0.0 ? 1.0 : (x0 < 0.0 ? -1.0 : 0.0);
  const double t_star = x0 > -1.0 ? std::abs(std::log1p(x0)) : kInf;
  ExactSolution exact;
  exact.x = [x0, sign, t_star](double t, Eigen::Ref<Vector> x) {
    x[0] = t >= t_star ? 0.0 : (x0 + 1.0) * std::exp(-sign * t) - 1.0;
  };
  exact.s = [sign, t_star](double t, Eigen::Ref<Vector> s) { s[0] = t >= t_star ? 0.0 : sign; };
  return exact;
}

NonlinearScene ArctanScene() {
  NonlinearScene scene;
  scene.name = "arctan";
  scene.title = "S10: x' in -sgn(arctan x)/(1+x^2), class (4), nonlinear g and h";
  NonlinearSignSystem& sys = scene.system;
  sys.n = 1;
  sys.m = 1;
  sys.description = "x' in -g(x) sgn(h(x)), g = 1/(1+x^2), h = arctan x";
  sys.g = [](const Vector& x, Eigen::Ref<DenseMatrix> G) { G(0, 0) = 1.0 / (1.0 + x[0] * x[0]); };
  // ∇g·s = g'(x) s, g'(x) = −2x/(1 + x²)².
  sys.g_jacobian_s = [](const Vector& x, const Vector& s, Eigen::Ref<DenseMatrix> J) {
    const double d = 1.0 + x[0] * x[0];
    J(0, 0) = -2.0 * x[0] / (d * d) * s[0];
  };
  sys.h = [](const Vector& x, Eigen::Ref<Vector> y) { y[0] = std::atan(x[0]); };
  sys.h_jacobian = [](const Vector& x, Eigen::Ref<DenseMatrix> H) { H(0, 0) = 1.0 / (1.0 + x[0] * x[0]); };
  scene.scheme.h = 0.05;
  scene.scheme.theta = 1.0;
  scene.scheme.gamma = 1.0;
  scene.x0 = Vector::Constant(1, 2.0);
  scene.T = 10.0;
  scene.exact = [](const Vector& x0) { return ArctanExact(x0[0]); };
  return scene;
}

ExactSolution ArctanExact(double x0) {
  const double sign = x0 > 0.0 ? 1.0 : (x0 < 0.0 ? -1.0 : 0.0);
  const double a0 = std::abs(x0) + std::abs(x0) * std::abs(x0) * std::abs(x0) / 3.0;  // = t*
  ExactSolution exact;
  exact.x = [sign, a0](double t, Eigen::Ref<Vector> x) {
    const double a = a0 - t;
    if (a <= 0.0) {
      x[0] = 0.0;
      return;
    }
    // Real root of r³ + 3r − 3a = 0 (Cardano), then Newton on r + r³/3 − a (derivative 1 + r²).
    const double A = 1.5 * a, D = std::sqrt(A * A + 1.0);
    double r = std::cbrt(A + D) - std::cbrt(D - A);
    for (int i = 0; i < 2; ++i) r -= (r + r * r * r / 3.0 - a) / (1.0 + r * r);
    x[0] = sign * r;
  };
  exact.s = [sign, a0](double t, Eigen::Ref<Vector> s) { s[0] = t >= a0 ? 0.0 : sign; };
  return exact;
}

}  // namespace smcbench

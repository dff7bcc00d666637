// The nonlinear scenes of docs/scenes.md as C++ builders (their g and h are code, not data): S9 `hypomonotone` (class
// (3), section "A simple hypomonotone case", `sixe`/`neuf`) and S10 `arctan` (class (4), Example `example4`).
// Each carries its system, the numerical parameters of docs/scenes.md and, where one is known, the exact solution.
// The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "problems/stepper/metrics.h"
#include "problems/stepper/nonlinear_stepper.h"

namespace smcbench {

struct NonlinearScene {
  std::string name;         // registry name ("hypomonotone", "arctan")
  std::string title;        // one line for `smcbench scenes`
  NonlinearSignSystem system;
  NonlinearScheme scheme;   // h, θ, γ, ρ, sign treatment
  Vector x0;
  double T = 0.0;           // horizon; N = NumSteps(T, scheme.h)
  // Exact solution of the continuous inclusion from a given x0 (so a `--x0` override keeps it); null if none.
  std::function<ExactSolution(const Vector& x0)> exact;

  std::int64_t num_steps() const { return NumSteps(T, scheme.h); }
};

// S9 `hypomonotone`: x' ∈ −(x + 1) sgn(x), class (3) with A₁ = B₁ = C₁ = 1, D₁ = 0, u = 0; x0 = 1.5, h = 0.1,
// θ = γ = 1, T = 2 (ours: the exact solution rests at 0 from t* = ln 2.5 ≈ 0.92). rho is the `neuf` shift
// (0 = the plain implicit scheme of Lemma youpi; ρ ≥ 1 makes the step strongly monotone).
NonlinearScene HypomonotoneScene(double rho = 0.0);
// Exact solution of x' ∈ −(x + 1) sgn(x) from x0: x0 > 0: x = (x0 + 1)e^{−t} − 1 until t* = ln(1 + x0), then 0;
// x0 < 0: x = (x0 + 1)e^{t} − 1 (reaches 0 at t* = −ln(1 + x0) only if x0 > −1; for x0 < −1 it diverges, g
// changes sign); s = sgn(x0) before t*, 0 after.
ExactSolution HypomonotoneExact(double x0);

// S10 `arctan`: x' ∈ −g(x) sgn(h(x)), g(x) = 1/(1 + x²), h(x) = arctan x; x0 = 2, h = 0.05, T = 10, θ = γ = 1.
NonlinearScene ArctanScene();
// Exact solution: x + x³/3 decreases at unit rate until x = 0 at t* = |x0| + |x0|³/3 (14/3 for x0 = 2), then
// rests (s = 0 there: g(0) = 1). Solved by Cardano's formula polished by two Newton steps.
ExactSolution ArctanExact(double x0);

}  // namespace smcbench

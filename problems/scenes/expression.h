// Arithmetic on scene parameters, so a scene file can write an entry of E as "1/tau^2" and a user can change τ
// with `--param tau=0.5` instead of editing four matrix entries (S8 `observer`, S11 `parasitic` of docs/scenes.md).
#pragma once

#include <map>
#include <string>
#include <string_view>

namespace smcbench {

using SceneParameters = std::map<std::string, double, std::less<>>;

// Evaluates a real expression: numbers (1, 2.5, 1e-3), parameter names, the constant pi, + − * / ^ (right
// associative, binding tighter than unary minus: -x^2 = −(x²)), parentheses and the functions sqrt, exp, log,
// sin, cos, tan, atan, abs. Throws InvalidInputError describing the defect and its position ("unknown name
// 'taux' at column 3 (parameters: k, tau)"), also for nesting deeper than 200 levels (parentheses, signs, ^).
// The result may be non-finite (1/0): callers check.
double EvaluateExpression(std::string_view text, const SceneParameters& parameters);

// True for names a parameter may take: [A-Za-z_][A-Za-z0-9_]*, and not pi or a function name.
bool IsValidParameterName(std::string_view name);

}  // namespace smcbench

// The one-step MCPs of the paper's nonlinear scenes S9 `hypomonotone` and S10 `arctan` (problems/stepper/
// nonlinear_scenes.h), captured from a run: the MCP `eq:MCP3` that the stepper solves at step k, rebuilt from the
// scene, its h, θ, γ, ρ and the state x_k of the run, with F written on the scalar type (so it has an
// extended-precision reference). Ids: "mcp/scene/<scene>/k<K>". The run is Algorithm 2 (newton-mlcp) with the
// exact `lemke` backend from the scene's x0, so x_k is the same on every machine to rounding.
#pragma once

#include <string>
#include <vector>

#include "problems/mcp/builtin_entry.h"

namespace smcbench {

// Ids in suite order: per scene the first step, the steps before, at and after the arrival on the sliding surface
// (the first k whose s_{k+1} is strictly inside (−1, 1)), found by running the scene.
std::vector<std::string> SceneStepMcpIds();
// BuiltinMcpMaker: any k in [0, the scene's number of steps).
bool MakeSceneStepMcp(const std::string& id, BuiltinMcpEntry* out);

}  // namespace smcbench

// The built-in AVI suite (`bench --suite avi`, docs/benchmarks.md "The AVI suite"): one-step AVIs captured along
// runs of the implicit-twisting scenes, random polytopes with planted solutions, degenerate vertices, unbounded
// polytopes and AVIs with no solution, every one built deterministically from its seed or its scene, each with its
// expected outcome and a certified reference where a solution is known.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "problems/avi_library/avi_library.h"

namespace smcbench {

// The scenes whose one-step problems the suite captures: those that ship with an implicit polytope law
// (explicit-twisting has no one-step problem: its steps are explicit).
inline constexpr const char* kAviSuiteScenes[] = {"twisting-double-integrator", "twisting", "regular-twisting"};

// The one-step AVIs of a linear scene with a polytope law at the given steps (k ≥ 1, in increasing order; steps
// past the run's end are ignored), captured from its default run with the named backend through the stepper's own
// path: the StepObserver sees each step's normalized reduction (AviSession), and the AVI is the stepper's
// (M = C S, H, K) with q = σ·q̃ (avi_reduction.h). Ids "avi/twisting/<scene>/k<step>"; the run's answer becomes
// the reference's candidate. InvalidInputError for a scene without a polytope law or an unknown backend.
std::vector<AviLibraryProblem> CaptureSceneAvis(const std::string& scene, const std::vector<std::int64_t>& steps,
                                                const std::string& backend = "lemke");

// The suite with its references attached. quick: the sizes CI runs (n ≤ 8, four steps per scene); otherwise n up to
// 32 and ten steps per scene.
AviProblemSet BuildAviSuite(bool quick);

}  // namespace smcbench

// The AVI half of the problem library: affine variational inequalities over polytopes (solvers/avi, docs/avi.md)
// with what a benchmark needs (stable id, source, tags, the outcome a correct backend must produce, a certified
// reference). Unlike an MCP's F, an AVI is data (M, q, H, K, E, f), so an entry holds the AffineVI itself.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "solvers/avi/affine_vi.h"
#include "solvers/avi/avi_verdict.h"
#include "solvers/core/verdict.h"

namespace smcbench {

// The name of the built-in suite (`bench --suite avi`) and of its records' suite.
inline constexpr const char* kAviSuiteName = "avi";

// One AVI of a suite: an AVI × backend is one benchmark job, judged by JudgeAvi (avi_verdict.h) against reference.
struct AviLibraryProblem {
  // Stable across runs and machines: "avi/<family>/<parameters>", e.g. "avi/planted/n8/s1" or
  // "avi/twisting/twisting/k40". Unique within a set.
  std::string id;
  // Where it came from: "capture:<scene>", "generated:<family>", "hand-made:<what it shows>".
  std::string source;
  std::shared_ptr<const AffineVI> problem;  // named by id
  std::vector<std::string> tags;            // "twisting", "planted", "degenerate", "unbounded", "infeasible", ...
  // kSolvable when a solution is known to exist (planted, or P bounded: Hartman–Stampacchia), kInfeasible when
  // none exists (proved in the generator's comment), kUnknown otherwise.
  ExpectedOutcome expected = ExpectedOutcome::kUnknown;
  // CertifyAvi on the problem from the known answers (the planted one, the run's): λ's forward error is judged
  // against it only where λ is unique (AviReference::lambda_unique); otherwise the residual rule alone decides.
  AviReference reference;
  std::map<std::string, std::string> metadata;  // seed, scene, step, h, boundedness, ... as text

  int size() const { return problem ? problem->size() : 0; }
};

struct AviProblemSet {
  std::string name;         // "avi", or a user's name
  std::string description;  // one line
  std::vector<AviLibraryProblem> problems;

  // InvalidInputError naming the id: empty or duplicate ids, a null problem, a verified reference whose λ has the
  // wrong size, a problem expected infeasible that carries a verified reference.
  void Validate() const;
};

}  // namespace smcbench

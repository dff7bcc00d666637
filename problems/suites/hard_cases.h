// The hard-case suite: a named list of problems on which backends are known or expected to struggle, each with the
// outcome a correct backend must produce, so that "no backend may wrongly claim success" is a test.
#pragma once

#include <string>
#include <vector>

#include "problems/library/problem_set.h"

namespace smcbench {

// The hard cases, ids "hard/<kind>/<name>", tags {<kind>, ...}, metadata["why"] a one-line reason. Kinds:
//   degenerate     z* at a bound with w* = 0 on some or all rows (wrapped generator, and q = 0);
//   cycling        degenerate first ratio tests where Lemke without a lexicographic rule can cycle;
//   near-singular  SPD with condition number 1e12 (relay and LCP), and a 3×3 SPD LCP with condition 1e13;
//   small-h        W = h·G at h = 1e-8 with every datum O(h) (the small-h family of families.h);
//   row-scaling    a 2×2 P-matrix box problem with rows scaled by 1e6 and 1e-5;
//   joint-scaling  a P-matrix problem with M and q scaled together by 1e-150 and 1e150;
//   free-row       M = [0], q = [0] on a free row (every z solves it);
//   h-to-zero      scene one-step matrices W = hC(I − hE)⁻¹B at h = 1e-6 … 1e-8;
//   non-unique     PSD singular (a segment of solutions);
//   infeasible     certificate rows (expected infeasible: every non-solved status is the right answer);
//   parasitic      S11's one-step problem (W = O(h³)) at the scene's initial state, h = 1e-3 … 1e-5, and planted;
//   siconos        the files of the Siconos collection some backend fails on (results/siconos-collection.md).
// siconos_dir: the collection root (holding lcp/, relay/, mlcp/); empty leaves the siconos cases out. Throws
// InvalidInputError if a listed file is missing or unreadable there (naming it), or if a scene file is broken.
ProblemSet HardSuite(const std::string& siconos_dir);

// The Siconos files the hard suite takes (relative to the collection root), in suite order.
std::vector<std::string> HardSiconosFiles();

}  // namespace smcbench

// The warm track's sequences (bench/replay/warm_track.h) for the suites of a run: the paper scenes' runs step by step
// (suite "paper"), the families' P-matrix problems with q moving along a trajectory (suite "families"), and the
// consecutive problems of a user's problem-set file that share M, l and u (a file suite). Each step certified as the
// cold records' problems are (AttachReferences), so the warm verdict is the cold one.
#pragma once

#include <string>
#include <vector>

#include "bench/replay/warm_track.h"
#include "problems/library/problem_set.h"

namespace smcbench {

// Which sequences a suite gets.
enum class WarmSuiteKind : int {
  kNone = 0,        // no sequence (hard, siconos, scale, tiny, mcp: no time-stepping order among their problems)
  kScenes = 1,      // "paper": SceneWarmSequences
  kFamilies = 2,    // "families": TrajectoryWarmSequences
  kCaptureFile = 3, // a problem-set file: CaptureWarmSequences over its problems
};
WarmSuiteKind WarmSuiteKindOf(const std::string& suite_name, bool is_file);

// Step k of K of a trajectory through base: q_k = q_0 + ε(1 + ‖q_0‖∞)(sin(2πk/K) a + (1 − cos(2πk/K)) b) with
// fixed a_i = sin(1.3 i + 0.7), b_i = cos(0.9 i + 0.2) and ε = relative_step: a smooth closed loop of q around
// q_0, M, l, u fixed. Id "<base id>/k<k>", base's tags, matrix tags and expected outcome; solution only at k = 0.
// Its expected outcome stays base's only when that holds for every q (base tagged a P-matrix: the caller's
// business); no reference (CertifyWarmSequence).
LibraryProblem TrajectoryStep(const LibraryProblem& base, int k, int steps, double relative_step);

// The families' trajectories: SPD and nonsymmetric P-matrix, LCP and relay bounds (quick: P-matrix relay at m = 8
// and P-matrix LCP at m = 64, 8 steps; else both families × both bounds × m = 8, 64, 256, 32 steps), seed 1.
std::vector<WarmSequence> TrajectoryWarmSequences(const std::string& suite, bool quick);

// The paper's linear scenes run with lemke (the paper suite's own settings: implicit or ZOH) for the first steps
// (quick: "sign" and "galias-yu-2007", 20 steps; else every linear scene, 100 steps), each step's one-step problem
// captured in order (capture.h; references attached, m ≤ 4) and cut at the first step whose M, l or u differs.
std::vector<WarmSequence> SceneWarmSequences(const std::string& suite, bool quick);

// Runs of at least two consecutive problems of set sharing M, l and u (file order), at most max_steps each, the
// first max_sequences of them. Id "<set>/warm/<first step's id>".
std::vector<WarmSequence> CaptureWarmSequences(const ProblemSet& set, int max_sequences, int max_steps);

// Attaches certified references to the steps that have none (AttachReferences, as the cold suites').
void CertifyWarmSequence(WarmSequence* sequence);

// The sequences of one suite of a run (by WarmSuiteKindOf), certified unless certify is false (only to list jobs).
std::vector<WarmSequence> WarmSequencesForSuite(const ProblemSet& set, WarmSuiteKind kind, bool quick,
                                                bool certify = true);

}  // namespace smcbench

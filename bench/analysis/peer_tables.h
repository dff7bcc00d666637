// Ours against the other libraries as tables of sorted time ratios: per size band cold and warm, per class × band
// with ours over the floor, per size against Siconos (in process and through its worker), and against the generic
// sparse path.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "bench/analysis/class_tables.h"
#include "bench/replay/results_io.h"
#include "bench/replay/size_band.h"

namespace smcbench {

// Ours against each external library's best, per size band, cold and warm: on each problem (warm: sequence) the
// fastest correct answer of our backends and of each peer family (the name's first part: "siconos", "bullet",
// "dart"), and the ratio peer time / our time over the problems both solve, sorted.
struct PeerRatioRow {
  SizeBand band = SizeBand::kTiny;
  bool warm = false;
  std::map<std::string, std::vector<double>> by_peer;  // family → sorted ratios
};
// Bands smallest first, for each the cold row then the warm row (a row only when some ratio exists).
std::vector<PeerRatioRow> OursAgainstPeersPerBand(const SuiteResults& suite);

// Ours against each external library's best per class × size band (cold), as OursAgainstPeersPerBand pools them,
// with ours over the floor beside them.
struct PeerClassRow {
  ProblemClass problem_class;
  std::map<std::string, std::vector<double>> by_peer;  // family → sorted ratios (library's best / ours)
  std::vector<double> ours_over_floor;                 // our best / floor on each problem, sorted
};
std::vector<PeerClassRow> OursAgainstPeersPerClass(const SuiteResults& suite);

// The paper suite against the generic sparse path (bench adds it: newton on sparse copies), over the problems both
// solve: the speed-ups and the fastest time over an arithmetic floor, each sorted.
struct SparsePathComparison {
  std::vector<double> speedups, over_floor;
};
SparsePathComparison CompareWithSparsePath(const SuiteResults& suite);

// Ours against the external adapters (siconos-*), per size: best of each side per problem, Siconos time / ours.
// in_process: Siconos timed in process (each Siconos problem's untimed first solve is the probe in its isolation
// worker, the timed ones call Siconos directly); through_worker: Siconos records timed through the worker
// (isolate=always, a probe that crashed, results from before the probe policy), each solve's IPC round trip included.
struct SiconosComparison {
  std::map<int, std::vector<double>> in_process, through_worker;  // m → sorted ratios
};
SiconosComparison CompareWithSiconos(const SuiteResults& suite);

}  // namespace smcbench

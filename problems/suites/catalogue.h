// The benchmark suites by name ("tiny", "paper", "families", "hard", "siconos", "scale", or a problem-set file):
// what `smcbench bench`, `library --write-suite` and the Google Benchmark replay build, below the command line so
// that bench/ and tools/ share one catalogue.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "problems/io/data_dirs.h"
#include "problems/library/problem_set.h"

namespace smcbench {

// The Siconos collection's problem files, in a fixed order: dir/{lcp,relay,mlcp}/*.dat, the `_block` LCP twins of
// dense files left out. InvalidInputError if dir is not a folder or holds none.
std::vector<std::filesystem::path> SiconosCollectionFiles(const std::filesystem::path& dir);

// The Siconos collection as a problem set (id "siconos/<kind>/<stem>"; files the reader rejects are skipped and
// listed in *rejected when given).
ProblemSet SiconosSuite(const std::string& dir, std::vector<std::string>* rejected = nullptr);

// A handful of small generated problems (SPD relay, P-matrix LCP, a mixed box, one infeasible LCP): what CI runs
// bench and report on end to end.
ProblemSet TinySuite();

struct SuiteRequest {
  // The collection of this installation or checkout ($SMCBENCH_SICONOS_DIR, share/smcbench/siconos or
  // tests/data/siconos: problems/io/data_dirs.h), never a path relative to the working directory.
  std::string siconos_dir = DataDirectory(DataFolder::kSiconosCollection);
  bool quick = false;  // smaller families / scale sizes
  // Attach certified reference solutions (AttachReferences, problems/library/references.h) to the problems small
  // enough, so the verdict can judge forward errors. `bench` turns it off here and attaches them itself, timed.
  bool references = true;
};

// The names BuildSuite knows (anything else must be a problem-set file).
inline constexpr const char* kSuiteNames[] = {"paper", "families", "hard", "siconos", "scale", "tiny"};

// "tiny", "paper", "families", "hard", "siconos", "scale", or the path of a problem-set file (problems/library).
// InvalidInputError for an unknown name.
ProblemSet BuildSuite(const std::string& name, const SuiteRequest& request);

// The checksum of a set's problems as they would be run and judged (ids, M, q, bounds, expected outcomes, certified
// references): FNV-1a 64 of the set's problem-set file image (problems/library/problem_set_io.h), as 16 hex digits.
// Two runs with equal checksums ran the same problems; a set read back from a file written with
// WriteProblemSetFile has the checksum of the set written.
std::string ProblemSetContentChecksum(const ProblemSet& set);

}  // namespace smcbench

// libFuzzer target for the problem-library reader (.smcps, problems/library/problem_set_io.h): any input must give a
// valid ProblemSet or an InvalidInputError; another exception, a crash, a hang or a sanitizer report is a bug.
// The format is checksummed, so a mutated file almost always fails the checksum before the decoder sees it: each
// input is read twice, as it is (the checksum check) and with its checksum rewritten (so the decoder itself judges
// every mutation). An accepted set must survive a write and a re-read unchanged (ids, sizes, re-written bytes).
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "problems/avi_library/avi_library.h"
#include "problems/library/problem_set_io.h"
#include "tests/fuzz/fuzz_checks.h"

namespace {

void ReadAndCheck(const std::string& bytes) {
  using smcbench::fuzz::Finding;
  smcbench::ProblemSet set;
  const auto read = [&] { set = smcbench::ReadProblemSetBytes(bytes, "fuzz.smcps"); };
  if (!smcbench::fuzz::AcceptOrReject(read)) return;
  // Accepted: from here on every exception is a finding (the reader promised a valid, writable set).
  smcbench::fuzz::NoExceptionAllowed("accepted set then ", [&] {
    set.Validate();
    for (const smcbench::LibraryProblem& p : set.problems) smcbench::fuzz::CheckAccepted(p.problem);
    std::ostringstream once;
    smcbench::WriteProblemSet(set, once);
    const smcbench::ProblemSet again = smcbench::ReadProblemSetBytes(once.str(), "fuzz-rewritten.smcps");
    if (again.problems.size() != set.problems.size()) Finding("re-read set has another number of problems");
    for (std::size_t i = 0; i < set.problems.size(); ++i) {
      if (again.problems[i].id != set.problems[i].id || again.problems[i].size() != set.problems[i].size()) {
        Finding("re-read set differs from the accepted one");
      }
    }
    std::ostringstream twice;
    smcbench::WriteProblemSet(again, twice);
    if (twice.str() != once.str()) Finding("write(read(write(set))) differs from write(set)");
  });
}

void ReadAvisAndCheck(const std::string& bytes) {
  using smcbench::fuzz::Finding;
  smcbench::AviProblemSet set;
  const auto read = [&] { set = smcbench::ReadAviProblemSetBytes(bytes, "fuzz.smcps"); };
  if (!smcbench::fuzz::AcceptOrReject(read)) return;
  smcbench::fuzz::NoExceptionAllowed("accepted AVI set then ", [&] {
    set.Validate();
    for (const smcbench::AviLibraryProblem& p : set.problems) {
      const smcbench::AffineVI& avi = *p.problem;
      if (avi.size() < 1 || !avi.M().allFinite() || !avi.q().allFinite() || !avi.H().allFinite() ||
          !avi.K().allFinite() || !avi.E().allFinite() || !avi.f().allFinite()) {
        Finding("accepted an empty or non-finite AVI");
      }
      if (p.reference.verified() && p.reference.reduced.z.size() != avi.size() + avi.inequality_count() +
                                                                        avi.equality_count()) {
        Finding("accepted a reference z* of the wrong size");
      }
    }
    std::ostringstream once;
    smcbench::WriteAviProblemSet(set, once);
    const smcbench::AviProblemSet again = smcbench::ReadAviProblemSetBytes(once.str(), "fuzz-rewritten.smcps");
    if (again.problems.size() != set.problems.size()) Finding("re-read AVI set has another number of problems");
    for (std::size_t i = 0; i < set.problems.size(); ++i) {
      if (again.problems[i].id != set.problems[i].id || again.problems[i].size() != set.problems[i].size()) {
        Finding("re-read AVI set differs from the accepted one");
      }
    }
    std::ostringstream twice;
    smcbench::WriteAviProblemSet(again, twice);
    if (twice.str() != once.str()) Finding("write(read(write(AVI set))) differs from write(AVI set)");
  });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  ReadAndCheck(bytes);
  ReadAvisAndCheck(bytes);
  smcbench::FixProblemSetChecksum(&bytes);
  ReadAndCheck(bytes);
  ReadAvisAndCheck(bytes);
  return 0;
}

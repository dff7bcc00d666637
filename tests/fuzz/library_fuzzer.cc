// libFuzzer target for the problem-library reader (.smcps, problems/library/problem_set_io.h): any input must give a
// valid ProblemSet or an InvalidInputError; another exception, a crash, a hang or a sanitizer report is a bug.
// The format is checksummed, so a mutated file almost always fails the checksum before the decoder sees it: each
// input is read twice, as it is (the checksum check) and with its checksum rewritten (so the decoder itself judges
// every mutation). An accepted set must survive a write and a re-read unchanged (ids, sizes, re-written bytes).
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

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

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  ReadAndCheck(bytes);
  smcbench::FixProblemSetChecksum(&bytes);
  ReadAndCheck(bytes);
  return 0;
}

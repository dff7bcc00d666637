// libFuzzer target for the AVI file reader (ParseAviText, problems/io/avi_file.h): any input must give an AviFile or
// an InvalidInputError; another exception, a crash, a hang or a sanitizer report is a bug. An accepted file must
// keep what the reader promises (consistent sizes, finite data, a solution of size n) and be a fixed point of the
// writer: the text written from it reads back to the same AVI and the same text.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "problems/io/avi_file.h"
#include "tests/fuzz/fuzz_checks.h"

namespace {

using smcbench::fuzz::Finding;

void CheckAcceptedAvi(const smcbench::AviFile& file) {
  const smcbench::AffineVI& avi = file.avi;
  const Eigen::Index n = avi.size();
  if (n <= 0) Finding("accepted an AVI with no unknowns");
  if (avi.M().rows() != n || avi.M().cols() != n || avi.q().size() != n) Finding("accepted inconsistent M, q");
  if (avi.H().rows() != avi.K().size() || (avi.H().rows() > 0 && avi.H().cols() != n)) {
    Finding("accepted inconsistent H, K");
  }
  if (avi.E().rows() != avi.f().size() || (avi.E().rows() > 0 && avi.E().cols() != n)) {
    Finding("accepted inconsistent E, f");
  }
  if (!avi.M().allFinite() || !avi.q().allFinite() || !avi.H().allFinite() || !avi.K().allFinite() ||
      !avi.E().allFinite() || !avi.f().allFinite()) {
    Finding("accepted a non-finite entry");
  }
  if (file.solution.size() != 0 && (file.solution.size() != n || !file.solution.allFinite())) {
    Finding("accepted a solution of the wrong size or not finite");
  }
  if (file.expected == smcbench::ExpectedOutcome::kInfeasible && file.solution.size() != 0) {
    Finding("accepted an infeasible AVI with a solution");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::optional<smcbench::AviFile> accepted;  // AffineVI has no empty state
  const auto read = [&] { accepted.emplace(smcbench::ParseAviText(text, "fuzz.avi.json", "fuzz")); };
  if (!smcbench::fuzz::AcceptOrReject(read)) return 0;
  const smcbench::AviFile& file = *accepted;
  // Accepted: from here on every exception is a finding (the reader promised a valid, writable AVI).
  smcbench::fuzz::NoExceptionAllowed("accepted AVI then ", [&] {
    CheckAcceptedAvi(file);
    const std::string once = smcbench::AviFileText(file.avi, file.solution, file.expected);
    const smcbench::AviFile again = smcbench::ParseAviText(once, "fuzz-rewritten.avi.json");
    if (again.avi.name() != file.avi.name() || again.expected != file.expected ||
        again.solution.size() != file.solution.size()) {
      Finding("re-read AVI differs from the accepted one");
    }
    const std::string twice = smcbench::AviFileText(again.avi, again.solution, again.expected);
    if (twice != once) Finding("write(read(write(file))) differs from write(file)");
  });
  return 0;
}

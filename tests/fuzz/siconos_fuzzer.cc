// libFuzzer target for the Siconos LCP / Relay / MLCP readers (SMCBENCH_FUZZ_KIND picks the kind): any input must
// give a valid BoxMLCP or an InvalidInputError; another exception, a crash, a hang or a sanitizer report is a bug.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "problems/io/siconos_format.h"
#include "tests/fuzz/fuzz_checks.h"

#ifndef SMCBENCH_FUZZ_KIND
#error "SMCBENCH_FUZZ_KIND must name a SiconosKind (tests/fuzz/CMakeLists.txt)"
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  smcbench::fuzz::AcceptOrReject([&] {
    const smcbench::BoxMLCP problem =
        smcbench::ReadSiconosStream(in, smcbench::SiconosKind::SMCBENCH_FUZZ_KIND, "fuzz-input");
    smcbench::fuzz::CheckAccepted(problem);
    // The merit function must be computable at the cold start of any accepted problem.
    smcbench::Vector z = smcbench::Vector::Zero(problem.size());
    smcbench::ProjectZeroOntoBox(problem.l(), problem.u(), &z);
    smcbench::Vector w;
    (void)problem.NaturalResidual(z, &w);
  });
  return 0;
}

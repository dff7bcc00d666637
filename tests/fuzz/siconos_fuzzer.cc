// libFuzzer target for the Siconos LCP / Relay / MLCP readers (SMCBENCH_FUZZ_KIND picks the kind): any input must
// give a valid BoxMLCP or an InvalidInputError; another exception, a crash, a hang or a sanitizer report is a bug.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <sstream>
#include <string>
#include <typeinfo>

#include "problems/io/siconos_format.h"

#ifndef SMCBENCH_FUZZ_KIND
#error "SMCBENCH_FUZZ_KIND must name a SiconosKind (tests/fuzz/CMakeLists.txt)"
#endif

namespace {

[[noreturn]] void Finding(const char* what) {
  std::fprintf(stderr, "FINDING: %s\n", what);
  std::abort();
}

// What the reader promises for an accepted file (siconos_format.h, BoxMLCP's constructor).
void CheckAccepted(const smcbench::BoxMLCP& p) {
  const Eigen::Index n = p.size();
  if (n <= 0) Finding("accepted a problem with no unknowns");
  if (p.q().size() != n || p.l().size() != n || p.u().size() != n) Finding("accepted inconsistent sizes");
  if (!p.q().allFinite()) Finding("accepted a non-finite q");
  for (Eigen::Index i = 0; i < n; ++i) {
    if (std::isnan(p.l()[i]) || std::isnan(p.u()[i]) || p.l()[i] > p.u()[i]) Finding("accepted bad bounds");
  }
  if (p.is_sparse()) {
    const smcbench::SparseMatrix& M = p.sparse_matrix();
    if (M.rows() != n || M.cols() != n) Finding("accepted a non-square sparse M");
    for (Eigen::Index k = 0; k < M.nonZeros(); ++k) {
      if (!std::isfinite(M.valuePtr()[k])) Finding("accepted a non-finite sparse M entry");
    }
  } else {
    const smcbench::DenseMatrix& M = p.dense_matrix();
    if (M.rows() != n || M.cols() != n) Finding("accepted a non-square M");
    if (!M.allFinite()) Finding("accepted a non-finite M");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    const smcbench::BoxMLCP problem =
        smcbench::ReadSiconosStream(in, smcbench::SiconosKind::SMCBENCH_FUZZ_KIND, "fuzz-input");
    CheckAccepted(problem);
    // The merit function must be computable at the cold start of any accepted problem.
    smcbench::Vector z = smcbench::Vector::Zero(problem.size());
    smcbench::ProjectZeroOntoBox(problem.l(), problem.u(), &z);
    smcbench::Vector w;
    (void)problem.NaturalResidual(z, &w);
  } catch (const smcbench::InvalidInputError& e) {
    // The expected outcome for bad input; the message must be one non-empty line (the CLI prints it as is).
    const std::string message = e.what();
    if (message.empty()) Finding("InvalidInputError with an empty message");
    if (message.find('\n') != std::string::npos) Finding("InvalidInputError message spans several lines");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "FINDING: unexpected %s: %s\n", typeid(e).name(), e.what());
    std::abort();
  }
  return 0;
}

// libFuzzer target for the Matrix Market reader (problems/io/matrix_market.h): the first byte picks the matrix
// (even) or the vector (odd) parser, the rest is the file. Any input must give a square finite M (or a vector) or
// an InvalidInputError with a one-line message; another exception, a crash, a hang or a sanitizer report is a bug.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "problems/io/matrix_market.h"
#include "tests/fuzz/fuzz_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string_view text(reinterpret_cast<const char*>(data) + 1, size - 1);
  smcbench::fuzz::AcceptOrReject([&] {
    if (data[0] % 2 == 0) {
      const smcbench::MatrixMarketMatrix M = smcbench::ParseMatrixMarketMatrix(text, "fuzz-input.mtx");
      // Never densify a sparse M: "10000 10000 0" is a valid file of 10⁸ zeros.
      const Eigen::Index rows = M.is_dense ? M.dense.rows() : M.sparse.rows();
      const Eigen::Index cols = M.is_dense ? M.dense.cols() : M.sparse.cols();
      if (rows != cols || rows < 1) smcbench::fuzz::Finding("accepted a non-square M");
      const double* values = M.is_dense ? M.dense.data() : M.sparse.valuePtr();
      const Eigen::Index count = M.is_dense ? M.dense.size() : M.sparse.nonZeros();
      for (Eigen::Index k = 0; k < count; ++k) {
        if (!std::isfinite(values[k])) smcbench::fuzz::Finding("accepted a non-finite M entry");
      }
    } else {
      const smcbench::Vector v = smcbench::ParseMatrixMarketVector(text, "fuzz-input_q.mtx");
      if (v.size() < 1) smcbench::fuzz::Finding("accepted an empty vector");
      for (Eigen::Index i = 0; i < v.size(); ++i) (void)std::isnan(v[i]);
    }
  });
  return 0;
}

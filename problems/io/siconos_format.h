// Readers for the Siconos Numerics LCP, Relay and MLCP text files (../shared/peer-data/siconos/README.md),
// and a writer of any box-MLCP in Siconos relay format so our problems can be handed to Siconos.
#pragma once

#include <iosfwd>
#include <string>

#include "solvers/core/problem.h"

namespace smcbench {

enum class SiconosKind { kLCP, kRelay, kMLCP };

// Reads a file; the kind is inferred from the parent folder name (lcp/, relay/, mlcp/) or the file name
// (containing "mlcp" or "relay"), else LCP. Throws InvalidInputError naming the file, the field and, where it
// applies, the index on any problem: unreadable file, truncated data, bad storage type, NaN/Inf, size mismatch,
// disagreeing MLCP storages. The problem's name is the file's stem ("lcp_mmc").
BoxMLCP ReadSiconosFile(const std::string& path);
BoxMLCP ReadSiconosFile(const std::string& path, SiconosKind kind);
BoxMLCP ReadSiconosStream(std::istream& in, SiconosKind kind, const std::string& name);

// Writes problem in relay format (n, dense storage 0, column-major M, q, lb, ub) at full precision (%.17g).
// Infinite bounds are written "inf"/"-inf" (read back by this reader and by glibc's scanf, which Siconos
// uses). Throws InvalidInputError if the stream or file fails.
void WriteSiconosRelay(const BoxMLCP& problem, std::ostream& out);
void WriteSiconosRelayFile(const BoxMLCP& problem, const std::string& path);

}  // namespace smcbench

// Readers for the Siconos Numerics LCP, Relay and MLCP text files (tests/data/siconos/README.md),
// and a writer of any box-MLCP in Siconos relay format so our problems can be handed to Siconos.
#pragma once

#include <iosfwd>
#include <string>

#include "solvers/core/problem.h"

namespace smcbench {

enum class SiconosKind { kLCP, kRelay, kMLCP };

// Reads a file; the kind is inferred from the parent folder name (lcp/, relay/, mlcp/) or the file name
// (containing "mlcp", checked first since "relay2_mlcp.dat" is an MLCP, or "relay"), else LCP. Throws
// InvalidInputError "Siconos <kind> '<file>': <field>[index]: <what> (line L)" on any problem: unreadable file,
// truncated data, non-numeric token, unknown or unsupported storage type, zero/negative sizes, sizes larger
// than the data left in the file (checked before allocating), NaN/Inf in M, q (and A..D, a, b), NaN bounds,
// lb > ub, disagreeing MLCP storages, trailing garbage. The problem's name is the file's stem ("lcp_mmc").
//
// What is read:
// - Numbers are whitespace-separated tokens parsed locale-independently (decimal/exponent form, inf, nan);
//   integers must be written as integers. '#' starts a comment up to the end of the line.
// - Matrix storage 0 (dense, column-major) gives a dense M; storage 1 (sparse-block, the lcp/*_block.dat
//   files) gives a SparseMatrix with the blocks' pattern; storage 2 (CSparse) is rejected as unsupported.
// - MLCP: the equality rows (blocksIsComp = 0, or the first n rows in type 2) get l = −∞, u = +∞, the
//   complementarity rows l = 0, u = +∞. When both storages are present they must agree entry by entry
//   (to 4ε relative) and the type-1 blocks must put the n equality rows first; the problem keeps type 1.
//   A rectangular type-1 M is rejected: Siconos' Rectangular_mlcp.dat (n = m = 1, M 3x2, and type-2 data
//   that matches neither M nor q) has no box-MLCP reading, and Siconos' own test collection leaves it out.
// - After the data a file may hold '#' comments, free-text notes that start a line after an empty line
//   (lcp_CPS_*.dat end with "Remark ..."), and, in MLCP files only, up to 2(n + m) numbers: the reference
//   solution older Siconos tools appended, which Siconos' reader ignores and so do we. Anything else is an error.
// Input is capped at 1 GiB.
BoxMLCP ReadSiconosFile(const std::string& path);
BoxMLCP ReadSiconosFile(const std::string& path, SiconosKind kind);
BoxMLCP ReadSiconosStream(std::istream& in, SiconosKind kind, const std::string& name);

// Writes problem in relay format (n, dense storage 0 with one column per line, q, lb, ub; a sparse M is written
// densely). Numbers use the shortest representation that round-trips (std::to_chars, locale-independent), so
// reading the file back is bit-exact; infinite bounds are written "inf"/"-inf" (read back by this reader and
// by glibc's scanf, which Siconos uses). Throws InvalidInputError if the stream or file fails.
void WriteSiconosRelay(const BoxMLCP& problem, std::ostream& out);
void WriteSiconosRelayFile(const BoxMLCP& problem, const std::string& path);

}  // namespace smcbench

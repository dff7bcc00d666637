// Export of library problems to the Siconos relay format (problems/io/siconos_format.h writes the file), with a
// clear refusal for the problems that format cannot express, and file names derived from problem ids.
#pragma once

#include <iosfwd>
#include <string>

#include "problems/library/problem_set.h"

namespace smcbench {

// The relay format stores M densely as text; larger problems are refused rather than written as n² numbers.
inline constexpr int kMaxSiconosRelayExportSize = 4096;

// True if every bound is finite (Siconos' RelayProblem needs finite lb and ub on every row: its relay solvers
// form ub − lb) and n ≤ kMaxSiconosRelayExportSize. Otherwise false with *why naming the reason, e.g. "row 3 has
// l = 0, u = inf (an LCP row)".
bool CanExportSiconosRelay(const LibraryProblem& problem, std::string* why = nullptr);

// Writes the problem with WriteSiconosRelay (bit-exact numbers; a sparse M is written densely). Throws
// InvalidInputError "problem '<id>': cannot be written in Siconos relay format: row 3 has l = 0, u = inf (an LCP
// row)" if CanExportSiconosRelay is false (nothing is written then), or if writing fails.
void ExportSiconosRelay(const LibraryProblem& problem, std::ostream& out);
void ExportSiconosRelayFile(const LibraryProblem& problem, const std::string& path);

// A portable file name for a problem id: "paper/sign/implicit/h0.01/k12" → "paper_sign_implicit_h0.01_k12.dat".
// Characters outside [A-Za-z0-9._+-] become '_', a leading '.' becomes '_' (no hidden files, no ".."), and an id
// longer than 150 characters is cut and suffixed with its 64-bit hash in hex. Distinct ids may map to the same
// name ("a/b" and "a_b"): callers writing a whole set must check.
std::string SiconosRelayFileName(const std::string& id);

}  // namespace smcbench

// The AVI file (`.avi.json`, docs/formats.md): an AffineVI (solvers/avi/affine_vi.h) as JSON a user can write by
// hand, with an optional reference λ*. Our own format because Siconos' AVI files (AVI_printInFile) hold only n, M
// and q, not the polytope P.
#pragma once

#include <optional>
#include <string>

#include "solvers/avi/affine_vi.h"
#include "solvers/core/types.h"
#include "solvers/core/verdict.h"

namespace smcbench {

inline constexpr const char* kAviFileFormat = "smcbench-avi";  // the "format" key
inline constexpr int kAviFileVersion = 1;                       // the "version" key
inline constexpr const char* kAviFileExtension = ".avi.json";
// A "solution" in a file must pass the AVI rule (PassesAviTolerance, multipliers from AviMultipliersAt) at this
// tolerance: loose enough for a λ* computed in double precision, tight enough that a wrong one is refused.
inline constexpr double kAviFileSolutionTolerance = 1e-8;

// What a file holds: the AVI, its reference λ* when the file gives one (empty otherwise), and the outcome a correct
// backend must produce: the file's "expected" when it says, else ExpectedAviOutcome (solvable on a bounded P).
struct AviFile {
  AffineVI avi;
  Vector solution;
  ExpectedOutcome expected = ExpectedOutcome::kUnknown;
};

// Reads path. Every defect is an InvalidInputError that starts with "AVI file '<path>'" and names the field: a
// missing key, an unknown key, a wrong "format" or "version", a value of the wrong type (a string "nan" included),
// a ragged matrix, sizes that disagree with n = size of q, a number that is not finite, E without f or f without E,
// a "solution" that does not solve the AVI, an "expected" other than "solvable", "infeasible" or "unknown", or
// "infeasible" with a solution or a bounded P (Hartman–Stampacchia), and the AffineVI constructor's own checks (a
// zero row, P empty).
// "name" is optional (default: the file name without ".avi.json" or ".json").
AviFile ReadAviFile(const std::string& path);
// The same on a text; source names it in messages.
AviFile ParseAviText(const std::string& text, const std::string& source, const std::string& default_name = "");

// The text of a file holding avi (and solution when not empty, which must have n entries): one matrix row per line,
// every number in the shortest form that reads back to the same double (std::to_chars; -0 as -0.0), so reading it
// back restores every bit. E and f are written only when p > 0, "expected" only when given.
std::string AviFileText(const AffineVI& avi, const Vector& solution = {},
                        std::optional<ExpectedOutcome> expected = std::nullopt);
// Writes AviFileText to path (InvalidInputError when it cannot be written).
void WriteAviFile(const AffineVI& avi, const std::string& path, const Vector& solution = {},
                  std::optional<ExpectedOutcome> expected = std::nullopt);

// Whether path names an AVI file by its extension (".avi.json", any case).
bool HasAviFileExtension(const std::string& path);

}  // namespace smcbench

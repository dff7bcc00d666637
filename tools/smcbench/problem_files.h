// Which reader a problem file goes through (`solve`, `collection`, `convert`): the kind chosen with --format, or
// guessed from the file's extension, folder, name and, when those say nothing, its content; a read that fails under
// a guessed kind says what was assumed, why, and which --format to use instead (docs/formats.md).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "problems/avi_library/avi_library.h"
#include "problems/io/avi_file.h"
#include "problems/library/problem_set.h"

namespace smcbench {

// kAvi: an affine variational inequality (problems/io/avi_file.h), not a box problem: only `solve` reads it.
enum class ProblemFormat { kLCP, kRelay, kMLCP, kSmcps, kMatrixMarket, kAvi };
std::string_view ToString(ProblemFormat format);  // "lcp", "relay", "mlcp", "smcps", "mtx", "avi": the --format values
std::optional<ProblemFormat> ParseProblemFormat(std::string_view text);
inline constexpr const char* kProblemFormatChoices = "lcp|relay|mlcp|smcps|mtx|avi";

struct FormatChoice {
  ProblemFormat format = ProblemFormat::kLCP;
  bool chosen = false;  // by the user (--format); otherwise guessed
  std::string reason;   // "chosen with --format", "guessed from the folder name 'lcp/'", ...
};

// The kind of path: requested if given, else the guess. Guessing, first match wins: the extension .smcps (or the
// .smcps magic bytes), .mtx and .avi.json; the folder lcp/, relay/, mlcp/; "mlcp" then "relay" in the file name; a
// JSON object whose "format" is "smcbench-avi"; else the content: the Siconos kinds the file reads as without
// error, if exactly one (an LCP if several: the old default; an LCP, whose error is then reported, if none).
FormatChoice ChooseProblemFormat(const std::string& path, std::optional<ProblemFormat> requested);

// The problems in path read under ChooseProblemFormat(path, requested): one for every kind but .smcps, whose
// problems are all returned (ids empty) or those named by ids, in that order; an id ending in '*' selects every id
// with that prefix. A Siconos or Matrix Market problem gets the id "<file stem>" and the source "file:<path>".
// An AVI file or a set of AVIs is refused (InvalidInputError: not box problems; `solve` reads them with
// ReadAviProblemFile and ReadAviProblemSetById).
// Throws InvalidInputError; under a guessed kind the message ends with what was assumed, why, and the --format to
// choose (naming the kind the file does read as, when one does).
std::vector<LibraryProblem> ReadProblemFile(const std::string& path, std::optional<ProblemFormat> requested,
                                            const std::vector<std::string>& ids = {});

// Whether path's header says it holds a set of AVIs (false on any error, so that the box reader reports it).
bool IsAviProblemSetFile(const std::string& path);

// The AVIs of a set of AVIs (.smcps format version 4): all of them (ids empty) or those named by ids, in that
// order, selected as ReadProblemFile selects box problems ('PREFIX*' by prefix; an unknown id lists what exists).
std::vector<AviLibraryProblem> ReadAviProblemSetById(const std::string& path, const std::vector<std::string>& ids);

// The AVI in path, which ChooseProblemFormat(path, requested) must take for an AVI file (InvalidInputError
// otherwise, naming the kind it was taken for). Under a guessed kind a reader's error ends with why it was guessed.
AviFile ReadAviProblemFile(const std::string& path, std::optional<ProblemFormat> requested);

// Writes one problem in the format its name asks for: ".mtx" Matrix Market (NAME.mtx + NAME_q/_l/_u.mtx),
// ".smcps" a one-problem set, anything else Siconos relay text.
void WriteProblemFile(const LibraryProblem& problem, const std::string& path);

}  // namespace smcbench

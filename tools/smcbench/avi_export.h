// `smcbench library --write-suite avi DIR`: the AVI suite as a folder of AVI files (problems/io/avi_file.h), since
// a .smcps set holds box problems only.
#pragma once

#include <cstddef>
#include <string>

#include "problems/avi_library/avi_library.h"

namespace smcbench {

// The file name of an AVI of a set: its id without the suite's "avi/" prefix, every character other than a letter,
// digit, '.', '_' or '-' replaced by '-', then ".avi.json" ("avi/planted/n8/s1" → "planted-n8-s1.avi.json").
std::string AviExportFileName(const std::string& id);

// Writes every AVI of set to dir/AviExportFileName(id), with its expected outcome and its verified reference λ* as
// "solution" (none when the reference is not verified), and dir/index.csv (file,id,n,m,p,expected,source).
// Creates dir. Returns the number of files written. InvalidInputError if two ids give one file name or a file cannot be written.
std::size_t ExportAviSet(const AviProblemSet& set, const std::string& dir);

}  // namespace smcbench

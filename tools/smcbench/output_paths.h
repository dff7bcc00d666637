// Output paths checked before any work: a command given a file where it needs a folder (or the other way round),
// a folder that does not exist, or one it may not write in fails at once with the flag named, not after minutes of
// simulating or certifying (docs/cli.md, "Every command").
#pragma once

#include <string>

namespace smcbench {

// An output file (created or overwritten later): InvalidInputError "FLAG: '<path>' ..." when the path is a folder,
// its folder does not exist or is not a folder, or the file or its folder is not writable.
void CheckOutputFile(const std::string& flag, const std::string& path);

// An output folder (created later with its parents if missing): InvalidInputError "FLAG: '<path>' ..." when the path
// is an existing file, or the folder (or, if it is missing, its nearest existing ancestor) is not a writable folder.
void CheckOutputFolder(const std::string& flag, const std::string& path);

}  // namespace smcbench

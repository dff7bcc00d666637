#include "tools/smcbench/output_paths.h"

#include <unistd.h>

#include <filesystem>
#include <system_error>

#include "solvers/core/problem.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;

bool Writable(const fs::path& p) { return ::access(p.c_str(), W_OK) == 0; }

[[noreturn]] void Fail(const std::string& flag, const std::string& path, const std::string& what) {
  throw InvalidInputError(flag + ": '" + path + "' " + what);
}

}  // namespace

void CheckOutputFile(const std::string& flag, const std::string& path) {
  if (path.empty()) throw InvalidInputError(flag + ": the file name is empty");
  std::error_code ec;
  const fs::path p(path);
  if (fs::is_directory(p, ec)) Fail(flag, path, "is a folder; a file name is expected here");
  const fs::path folder = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  if (!fs::exists(folder, ec)) Fail(flag, path, "cannot be written: its folder '" + folder.string() + "' does not exist");
  if (!fs::is_directory(folder, ec)) Fail(flag, path, "cannot be written: '" + folder.string() + "' is not a folder");
  if (fs::exists(p, ec) ? !Writable(p) : !Writable(folder)) Fail(flag, path, "cannot be written (permission denied)");
}

void CheckOutputFolder(const std::string& flag, const std::string& path) {
  if (path.empty()) throw InvalidInputError(flag + ": the folder name is empty");
  std::error_code ec;
  fs::path p = fs::absolute(fs::path(path), ec);
  if (fs::exists(p, ec) && !fs::is_directory(p, ec)) Fail(flag, path, "is a file; a folder is expected here");
  // The folder itself, or the nearest ancestor that exists (the missing ones are created later).
  while (!fs::exists(p, ec) && p.has_parent_path() && p.parent_path() != p) p = p.parent_path();
  if (!fs::is_directory(p, ec)) Fail(flag, path, "cannot be created: '" + p.string() + "' is not a folder");
  if (!Writable(p)) Fail(flag, path, "cannot be written: '" + p.string() + "' is not writable");
}

}  // namespace smcbench

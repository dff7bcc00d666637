#include "problems/io/data_dirs.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>

#if !defined(SMCBENCH_CHECKOUT_SCENES_DIR) || !defined(SMCBENCH_CHECKOUT_SICONOS_DIR)
#error "SMCBENCH_CHECKOUT_SCENES_DIR and SMCBENCH_CHECKOUT_SICONOS_DIR must be defined (problems/CMakeLists.txt)"
#endif

namespace smcbench {

std::string_view DataFolderName(DataFolder folder) {
  switch (folder) {
    case DataFolder::kScenes: return "scenes";
    case DataFolder::kSiconosCollection: return "siconos";
  }
  return "";
}

std::string_view DataFolderVariable(DataFolder folder) {
  switch (folder) {
    case DataFolder::kScenes: return "SMCBENCH_SCENES_DIR";
    case DataFolder::kSiconosCollection: return "SMCBENCH_SICONOS_DIR";
  }
  return "";
}

namespace {

std::string_view CheckoutDirectory(DataFolder folder) {
  switch (folder) {
    case DataFolder::kScenes: return SMCBENCH_CHECKOUT_SCENES_DIR;
    case DataFolder::kSiconosCollection: return SMCBENCH_CHECKOUT_SICONOS_DIR;
  }
  return "";
}

// <prefix>/share/smcbench/<name> beside the file holding this code, or empty. Five levels up reach the prefix from
// <prefix>/bin and from <prefix>/lib/python3.11/site-packages/smcbench (a pip install into a virtual environment,
// whose data files land in <venv>/share) as from <prefix>/lib/python3/dist-packages/smcbench (cmake --install).
std::string InstalledDirectory(DataFolder folder) {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&InstalledDirectory), &info) == 0 || info.dli_fname == nullptr) return {};
  std::error_code error;
  std::filesystem::path parent = std::filesystem::canonical(info.dli_fname, error).parent_path();
  if (error) return {};
  for (int up = 0; up < 5 && parent.has_relative_path(); ++up, parent = parent.parent_path()) {
    const std::filesystem::path candidate = parent / "share" / "smcbench" / DataFolderName(folder);
    if (std::filesystem::is_directory(candidate, error)) return candidate.string();
  }
  return {};
}

}  // namespace

std::string DataDirectory(DataFolder folder) {
  const std::string variable(DataFolderVariable(folder));
  if (const char* dir = std::getenv(variable.c_str()); dir && *dir) return dir;
  if (std::string installed = InstalledDirectory(folder); !installed.empty()) return installed;
  return std::string(CheckoutDirectory(folder));
}

}  // namespace smcbench

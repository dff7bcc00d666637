// DataDirectory: in a build tree every data folder is the checkout's own (whatever the working directory), and the
// environment variables override it. The installed and moved-prefix lookup is checked by tools/install-check.sh.
#include "problems/io/data_dirs.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>

#include <unistd.h>

namespace smcbench {
namespace {

namespace fs = std::filesystem;

constexpr DataFolder kFolders[] = {DataFolder::kScenes, DataFolder::kSiconosCollection};

// Sets or unsets one environment variable for the lifetime of the guard, then restores it.
class EnvironmentGuard {
 public:
  EnvironmentGuard(std::string name, const char* value) : name_(std::move(name)) {
    if (const char* old = std::getenv(name_.c_str())) old_ = old;
    if (value) {
      ::setenv(name_.c_str(), value, 1);
    } else {
      ::unsetenv(name_.c_str());
    }
  }
  ~EnvironmentGuard() {
    if (old_) {
      ::setenv(name_.c_str(), old_->c_str(), 1);
    } else {
      ::unsetenv(name_.c_str());
    }
  }
  EnvironmentGuard(const EnvironmentGuard&) = delete;
  EnvironmentGuard& operator=(const EnvironmentGuard&) = delete;

 private:
  std::string name_;
  std::optional<std::string> old_;
};

// Changes the working directory for the lifetime of the guard.
class WorkingDirectoryGuard {
 public:
  explicit WorkingDirectoryGuard(const fs::path& dir) : old_(fs::current_path()) { fs::current_path(dir); }
  ~WorkingDirectoryGuard() { fs::current_path(old_); }
  WorkingDirectoryGuard(const WorkingDirectoryGuard&) = delete;
  WorkingDirectoryGuard& operator=(const WorkingDirectoryGuard&) = delete;

 private:
  fs::path old_;
};

TEST(DataDirectory, NamesAndVariables) {
  EXPECT_EQ(DataFolderName(DataFolder::kScenes), "scenes");
  EXPECT_EQ(DataFolderName(DataFolder::kSiconosCollection), "siconos");
  EXPECT_EQ(DataFolderVariable(DataFolder::kScenes), "SMCBENCH_SCENES_DIR");
  EXPECT_EQ(DataFolderVariable(DataFolder::kSiconosCollection), "SMCBENCH_SICONOS_DIR");
}

// A test binary lives in the build tree, where no share/smcbench is installed: the checkout's folders, as absolute
// paths, from any working directory (the installed tool's bug was a default relative to it).
TEST(DataDirectory, BuildTreeUsesTheCheckoutFromAnyWorkingDirectory) {
  const fs::path empty = fs::temp_directory_path() / ("smcbench-data-dirs-" + std::to_string(::getpid()));
  fs::create_directories(empty);
  {
    WorkingDirectoryGuard cd(empty);
    EnvironmentGuard no_scenes("SMCBENCH_SCENES_DIR", nullptr);
    EnvironmentGuard no_siconos("SMCBENCH_SICONOS_DIR", nullptr);
    EXPECT_EQ(fs::path(DataDirectory(DataFolder::kScenes)),
              fs::path(SMCBENCH_SOURCE_DIR) / "problems" / "scenes");
    EXPECT_EQ(fs::path(DataDirectory(DataFolder::kSiconosCollection)),
              fs::path(SMCBENCH_PEER_DATA_DIR) / "siconos");
    for (DataFolder folder : kFolders) {
      const fs::path dir = DataDirectory(folder);
      EXPECT_TRUE(dir.is_absolute()) << dir;
      EXPECT_TRUE(fs::is_directory(dir)) << dir;
    }
    EXPECT_TRUE(fs::is_regular_file(fs::path(DataDirectory(DataFolder::kScenes)) / "sign.json"));
    EXPECT_TRUE(fs::is_regular_file(fs::path(DataDirectory(DataFolder::kSiconosCollection)) / "lcp" / "lcp_mmc.dat"));
  }
  fs::remove_all(empty);
}

TEST(DataDirectory, EnvironmentVariableOverridesAndEmptyIsIgnored) {
  for (DataFolder folder : kFolders) {
    const std::string variable(DataFolderVariable(folder));
    std::string default_dir;
    {
      EnvironmentGuard unset(variable, nullptr);
      default_dir = DataDirectory(folder);
    }
    {
      // The folder need not exist: the caller reports a missing folder with its own flag's name.
      EnvironmentGuard set(variable, "/somewhere/else");
      EXPECT_EQ(DataDirectory(folder), "/somewhere/else") << variable;
    }
    {
      EnvironmentGuard empty(variable, "");
      EXPECT_EQ(DataDirectory(folder), default_dir) << variable;
    }
  }
  // One variable moves one folder only.
  EnvironmentGuard no_scenes("SMCBENCH_SCENES_DIR", nullptr);
  const std::string scenes = DataDirectory(DataFolder::kScenes);
  EnvironmentGuard set("SMCBENCH_SICONOS_DIR", "/somewhere/else");
  EXPECT_EQ(DataDirectory(DataFolder::kScenes), scenes);
}

}  // namespace
}  // namespace smcbench

// The data folders of this smcbench (the scenes, the Siconos collection): one lookup for every program and the
// Python module, so a default path resolves from a checkout's build tree and from an installed, even moved, prefix.
#pragma once

#include <string>
#include <string_view>

namespace smcbench {

// The data folders smcbench installs under <prefix>/share/smcbench (cmake/SmcbenchInstall.cmake).
enum class DataFolder {
  kScenes,             // share/smcbench/scenes: the scene files (checkout: problems/scenes)
  kSiconosCollection,  // share/smcbench/siconos: the Siconos collection (checkout: tests/data/siconos)
};

// "scenes", "siconos": the folder's name under share/smcbench.
std::string_view DataFolderName(DataFolder folder);

// The environment variable that overrides the folder: SMCBENCH_SCENES_DIR, SMCBENCH_SICONOS_DIR.
std::string_view DataFolderVariable(DataFolder folder);

// Where the folder is, first match wins:
//  1. $SMCBENCH_SCENES_DIR / $SMCBENCH_SICONOS_DIR, when set and not empty;
//  2. <prefix>/share/smcbench/<name> of the installation holding this code: the file holding it (the program
//     <prefix>/bin/smcbench, or the Python module .../lib/python3*/site-packages/smcbench/_smcbench*.so) is found
//     with dladdr and its parent folders are searched, so a moved prefix or a virtual environment still works;
//  3. the checkout's folder this code was built from (compile definitions, problems/CMakeLists.txt).
// Never relative to the working directory, so the answer does not depend on where the program is started.
std::string DataDirectory(DataFolder folder);

}  // namespace smcbench

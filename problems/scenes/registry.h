// The scenes of docs/scenes.md by name. An explicit list (no static registration): a linear scene is a JSON file in
// this folder; a scene that needs code is a factory function. Adding one is one line in registry.cc.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "problems/scenes/scene.h"

namespace smcbench {

// Registered names in the order of docs/scenes.md (S1 sign, S2 galias-yu-2007, ...).
std::vector<std::string_view> SceneNames();
// The report's scenes S1–S11 alone (the paper's suites and problem sets are made of these), in the same order.
std::vector<std::string_view> PaperSceneNames();

// The folder holding the scene files: DataDirectory(DataFolder::kScenes) (problems/io/data_dirs.h):
// $SMCBENCH_SCENES_DIR if set, else the installed <prefix>/share/smcbench/scenes of an installed program or Python
// module, else this source folder.
std::string ScenesDirectory();

// A registered name, or a path to a scene file (anything that is not a registered name and names an existing file,
// or ends in .json). Throws InvalidInputError: unknown name (listing the known ones), unreadable or malformed file
// (naming the field).
std::unique_ptr<Scene> LoadScene(std::string_view name_or_path);

}  // namespace smcbench

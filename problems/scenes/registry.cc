#include "problems/scenes/registry.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <system_error>

#include "problems/io/data_dirs.h"
#include "problems/scenes/linear_scene.h"
#include "problems/scenes/nonlinear_scene.h"
#include "problems/scenes/super_twisting_scene.h"

namespace smcbench {
namespace {

using Factory = std::unique_ptr<Scene> (*)();

struct Entry {
  std::string_view name;
  std::string_view file;  // a JSON file in ScenesDirectory(), or empty for a C++ scene
  Factory make;           // the C++ scene, or null for a file
  bool paper = false;     // one of the report's S1–S11
};

// The registry, in the order of docs/scenes.md. Nonlinear scenes (S9 hypomonotone, S10 arctan) are C++ scenes.
constexpr Entry kScenes[] = {
    {"sign", "sign.json", nullptr, true},                      // S1
    {"galias-yu-2007", "galias-yu-2007.json", nullptr, true},  // S2
    {"multi-surface", "multi-surface.json", nullptr, true},    // S3
    {"filippov", "filippov.json", nullptr, true},              // S4
    {"zoh-siso", "zoh-siso.json", nullptr, true},              // S5
    {"zoh-mimo", "zoh-mimo.json", nullptr, true},              // S6
    {"lyapunov", "lyapunov.json", nullptr, true},              // S7
    {"observer", "observer.json", nullptr, true},              // S8
    {"hypomonotone", "", &MakeHypomonotoneScene, true},        // S9
    {"arctan", "", &MakeArctanScene, true},                    // S10
    {"parasitic", "parasitic.json", nullptr, true},            // S11
    // Higher-order sliding modes (docs/smc.md): super-twisting, implicit (BPE 2020) and explicit Euler.
    {"super-twisting", "super-twisting.json", nullptr, false},
    {"super-twisting-explicit", "super-twisting-explicit.json", nullptr, false},
    {"super-twisting-disturbed", "super-twisting-disturbed.json", nullptr, false},
    {"super-twisting-disturbed-explicit", "super-twisting-disturbed-explicit.json", nullptr, false},
    // Twisting (docs/smc.md, "Implicit twisting"): Siconos' tutorial and its three controllers on its regression plant.
    {"twisting-double-integrator", "twisting-double-integrator.json", nullptr, false},
    {"twisting", "twisting.json", nullptr, false},
    {"regular-twisting", "regular-twisting.json", nullptr, false},
    {"explicit-twisting", "explicit-twisting.json", nullptr, false},
};

// A scene file: a super-twisting scene if its system type says so, else a linear scene (whose reader reports every
// defect, unreadable or malformed files included).
std::unique_ptr<Scene> SceneFromFile(const std::string& path) {
  std::ifstream in(path);
  if (in) {
    std::ostringstream text;
    text << in.rdbuf();
    const nlohmann::json doc = nlohmann::json::parse(text.str(), nullptr, /*allow_exceptions=*/false);
    if (!doc.is_discarded() && IsSuperTwistingDocument(doc)) return SuperTwistingScene::FromJson(doc, path);
  }
  return LinearScene::FromFile(path);
}

}  // namespace

std::vector<std::string_view> SceneNames() {
  std::vector<std::string_view> names;
  for (const Entry& e : kScenes) names.push_back(e.name);
  return names;
}

std::vector<std::string_view> PaperSceneNames() {
  std::vector<std::string_view> names;
  for (const Entry& e : kScenes) {
    if (e.paper) names.push_back(e.name);
  }
  return names;
}

std::string ScenesDirectory() { return DataDirectory(DataFolder::kScenes); }

std::unique_ptr<Scene> LoadScene(std::string_view name_or_path) {
  for (const Entry& e : kScenes) {
    if (e.name != name_or_path) continue;
    if (e.make) return e.make();
    auto scene = SceneFromFile((std::filesystem::path(ScenesDirectory()) / e.file).string());
    if (scene->info().name != e.name) {
      throw InvalidInputError("scene file for '" + std::string(e.name) + "' declares the name '" +
                              scene->info().name + "'");
    }
    return scene;
  }
  const std::string path(name_or_path);
  std::error_code ec;
  const bool looks_like_path = path.find('/') != std::string::npos ||
                               (path.size() > 5 && path.compare(path.size() - 5, 5, ".json") == 0);
  if (looks_like_path || std::filesystem::is_regular_file(path, ec)) return SceneFromFile(path);
  std::string known;
  for (const Entry& e : kScenes) known += (known.empty() ? "" : ", ") + std::string(e.name);
  throw InvalidInputError("unknown scene '" + path + "' (known: " + known + "; or give the path of a scene file)");
}

}  // namespace smcbench

// libFuzzer target for the scene-file reader (LinearScene::FromText, with the expression evaluator it uses): any
// input must give a scene or an InvalidInputError; another exception, a crash, a hang or a sanitizer report is a bug.
// An accepted scene is also discretized with its own defaults, as `smcbench simulate` does before the first step.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>
#include <typeinfo>

#include "problems/scenes/linear_scene.h"
#include "tests/fuzz/fuzz_checks.h"

namespace {

using smcbench::fuzz::Finding;

// Only non-empty: a scene error may quote the offending lines of the file.
void CheckMessage(const smcbench::InvalidInputError& e) {
  const std::string message = e.what();
  if (message.empty()) Finding("InvalidInputError with an empty message");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const auto scene = smcbench::LinearScene::FromText(text, "fuzz.json");
    const smcbench::SceneInfo& info = scene->info();
    if (info.n <= 0 || info.m <= 0) Finding("accepted a scene without state or surfaces");
    const smcbench::SimulationSettings& defaults = scene->defaults();
    if (defaults.x0.size() != info.n || !(defaults.h > 0.0)) Finding("accepted invalid default settings");
    try {
      (void)scene->Discretization(defaults);
      (void)scene->Exact(defaults);
    } catch (const smcbench::InvalidInputError& e) {
      CheckMessage(e);  // e.g. I − hθE singular for these parameters: an error, not a crash
    }
  } catch (const smcbench::InvalidInputError& e) {
    CheckMessage(e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "FINDING: unexpected %s: %s\n", typeid(e).name(), e.what());
    std::abort();
  }
  return 0;
}

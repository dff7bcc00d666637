// libFuzzer target for the scene-file reader (LinearScene::FromText, with the expression evaluator it uses): any
// input must give a scene or an InvalidInputError; another exception, a crash, a hang or a sanitizer report is a bug.
// An accepted scene is also discretized with its own defaults, as `smcbench simulate` does before the first step.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "problems/scenes/linear_scene.h"
#include "tests/fuzz/fuzz_checks.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using smcbench::fuzz::AcceptOrReject;
  using smcbench::fuzz::Finding;
  using smcbench::fuzz::MessageRule;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  // A scene error may quote the offending lines of the file: its message must only be non-empty.
  AcceptOrReject(
      [&] {
        const auto scene = smcbench::LinearScene::FromText(text, "fuzz.json");
        const smcbench::SceneInfo& info = scene->info();
        if (info.n <= 0 || info.m <= 0) Finding("accepted a scene without state or surfaces");
        const smcbench::SimulationSettings& defaults = scene->defaults();
        if (defaults.x0.size() != info.n || !(defaults.h > 0.0)) Finding("accepted invalid default settings");
        AcceptOrReject(  // an error (e.g. I − hθE singular for these parameters), not a crash
            [&] {
              (void)scene->Discretization(defaults);
              (void)scene->Exact(defaults);
            },
            MessageRule::kNonEmpty);
      },
      MessageRule::kNonEmpty);
  return 0;
}

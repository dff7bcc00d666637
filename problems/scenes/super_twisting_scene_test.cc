// Scene files for the higher-order sliding modes (docs/smc.md): the super-twisting scenes by name, their summary and
// their checks; and the time-varying relation term e(t) of linear scenes (y = C x + D + e(t)).
#include "problems/scenes/super_twisting_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "problems/scenes/linear_scene.h"
#include "problems/scenes/registry.h"
#include "problems/scenes/run_summary.h"
#include "problems/scenes/scene_overrides.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

using json = nlohmann::json;

TEST(SuperTwistingScenes, RegisteredScenesLoadAndRunAsTheirFilesSay) {
  for (const char* name : {"super-twisting", "super-twisting-explicit", "super-twisting-disturbed",
                           "super-twisting-disturbed-explicit"}) {
    const auto scene = LoadScene(name);
    ASSERT_NE(dynamic_cast<const SuperTwistingScene*>(scene.get()), nullptr) << name;
    EXPECT_EQ(scene->info().n, 2);
    EXPECT_EQ(scene->info().m, 1);
    const SceneRunSettings run = ApplySceneOverrides(*scene, {}, OverrideSpelling::kCommandLine);
    EXPECT_TRUE(run.backend.empty()) << name << ": the closed form and the explicit scheme need no backend";
    const Trajectory tr = scene->Run(run.settings, nullptr);
    ASSERT_TRUE(tr.ok()) << name;
    const json summary = SimulationSummary(*scene, run.settings, "", tr, run.reach_tolerance, 0.0);
    const json& st = summary.at("super_twisting");
    ASSERT_FALSE(st.at("convergence_step").is_null()) << name << ": never inside the scene's band";
    EXPECT_LE(st.at("max_abs_sigma_tail").get<double>(), st.at("band").get<double>()) << name;
  }
  // The undisturbed implicit scene: σ = 0 exactly over the whole tail, so the precision is 0, not small.
  const auto scene = LoadScene("super-twisting");
  const Trajectory tr = scene->Run(scene->defaults(), nullptr);
  const json summary = SimulationSummary(*scene, scene->defaults(), "", tr, 1e-9, 0.0);
  EXPECT_EQ(summary["super_twisting"]["max_abs_sigma_tail"].get<double>(), 0.0);
  EXPECT_EQ(summary["super_twisting"]["max_abs_sigma_dot_tail"].get<double>(), 0.0);
  EXPECT_EQ(summary["algorithm"], "closed-form");
}

TEST(SuperTwistingScenes, AlgorithmMcpOnNewtonGivesTheClosedFormsRun) {
  const auto scene = LoadScene("super-twisting-disturbed");
  SceneOverrides o;
  o.algorithm = "mcp";
  const SceneRunSettings run = ApplySceneOverrides(*scene, o, OverrideSpelling::kCommandLine);
  EXPECT_EQ(run.backend, "newton");
  auto newton = CreateSolver(run.backend);
  CheckSceneBackend(run, *newton, OverrideSpelling::kCommandLine);
  const Trajectory via_mcp = scene->Run(run.settings, newton.get());
  const Trajectory closed = scene->Run(scene->defaults(), nullptr);
  ASSERT_TRUE(via_mcp.ok()) << via_mcp.first_failure_message;
  EXPECT_LE((via_mcp.x - closed.x).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_GT(via_mcp.total_iterations, 0);
}

TEST(SuperTwistingScenes, WrongAlgorithmsAndFieldsAreNamed) {
  const auto scene = LoadScene("super-twisting");
  SceneOverrides o;
  o.algorithm = "newton-mlcp";
  try {
    ApplySceneOverrides(*scene, o, OverrideSpelling::kPython);
    FAIL() << "newton-mlcp accepted for a super-twisting scene";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("algorithm"), std::string::npos) << e.what();
  }
  const auto hypomonotone = LoadScene("hypomonotone");
  o.algorithm = "closed-form";
  EXPECT_THROW(ApplySceneOverrides(*hypomonotone, o, OverrideSpelling::kPython), InvalidInputError);
  const std::string bad = R"({"name": "st", "description": "d", "system": {"type": "super-twisting", "k1": 1,
      "k2": -1}, "simulation": {"method": "implicit", "h": 0.01, "T": 1, "x0": [1, 0]}})";
  try {
    SuperTwistingScene::FromJson(json::parse(bad), "bad.json");
    FAIL() << "k2 < 0 accepted";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("k2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos) << e.what();
  }
  const std::string typo = R"({"name": "st", "description": "d", "system": {"type": "super-twisting", "k1": 1,
      "k2": 1, "disturbance": {"sinusoid": []}}, "simulation": {"method": "implicit", "h": 0.01, "T": 1, "x0": [1, 0]}})";
  try {
    SuperTwistingScene::FromJson(json::parse(typo), "typo.json");
    FAIL() << "an unknown key accepted";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("system.disturbance"), std::string::npos) << e.what();
  }
}

// x' ∈ −sgn(x + e(t)) (E = 0, B = C = 1): the implicit scheme slides on y = x + e = 0, i.e. x_k = −e(t_k) exactly once
// |e(t_{k+1}) − e(t_k)| ≤ h (here |e'| ≤ 0.2 < 1), from x0 = 1 after about 1 time unit.
std::string OffsetScene(const std::string& offset) {
  return R"json({"name": "offset", "description": "x' in -sgn(x + e(t))", "parameters": {"a": 0.2},
    "system": {"type": "sign", "E": [[0]], "B": [[1]], "C": [[1]], "relation_offset": [)json" +
         offset + R"json(]}, "simulation": {"method": "implicit", "h": 0.01, "T": 5, "x0": [1]}})json";
}

TEST(RelationOffset, ImplicitRunSlidesOnCxPlusEEqualsZero) {
  auto lemke = CreateSolver("lemke");
  {
    // A constant e shifts the surface: x slides on x = −0.3.
    const auto scene = LinearScene::FromText(OffsetScene("0.3"), "constant.json");
    const Trajectory tr = scene->Run(scene->defaults(), lemke.get());
    ASSERT_TRUE(tr.ok());
    EXPECT_NEAR(tr.x_final[0], -0.3, 1e-12);
    EXPECT_NEAR(tr.y_final[0], 0.0, 1e-12);
  }
  const auto scene = LinearScene::FromText(OffsetScene(R"({"type": "sin", "amplitude": "a", "omega": 1})"), "sin.json");
  for (bool rebuild : {false, true}) {
    Trajectory tr;
    if (rebuild) {
      SimulationSettings s = scene->defaults();
      SimulateRebuildingEachStep(scene->Model(s.parameters), s.method, s.h, s.theta, s.x0, NumSteps(s.T, s.h),
                                 lemke.get(), s.stepper, &tr);
    } else {
      tr = scene->Run(scene->defaults(), lemke.get());
    }
    ASSERT_TRUE(tr.ok());
    int sliding = 0;
    for (std::int64_t k = 0; k <= tr.steps_taken; ++k) {
      const double e = 0.2 * std::sin(tr.t[static_cast<std::size_t>(k)]);
      // y_k is recorded with e(t_k).
      ASSERT_NEAR(tr.y(0, k), tr.x(0, k) + e, 1e-15) << k;
      if (tr.t[static_cast<std::size_t>(k)] >= 1.5) {
        ASSERT_NEAR(tr.x(0, k), -e, 1e-12) << "rebuild " << rebuild << ", k = " << k;
        ++sliding;
      }
    }
    EXPECT_GT(sliding, 300);
  }
  // The explicit scheme sees e(t_k) in sgn(y_k): it chatters around x = −e(t) within h.
  SimulationSettings s = scene->defaults();
  s.method = Method::kExplicit;
  s.theta = 0.0;
  const Trajectory tr = scene->Run(s, nullptr);
  for (std::int64_t k = 0; k <= tr.steps_taken; ++k) {
    if (tr.t[static_cast<std::size_t>(k)] >= 1.5) {
      ASSERT_LE(std::abs(tr.y(0, k)), 2 * s.h) << k;
    }
  }
}

TEST(RelationOffset, WrongSizeNamesTheField) {
  try {
    LinearScene::FromText(OffsetScene("0.1, 0.2"), "two.json");
    FAIL() << "two entries accepted for m = 1";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("system.relation_offset"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace smcbench

// The overrides every caller of a scene run shares (scene_overrides.h): the same values refused with the same words
// in both spellings, the defaults they fall back on, the backend they pick and the notes they leave.
#include "problems/scenes/scene_overrides.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "problems/scenes/registry.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

// The message of the InvalidInputError the overrides raise, or "" if they pass.
std::string ErrorOf(const std::string& scene_name, const SceneOverrides& o, OverrideSpelling spelling) {
  const auto scene = LoadScene(scene_name);
  try {
    ApplySceneOverrides(*scene, o, spelling);
  } catch (const InvalidInputError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneOverrides, BadNumbersNameTheFieldInTheCallersSpellingAndTheValue) {
  struct Case {
    SceneOverrides overrides;
    std::string command_line, python;
  };
  SceneOverrides h, T, theta, max_iter, newton_max, tol, substeps, reach;
  h.h = 0.0;
  T.T = -1.0;
  theta.theta = 2.0;
  max_iter.max_iterations = -1;
  newton_max.newton_max_iterations = 0;
  tol.tolerance = -1e-3;
  substeps.plant_substeps = 0;
  reach.reach_tolerance = -1.0;
  const Case cases[] = {
      {h, "--h must be a positive finite time step, got 0", "h must be a positive finite time step, got 0"},
      {T, "--T must be a finite horizon >= 0, got -1", "T must be a finite horizon >= 0, got -1"},
      {theta, "--theta must lie in [0, 1], got 2", "theta must lie in [0, 1], got 2"},
      {max_iter, "--max-iter must be an integer >= 0 (0: the backend's default), got -1",
       "max_iterations must be an integer >= 0 (0: the backend's default), got -1"},
      {newton_max, "--newton-max-iter: the newton iteration limit must be >= 1, got 0",
       "newton_max_iterations: the newton iteration limit must be >= 1, got 0"},
      {tol, "--tol must be a positive finite number, got -0.001", "tol must be a positive finite number, got -0.001"},
      {substeps, "--plant-substeps must be an integer >= 1, got 0", "plant_substeps must be an integer >= 1, got 0"},
      {reach, "--reach-tol must be finite and >= 0, got -1", "reach_tol must be finite and >= 0, got -1"},
  };
  for (const Case& c : cases) {
    EXPECT_EQ(ErrorOf("sign", c.overrides, OverrideSpelling::kCommandLine), c.command_line);
    EXPECT_EQ(ErrorOf("sign", c.overrides, OverrideSpelling::kPython), c.python);
  }
  SceneOverrides method, parameter, on_failure;
  method.method = "rk4";
  parameter.parameters = {{"tao", 1.0}};
  on_failure.on_failure = "retry";
  EXPECT_EQ(ErrorOf("sign", method, OverrideSpelling::kCommandLine),
            "--method: unknown method 'rk4' (known: implicit, explicit, zoh, zoh-explicit)");
  EXPECT_EQ(ErrorOf("observer", parameter, OverrideSpelling::kPython),
            "parameters: the scene has no parameter 'tao' (parameters: k, tau)");
  EXPECT_EQ(ErrorOf("sign", on_failure, OverrideSpelling::kCommandLine),
            "--on-failure: expected stop or continue, got 'retry'");
  // The whole is validated too: an x0 of the wrong size, a method the scene cannot run.
  SceneOverrides x0, zoh;
  x0.x0 = Vector::Zero(3);
  zoh.method = "zoh";
  EXPECT_THAT(ErrorOf("galias-yu-2007", x0, OverrideSpelling::kPython), HasSubstr("x0 has 3 entries"));
  EXPECT_THAT(ErrorOf("sign", zoh, OverrideSpelling::kPython), HasSubstr("needs a ZOH plant"));
}

TEST(SceneOverrides, UnsetFieldsKeepTheScenesValues) {
  const auto scene = LoadScene("observer");
  SceneOverrides o;
  o.parameters = {{"tau", 0.5}};
  o.tolerance = 1e-8;
  const SceneRunSettings run = ApplySceneOverrides(*scene, o, OverrideSpelling::kPython);
  const SimulationSettings& d = scene->defaults();
  EXPECT_EQ(run.settings.method, d.method);
  EXPECT_EQ(run.settings.h, d.h);
  EXPECT_EQ(run.settings.T, d.T);
  EXPECT_EQ(run.settings.theta, d.theta);
  EXPECT_EQ(run.settings.x0, d.x0);
  EXPECT_EQ(run.settings.parameters.at("tau"), 0.5);
  EXPECT_EQ(run.settings.stepper.solver.tolerance, 1e-8);
  EXPECT_EQ(run.reach_tolerance, 1e-7);  // 10 × tol
  EXPECT_EQ(run.backend, d.solver.empty() ? std::string(kDefaultSceneBackend) : d.solver);
  EXPECT_TRUE(run.notes.empty());
  EXPECT_FALSE(run.nonlinear);
}

TEST(SceneOverrides, ExplicitAloneIsClassicalExplicitEuler) {
  const auto scene = LoadScene("galias-yu-2007");
  SceneOverrides o;
  o.method = "explicit";
  o.solver = "lemke";
  SceneRunSettings run = ApplySceneOverrides(*scene, o, OverrideSpelling::kCommandLine);
  EXPECT_EQ(run.settings.theta, 0.0);
  EXPECT_EQ(run.settings.gamma, 0.0);
  EXPECT_EQ(run.backend, "");  // no one-step problem, no backend
  EXPECT_THAT(run.notes, ElementsAre("--solver is ignored: method explicit solves no one-step problem"));
  o.theta = 0.5;
  o.solver.reset();
  run = ApplySceneOverrides(*scene, o, OverrideSpelling::kCommandLine);
  EXPECT_EQ(run.settings.theta, 0.5);
  EXPECT_TRUE(run.notes.empty());
}

TEST(SceneOverrides, NotesForOverridesWithoutEffect) {
  SceneOverrides o;
  o.gamma = 0.5;
  o.algorithm = "mcp";
  const auto sign = LoadScene("sign");
  EXPECT_THAT(ApplySceneOverrides(*sign, o, OverrideSpelling::kPython).notes,
              ElementsAre("algorithm, newton_tol and newton_max_iterations apply to nonlinear scenes only; a linear "
                          "scene solves one box-MLCP per step",
                          "gamma has no effect on a linear scene (g(x) = B is constant)"));
  // A ZOH plant's points between samples need a ZOH method.
  SceneOverrides implicit;
  implicit.method = "implicit";
  implicit.plant_substeps = 3;
  EXPECT_THAT(ErrorOf("zoh-siso", implicit, OverrideSpelling::kCommandLine),
              HasSubstr("--plant-substeps 3 needs method zoh or zoh-explicit"));
  implicit.plant_substeps = 1;
  EXPECT_EQ(ErrorOf("zoh-siso", implicit, OverrideSpelling::kCommandLine), "");
}

TEST(SceneOverrides, AlgorithmOneTakesNewtonAndRefusesABoxOnlyBackend) {
  const auto scene = LoadScene("hypomonotone");
  SceneOverrides o;
  o.algorithm = "mcp";
  SceneRunSettings run = ApplySceneOverrides(*scene, o, OverrideSpelling::kCommandLine);
  EXPECT_TRUE(run.nonlinear);
  EXPECT_EQ(run.backend, "newton");
  EXPECT_NO_THROW(CheckSceneBackend(run, *CreateSolver(run.backend), OverrideSpelling::kCommandLine));
  o.solver = "lemke";
  run = ApplySceneOverrides(*scene, o, OverrideSpelling::kPython);
  try {
    CheckSceneBackend(run, *CreateSolver(run.backend), OverrideSpelling::kPython);
    FAIL() << "lemke accepted for Algorithm 1";
  } catch (const InvalidInputError& e) {
    EXPECT_EQ(std::string(e.what()), "algorithm mcp needs a backend that solves nonlinear MCPs (newton); 'lemke' "
                                     "solves box-MLCPs only: use algorithm newton-mlcp with it");
  }
}

TEST(SceneOverrides, ZohPlantOfNeedsAZohSystem) {
  const auto zoh = LoadScene("zoh-siso");
  const ZohSmcSystem plant = ZohPlantOf(*zoh, zoh->defaults().parameters);
  EXPECT_EQ(plant.F.rows(), 2);
  EXPECT_THROW(ZohPlantOf(*LoadScene("sign"), {}), InvalidInputError);
  EXPECT_THROW(ZohPlantOf(*LoadScene("arctan"), {}), InvalidInputError);
}

}  // namespace
}  // namespace smcbench

// Scene files for the higher-order sliding modes (docs/smc.md): the super-twisting scenes by name, their summary and
// their checks; and the time-varying relation term e(t) of linear scenes (y = C x + D + e(t)).
#include "problems/scenes/super_twisting_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <variant>
#include <vector>

#include "problems/scenes/linear_scene.h"
#include "problems/scenes/registry.h"
#include "problems/scenes/run_summary.h"
#include "problems/scenes/scene_overrides.h"
#include "problems/stepper/linear_stepper.h"
#include "problems/stepper/sampled_plant.h"
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

// The same relation term on a ZOH plant with the equivalent-control SMC (zoh-siso's plant, h = 0.01): x' = F x + G u,
// u = −(CG)⁻¹(CF x_k + α s_{k+1}), s_{k+1} ∈ Sgn(C x_{k+1} + e(t_{k+1})). Without a disturbance the ZOH prediction
// x_{k+1} is the plant's next sample, so once sliding C x_k + e(t_k) = 0 at every sample up to rounding, as long as
// the step can follow e: |e(t_{k+1}) − e(t_k)| ≤ α CΓ ≈ α h (here sup|ė| = 0.2 < α = 1). Reaching: σ = C x + e falls
// at rate α from σ0 = 1.1 + e(0), so every run below slides from t = 2 on.
std::string ZohOffsetScene(const std::string& offset_key, const std::string& method = "zoh") {
  return R"json({"name": "zoh-offset", "description": "ZOH ECB-SMC, y = C x + e(t)", "parameters": {"a": 0.2},
    "system": {"type": "zoh", "F": [[0, 1], [2, -2]], "G": [[0], [1]], "C": [[1, 1]], "alpha": 1)json" +
         offset_key + R"json(}, "simulation": {"method": ")json" + method +
         R"json(", "h": 0.01, "T": 5, "x0": [0.55, 0.55]}})json";
}

constexpr double kZohSlidingFrom = 2.0;

TEST(RelationOffset, ZohConstantOffsetShiftsTheSurface) {
  auto lemke = CreateSolver("lemke");
  for (const char* method : {"zoh", "implicit"}) {  // the ZOH step and the θ-method on the closed loop
    const auto scene = LinearScene::FromText(ZohOffsetScene(R"(, "relation_offset": [0.3])", method), "c.json");
    const Trajectory tr = scene->Run(scene->defaults(), lemke.get());
    ASSERT_TRUE(tr.ok()) << method << ": " << tr.first_failure_message;
    int sliding = 0;
    for (std::int64_t k = 0; k <= tr.steps_taken; ++k) {
      const double cx = tr.x(0, k) + tr.x(1, k);
      ASSERT_NEAR(tr.y(0, k), cx + 0.3, 1e-15) << method << " k = " << k;  // y_k = C x_k + D, D = e
      if (tr.t[static_cast<std::size_t>(k)] >= kZohSlidingFrom) {
        ASSERT_NEAR(cx, -0.3, 1e-10) << method << " k = " << k;
        ++sliding;
      }
    }
    EXPECT_GT(sliding, 250) << method;
  }
}

TEST(RelationOffset, ZohTracksASinusoidalOffsetAtEverySample) {
  auto lemke = CreateSolver("lemke");
  const std::string key = R"(, "relation_offset": [{"type": "sin", "amplitude": "a", "omega": 1}])";
  for (const char* method : {"zoh", "implicit"}) {
    const auto scene = LinearScene::FromText(ZohOffsetScene(key, method), "sin.json");
    for (bool rebuild : {false, true}) {
      Trajectory tr;
      const SimulationSettings s = scene->defaults();
      if (rebuild) {
        SimulateRebuildingEachStep(scene->Model(s.parameters), s.method, s.h, s.theta, s.x0, NumSteps(s.T, s.h),
                                   lemke.get(), s.stepper, &tr);
      } else {
        tr = scene->Run(s, lemke.get());
      }
      ASSERT_TRUE(tr.ok()) << method;
      int sliding = 0;
      for (std::int64_t k = 0; k <= tr.steps_taken; ++k) {
        const double t = tr.t[static_cast<std::size_t>(k)];
        const double e = 0.2 * std::sin(t);
        const double cx = tr.x(0, k) + tr.x(1, k);
        ASSERT_NEAR(tr.y(0, k), cx + e, 1e-14) << k;  // y_k has e(t_k)
        if (t >= kZohSlidingFrom) {
          // Exact at the samples (see ZohOffsetScene), not merely O(h sup|ė|): rounding of the step only.
          ASSERT_LE(std::abs(cx + e), 1e-12) << method << (rebuild ? " rebuilt" : "") << " k = " << k;
          ++sliding;
        }
      }
      EXPECT_GT(sliding, 250) << method;
    }
  }
}

// Every row a sink receives: t, x (n = 2) and y (m = 1).
class ZohRows final : public TrajectorySink {
 public:
  void OnRows(const TrajectoryBlock& block) override {
    for (std::int64_t j = 0; j < block.rows; ++j) {
      const auto c = static_cast<Eigen::Index>(j);
      t.push_back(block.t[static_cast<std::size_t>(j)]);
      cx.push_back(block.x(0, c) + block.x(1, c));
      y.push_back(block.y(0, c));
    }
  }
  std::vector<double> t, cx, y;
};

TEST(RelationOffset, ZohPlantBetweenSamplesStaysWithinTwoHSupEdot) {
  // Between samples the held input cannot follow e: y(t_k + τ) = y_k + ∫₀^τ (CF (x − x_k) − α s_{k+1} + ė) with
  // y_k = 0 and α|s_{k+1}| ≈ |e(t_{k+1}) − e(t_k)|/h ≤ sup|ė|, so |y| ≤ 2 h sup|ė| + O(h²) = 4e-3 + O(1e-4).
  const std::string key = R"(, "relation_offset": [{"type": "sin", "amplitude": "a", "omega": 1}])";
  const auto scene = LinearScene::FromText(ZohOffsetScene(key), "sin.json");
  auto lemke = CreateSolver("lemke");
  const SimulationSettings s = scene->defaults();
  const Trajectory tr = scene->Run(s, lemke.get());
  ASSERT_TRUE(tr.ok());
  ZohRows rows;
  SampledPlantSink plant(ZohPlantOf(*scene, s.parameters), s.h, 10, &rows);
  FeedRecorded(tr, &plant);
  plant.Finish();
  ASSERT_EQ(static_cast<std::int64_t>(rows.t.size()), plant.RowsFor(tr.steps_taken));
  double worst = 0.0;
  for (std::size_t r = 0; r < rows.t.size(); ++r) {
    ASSERT_NEAR(rows.y[r], rows.cx[r] + 0.2 * std::sin(rows.t[r]), 1e-14) << "row " << r;  // y = C x + e(t)
    if (rows.t[r] >= kZohSlidingFrom) worst = std::max(worst, std::abs(rows.y[r]));
  }
  EXPECT_LE(worst, 2.0 * s.h * 0.2);
  EXPECT_GT(worst, 1e-6);  // the held input does leave the surface between samples
}

// The inputs of two runs of the same length, bit for bit (the last column is NaN in both: no step applied it).
bool SameInputs(const Trajectory& a, const Trajectory& b) {
  const auto applied = static_cast<Eigen::Index>(a.steps_taken);
  return a.steps_taken == b.steps_taken && a.u.rows() == b.u.rows() && a.u.leftCols(applied) == b.u.leftCols(applied);
}

TEST(RelationOffset, ZohWithoutTheKeyRunsBitForBitAsWithAZeroOffset) {
  auto lemke = CreateSolver("lemke");
  for (const char* method : {"zoh", "zoh-explicit", "implicit"}) {
    const auto plain = LinearScene::FromText(ZohOffsetScene("", method), "plain.json");
    const auto zero = LinearScene::FromText(ZohOffsetScene(R"(, "relation_offset": [0])", method), "zero.json");
    const Trajectory a = plain->Run(plain->defaults(), lemke.get());
    const Trajectory b = zero->Run(zero->defaults(), lemke.get());
    EXPECT_TRUE(a.x == b.x && a.s == b.s && a.y == b.y) << method;
    ASSERT_EQ(a.has_input, b.has_input) << method;
    if (a.has_input) {
      EXPECT_TRUE(SameInputs(a, b)) << method;
    }
  }
  // A time-dependent e(t) ≡ 0 goes through the stepper's offset path (q − e, y + e) and changes no bit either.
  const auto scene = LinearScene::FromText(ZohOffsetScene(""), "plain.json");
  const SimulationSettings s = scene->defaults();
  ZohSmcSystem system = std::get<ZohSmcSystem>(scene->Model(s.parameters));
  const Trajectory without = LinearStepper(DiscretizeZoh(system, s.h, SignTreatment::kImplicit))
                                 .Run(s.x0, NumSteps(s.T, s.h), lemke.get(), s.stepper);
  system.relation_offset = [](double, Eigen::Ref<Vector> e) { e.setZero(); };
  const Trajectory with = LinearStepper(DiscretizeZoh(system, s.h, SignTreatment::kImplicit))
                              .Run(s.x0, NumSteps(s.T, s.h), lemke.get(), s.stepper);
  ASSERT_TRUE(without.ok() && with.ok());
  EXPECT_TRUE(without.x == with.x && without.s == with.s && without.y == with.y);
  EXPECT_TRUE(SameInputs(without, with));
}

TEST(RelationOffset, ZohWrongSizeNamesTheKey) {
  try {
    LinearScene::FromText(ZohOffsetScene(R"(, "relation_offset": [0.1, 0.2])"), "two.json");
    FAIL() << "two entries accepted for m = 1";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("system.relation_offset has 2 entries but C has m = 1"), std::string::npos)
        << e.what();
  }
  ZohSmcSystem system = std::get<ZohSmcSystem>(LinearScene::FromText(ZohOffsetScene(""), "p.json")->Model({}));
  system.D = Vector::Zero(2);
  try {
    system.Validate();
    FAIL() << "D of size 2 accepted for m = 1";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("ZohSmcSystem: D has size 2"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace smcbench

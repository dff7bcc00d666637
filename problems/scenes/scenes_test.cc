// Scene files and the registry: every registered scene parses and runs; every kind of malformed file is an error
// naming the field; parameters, forcing and the exact solution of S1 do what the format says.
// The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "problems/scenes/expression.h"
#include "problems/scenes/linear_scene.h"
#include "problems/scenes/nonlinear_scene.h"
#include "problems/scenes/registry.h"
#include "problems/stepper/stepper_test_util.h"
#include "solvers/registry/registry.h"
#include "solvers/siconos/external_backends.h"

namespace smcbench {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

// Expects fn to throw InvalidInputError whose message contains every one of parts.
template <typename Fn>
void ExpectError(Fn fn, std::initializer_list<const char*> parts) {
  try {
    fn();
    ADD_FAILURE() << "no error; expected one containing '" << *parts.begin() << "'";
  } catch (const InvalidInputError& e) {
    for (const char* part : parts) EXPECT_THAT(e.what(), HasSubstr(part));
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line: " << e.what();
  }
}

// ---------------------------------------------------------------------------------------------------------------
// Expressions

TEST(Expression, ArithmeticPrecedenceAndFunctions) {
  const SceneParameters p{{"tau", 0.5}, {"k", 2.0}};
  EXPECT_DOUBLE_EQ(EvaluateExpression("1/tau^2", p), 4.0);
  EXPECT_DOUBLE_EQ(EvaluateExpression("-2/tau", p), -4.0);
  EXPECT_DOUBLE_EQ(EvaluateExpression("-k^2", p), -4.0);  // −(k²)
  EXPECT_DOUBLE_EQ(EvaluateExpression("2^3^2", p), 512.0);  // right associative
  EXPECT_DOUBLE_EQ(EvaluateExpression(" (1 + k) * 3 - 4 / 2 ", p), 7.0);
  EXPECT_DOUBLE_EQ(EvaluateExpression("sqrt(k*8) + sin(pi/2) + .5e1", p), 4.0 + 1.0 + 5.0);
  EXPECT_DOUBLE_EQ(EvaluateExpression("1e-3", p), 1e-3);
  EXPECT_TRUE(std::isinf(EvaluateExpression("1/0", p)));
}

TEST(Expression, DefectsNameWhatAndWhere) {
  const SceneParameters p{{"tau", 0.5}};
  ExpectError([&] { EvaluateExpression("1/taux", p); }, {"unknown name 'taux'", "parameters: tau", "column 3"});
  ExpectError([&] { EvaluateExpression("(1+2", p); }, {"missing ')'"});
  ExpectError([&] { EvaluateExpression("1 2", p); }, {"unexpected '2'"});
  ExpectError([&] { EvaluateExpression("", p); }, {"empty expression"});
  ExpectError([&] { EvaluateExpression("sqrt 2", p); }, {"needs '('"});
  ExpectError([&] { EvaluateExpression("nan", p); }, {"unknown name 'nan'"});
  EXPECT_TRUE(IsValidParameterName("tau_2"));
  EXPECT_FALSE(IsValidParameterName("pi"));
  EXPECT_FALSE(IsValidParameterName("sqrt"));
  EXPECT_FALSE(IsValidParameterName("2x"));
}

// ---------------------------------------------------------------------------------------------------------------
// Registry and the shipped scene files

TEST(Registry, NamesAreThoseOfScenesMd) {
  std::vector<std::string> names;
  for (auto n : SceneNames()) names.emplace_back(n);
  EXPECT_THAT(names, ::testing::ElementsAre("sign", "galias-yu-2007", "multi-surface", "filippov", "zoh-siso",
                                            "zoh-mimo", "lyapunov", "observer", "hypomonotone", "arctan",
                                            "parasitic", "super-twisting", "super-twisting-explicit",
                                            "super-twisting-disturbed", "super-twisting-disturbed-explicit",
                                            "twisting-double-integrator", "twisting", "regular-twisting",
                                            "explicit-twisting"));
}

TEST(Registry, UnknownNameListsTheKnownOnes) {
  ExpectError([] { LoadScene("sine"); }, {"unknown scene 'sine'", "sign", "galias-yu-2007", "parasitic"});
}

TEST(Registry, AcceptsAPathToASceneFile) {
  const auto scene = LoadScene(ScenesDirectory() + "/observer.json");
  EXPECT_EQ(scene->info().name, "observer");
  EXPECT_EQ(scene->info().n, 4);
  ExpectError([] { LoadScene("/nonexistent/scene.json"); }, {"/nonexistent/scene.json", "cannot be read"});
}

// The twisting scenes: their one-step matrices are singular (s is not unique, only what the plant sees) and their
// laws polytopes; twisting_scene_test runs them with every backend against Siconos' data instead.
bool IsTwistingScene(std::string_view name) {
  return name == "twisting-double-integrator" || name == "twisting" || name == "regular-twisting" ||
         name == "explicit-twisting";
}

// Every scene parses and runs with its own settings (and implicitly, for the ZOH scenes, the Euler discretization
// of the closed loop) to the end, every one-step problem solved, with both exact backends and the reference.
TEST(Registry, EveryScenePassesAndRunsToTheEnd) {
  stepper_test::ReferenceSolver reference;
  const auto lemke = CreateSolver("lemke");
  const auto enumerative = CreateSolver("enum");
  for (auto name : SceneNames()) {
    SCOPED_TRACE(std::string(name));
    const auto scene = LoadScene(name);
    EXPECT_EQ(scene->info().name, name);
    if (IsTwistingScene(name)) continue;
    EXPECT_FALSE(scene->info().description.empty());
    EXPECT_FALSE(scene->info().reference.empty());
    const SimulationSettings& d = scene->defaults();
    EXPECT_EQ(d.x0.size(), scene->info().n);
    std::vector<Method> methods{d.method};
    if (d.method != Method::kImplicit) methods.push_back(Method::kImplicit);
    for (Method method : methods) {
      SimulationSettings s = d;
      s.method = method;
      for (Solver* solver : {static_cast<Solver*>(&reference), lemke.get(), enumerative.get()}) {
        SCOPED_TRACE(std::string(ToString(method)) + " with " + std::string(solver->info().name));
        const Trajectory t = scene->Run(s, solver);
        EXPECT_TRUE(t.ok()) << t.first_failure_message << " at step " << t.first_failed_step;
        EXPECT_EQ(t.steps_taken, NumSteps(s.T, s.h));
        EXPECT_TRUE(t.x_final.allFinite());
        EXPECT_LE(t.max_residual, s.stepper.solver.tolerance);
      }
    }
  }
}

// The same scene run by every exact backend gives the same trajectory (the one-step problems of S1–S8 have unique
// solutions: CS is a P-matrix for these data).
TEST(Registry, ExactBackendsAgreeOnEveryLinearScene) {
  stepper_test::ReferenceSolver reference;
  const auto lemke = CreateSolver("lemke");
  const auto enumerative = CreateSolver("enum");
  for (auto name : SceneNames()) {
    if (name == "parasitic") continue;  // nearly singular one-step matrix: agreement is a measurement, not a test
    if (IsTwistingScene(name)) continue;
    SCOPED_TRACE(std::string(name));
    const auto scene = LoadScene(name);
    const Trajectory a = scene->Run(scene->defaults(), &reference);
    for (Solver* solver : {lemke.get(), enumerative.get()}) {
      const Trajectory b = scene->Run(scene->defaults(), solver);
      ASSERT_EQ(a.x.cols(), b.x.cols());
      EXPECT_LE((a.x - b.x).cwiseAbs().maxCoeff(), 1e-10 * (1.0 + a.x.cwiseAbs().maxCoeff()));
    }
  }
}

// The iterative backends stop at relative residual 1e-10 per step, so their trajectories differ from the exact
// ones by what those residuals accumulate to: measured ≤ 3e-10 on every scene (Newton on S4); 1e-9 here.
TEST(Registry, IterativeBackendsAgreeWithTheExactOnes) {
  stepper_test::ReferenceSolver reference;
  for (const char* backend : {"psor", "newton"}) {
    const auto solver = CreateSolver(backend);
    for (auto name : SceneNames()) {
      if (IsTwistingScene(name)) continue;
      SCOPED_TRACE(std::string(name) + " with " + backend);
      const auto scene = LoadScene(name);
      const Trajectory a = scene->Run(scene->defaults(), &reference);
      const Trajectory b = scene->Run(scene->defaults(), solver.get());
      ASSERT_TRUE(b.ok()) << b.first_failure_message;
      EXPECT_LE((a.x - b.x).cwiseAbs().maxCoeff(), 1e-9 * (1.0 + a.x.cwiseAbs().maxCoeff()));
    }
  }
}

TEST(Registry, ScenesDirectoryCanBeOverridden) {
  const fs::path dir = fs::temp_directory_path() / ("scenes_dir_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  fs::copy_file(ScenesDirectory() + "/sign.json", dir / "sign.json", fs::copy_options::overwrite_existing);
  ::setenv("SMCBENCH_SCENES_DIR", dir.c_str(), 1);
  EXPECT_EQ(ScenesDirectory(), dir.string());
  EXPECT_EQ(LoadScene("sign")->info().source, (dir / "sign.json").string());
  ExpectError([] { LoadScene("observer"); }, {"observer.json", "cannot be read"});
  ::unsetenv("SMCBENCH_SCENES_DIR");
  fs::remove_all(dir);
}

// ---------------------------------------------------------------------------------------------------------------
// The nonlinear scenes (C++): S9 and S10 through the same interface

// Algorithm 1 (the step's MCP, newton) and Algorithm 2 (outer Newton, each iteration a box-MLCP on any backend)
// stop on the same merit function at 1e-10, so their trajectories agree to that order on both scenes.
TEST(NonlinearScenes, AlgorithmOneAndTwoAgreeWithEveryBackend) {
  const auto newton = CreateSolver("newton");
  for (const char* name : {"hypomonotone", "arctan"}) {
    const auto scene = LoadScene(name);
    EXPECT_EQ(scene->info().source, "built-in");
    SimulationSettings s = scene->defaults();
    s.algorithm = NonlinearAlgorithm::kMcp;
    const Trajectory mcp = scene->Run(s, newton.get());
    ASSERT_TRUE(mcp.ok()) << name << ": " << mcp.first_failure_message;
    s.algorithm = NonlinearAlgorithm::kNewtonMlcp;
    for (auto backend : SolverNames()) {
      if (IsExternalBackend(backend)) continue;  // judged in the paper report and solvers/siconos/
      SCOPED_TRACE(std::string(name) + " with " + std::string(backend));
      const auto solver = CreateSolver(backend);
      const Trajectory mlcp = scene->Run(s, solver.get());
      ASSERT_TRUE(mlcp.ok()) << mlcp.first_failure_message;
      EXPECT_LE((mcp.x - mlcp.x).cwiseAbs().maxCoeff(), 1e-9);
      EXPECT_LE(std::abs(mlcp.x_final[0]), 1e-12);  // both rest exactly (to rounding) at the origin
    }
  }
}

TEST(NonlinearScenes, ParametersMethodsAndExactSolutions) {
  const auto scene = LoadScene("hypomonotone");
  EXPECT_EQ(scene->defaults().parameters.at("rho"), 0.0);
  EXPECT_TRUE(scene->Supports(Method::kExplicit));
  EXPECT_FALSE(scene->Supports(Method::kZoh));
  const auto lemke = CreateSolver("lemke");
  SimulationSettings s = scene->defaults();
  s.parameters["rho"] = 1.0;
  const Trajectory shifted = scene->Run(s, lemke.get());
  EXPECT_NE(shifted.description.find("rho=1"), std::string::npos) << shifted.description;
  ASSERT_TRUE(shifted.ok());
  EXPECT_LE(std::abs(shifted.x_final[0]), 1e-15);
  // The exact solution follows --x0: from x0 = 0.5, x(t) = 1.5 e^{-t} − 1 until t* = ln 1.5.
  s.x0 = Vector::Constant(1, 0.5);
  const auto exact = scene->Exact(s);
  ASSERT_TRUE(exact.has_value());
  Vector x(1);
  exact->x(0.2, x);
  EXPECT_NEAR(x[0], 1.5 * std::exp(-0.2) - 1.0, 1e-15);
  // Explicit sign: the classical scheme chatters around 0 instead of resting there.
  s = scene->defaults();
  s.method = Method::kExplicit;
  s.theta = s.gamma = 0.0;
  s.T = 5.0;
  const Trajectory explicit_run = scene->Run(s, nullptr);
  EXPECT_GT(std::abs(explicit_run.x_final[0]), 1e-3);

  ExpectError([&] {
    SimulationSettings bad = scene->defaults();
    bad.parameters["tau"] = 1.0;
    scene->Run(bad, lemke.get());
  }, {"hypomonotone", "no parameter 'tau'"});
  ExpectError([&] {
    SimulationSettings bad = scene->defaults();
    bad.parameters["rho"] = -1.0;
    scene->Run(bad, lemke.get());
  }, {"rho"});
  ExpectError([&] {
    SimulationSettings bad = scene->defaults();
    bad.method = Method::kZoh;
    scene->Run(bad, lemke.get());
  }, {"ZOH needs a linear plant"});
  ExpectError([&] {
    SimulationSettings bad = scene->defaults();
    bad.newton_tolerance = 0.0;
    scene->Run(bad, lemke.get());
  }, {"newton tolerance"});
  ExpectError([&] {
    SimulationSettings bad = scene->defaults();
    bad.newton_max_iterations = 0;
    scene->Run(bad, lemke.get());
  }, {"newton iteration limit"});
}

// A Newton budget too small for the step is reported as a status with the step, not an exception.
TEST(NonlinearScenes, NewtonBudgetExhaustedIsAStatusWithTheStep) {
  const auto scene = LoadScene("arctan");
  SimulationSettings s = scene->defaults();
  s.newton_max_iterations = 1;
  const auto lemke = CreateSolver("lemke");
  const Trajectory t = scene->Run(s, lemke.get());
  EXPECT_FALSE(t.ok());
  EXPECT_EQ(t.first_failure_status, SolveStatus::kIterationLimit);
  EXPECT_GE(t.first_failed_step, 1);
}

// ---------------------------------------------------------------------------------------------------------------
// What the format means

TEST(SceneFormat, ParametersOverrideTheModel) {
  const auto scene = LoadScene("observer");
  const auto* linear = dynamic_cast<const LinearScene*>(scene.get());
  ASSERT_NE(linear, nullptr);
  EXPECT_EQ(linear->parameters().at("tau"), 0.001);
  const auto model = std::get<LinearSignSystem>(linear->Model({{"tau", 0.5}}));
  EXPECT_DOUBLE_EQ(model.E(3, 0), 4.0);   // 1/τ²
  EXPECT_DOUBLE_EQ(model.E(3, 3), -4.0);  // −2/τ
  EXPECT_DOUBLE_EQ(model.E(1, 0), 1.0);   // k keeps its default
  ExpectError([&] { linear->Model({{"tao", 0.5}}); }, {"no parameter 'tao'", "tau", "k"});
  // A parameter value that makes an entry infinite is named with the entry.
  ExpectError([&] { linear->Model({{"tau", 0.0}}); }, {"scene 'observer'", "system.E[3][0]", "not finite", "tau = 0"});
  // Through Run as well, via the settings.
  SimulationSettings s = scene->defaults();
  s.parameters["tau"] = 0.5;
  s.T = 1.0;
  stepper_test::ReferenceSolver reference;
  EXPECT_TRUE(scene->Run(s, &reference).ok());
}

TEST(SceneFormat, SinusoidalForcingIsTimeDependentG) {
  const auto scene = LoadScene("lyapunov");
  const auto* linear = dynamic_cast<const LinearScene*>(scene.get());
  const auto model = std::get<LinearSignSystem>(linear->Model({{"alpha", 0.25}}));
  ASSERT_TRUE(static_cast<bool>(model.forcing));
  EXPECT_EQ(model.g.size(), 0);  // no constant part
  Vector g(1);
  model.forcing(0.7, g);
  EXPECT_DOUBLE_EQ(g[0], 0.25 * std::sin(0.7));
}

TEST(SceneFormat, ZohSceneSupportsAllFourMethodsSignSceneOnlyTwo) {
  const auto zoh = LoadScene("zoh-siso");
  const auto sign = LoadScene("galias-yu-2007");
  for (Method m : {Method::kImplicit, Method::kExplicit, Method::kZoh, Method::kZohExplicit}) {
    EXPECT_TRUE(zoh->Supports(m));
  }
  EXPECT_TRUE(sign->Supports(Method::kExplicit));
  EXPECT_FALSE(sign->Supports(Method::kZoh));
  SimulationSettings s = sign->defaults();
  s.method = Method::kZoh;
  stepper_test::ReferenceSolver reference;
  ExpectError([&] { sign->Run(s, &reference); }, {"galias-yu-2007", "needs a ZOH plant"});
}

// S1 with the exact solution: Lemma (yahoo), x_k = 0 exactly from k0+1 (or k0+2) on; error norms are O(h).
TEST(SceneFormat, SignSceneExactSolutionAndFiniteArrival) {
  const auto scene = LoadScene("sign");
  stepper_test::ReferenceSolver reference;
  SimulationSettings s = scene->defaults();
  const Trajectory t = scene->Run(s, &reference);
  const auto exact = scene->Exact(s);
  ASSERT_TRUE(exact.has_value());
  const std::int64_t k0 = static_cast<std::int64_t>(std::ceil(1.01 / 0.01)) - 1;
  std::int64_t arrival = -1;
  for (std::int64_t k = 0; k <= t.steps_taken; ++k) {
    if (t.x(0, k) == 0.0 && arrival < 0) arrival = k;
    if (arrival >= 0) {
      EXPECT_EQ(t.x(0, k), 0.0) << "k = " << k;
    }
  }
  EXPECT_TRUE(arrival == k0 + 1 || arrival == k0 + 2) << arrival;
  const SolutionErrors e = ComputeErrors(t, *exact);
  ASSERT_TRUE(e.x && e.s);
  EXPECT_LE(e.x->max, 0.011);  // the discrete state lags by at most one step of size h
  // |x0|/h is an integer here: s_k = 1 up to the arrival step, where x_k/h = 1 up to rounding; then 0 = s(t).
  EXPECT_LE(e.s->max, 1e-12);
  EXPECT_LE(e.s->l1, 2 * 0.01);
  // With --x0 overridden the exact solution follows.
  s.x0[0] = -0.5;
  const auto exact2 = scene->Exact(s);
  Vector x(1), sv(1);
  exact2->x(0.25, x);
  exact2->s(0.25, sv);
  EXPECT_DOUBLE_EQ(x[0], -0.25);
  EXPECT_EQ(sv[0], -1.0);
  exact2->x(0.75, x);
  exact2->s(0.75, sv);
  EXPECT_EQ(x[0], 0.0);
  EXPECT_EQ(sv[0], 0.0);
}

TEST(SceneFormat, SettingsValidationNamesTheField) {
  const auto scene = LoadScene("galias-yu-2007");
  stepper_test::ReferenceSolver reference;
  const auto run = [&](auto change) {
    SimulationSettings s = scene->defaults();
    change(s);
    scene->Run(s, &reference);
  };
  ExpectError([&] { run([](SimulationSettings& s) { s.h = 0.0; }); }, {"h must be", "got 0"});
  ExpectError([&] { run([](SimulationSettings& s) { s.h = -0.1; }); }, {"h must be", "-0.1"});
  ExpectError([&] { run([](SimulationSettings& s) { s.T = -1.0; }); }, {"T must be", "-1"});
  ExpectError([&] { run([](SimulationSettings& s) { s.theta = 1.5; }); }, {"theta must lie in [0, 1]", "1.5"});
  ExpectError([&] { run([](SimulationSettings& s) { s.gamma = -0.5; }); }, {"gamma must lie in [0, 1]"});
  ExpectError([&] { run([](SimulationSettings& s) { s.x0 = Vector::Zero(3); }); }, {"x0 has 3 entries", "n = 2"});
  ExpectError([&] { run([](SimulationSettings& s) { s.x0[1] = std::nan(""); }); }, {"x0[1] is not finite"});
  ExpectError([&] { run([](SimulationSettings& s) { s.h = 1e-12; s.T = 1e3; }); }, {"steps"});
}

// ---------------------------------------------------------------------------------------------------------------
// Malformed scene files: one test per kind of defect, written to a temporary folder and read from there.

class MalformedScene : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("scenes_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A valid S2-like document; each test breaks one thing.
  static nlohmann::json Valid() {
    return nlohmann::json::parse(R"({
      "format": "smcbench-scene/1",
      "name": "test",
      "description": "a valid scene",
      "parameters": {"c1": 1, "alpha": 1},
      "system": {"type": "sign", "E": [[0, 1], [0, "-c1"]], "B": [[0], ["alpha"]], "C": [["c1", 1]], "D": [0]},
      "simulation": {"method": "implicit", "theta": 1, "h": 0.1, "T": 1, "x0": [0, 2.21]}
    })");
  }

  // Writes text to a file and loads it through the registry's path branch.
  void ExpectTextError(const std::string& text, std::initializer_list<const char*> parts) {
    const fs::path path = dir_ / "scene.json";
    std::ofstream(path) << text;
    ExpectError([&] { LoadScene(path.string()); }, parts);
  }
  void ExpectFileError(const nlohmann::json& doc, std::initializer_list<const char*> parts) {
    ExpectTextError(doc.dump(), parts);
  }

  fs::path dir_;
};

TEST_F(MalformedScene, ValidDocumentLoads) {
  const fs::path path = dir_ / "scene.json";
  std::ofstream(path) << Valid().dump();
  EXPECT_EQ(LoadScene(path.string())->info().name, "test");
}

TEST_F(MalformedScene, NotJson) { ExpectTextError("{\"name\": \"x\",", {"scene.json", "not valid JSON"}); }

TEST_F(MalformedScene, MissingKey) {
  auto doc = Valid();
  doc["simulation"].erase("h");
  ExpectFileError(doc, {"scene.json", "missing key 'simulation.h'"});
  doc = Valid();
  doc["system"].erase("B");
  ExpectFileError(doc, {"missing key 'system.B'"});
  doc = Valid();
  doc.erase("system");
  ExpectFileError(doc, {"missing key 'system'"});
}

TEST_F(MalformedScene, UnknownKey) {
  auto doc = Valid();
  doc["simulation"]["thetta"] = 0.5;
  ExpectFileError(doc, {"simulation", "unknown key 'thetta'", "theta"});
}

TEST_F(MalformedScene, WrongType) {
  auto doc = Valid();
  doc["simulation"]["h"] = "0.1";
  ExpectFileError(doc, {"simulation.h", "expected a number, got string"});
  doc = Valid();
  doc["system"]["E"][1][0] = true;
  ExpectFileError(doc, {"system.E[1][0]", "expected a number or an expression string, got boolean"});
  doc = Valid();
  doc["system"]["B"] = nlohmann::json::array({0, 1});
  ExpectFileError(doc, {"system.B[0]", "expected a row", "[[a], [b]]"});
  doc = Valid();
  doc["name"] = 3;
  ExpectFileError(doc, {"name", "expected a string, got number"});
}

TEST_F(MalformedScene, WrongMatrixShape) {
  auto doc = Valid();
  doc["system"]["B"] = nlohmann::json::parse("[[0], [1], [2]]");
  ExpectFileError(doc, {"system.B is 3x1 but must be 2x1"});
  doc = Valid();
  doc["system"]["E"] = nlohmann::json::parse("[[0, 1, 2], [0, 1, 2]]");
  ExpectFileError(doc, {"system.E is 2x3", "square"});
  doc = Valid();
  doc["system"]["C"] = nlohmann::json::parse("[[1, 1], [1]]");
  ExpectFileError(doc, {"system.C[1] has 1 entries", "same length"});
  doc = Valid();
  doc["system"]["D"] = nlohmann::json::parse("[0, 0]");
  ExpectFileError(doc, {"system.D has 2 entries", "m = 1"});
  doc = Valid();
  doc["simulation"]["x0"] = nlohmann::json::parse("[1, 2, 3]");
  ExpectFileError(doc, {"simulation.x0 has 3 entries", "n = 2"});
}

TEST_F(MalformedScene, NotFinite) {
  auto doc = Valid();
  doc["system"]["E"][0][0] = "0/0";
  ExpectFileError(doc, {"system.E[0][0]", "'0/0' is not finite (nan)"});
  // A literal that overflows is rejected by the JSON parser itself.
  ExpectTextError(Valid().dump().replace(Valid().dump().find("2.21"), 4, "1e999"), {"scene.json", "overflow", "1e999"});
  doc = Valid();
  doc["system"]["B"][1][0] = "alpha/(c1-1)";
  ExpectFileError(doc, {"system.B[1][0]", "not finite", "c1 = 1"});
}

TEST_F(MalformedScene, BadExpression) {
  auto doc = Valid();
  doc["system"]["E"][1][1] = "-c2";
  ExpectFileError(doc, {"system.E[1][1]", "unknown name 'c2'", "parameters: alpha, c1"});
  doc = Valid();
  doc["parameters"]["sqrt"] = 2;
  ExpectFileError(doc, {"parameters", "'sqrt' is not a usable name"});
}

TEST_F(MalformedScene, StepNotPositive) {
  auto doc = Valid();
  doc["simulation"]["h"] = 0;
  ExpectFileError(doc, {"simulation.h", "must be > 0, got 0"});
  doc["simulation"]["h"] = -0.01;
  ExpectFileError(doc, {"simulation.h", "must be > 0, got -0.01"});
}

TEST_F(MalformedScene, NegativeHorizon) {
  auto doc = Valid();
  doc["simulation"]["T"] = -1;
  ExpectFileError(doc, {"simulation.T", "must be >= 0, got -1"});
}

TEST_F(MalformedScene, ThetaOutsideUnitInterval) {
  auto doc = Valid();
  doc["simulation"]["theta"] = 1.5;
  ExpectFileError(doc, {"simulation.theta", "must lie in [0, 1], got 1.5"});
  doc["simulation"]["theta"] = -0.1;
  ExpectFileError(doc, {"simulation.theta", "-0.1"});
}

TEST_F(MalformedScene, UnknownOrIncompatibleMethodAndType) {
  auto doc = Valid();
  doc["simulation"]["method"] = "rk4";
  ExpectFileError(doc, {"simulation.method", "unknown method 'rk4'", "zoh-explicit"});
  doc = Valid();
  doc["simulation"]["method"] = "zoh";
  ExpectFileError(doc, {"simulation.method", "needs a system of type 'zoh'"});
  doc = Valid();
  doc["system"]["type"] = "nonlinear";
  ExpectFileError(doc, {"system.type", "unknown system type 'nonlinear'"});
  doc = Valid();
  doc["format"] = "smcbench-scene/2";
  ExpectFileError(doc, {"format", "unsupported format"});
}

TEST_F(MalformedScene, ZohWithSingularCG) {
  auto doc = Valid();
  doc["system"] = nlohmann::json::parse(R"({"type": "zoh", "F": [[0, 1], [2, -2]], "G": [[1], [0]],
                                            "C": [[0, 1]], "alpha": 1})");
  ExpectFileError(doc, {"scene.json", "CG is singular"});
}

TEST_F(MalformedScene, BadForcing) {
  auto doc = Valid();
  doc["system"]["forcing"] = nlohmann::json::parse(R"([0])");
  ExpectFileError(doc, {"system.forcing has 1 entries", "n = 2"});
  doc["system"]["forcing"] = nlohmann::json::parse(R"([0, {"type": "square", "amplitude": 1}])");
  ExpectFileError(doc, {"system.forcing[1].type", "unknown forcing type 'square'"});
  doc["system"]["forcing"] = nlohmann::json::parse(R"([0, {"type": "sin"}])");
  ExpectFileError(doc, {"missing key 'system.forcing[1].amplitude'"});
}

TEST_F(MalformedScene, ExactSolutionThatDoesNotApply) {
  auto doc = Valid();
  doc["exact_solution"] = "sign";
  ExpectFileError(doc, {"exact_solution 'sign' needs", "not scalar"});
  doc["exact_solution"] = "bogus";
  ExpectFileError(doc, {"exact_solution", "unknown kind 'bogus'"});
}


// ---------------------------------------------------------------------------------------------------------------
// Regressions found by tests/fuzz/scene_fuzzer.

// The recursive-descent evaluator recursed once per '(' or sign: a scene file with 50 000 nested parentheses (or
// 200 000 minus signs) in a matrix entry overflowed the stack (SIGSEGV; ASan stack-overflow in Parser::Unary).
TEST(SceneFuzzRegression, DeeplyNestedExpressionIsAnErrorNotAStackOverflow) {
  const SceneParameters none;
  const std::string parens = std::string(50000, '(') + "1" + std::string(50000, ')');
  ExpectError([&] { EvaluateExpression(parens, none); }, {"nested deeper than 200 levels", "at column 201"});
  ExpectError([&] { EvaluateExpression(std::string(200000, '-') + "1", none); }, {"nested deeper than 200 levels"});
  std::string powers = "1";
  for (int i = 0; i < 1000; ++i) powers += "^1";
  ExpectError([&] { EvaluateExpression(powers, none); }, {"nested deeper than 200 levels"});
  // Depth within the bound still evaluates.
  EXPECT_EQ(EvaluateExpression(std::string(150, '(') + "2" + std::string(150, ')'), none), 2.0);
  EXPECT_EQ(EvaluateExpression(std::string(150, '-') + "2", none), 2.0);

  nlohmann::json doc = nlohmann::json::parse(R"({
    "format": "smcbench-scene/1", "name": "deep", "description": "nested expression",
    "system": {"type": "sign", "E": [[0]], "B": [[1]], "C": [[1]]},
    "simulation": {"method": "implicit", "h": 0.1, "T": 1, "x0": [1]}
  })");
  doc["system"]["E"][0][0] = parens;
  ExpectError([&] { LinearScene::FromText(doc.dump(), "deep.json"); },
              {"deep.json", "system.E[0][0]", "nested deeper than 200 levels"});
}


// ---------------------------------------------------------------------------------------------------------------
// Siconos' equivalent control, the plant disturbance and the control input in scene files.

TEST(SceneFormat, DisturbedSmcSceneReadsItsControllerAndDisturbance) {
  const auto scene = LoadScene(std::string(SMCBENCH_SCENES_TEST_DIR) + "/smc-disturbed.json");
  const auto* linear = dynamic_cast<const LinearScene*>(scene.get());
  ASSERT_NE(linear, nullptr);
  const LinearModel model = linear->Model({});
  const auto& z = std::get<ZohSmcSystem>(model);
  ASSERT_TRUE(z.equivalent_control);
  EXPECT_EQ(z.equivalent_control->theta, 0.5);
  EXPECT_TRUE(z.disturbance.W == z.G);  // matched: no matrix given
  ASSERT_EQ(z.disturbance.sinusoids.size(), 1u);
  EXPECT_EQ(z.disturbance.sinusoids[0].amplitude[0], 0.5);
  EXPECT_EQ(z.disturbance.sinusoids[0].omega, 50.0);
  // Parameters reach the controller and the disturbance.
  const LinearModel model2 = linear->Model({{"theta", 1.0}, {"amplitude", 0.25}});
  const auto& z2 = std::get<ZohSmcSystem>(model2);
  EXPECT_EQ(z2.equivalent_control->theta, 1.0);
  EXPECT_EQ(z2.disturbance.sinusoids[0].amplitude[0], 0.25);
  ExpectError([&] { linear->Model({{"theta", 1.5}}); }, {"equivalent_control.theta must lie in [0, 1]", "1.5"});
  // Runs with every ZOH method and reports its input.
  stepper_test::ReferenceSolver reference;
  for (Method method : {Method::kZoh, Method::kZohExplicit, Method::kImplicit}) {
    SimulationSettings s = scene->defaults();
    s.method = method;
    const Trajectory tr = scene->Run(s, &reference);
    EXPECT_TRUE(tr.ok()) << ToString(method);
    EXPECT_EQ(tr.has_input, method != Method::kImplicit) << ToString(method);
  }
  // S1 reports u = −s; the other class-(2) scenes report no input.
  const auto sign = LoadScene("sign");
  EXPECT_TRUE(sign->Run(sign->defaults(), &reference).has_input);
  const auto galias_yu = LoadScene("galias-yu-2007");
  EXPECT_FALSE(galias_yu->Run(galias_yu->defaults(), &reference).has_input);
}

// simulation.plant_substeps, a whole number ≥ 1 on ZOH plants only.
TEST_F(MalformedScene, PlantSubstepsIsAWholeNumberOnZohPlants) {
  auto doc = nlohmann::json::parse(R"({
    "name": "z", "description": "zoh",
    "system": {"type": "zoh", "F": [[0, 1], [2, -2]], "G": [[0], [1]], "C": [[1, 1]]},
    "simulation": {"method": "zoh", "h": 0.05, "T": 1, "x0": [0.5, 0.5], "plant_substeps": 8}
  })");
  EXPECT_EQ(LinearScene::FromText(doc.dump(), "z.json")->defaults().plant_substeps, 8);
  EXPECT_EQ(LoadScene("zoh-siso")->defaults().plant_substeps, 1) << "absent: the samples alone";
  for (const auto& [value, message] : std::vector<std::pair<nlohmann::json, const char*>>{
           {0, "simulation.plant_substeps: must be an integer in [1, 1000000], got 0"},
           {-2, "got -2"},
           {1.5, "got 1.5"},
           {2e6, "must be an integer in [1, 1000000]"},
           {"4", "simulation.plant_substeps: expected a number"}}) {
    doc["simulation"]["plant_substeps"] = value;
    ExpectFileError(doc, {message});
  }
  doc = nlohmann::json::parse(R"({
    "name": "s", "description": "sign", "system": {"type": "sign", "E": [[0]], "B": [[1]], "C": [[1]]},
    "simulation": {"method": "implicit", "h": 0.05, "T": 1, "x0": [0.5], "plant_substeps": 2}
  })");
  ExpectFileError(doc, {"simulation.plant_substeps: needs a system of type 'zoh'"});
}

TEST_F(MalformedScene, ControllerAndDisturbanceDefectsNameTheField) {
  const auto zoh = [] {
    return nlohmann::json::parse(R"({
      "name": "z", "description": "zoh",
      "system": {"type": "zoh", "F": [[0, 1], [2, -2]], "G": [[0], [1]], "C": [[1, 1]],
                 "equivalent_control": {"theta": 0.5},
                 "disturbance": {"constant": [0.1], "sinusoids": [{"amplitude": [0.5], "omega": 50, "phase": 0}]}},
      "simulation": {"method": "zoh", "h": 0.05, "T": 1, "x0": [0.5, 0.5]}
    })");
  };
  {
    const fs::path path = dir_ / "scene.json";
    std::ofstream(path) << zoh().dump();
    EXPECT_EQ(LoadScene(path.string())->info().name, "z");
  }
  auto doc = zoh();
  doc["system"]["equivalent_control"] = 0.5;
  ExpectFileError(doc, {"system.equivalent_control: expected an object {\"theta\""});
  doc = zoh();
  doc["system"]["equivalent_control"]["theta"] = 2;
  ExpectFileError(doc, {"system.equivalent_control.theta: must lie in [0, 1], got 2"});
  doc = zoh();
  doc["system"]["equivalent_control"]["gain"] = 1;
  ExpectFileError(doc, {"system.equivalent_control: unknown key 'gain' (allowed: theta)"});
  doc = zoh();
  doc["system"]["equivalent_control"].erase("theta");
  ExpectFileError(doc, {"missing key 'system.equivalent_control.theta'"});
  doc = zoh();
  doc["system"]["disturbance"]["matrix"] = {{1.0, 0.0}};
  ExpectFileError(doc, {"system.disturbance.matrix is 1x2 but must be 2x2"});
  doc = zoh();
  doc["system"]["disturbance"]["constant"] = {0.1, 0.2};
  ExpectFileError(doc, {"system.disturbance.constant has 2 entries but the disturbance has m = 1 (matched: W = G)"});
  doc = zoh();
  doc["system"]["disturbance"]["matrix"] = {{1.0, 0.0}, {0.0, 1.0}};
  ExpectFileError(doc, {"system.disturbance.constant has 1 entries", "q = 2"});
  doc = zoh();
  doc["system"]["disturbance"]["sinusoids"][0]["amplitude"] = 0.5;
  ExpectFileError(doc, {"system.disturbance.sinusoids[0].amplitude: expected an array"});
  doc = zoh();
  doc["system"]["disturbance"]["sinusoids"][0].erase("omega");
  ExpectFileError(doc, {"missing key 'system.disturbance.sinusoids[0].omega'"});
  doc = zoh();
  doc["system"]["disturbance"]["sinusoids"][0]["frequency"] = 3;
  ExpectFileError(doc, {"system.disturbance.sinusoids[0]: unknown key 'frequency'"});
  doc = zoh();
  doc["system"]["disturbance"]["sinusoids"] = {{"amplitude", {1}}};
  ExpectFileError(doc, {"system.disturbance.sinusoids: expected an array"});
  doc = zoh();
  doc["system"]["disturbance"] = nlohmann::json::object();
  ExpectFileError(doc, {"system.disturbance: has neither 'constant' nor 'sinusoids'"});
  doc = zoh();
  doc["system"]["disturbance"]["sinusoids"][0]["omega"] = "w";
  ExpectFileError(doc, {"system.disturbance.sinusoids[0].omega", "unknown name 'w'"});
  // Keys of one system type on the other.
  doc = Valid();
  doc["system"]["equivalent_control"] = {{"theta", 0.5}};
  ExpectFileError(doc, {"system: unknown key 'equivalent_control'"});
  doc = Valid();
  doc["system"]["control_input"] = "yes";
  ExpectFileError(doc, {"system.control_input: expected true or false, got string"});
}

}  // namespace
}  // namespace smcbench

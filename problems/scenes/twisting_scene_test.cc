// The twisting scenes against Siconos' published data (tests/data/siconos-control/README.md): its tutorial
// (examples/control/Relay/Twisting, implicit twisting of a double integrator) and its regression tests
// control/src/tests/TwistingTest.cpp (Twisting, RegularTwisting, ExplicitTwisting on a ZOH-sampled plant), with the
// columns and tolerances of Siconos' own comparisons; and the polytope law of scene files (system.law).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "problems/scenes/linear_scene.h"
#include "problems/scenes/registry.h"
#include "problems/stepper/linear_stepper.h"
#include "solvers/core/sanitized_build.h"
#include "solvers/avi/affine_vi.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

// Siconos' ASCII matrix file: "rows cols" then the rows.
DenseMatrix ReadSiconosMatrix(const std::string& name) {
  const std::string path = std::string(SMCBENCH_PEER_DATA_DIR) + "/siconos-control/" + name;
  std::ifstream in(path);
  int rows = 0, cols = 0;
  in >> rows >> cols;
  DenseMatrix A(rows, cols);
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) in >> A(i, j);
  }
  if (!in) ADD_FAILURE() << "cannot read " << path;
  return A;
}

// Which columns Siconos compares: the tutorial t, x (its λ are "very sensitive to numerical approximations"); the
// implicit controllers t, x and λ₁ + βλ₂ (what the plant sees: λ is not unique); the explicit one every column.
enum class Columns { kTimeAndState, kStateAndPlantInput, kAll };

struct SiconosCase {
  const char* scene;
  const char* reference;
  Columns columns;
  double beta;            // λ₁ + βλ₂
  double tolerance;       // Siconos' own, on max |Δ| over the compared columns
  double solver_tolerance;
};

// Max |Δ| over the compared columns of the first `rows` rows (λ = u = −s; a run's last row has no input).
double MaxDeviation(const Trajectory& tr, const DenseMatrix& ref, const SiconosCase& c, Eigen::Index rows) {
  double worst = 0.0;
  for (Eigen::Index k = 0; k < rows; ++k) {
    std::vector<std::pair<double, double>> pairs = {
        {tr.t[static_cast<std::size_t>(k)], ref(k, 0)}, {tr.x(0, k), ref(k, 1)}, {tr.x(1, k), ref(k, 2)}};
    const bool input = k < static_cast<Eigen::Index>(tr.steps_taken);
    if (c.columns == Columns::kStateAndPlantInput && input) {
      pairs.push_back({tr.u(0, k) + c.beta * tr.u(1, k), ref(k, 3) + c.beta * ref(k, 4)});
    } else if (c.columns == Columns::kAll && input) {
      pairs.push_back({tr.u(0, k), ref(k, 3)});
      pairs.push_back({tr.u(1, k), ref(k, 4)});
    }
    for (const auto& [ours, theirs] : pairs) worst = std::max(worst, std::abs(ours - theirs));
  }
  return worst;
}

// The scene's defaults with the case's β (Siconos' SMCTest runs the Twisting controller with β = 0.1) and tolerance.
SimulationSettings SettingsFor(const Scene& scene, const SiconosCase& c) {
  SimulationSettings settings = scene.defaults();
  if (const auto beta = settings.parameters.find("beta"); beta != settings.parameters.end()) beta->second = c.beta;
  settings.stepper.solver.tolerance = c.solver_tolerance;
  return settings;
}

// The default tolerance of every backend: Siconos' regression files are met with it (the step verdict,
// problems/stepper/step_verdict.h, continues every run from the exact step on the answer's active set).
const double kDefaultTolerance = SolverOptions{}.tolerance;

// Steps a backend other than lemke, enum and auto runs under a sanitizer: the same code paths as the whole run,
// which there took minutes (ipopt's interior point alone 150 s on regular-twisting). The Release build runs every
// backend on the whole horizon.
constexpr std::int64_t kSanitizedSteps = 40;

// Runs the scene with every box backend; the exact ones (lemke, enum) must solve every step, and every backend that
// solves every step must reproduce Siconos' data to its tolerance (a run that claims success and differs is wrong).
// Prints one table row per backend (docs/smc.md, "Implicit twisting").
void CompareWithEveryBackend(const SiconosCase& c) {
  const auto scene = LoadScene(c.scene);
  const DenseMatrix ref = ReadSiconosMatrix(c.reference);
  const SimulationSettings whole = SettingsFor(*scene, c);
  int exact_passed = 0;
  for (std::string_view name : SolverNames()) {
    auto solver = CreateSolver(name);
    if (!solver->info().box) continue;
    const bool required = name == "lemke" || name == "enum";
    SimulationSettings settings = whole;
    if (kSanitizedBuild && !required && name != "auto") settings.T = kSanitizedSteps * settings.h;
    const Eigen::Index rows = std::min<Eigen::Index>(ref.rows(), NumSteps(settings.T, settings.h) + 1);
    const Trajectory tr = scene->Run(settings, solver.get());
    const bool solved = tr.ok();
    const double deviation = solved ? MaxDeviation(tr, ref, c, rows) : NAN;
    std::printf("| %s | %s | %s | %.3g |\n", c.scene, std::string(name).c_str(),
                solved ? "every step" : ToString(tr.first_failure_status).data(), deviation);
    if (required) {
      ASSERT_TRUE(solved) << c.scene << " with " << name << ": step " << tr.first_failed_step << ": "
                          << tr.first_failure_message;
      ++exact_passed;
    }
    if (solved) {
      EXPECT_LE(deviation, c.tolerance) << c.scene << " with " << name << " against " << c.reference;
    }
  }
  EXPECT_EQ(exact_passed, 2) << "lemke and enum are built in";
}

TEST(TwistingScenes, SiconosTutorialDoubleIntegrator) {
  // examples/control/Relay/Twisting.cpp: compareRefFile(t, x1, x2) ≤ 1e-12.
  CompareWithEveryBackend(
      {"twisting-double-integrator", "Twisting.ref", Columns::kTimeAndState, 0.3, 1e-12, kDefaultTolerance});
}

TEST(TwistingScenes, SiconosTwistingZoh) {
  // TwistingTest::test_Twisting_ZOH: ‖(t, x, λ₁ + βλ₂) − ref‖∞ < 7.5e-11, at the default tolerance.
  CompareWithEveryBackend({"twisting", "itw2.ref", Columns::kStateAndPlantInput, 0.2, 7.5e-11, kDefaultTolerance});
}

TEST(TwistingScenes, SiconosSmcTestTwistingZoh) {
  // SMCTest::test_itw_ZOH: the same Twisting controller and plant with β = 0.1, ‖(t, x) − ref‖∞ < 1.5e-8 (its
  // leftCols(3)); λ₁ + βλ₂ is held to the same here.
  CompareWithEveryBackend({"twisting", "itw.ref", Columns::kStateAndPlantInput, 0.1, 1.5e-8, kDefaultTolerance});
}

TEST(TwistingScenes, SiconosRegularTwistingZoh) {
  // TwistingTest::test_RegularTwisting_Lsodar compares a plant integrated otherwise (Lsodar) with reg_itw.ref to
  // 5e-9, which is our case: Siconos computes e^{Fh} and ∫e^{Fτ}dτ G by integrating an ODE, we by one Padé
  // exponential; the ~4e-15 relative difference per step grows with the unstable plant (eigenvalue −1 + √20) and
  // by 2/h where the box's rank-one M puts x₁ on its surface (test_RegularTwisting_ZOH's 7.5e-11 is met to step 21).
  // Stated as the polytope (Siconos' own statement); as a box-MLCP, enum stops on its singular blocks.
  CompareWithEveryBackend(
      {"regular-twisting", "reg_itw.ref", Columns::kStateAndPlantInput, 0.2, 5e-9, kDefaultTolerance});
}

TEST(TwistingScenes, EveryRowOfSiconosFilesReplayedOneStep) {
  // From each row's x_k (the file's), one step of ours (lemke and enum, the default tolerance) must land on the
  // next row's x_{k+1}, and give its λ₁ + βλ₂ (the ZOH files: row k holds the λ_k computed from x_k; the tutorial's
  // row k + 1 holds the λ of the step into it), within test_Twisting_ZOH's 7.5e-11. What differs here is the step
  // alone: the whole runs' growth of the exponentials' ~4e-15 (the unstable plant) is taken out.
  const SiconosCase cases[] = {
      {"twisting-double-integrator", "Twisting.ref", Columns::kTimeAndState, 0.3, 7.5e-11, kDefaultTolerance},
      {"twisting", "itw2.ref", Columns::kStateAndPlantInput, 0.2, 7.5e-11, kDefaultTolerance},
      {"twisting", "itw.ref", Columns::kStateAndPlantInput, 0.1, 7.5e-11, kDefaultTolerance},
      {"regular-twisting", "reg_itw.ref", Columns::kStateAndPlantInput, 0.2, 7.5e-11, kDefaultTolerance}};
  for (const char* backend : {"lemke", "enum"}) {
    auto solver = CreateSolver(backend);
    for (const SiconosCase& c : cases) {
      const auto scene = LoadScene(c.scene);
      const SimulationSettings settings = SettingsFor(*scene, c);
      LinearStepper stepper(dynamic_cast<const LinearScene&>(*scene).Discretization(settings));
      const DenseMatrix ref = ReadSiconosMatrix(c.reference);
      const bool tutorial = c.columns == Columns::kTimeAndState;
      double worst_x = 0.0, worst_input = 0.0;
      Eigen::Index worst_row = -1;
      for (Eigen::Index k = 0; k + 1 < ref.rows(); ++k) {
        const Vector x = ref.row(k).segment(1, 2).transpose();
        const Trajectory tr = stepper.Run(x, 1, solver.get(), settings.stepper);
        ASSERT_TRUE(tr.ok()) << c.reference << " row " << k << " with " << backend << ": " << tr.first_failure_message;
        const double dx = (tr.x.col(1) - ref.row(k + 1).segment(1, 2).transpose()).cwiseAbs().maxCoeff();
        const Eigen::Index input_row = tutorial ? k + 1 : k;
        const double di = std::abs(tr.u(0, 0) + c.beta * tr.u(1, 0) - ref(input_row, 3) - c.beta * ref(input_row, 4));
        if (std::max(dx, di) > std::max(worst_x, worst_input)) worst_row = k;
        worst_x = std::max(worst_x, dx);
        worst_input = std::max(worst_input, di);
      }
      std::printf("| %s | %s | replayed %ld rows: x %.3g, lambda1 + beta lambda2 %.3g (worst row %ld) |\n",
                  c.reference, backend, static_cast<long>(ref.rows() - 1), worst_x, worst_input,
                  static_cast<long>(worst_row));
      EXPECT_LE(worst_x, c.tolerance) << c.reference << " with " << backend << ", row " << worst_row;
      EXPECT_LE(worst_input, c.tolerance) << c.reference << " with " << backend << ", row " << worst_row;
    }
  }
}

TEST(TwistingScenes, SiconosExplicitTwistingZohStepByStep) {
  // The explicit scheme does not contract what differs: the ~4e-15 per step of the exponentials grows by the
  // plant's e^{3.47 h} per step until a sign differs (the runs then part). So the comparison is Siconos' step,
  // replayed: from each reference row x_k, our controller's u_k must be the reference's, and our ZOH step with it
  // must land on the reference's x_{k+1} within 7.5e-11 (test_ExplicitTwisting_ZOH's tolerance); the whole run
  // agrees to that tolerance until the differences have grown to it.
  const auto scene = LoadScene("explicit-twisting");
  const auto* linear = dynamic_cast<const LinearScene*>(scene.get());
  ASSERT_NE(linear, nullptr);
  const DenseMatrix ref = ReadSiconosMatrix("etw_ZOH.ref");
  const OneStepData d = linear->Discretization(scene->defaults());
  double step_deviation = 0.0;
  for (Eigen::Index k = 0; k + 1 < ref.rows(); ++k) {
    const Vector x = ref.row(k).segment(1, 2).transpose();
    Vector s(2);
    for (int i = 0; i < 2; ++i) s[i] = x[i] > 0.0 ? 1.0 : (x[i] < 0.0 ? -1.0 : 0.0);  // explicit sgn(y_k)
    const Vector u = d.input_x * x + d.input_s * s;
    ASSERT_EQ(u[0], ref(k, 3)) << "row " << k;
    ASSERT_EQ(u[1], ref(k, 4)) << "row " << k;
    const Vector next = d.R * x - d.S * s;
    step_deviation = std::max(step_deviation, (next - ref.row(k + 1).segment(1, 2).transpose()).cwiseAbs().maxCoeff());
  }
  EXPECT_LE(step_deviation, 7.5e-11);
  const Trajectory tr = scene->Run(scene->defaults(), nullptr);
  ASSERT_EQ(tr.steps_taken, ref.rows() - 1);
  Eigen::Index agree = 0;
  while (agree < ref.rows() &&
         (tr.x.col(agree) - ref.row(agree).segment(1, 2).transpose()).cwiseAbs().maxCoeff() <= 7.5e-11) {
    ++agree;
  }
  std::printf("| explicit-twisting | (none) | step by step %.3g | whole run within 7.5e-11 to step %ld |\n",
              step_deviation, static_cast<long>(agree) - 1);
  EXPECT_GE(agree, 30);
}

TEST(TwistingScenes, WarmStepsKeepSiconosToleranceAndNeverPivotMore) {
  // Each AVI step warm from the previous one (AviSession: the reduction's last active set first, then the backend
  // from the previous (λ, μ); lemke ignores the latter) against every step cold; both within Siconos' tolerance.
  // The reused set answers only where the reduction's free block can be factored: with G of rank one, M = C S is
  // rank one, so a λ inside P (no face active) leaves it singular and those steps go to the backend anyway.
  const SiconosCase cases[] = {
      {"twisting-double-integrator", "Twisting.ref", Columns::kTimeAndState, 0.3, 1e-12, kDefaultTolerance},
      {"twisting", "itw2.ref", Columns::kStateAndPlantInput, 0.2, 7.5e-11, kDefaultTolerance},
      {"regular-twisting", "reg_itw.ref", Columns::kStateAndPlantInput, 0.2, 5e-9, kDefaultTolerance}};
  auto lemke = CreateSolver("lemke");
  for (const SiconosCase& c : cases) {
    const auto scene = LoadScene(c.scene);
    const DenseMatrix ref = ReadSiconosMatrix(c.reference);
    SimulationSettings warm = SettingsFor(*scene, c);
    SimulationSettings cold = warm;
    cold.stepper.warm_start = false;
    cold.stepper.session.reuse_active_set = false;
    const Trajectory warm_run = scene->Run(warm, lemke.get());
    const Trajectory cold_run = scene->Run(cold, lemke.get());
    ASSERT_TRUE(warm_run.ok() && cold_run.ok()) << c.scene;
    const Eigen::Index rows = std::min<Eigen::Index>(ref.rows(), warm_run.steps_taken + 1);
    EXPECT_LE(MaxDeviation(warm_run, ref, c, rows), c.tolerance) << c.scene;
    EXPECT_LE(MaxDeviation(cold_run, ref, c, rows), c.tolerance) << c.scene;
    const auto per_step = [](const Trajectory& tr) {
      return static_cast<double>(tr.total_iterations) / static_cast<double>(tr.steps_taken);
    };
    std::printf("| %s | lemke | pivots per step: cold %.3g, warm %.3g |\n", c.scene, per_step(cold_run),
                per_step(warm_run));
    EXPECT_LE(warm_run.total_iterations, cold_run.total_iterations) << c.scene;
  }
}

TEST(TwistingScenes, PolytopeLawStatesTheParallelogramAndFollowsH) {
  const auto scene = LoadScene("twisting");
  const auto* linear = dynamic_cast<const LinearScene*>(scene.get());
  ASSERT_NE(linear, nullptr);
  SimulationSettings settings = scene->defaults();
  settings.h = 0.01;
  const OneStepData d = linear->Discretization(settings);
  ASSERT_TRUE(d.has_polytope_law());
  DenseMatrix H(4, 2);
  H << 1, 0, -0.005, 1, -1, 0, 0.005, -1;  // |s₁| ≤ 1, |s₂ − (h/2)s₁| ≤ 1 with h = 0.01
  EXPECT_LE((d.law.H - H).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_EQ(d.law.K, Vector::Constant(4, -1.0));
  // The box variant is Siconos' parallelogram with h = 0, whatever the step.
  const auto regular = LoadScene("regular-twisting");
  const OneStepData box = dynamic_cast<const LinearScene&>(*regular).Discretization(settings);
  DenseMatrix box_rows(4, 2);
  box_rows << 1, 0, 0, 1, -1, 0, 0, -1;
  EXPECT_EQ(box.law.H, box_rows);
  // An explicit method is refused with a polytope law.
  settings.method = Method::kZohExplicit;
  EXPECT_FALSE(scene->Supports(Method::kZohExplicit));
  try {
    linear->Discretization(settings);
    ADD_FAILURE() << "an explicit method with a polytope law must be refused";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("polytope law"), std::string::npos) << e.what();
  }
}

TEST(TwistingScenes, EverySolvedStepIsAnAviSolutionCheckedByItsFaces) {
  // An independent check of the tutorial's steps: s_{k+1} ∈ P and y_{k+1} = C x_{k+1} ∈ N_P(s_{k+1}), i.e. y is a
  // nonnegative combination of the outward normals −H_i of the rows active at s (none: y = 0), recomputed here.
  const auto scene = LoadScene("twisting-double-integrator");
  const auto* linear = dynamic_cast<const LinearScene*>(scene.get());
  const OneStepData d = linear->Discretization(scene->defaults());
  auto lemke = CreateSolver("lemke");
  const Trajectory tr = scene->Run(scene->defaults(), lemke.get());
  ASSERT_TRUE(tr.ok());
  for (std::int64_t k = 1; k <= tr.steps_taken; ++k) {
    const Vector s = tr.s.col(k), y = tr.y.col(k);
    const Vector slack = d.law.H * s - d.law.K;
    ASSERT_GE(slack.minCoeff(), -1e-12) << "step " << k;
    std::vector<int> active;
    for (int i = 0; i < 4; ++i) {
      if (slack[i] <= 1e-9) active.push_back(i);
    }
    const double scale = 1.0 + tr.x.col(k - 1).cwiseAbs().maxCoeff();
    if (active.empty()) {
      EXPECT_LE(y.cwiseAbs().maxCoeff(), 1e-9 * scale) << "step " << k;
      continue;
    }
    // y = −Σ μ_i H_iᵀ with μ ≥ 0 over the active rows (at most 2 in the plane): least squares, then the checks.
    DenseMatrix A(2, static_cast<Eigen::Index>(active.size()));
    for (std::size_t c = 0; c < active.size(); ++c) {
      A.col(static_cast<Eigen::Index>(c)) = -d.law.H.row(active[c]).transpose();
    }
    const Vector mu = A.colPivHouseholderQr().solve(y);
    EXPECT_GE(mu.minCoeff(), -1e-9 * scale) << "step " << k;
    EXPECT_LE((A * mu - y).cwiseAbs().maxCoeff(), 1e-9 * scale) << "step " << k;
  }
}

TEST(TwistingScenes, RebuildingEachStepGivesThePrefactoredRun) {
  // The general simulator's path (a fresh AVI and SolveAvi every step) against the stepper's AviSession.
  auto lemke = CreateSolver("lemke");
  for (const char* name : {"twisting-double-integrator", "twisting"}) {
    const auto scene = LoadScene(name);
    const auto* linear = dynamic_cast<const LinearScene*>(scene.get());
    SimulationSettings s = scene->defaults();
    s.stepper.solver.tolerance = 1e-13;
    s.T = 5.0;
    const Trajectory prefactored = scene->Run(s, lemke.get());
    Trajectory rebuilt;
    SimulateRebuildingEachStep(linear->Model(s.parameters, s.h), s.method, s.h, s.theta, s.x0, NumSteps(s.T, s.h),
                               lemke.get(), s.stepper, &rebuilt);
    ASSERT_TRUE(prefactored.ok() && rebuilt.ok()) << name << ": " << rebuilt.first_failure_message;
    EXPECT_LE((prefactored.x - rebuilt.x).cwiseAbs().maxCoeff(), 1e-10 * (1.0 + prefactored.x.cwiseAbs().maxCoeff()))
        << name;
  }
}

TEST(TwistingScenes, BadLawsAreErrorsNamingTheField) {
  const auto fails_with = [](const std::string& law, const std::string& what) {
    const std::string text = R"({"name": "bad", "description": "d", "system": {"type": "sign", "E": [[0]], "B": [[1]],
      "C": [[1]], "law": )" + law + R"(}, "simulation": {"method": "implicit", "h": 0.1, "T": 1, "x0": [1]}})";
    try {
      LinearScene::FromText(text, "bad.json");
      ADD_FAILURE() << law << ": accepted";
    } catch (const InvalidInputError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  fails_with(R"({"box": 1})", "system.law: unknown key 'box'");
  fails_with(R"({"polytope": {"H": [[1, 0]], "K": [0]}})", "system.law.polytope.H is 1x2 but must be 1x1");
  fails_with(R"({"polytope": {"H": [[1], [-1]], "K": [0]}})", "system.law.polytope.K has 1 entries");
  fails_with(R"({"polytope": {"H": [[1], [-1]], "K": [1, 1]}})", "is empty");
  fails_with(R"({"polytope": {"H": [["1/q"], [-1]], "K": [1, 1]}})", "system.law.polytope.H[0][0]");
}

}  // namespace
}  // namespace smcbench

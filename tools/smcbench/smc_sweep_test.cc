// `smcbench smc-sweep` against facts known without our code: on smc-disturbed (σ' = 2(u + d), d = 0.5 sin 50t unknown
// to the controller) the implicit controller leaves σ_{k+1} = 2∫ d over the step, so its band is h to within the
// peak of the sine, of order 1 in h; the explicit input jumps by 2α about every other step (variation of order −1).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <unistd.h>

#include "bench/figures/gnuplot_figure.h"
#include "problems/scenes/registry.h"
#include "solvers/core/problem.h"
#include "tools/smcbench/smc_sweep.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

TEST(SmcSweep, BandsAndOrdersOnTheDisturbedScene) {
  SmcSweepOptions options;
  options.scene = ScenesDirectory() + "/smc-disturbed.json";
  options.steps = {0.01, 0.005, 0.0025};
  const fs::path dir = fs::temp_directory_path() / ("smc_sweep_test_" + std::to_string(::getpid()));
  options.out_dir = dir.string();
  options.plots = GnuplotAvailable();
  const SmcSweepResult r = RunSmcSweep(options);
  ASSERT_EQ(r.rows.size(), 6u);
  for (const SmcSweepRow& row : r.rows) {
    ASSERT_TRUE(row.completed) << row.method << " " << row.h;
    ASSERT_GE(row.chattering.from_step, 0);
    if (row.method == "zoh") {
      EXPECT_LE(row.chattering.sigma_band, row.h * (1 + 1e-12)) << row.h;  // |2 ∫ 0.5 sin| ≤ h
      EXPECT_GE(row.chattering.sigma_band, 0.95 * row.h) << row.h;
      EXPECT_LE(row.chattering.u_max_jump, 25.0 * row.h * 1.01) << row.h;  // |Δd| ≤ h ω A
    } else {
      EXPECT_NEAR(row.chattering.u_max_jump, 2.0, 0.05) << row.h;  // 2α
    }
  }
  EXPECT_NEAR(r.band_order_implicit, 1.0, 0.05);
  EXPECT_NEAR(r.band_order_explicit, 1.0, 0.3);
  EXPECT_NEAR(r.variation_order_implicit, 0.0, 0.05);
  EXPECT_LT(r.variation_order_explicit, -0.8);
  EXPECT_THAT(r.markdown, HasSubstr("| zoh-explicit | 0.0025 |"));
  EXPECT_TRUE(fs::is_regular_file(dir / "smc-sweep.md"));
  if (options.plots) {
    for (const char* file : {"sigma-band.png", "sigma-band.svg", "sigma-band.dat", "sigma-band.gp",
                             "input-variation.svg", "input-variation.dat", "input-variation.gp"}) {
      EXPECT_TRUE(fs::is_regular_file(dir / file)) << file;
    }
  }
  fs::remove_all(dir);
}

TEST(SmcSweep, BadInputNamesTheOption) {
  SmcSweepOptions options;
  options.scene = "sign";
  try {
    RunSmcSweep(options);
    ADD_FAILURE() << "no error";
  } catch (const InvalidInputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("smc-sweep: scene 'sign' is not a ZOH plant"));
  }
  options.scene = "zoh-siso";
  options.steps = {0.1, -0.1};
  try {
    RunSmcSweep(options);
    ADD_FAILURE() << "no error";
  } catch (const InvalidInputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("--h: every step must be a finite number > 0, got -0.1"));
  }
}

}  // namespace
}  // namespace smcbench

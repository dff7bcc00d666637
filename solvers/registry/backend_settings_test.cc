// The one `--set BACKEND.OPTION=VALUE` parser (backend_settings.h): what it accepts, where a setting lands, and the
// one-line errors for each kind of bad setting. The commands (solve, simulate, bench) only call it.
#include "solvers/registry/backend_settings.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "solvers/auto/auto_solver.h"
#include "solvers/lemke/lemke_solver.h"
#include "solvers/psor/psor_solver.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

using ::testing::HasSubstr;

std::string ErrorOf(const std::vector<std::string>& settings, const std::vector<Solver*>& selected) {
  try {
    ApplyBackendSettings(settings, selected);
  } catch (const InvalidInputError& e) {
    return e.what();
  }
  return "";
}

TEST(BackendSettings, ParsesAtTheFirstDotAndTheFirstEqualsAfterIt) {
  const BackendSetting s = ParseBackendSetting("siconos-lcp-lemke.max_size=1e3=x");
  EXPECT_EQ(s.backend, "siconos-lcp-lemke");
  EXPECT_EQ(s.option, "max_size");
  EXPECT_EQ(s.value, "1e3=x");
  const BackendSetting empty_value = ParseBackendSetting("psor.omega=");
  EXPECT_EQ(empty_value.value, "");  // the option's binder refuses it, naming the option
  for (const char* bad : {"psor", "psor.omega", "psor=1.2", "=psor.omega", ".omega=1", "psor.=1", "psor=1.omega"}) {
    try {
      ParseBackendSetting(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const InvalidInputError& e) {
      EXPECT_THAT(e.what(), HasSubstr(std::string("--set expects BACKEND.OPTION=VALUE, got '") + bad + "'")) << bad;
    }
  }
}

TEST(BackendSettings, AppliesToTheSelectedBackendAndToAutosInstanceOfIt) {
  PsorSolver psor;
  LemkeSolver lemke;
  ApplyBackendSettings({"psor.omega=1.25", "lemke.free_row_method=split", "psor.omega=1.5"}, {&psor, &lemke});
  EXPECT_EQ(psor.options().omega, 1.5);  // the later setting wins
  EXPECT_EQ(lemke.options().free_row_method, LemkeOptions::FreeRows::kSplit);
  // A choice option that was integer-coded reads its old number as the name it stood for (old command lines).
  ApplyBackendSettings({"lemke.free_row_method=2"}, {&lemke});
  EXPECT_EQ(lemke.options().free_row_method, LemkeOptions::FreeRows::kBasic);
  ApplyBackendSettings({"lemke.free_row_method=split", "lemke.covering_vector=1"}, {&lemke});
  EXPECT_EQ(lemke.options().free_row_method, LemkeOptions::FreeRows::kSplit);
  EXPECT_EQ(lemke.options().covering_vector, LemkeOptions::Covering::kRowScaled);

  AutoSolver automatic;
  ApplyBackendSettings({"psor.omega=0.75", "auto.fallback=false"}, {&automatic});
  EXPECT_EQ(static_cast<PsorSolver&>(automatic.candidate(AutoCandidate::kPsor)).options().omega, 0.75);
  EXPECT_FALSE(automatic.options().fallback);
}

TEST(BackendSettings, EachBadSettingIsOneLineNamingItAndNothingIsApplied) {
  PsorSolver psor;
  const std::vector<Solver*> selected = {&psor};
  // Not selected: rejected (a setting that changes nothing is a typo in --solver or a leftover).
  std::string error = ErrorOf({"psor.omega=1.2", "lemke.pivot_tolerance=1e-8"}, selected);
  EXPECT_THAT(error, HasSubstr("--set lemke.pivot_tolerance=1e-8 names backend 'lemke', which this run does not use "
                               "(it uses 'psor'); choose it with --solver"));
  EXPECT_EQ(psor.options().omega, PsorOptions{}.omega) << "the valid setting before it must not be applied";
  // Unknown backend: the registry's names.
  error = ErrorOf({"nosuch.omega=1"}, selected);
  EXPECT_THAT(error, HasSubstr("--set nosuch.omega=1: unknown solver 'nosuch' (known: lemke, psor"));
  // Unknown option: the backend's options and where to read about them.
  error = ErrorOf({"psor.omgea=1.2"}, selected);
  EXPECT_THAT(error, HasSubstr("--set psor.omgea=1.2: psor: unknown option 'omgea' (known: omega,"));
  EXPECT_THAT(error, HasSubstr("`smcbench list` shows every backend's options"));
  // Bad value: the option and what it expects; a value out of range is refused by the backend's own check.
  EXPECT_THAT(ErrorOf({"psor.omega=fast"}, selected), HasSubstr("option 'omega' expects a number, got 'fast'"));
  EXPECT_THAT(ErrorOf({"psor.omega=2.5"}, selected), HasSubstr("invalid value for option 'omega'"));
  EXPECT_THAT(ErrorOf({"lemke.free_row_method=7"}, {&psor}),
              HasSubstr("option 'free_row_method' expects one of auto, schur, basic, split, or an old number 0=auto "
                        "1=schur 2=basic 3=split, got '7'"));
  // Checked even when not selected: the error does not depend on --solver.
  EXPECT_THAT(ErrorOf({"lemke.no_such=1"}, selected), HasSubstr("lemke: unknown option 'no_such'"));
  for (const char* text : {"psor.omega=2.5", "nosuch.x=1", "lemke.x=1", "x"}) {
    EXPECT_EQ(ErrorOf({text}, selected).find('\n'), std::string::npos) << text;
  }
  EXPECT_EQ(psor.options().omega, PsorOptions{}.omega);
}

TEST(BackendSettings, ASelectionCheckedByNameCanRunOneBackendAtATime) {
  const std::vector<std::string> settings = {"psor.omega=1.5", "enum.size_limit=3", "lemke.covering_vector=ones"};
  CheckBackendSettings(settings, {"psor", "auto", "lemke"});  // auto takes enum's setting
  EXPECT_THROW(CheckBackendSettings(settings, {"psor", "lemke"}), InvalidInputError);  // nobody takes enum's
  EXPECT_EQ(SettingsReaching("psor", settings), std::vector<std::string>{"psor.omega=1.5"});
  EXPECT_EQ(SettingsReaching("auto", settings), settings);  // psor, enum and lemke are all candidates of auto
  EXPECT_TRUE(SettingsReaching("newton", settings).empty());
}

}  // namespace
}  // namespace smcbench

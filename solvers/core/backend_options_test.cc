// Why: pins down the two option mechanisms every backend shares: BackendWithOptions' accessors (each way of
// changing the options tells prepared sessions to check them again) and OptionBinder's old numbers for choice
// options that used to be integer-coded (`--set lemke.free_row_method=2` still works).
#include "solvers/core/backend_options.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "solvers/core/options.h"

namespace smcbench {
namespace {
using ::testing::HasSubstr;

struct ScaleOptions {
  double factor = 1.0;
};

// A backend that refuses every problem: enough to own typed options.
class ScaleBackend final : public BackendWithOptions<ScaleOptions> {
 public:
  ScaleBackend() = default;
  explicit ScaleBackend(const ScaleOptions& options) : BackendWithOptions(options) {}
  const SolverInfo& info() const override {
    static const SolverInfo kInfo = [] {
      SolverInfo i;
      i.name = "scale";
      return i;
    }();
    return kInfo;
  }

 protected:
  void DoSolve(const BoxMLCP& /*problem*/, const SolverOptions& /*options*/, SolveResult* result) override {
    result->status = SolveStatus::kNotApplicable;
  }
};

TEST(BackendOptions, ConstructorStoresTheOptionsWithoutAChange) {
  ScaleBackend backend(ScaleOptions{2.5});
  EXPECT_EQ(backend.options().factor, 2.5);
  EXPECT_EQ(ScaleBackend().options().factor, 1.0);
}

TEST(BackendOptions, MutableOptionsAndSetOptionsBothMarkTheOptionsChanged) {
  ScaleBackend backend;
  const std::uint64_t before = backend.option_generation();
  backend.mutable_options().factor = 3.0;
  EXPECT_EQ(backend.options().factor, 3.0);
  const std::uint64_t after_mutable = backend.option_generation();
  EXPECT_NE(after_mutable, before);
  backend.set_options(ScaleOptions{4.0});
  EXPECT_EQ(backend.options().factor, 4.0);
  EXPECT_NE(backend.option_generation(), after_mutable);
  // Reading never counts as a change.
  const std::uint64_t now = backend.option_generation();
  EXPECT_EQ(static_cast<const ScaleBackend&>(backend).options().factor, 4.0);
  EXPECT_EQ(backend.option_generation(), now);
}

enum class Method { kAuto = 10, kSchur = 20, kSplit = 30 };

// An option bound the way lemke.free_row_method is: names, and the old numbers 0, 1, 2 in that order.
OptionBinder MethodBinder(Method* method) {
  OptionBinder binder;
  binder.Add("method", method,
             {{"auto", static_cast<int>(Method::kAuto)}, {"schur", static_cast<int>(Method::kSchur)},
              {"split", static_cast<int>(Method::kSplit)}},
             {"auto", "schur", "split"}, "how");
  return binder;
}

TEST(OptionsLegacyNumbers, NameAndOldNumberSetTheSameValue) {
  Method method = Method::kAuto;
  const OptionBinder binder = MethodBinder(&method);
  std::string error;
  ASSERT_TRUE(binder.Set("method", "split", &error)) << error;
  EXPECT_EQ(method, Method::kSplit);
  ASSERT_TRUE(binder.Set("method", "0", &error)) << error;
  EXPECT_EQ(method, Method::kAuto);
  ASSERT_TRUE(binder.Set("method", "1", &error)) << error;
  EXPECT_EQ(method, Method::kSchur);
  ASSERT_TRUE(binder.Set("method", "2", &error)) << error;
  EXPECT_EQ(method, Method::kSplit);
  EXPECT_EQ(binder.ValueText("method"), "split") << "printed by name, never by number";
}

TEST(OptionsLegacyNumbers, OutOfRangeNumbersAndUnknownNamesAreRejectedListingWhatIsAccepted) {
  Method method = Method::kSchur;
  const OptionBinder binder = MethodBinder(&method);
  const std::string accepted =
      "option 'method' expects one of auto, schur, split, or an old number 0=auto 1=schur 2=split, got '";
  for (const char* bad : {"3", "-1", "+1", " 1", "1.0", "01x", "99999999999999999999", "", "Schur", "10"}) {
    std::string error;
    EXPECT_FALSE(binder.Set("method", bad, &error)) << bad;
    EXPECT_EQ(error, accepted + bad + "'");
    EXPECT_EQ(method, Method::kSchur) << "a rejected value is not kept: " << bad;
  }
}

TEST(OptionsLegacyNumbers, AnOptionWithoutOldNumbersReadsNoNumber) {
  Method method = Method::kAuto;
  OptionBinder binder;
  binder.Add("method", &method,
             {{"auto", static_cast<int>(Method::kAuto)}, {"split", static_cast<int>(Method::kSplit)}}, "how");
  std::string error;
  EXPECT_FALSE(binder.Set("method", "0", &error));
  EXPECT_EQ(error, "option 'method' expects one of auto, split, got '0'");
  EXPECT_THAT(binder.Help(), HasSubstr("method = auto (one of auto split)  how"));
}

TEST(OptionsLegacyNumbers, OldNumbersMayNameAnySubsetInAnyOrder) {
  // siconos-*.isolate: a former boolean, 0 = never, 1 = always; "first" has no old number.
  enum class Isolation { kNever, kFirst, kAlways };
  Isolation isolation = Isolation::kFirst;
  OptionBinder binder;
  binder.Add("isolate", &isolation,
             {{"first", static_cast<int>(Isolation::kFirst)}, {"always", static_cast<int>(Isolation::kAlways)},
              {"never", static_cast<int>(Isolation::kNever)}},
             {"never", "always"}, "where");
  std::string error;
  ASSERT_TRUE(binder.Set("isolate", "1", &error)) << error;
  EXPECT_EQ(isolation, Isolation::kAlways);
  ASSERT_TRUE(binder.Set("isolate", "0", &error)) << error;
  EXPECT_EQ(isolation, Isolation::kNever);
  EXPECT_FALSE(binder.Set("isolate", "2", &error));
  EXPECT_THAT(binder.Help(), HasSubstr("isolate = never (one of first always never; old number 0=never 1=always)"));
}

TEST(OptionsLegacyNumbers, AnOldNumberNamingNoChoiceIsAProgrammingError) {
  Method method = Method::kAuto;
  OptionBinder binder;
  EXPECT_THROW(binder.Add("method", &method, {{"auto", static_cast<int>(Method::kAuto)}}, {"auto", "shur"}, "how"),
               std::logic_error);
}

}  // namespace
}  // namespace smcbench

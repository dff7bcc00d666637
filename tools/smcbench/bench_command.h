// `smcbench bench` (replay suites of one-step problems on every backend, write results/…/results.{json,csv}) and
// `smcbench report DIR` (results → report.md with plots), plus the suites by name.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "problems/library/problem_set.h"

namespace CLI {
class App;
}

namespace smcbench {

// The Siconos collection's problem files, in a fixed order: dir/{lcp,relay,mlcp}/*.dat, the `_block` LCP twins of
// dense files left out. InvalidInputError if dir is not a folder or holds none.
std::vector<std::filesystem::path> SiconosCollectionFiles(const std::filesystem::path& dir);

// The Siconos collection as a problem set (id "siconos/<kind>/<stem>"; files the reader rejects are skipped and
// listed in *rejected when given).
ProblemSet SiconosSuite(const std::string& dir, std::vector<std::string>* rejected = nullptr);

// A handful of small generated problems (SPD relay, P-matrix LCP, a mixed box, one infeasible LCP): what CI runs
// bench and report on end to end.
ProblemSet TinySuite();

struct SuiteRequest {
  std::string siconos_dir = "../shared/peer-data/siconos";
  bool quick = false;  // smaller families / scale sizes
  // Attach certified reference solutions (AttachReferences, problems/library/references.h) to the problems small
  // enough, so the verdict can judge forward errors. `bench` turns it off here and attaches them itself, timed.
  bool references = true;
};

// "tiny", "paper", "families", "hard", "siconos", "scale", or the path of a problem-set file (problems/library).
// InvalidInputError for an unknown name.
ProblemSet BuildSuite(const std::string& name, const SuiteRequest& request);

// True when text matches the glob pattern ('*' any run of characters, '?' one character, no escapes): how
// `bench --allow-wrong 'siconos-*'` names backends.
bool GlobMatch(std::string_view pattern, std::string_view text);

// `bench`'s exit status when some result is wrong (Verdict IsWrong) on a backend not excused by --allow-wrong.
inline constexpr int kExitWrongAnswers = 3;

class BenchCommand {
 public:
  explicit BenchCommand(CLI::App* app);
  ~BenchCommand();
  bool bench_parsed() const;
  bool report_parsed() const;
  int RunBench(const std::string& command_line, std::ostream& out, std::ostream& err) const;
  int RunReport(std::ostream& out, std::ostream& err) const;

  struct Flags;

 private:
  CLI::App* bench_ = nullptr;
  CLI::App* report_ = nullptr;
  std::unique_ptr<Flags> flags_;
};

}  // namespace smcbench

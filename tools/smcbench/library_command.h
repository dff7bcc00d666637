// `smcbench library FILE`: what a problem-set file (problems/library, ".smcps") holds — name, counts, sizes, bound
// kinds, matrix-class tags, expected outcomes, certified references — optionally one line per problem;
// `--certify OUT` to attach certified reference solutions (problems/library/references.h; on a set of AVIs
// problems/avi_library/avi_references.h) and write the set, and `--export-relay DIR` to write every problem of a set
// of box-MLCPs in Siconos relay format for Siconos' own tools.
#pragma once

#include <iosfwd>
#include <memory>
#include <string>

#include "problems/library/problem_set.h"
#include "problems/library/problem_set_io.h"

namespace CLI {
class App;
}

namespace smcbench {

// The summary `smcbench library FILE` prints (info may be null: then the file line is left out).
std::string ProblemSetSummary(const ProblemSet& set, const ProblemSetFileInfo* info);

// Writes every problem the relay format can express to dir/<SiconosRelayFileName(id)> (a "-2", "-3", ... suffix
// when two ids sanitize to the same name) and dir/index.csv (file,id,n,expected). Returns the number written;
// *skipped receives one "<id>: <why>" line per problem left out (infinite bounds, n too large). Creates dir.
// InvalidInputError if dir cannot be created or a file cannot be written.
std::size_t ExportProblemSetRelay(const ProblemSet& set, const std::string& dir, std::string* skipped);

class LibraryCommand {
 public:
  explicit LibraryCommand(CLI::App* app);
  ~LibraryCommand();
  bool parsed() const;
  // 0 on success; 1 (with one line per skipped problem on err) if --export-relay had to skip problems.
  // --certify runs before --list and --export-relay, so they show and export the certified set.
  int Run(std::ostream& out, std::ostream& err) const;

  struct Flags;

 private:
  int RunAviSet(std::ostream& out) const;  // Run on a set of AVIs

  CLI::App* command_;
  std::unique_ptr<Flags> flags_;
};

}  // namespace smcbench

// Runs the smcbench command line in-process for tests: argv in, exit code and both streams out.
#pragma once

#include <sstream>
#include <string>
#include <vector>

#include "tools/smcbench/commands.h"

namespace smcbench::test_support {

struct CliRun {
  int code;
  std::string out, err;
};

inline CliRun RunSmcbench(std::vector<std::string> args) {
  args.insert(args.begin(), "smcbench");
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  std::ostringstream out, err;
  const int code = RunCli(static_cast<int>(argv.size()), argv.data(), out, err);
  return {code, out.str(), err.str()};
}

}  // namespace smcbench::test_support

// Entry point of the smcbench command-line program; all logic is in commands.cc. Here only `--version`, which
// depends on being this program (an installed copy finds its scenes itself: problems/scenes/registry.h).
#include <cstring>
#include <iostream>

#include "smcbench/version.h"
#include "tools/smcbench/commands.h"

int main(int argc, char** argv) {
  if (argc == 2 && std::strcmp(argv[1], "--version") == 0) {
    std::cout << "smcbench " << smcbench::Version() << " (git " << smcbench::GitRevision() << ")\n";
    return 0;
  }
  return smcbench::RunCli(argc, argv, std::cout, std::cerr);
}

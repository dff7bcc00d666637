// Entry point of the smcbench command-line program; all logic, `--version` included, is in RunCli (commands.cc),
// which an out-of-tree program registering its own backend calls too (examples/custom-backend).
#include <iostream>

#include "tools/smcbench/commands.h"

int main(int argc, char** argv) { return smcbench::RunCli(argc, argv, std::cout, std::cerr); }

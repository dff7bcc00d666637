// Entry point of the smcbench command-line program; all logic is in commands.cc.
#include <iostream>

#include "tools/smcbench/commands.h"

int main(int argc, char** argv) { return smcbench::RunCli(argc, argv, std::cout, std::cerr); }

// Silencing Siconos' unconditional printf in process with two pointer swaps; shared by the box and MCP adapters.
#pragma once

#include <cstdio>

namespace smcbench {

// Points the C streams stdout and stderr at sink for the lifetime of the object: silences what Siconos prints
// through stdio (printf, fprintf(stderr)) without a system call, where QuietStdio costs several. glibc's stdout and
// stderr are ordinary variables (glibc manual, "Standard Streams"). Output written to descriptors 1 and 2 directly
// is not caught (ProbedProblems::Console says when that happens). sink nullptr: does nothing.
class SwappedStdio {
 public:
  explicit SwappedStdio(FILE* sink) : sink_(sink) {
    if (sink_ == nullptr) return;
    saved_out_ = stdout;
    saved_err_ = stderr;
    stdout = sink_;
    stderr = sink_;
  }
  ~SwappedStdio() {
    if (sink_ == nullptr) return;
    stdout = saved_out_;
    stderr = saved_err_;
  }
  SwappedStdio(const SwappedStdio&) = delete;
  SwappedStdio& operator=(const SwappedStdio&) = delete;

 private:
  FILE* sink_;
  FILE* saved_out_ = nullptr;
  FILE* saved_err_ = nullptr;
};

}  // namespace smcbench

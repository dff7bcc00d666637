// The Siconos adapters on every file of the Siconos collection (tests/data/siconos): the answer computed in this
// process equals the probe's in the worker bit for bit. Here, not beside the adapters, because the collection is
// read with problems/io, a layer above solvers/. Built only with Siconos.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "problems/io/siconos_format.h"
#include "solvers/registry/registry.h"
#include "solvers/isolation/child_process.h"

// Siconos leaks a few bytes per call in some solvers: tell LeakSanitizer (ASan builds only) that those leaks are
// Siconos' (as solvers/siconos/siconos_solver_test.cc does).
extern "C" const char* __lsan_default_suppressions() { return "leak:libsiconos_numerics.so\n"; }

namespace smcbench {
namespace {

// The box adapters (the siconos-mcp-* ones refuse box-MLCPs).
std::vector<std::string> SiconosNames() {
  std::vector<std::string> names;
  for (auto name : SolverNames()) {
    if (name.substr(0, 8) == "siconos-" && name.substr(0, 12) != "siconos-mcp-") names.emplace_back(name);
  }
  return names;
}

std::unique_ptr<Solver> Make(const std::string& name) { return CreateSolver(name); }

bool SameBits(const Vector& a, const Vector& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

// Every file of the Siconos collection (tests/data/siconos) the reader accepts.
std::vector<std::filesystem::path> CollectionFiles() {
  namespace fs = std::filesystem;
  const fs::path collection = SMCBENCH_PEER_DATA_DIR "/siconos";
  std::vector<fs::path> files;
  for (const char* sub : {"lcp", "relay", "mlcp"}) {
    for (const auto& e : fs::directory_iterator(collection / sub)) {
      // Rectangular_mlcp.dat has no box-MLCP reading (tests/siconos_collection_test.cc).
      if (e.path().extension() == ".dat" && e.path().filename() != "Rectangular_mlcp.dat") files.push_back(e.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(SiconosProbe, InProcessAnswerEqualsTheProbesBitForBitOnTheSiconosCollection) {
  // A fresh backend per file: its first solve is the probe in the worker, its second the same call in this
  // process. Both start from the same Siconos state (a fresh session, the direct solvers' cache empty), so the
  // status, Siconos' code and z must agree to the last bit.
  const auto files = CollectionFiles();
  ASSERT_EQ(files.size(), 44u);
  SolverOptions options;
  options.time_limit_seconds = 1.0;  // mlcp_FB runs far past any test's budget on deltasigma_mlcp (README)
  int compared = 0, not_back = 0;
  std::set<std::string> backends_compared;
  for (const std::string& name : SiconosNames()) {
    for (const auto& file : files) {
      SCOPED_TRACE(name + " on " + file.filename().string());
      const BoxMLCP p = ReadSiconosFile(file.string());
      auto solver = Make(name);
      const SolveResult probe = solver->Solve(p, options);
      if (!AnswerProcessOf(probe).has_value()) continue;  // refused before any Siconos call
      EXPECT_EQ(AnswerProcessOf(probe), AnswerProcess::kWorker);
      const bool came_back = probe.status != SolveStatus::kTimeLimit && std::isnan(probe.GetDetail("siconos_signal")) &&
                             !std::isnan(probe.GetDetail("siconos_info"));
      if (!came_back) {  // probed again under the same 1 s limit, never run here
        ++not_back;
        EXPECT_EQ(AnswerProcessOf(solver->Solve(p, options)), AnswerProcess::kWorker);
        continue;
      }
      // The second call gets a limit no probe reaches: a problem whose probe took longer than the call's limit
      // stays in the worker (with its warm direct-* cache), which on a slow machine is a probe near 1 s.
      SolverOptions generous = options;
      generous.time_limit_seconds = 600.0;
      const SolveResult again = solver->Solve(p, generous);
      EXPECT_EQ(AnswerProcessOf(again), AnswerProcess::kThisProcess);
      EXPECT_EQ(again.status, probe.status) << probe.message << " / " << again.message;
      EXPECT_EQ(again.GetDetail("siconos_info"), probe.GetDetail("siconos_info"));
      EXPECT_EQ(again.iterations, probe.iterations);
      EXPECT_TRUE(SameBits(again.z, probe.z));
      ++compared;
      backends_compared.insert(name);
    }
  }
  EXPECT_GE(compared, 250) << not_back << " probes did not come back";
  EXPECT_EQ(backends_compared.size(), 13u);
}

}  // namespace
}  // namespace smcbench

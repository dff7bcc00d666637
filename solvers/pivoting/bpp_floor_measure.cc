// bpp's cold solve against the floor of issue 34: one dense factorization of M (Eigen's LLT for a symmetric
// positive definite M, PartialPivLU otherwise) of the same problem, timed in the same run, so the ratio holds on a
// loaded machine. Columns: bpp refactoring every active set from the Jacobi-scaled guess (factor_updates = false,
// guess_sweeps = 0: the method as published), bpp with Schur-complement updates from that guess, and bpp's
// defaults (updates, and 3 projected Gauss–Seidel sweeps for the first set where M is symmetric); sets solved and
// fresh factorizations of each. The fastest of 21 samples (7 above m = 256) of ≥ 3 ms each, taken in
// turn, seed 1, cold solves
// (Solver::Solve with measure_time off; the base's equilibration of a new matrix is done once, in the warm-up).
//   bpp_floor_measure [MAX_M [CLASS]]   m = 16 … 1024 (or up to MAX_M); CLASS (e.g. spd-relay): that row group only
#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "solvers/core/duration_text.h"
#include "solvers/generators/random_problems.h"
#include "solvers/core/sample_time.h"
#include "solvers/pivoting/bpp_solver.h"

namespace smcbench {
namespace {

constexpr double kSampleSeconds = 3e-3;  // one sample: repeats lasting at least this long

std::string Ns(double ns) { return DurationText(ns * 1e-9); }

void Run(int max_m, const char* only) {
  BppOptions fresh_options, updated_options;
  fresh_options.factor_updates = false;
  fresh_options.guess_sweeps = 0;
  updated_options.guess_sweeps = 0;
  BppSolver fresh(fresh_options), updated(updated_options), swept;
  SolverOptions options;
  options.measure_time = false;
  options.time_limit_seconds = 20.0;
  std::printf(
      "| class | m | floor | factorization | bpp, refactor every set | bpp, updates | bpp default | "
      "refactor / floor | updates / floor | default / floor | sets: refactor / updates (factored) / default (factored) |\n"
      "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---|\n");
  for (MatrixFamily family : {MatrixFamily::kSymmetricPositiveDefinite, MatrixFamily::kNonsymmetricPMatrix,
                              MatrixFamily::kDiagonallyDominant, MatrixFamily::kSkewPMatrix}) {
    for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay, BoundKind::kMixed}) {
      for (int m : {16, 32, 64, 128, 256, 512, 1024}) {
        if (m > max_m || (only != nullptr && ToString(family) + "-" + ToString(bounds) != only)) continue;
        // The strongly nonsymmetric class runs Murty's single pivots (thousands of sets when refactoring).
        if (family == MatrixFamily::kSkewPMatrix && m > 128) continue;
        GeneratorOptions g;
        g.family = family;
        g.bounds = bounds;
        g.size = m;
        g.seed = 1;
        const BoxMLCP problem = GenerateProblem(g).problem;
        const DenseMatrix& M = problem.dense_matrix();
        const bool spd = family == MatrixFamily::kSymmetricPositiveDefinite;
        Eigen::LLT<DenseMatrix> llt(m);
        Eigen::PartialPivLU<DenseMatrix> lu(m);
        const auto factor = [&] {
          if (spd) {
            llt.compute(M);
          } else {
            lu.compute(M);
          }
        };
        SolveResult results[3];
        BppSolver* solvers[3] = {&fresh, &updated, &swept};
        const auto solve0 = [&] { solvers[0]->Solve(problem, options, &results[0]); };
        const auto solve1 = [&] { solvers[1]->Solve(problem, options, &results[1]); };
        const auto solve2 = [&] { solvers[2]->Solve(problem, options, &results[2]); };
        factor();
        solve0();
        solve1();
        solve2();  // warm-up: workspaces sized, the equilibrated copy made
        // The fastest of 21 samples of each (7 above 256 rows), taken in turn: on a loaded machine the fastest sample is the least
        // disturbed one, and taking them in turn exposes all four to the same load.
        double floor = kInf, times[3] = {kInf, kInf, kInf};
        const int rounds = m <= 256 ? 21 : 7;
        for (int round = 0; round < rounds; ++round) {
          floor = std::min(floor, SampleNs(factor, kSampleSeconds));
          times[0] = std::min(times[0], SampleNs(solve0, kSampleSeconds));
          times[1] = std::min(times[1], SampleNs(solve1, kSampleSeconds));
          times[2] = std::min(times[2], SampleNs(solve2, kSampleSeconds));
        }
        std::printf("| %s-%s | %d | %s | %s |", ToString(family).c_str(), ToString(bounds).c_str(), m,
                    spd ? "LLT" : "LU", Ns(floor).c_str());
        for (int k = 0; k < 3; ++k) {
          std::printf(" %s |", results[k].solved() ? Ns(times[k]).c_str()
                                                  : std::string(ToString(results[k].status)).c_str());
        }
        for (int k = 0; k < 3; ++k) std::printf(" %.2f |", times[k] / floor);
        std::printf(" %d / %d (%d) / %d (%d) |\n", results[0].iterations, results[1].iterations,
                    static_cast<int>(results[1].GetDetail("factorizations")), results[2].iterations,
                    static_cast<int>(results[2].GetDetail("factorizations")));
        std::fflush(stdout);
      }
    }
  }
}

}  // namespace
}  // namespace smcbench

int main(int argc, char** argv) {
  const int max_m = argc > 1 ? std::atoi(argv[1]) : 1024;
  if (max_m < 16) {
    std::fprintf(stderr, "usage: %s [MAX_M >= 16 [CLASS-BOUNDS]] (docs/auto.md)\n", argv[0]);
    return 2;
  }
  smcbench::Run(max_m, argc > 2 ? argv[2] : nullptr);
  return 0;
}

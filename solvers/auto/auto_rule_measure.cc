// The measurements behind auto's rule (docs/auto.md), as markdown tables: run it to check the thresholds on another
// machine. Cold solves of seeded problems with a planted solution, median over 7 samples of ≥ 2 ms each.
//   auto_rule_measure sizes       every candidate and auto on the generated families, m = 3 … 128
//   auto_rule_measure condition   psor against lemke and bpp on SPD M of condition 1e2 … 1e8, m = 16, 64, 256
//   auto_rule_measure spd-test    cost of auto's SPD test (symmetry, Cholesky, condition estimate) against psor
//   auto_rule_measure overhead    a one-off solve through auto against the same solve by the backend it chose
//                                 (fastest of 15 samples each, taken in turn)
//   auto_rule_measure handover [MAX_M]
//                                 bpp with a cap of c·m single pivots, then lemke when it hands over (auto's chain),
//                                 against lemke alone and bpp without a cap, per class × bounds × m = 16 … 256
//   auto_rule_measure classes [MAX_M]
//                                 every matrix class the generators know × bounds × size (m = 4 … 256, or up to
//                                 MAX_M): each candidate, newton-min and auto, auto over the fastest, what auto chose
#include <Eigen/Cholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "solvers/auto/auto_solver.h"
#include "solvers/core/duration_text.h"
#include "solvers/core/sample_time.h"
#include "solvers/generators/random_problems.h"
#include "solvers/lemke/lemke_solver.h"
#include "solvers/newton/newton_min_solver.h"
#include "solvers/pivoting/bpp_solver.h"

namespace smcbench {
namespace {

using Clock = std::chrono::steady_clock;

// Median over 7 samples of the time per call of f, each sample repeating f until it lasts ≥ 2 ms; ns.
template <typename F>
double MedianNs(F f) {
  f();  // warm-up: sizes workspaces, fills per-matrix caches
  std::vector<double> samples;
  for (int k = 0; k < 7; ++k) samples.push_back(SampleNs(f, 2e-3));
  std::sort(samples.begin(), samples.end());
  return samples[3];
}

// The fastest of 15 samples of each of f and g (each sample repeats its function until it lasts ≥ 2 ms), taken in
// turn so that both see the same machine load: the fastest sample is the one least disturbed by other processes.
template <typename F, typename G>
std::pair<double, double> FastestInTurnNs(F f, G g) {
  f();
  g();
  double best_f = kInf, best_g = kInf;
  for (int k = 0; k < 15; ++k) {
    best_f = std::min(best_f, SampleNs(f, 2e-3));
    best_g = std::min(best_g, SampleNs(g, 2e-3));
  }
  return {best_f, best_g};
}

std::string Ns(double ns) { return DurationText(ns * 1e-9); }

SolverOptions TimedOptions() {
  SolverOptions options;
  options.measure_time = false;
  options.time_limit_seconds = 10.0;
  return options;
}

void Sizes() {
  AutoSolver automatic;
  const AutoCandidate candidates[] = {AutoCandidate::kEnum, AutoCandidate::kPsor, AutoCandidate::kLemke,
                                      AutoCandidate::kNewton, AutoCandidate::kBpp};
  constexpr int kCandidates = 5;
  std::printf("Geometric mean over seeds 1, 2, 3 of the median cold-solve time; a failure names its status.\n\n"
              "| problem | m | enum | psor | lemke | newton | bpp | auto | auto chose |\n"
              "|---|---:|---:|---:|---:|---:|---:|---:|---|\n");
  const SolverOptions options = TimedOptions();
  for (MatrixFamily family : {MatrixFamily::kSymmetricPositiveDefinite, MatrixFamily::kNonsymmetricPMatrix}) {
    for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay, BoundKind::kMixed}) {
      for (int m : {3, 4, 6, 8, 10, 12, 16, 24, 32, 48, 64, 96, 128}) {
        std::printf("| %s-%s | %d |", ToString(family).c_str(), ToString(bounds).c_str(), m);
        std::string chose;
        for (int column = 0; column <= kCandidates; ++column) {
          Solver& solver = column < kCandidates ? automatic.candidate(candidates[column]) : automatic;
          if (column == 0 && m > 16) {
            std::printf(" – |");
            continue;
          }
          double log_sum = 0.0;
          int solved = 0;
          std::string failure;
          for (std::uint64_t seed : {1u, 2u, 3u}) {
            GeneratorOptions g;
            g.family = family;
            g.bounds = bounds;
            g.size = m;
            g.seed = seed;
            const BoxMLCP problem = GenerateProblem(g).problem;
            SolveResult result;
            const double ns = MedianNs([&] { solver.Solve(problem, options, &result); });
            if (result.solved()) {
              log_sum += std::log(ns);
              ++solved;
            } else {
              failure = std::string(ToString(result.status));
            }
            if (column == kCandidates) {
              const std::optional<AutoCandidate> chosen = ChosenCandidateOf(result);
              const std::string name(chosen ? ToString(*chosen) : "?");
              if (chose.find(name) == std::string::npos) chose += (chose.empty() ? "" : ", ") + name;
            }
          }
          std::printf(" %s%s |", solved ? Ns(std::exp(log_sum / solved)).c_str() : "",
                      failure.empty() ? "" : (" " + failure).c_str());
        }
        std::printf(" %s |\n", chose.c_str());
        std::fflush(stdout);
      }
    }
  }
}

void Condition() {
  AutoSolver automatic;
  AutoOptions no_bpp;
  no_bpp.bpp_max_size = 0;
  AutoSolver without_bpp(no_bpp);  // the psor-or-lemke rule alone (and what a session gets)
  Solver& psor = automatic.candidate(AutoCandidate::kPsor);
  Solver& lemke = automatic.candidate(AutoCandidate::kLemke);
  Solver& bpp = automatic.candidate(AutoCandidate::kBpp);
  const SolverOptions options = TimedOptions();
  std::printf("| m | bounds | condition | rcond estimate | psor | sweeps | lemke | pivots | bpp | active sets | "
              "auto chose | without bpp |\n|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---|\n");
  // "12.3 µs" or "12.3 µs stalled": a time, and the status when it is not solved.
  const auto timed = [](double ns, const SolveResult& r) {
    return Ns(ns) + (r.solved() ? "" : " " + std::string(ToString(r.status)));
  };
  for (int m : {16, 64, 256}) {
    for (bool relay : {false, true}) {
      for (double condition : {1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8}) {
        const BoxMLCP problem = GenerateSpdWithCondition(m, condition, relay ? BoundKind::kRelay : BoundKind::kLCP).problem;
        const Eigen::LLT<DenseMatrix> cholesky(problem.dense_matrix());
        SolveResult p, l, b;
        const double tp = MedianNs([&] { psor.Solve(problem, options, &p); });
        const double tl = MedianNs([&] { lemke.Solve(problem, options, &l); });
        const double tb = MedianNs([&] { bpp.Solve(problem, options, &b); });
        const AutoCandidate chosen = automatic.ChoiceFor(problem).chosen();
        const AutoCandidate chosen_without_bpp = without_bpp.ChoiceFor(problem).chosen();
        std::printf("| %d | %s | %.0e | %.2e | %s | %d | %s | %d | %s | %d | %s | %s |\n", m,
                    relay ? "relay" : "LCP", condition, cholesky.rcond(), timed(tp, p).c_str(), p.iterations,
                    timed(tl, l).c_str(), l.iterations, timed(tb, b).c_str(), b.iterations,
                    std::string(ToString(chosen)).c_str(), std::string(ToString(chosen_without_bpp)).c_str());
        std::fflush(stdout);
      }
    }
  }
}

void SpdTest() {
  AutoSolver automatic;
  Solver& psor = automatic.candidate(AutoCandidate::kPsor);
  const SolverOptions options = TimedOptions();
  std::printf("| m | symmetry test + Cholesky + condition estimate | psor solve (spd-relay) |\n|---:|---:|---:|\n");
  for (int m : {16, 64, 128, 256, 512, 1024}) {
    GeneratorOptions g;
    g.size = m;
    g.bounds = BoundKind::kRelay;
    const BoxMLCP problem = GenerateProblem(g).problem;
    double rcond = 0.0;
    const double test = MedianNs([&] {
      const bool symmetric = problem.IsSymmetric();
      const Eigen::LLT<DenseMatrix> cholesky(problem.dense_matrix());
      rcond = symmetric ? cholesky.rcond() : 0.0;
    });
    SolveResult result;
    const double solve = MedianNs([&] { psor.Solve(problem, options, &result); });
    std::printf("| %d | %s | %s |\n", m, Ns(test).c_str(), Ns(solve).c_str());
    std::fflush(stdout);
  }
}

void Overhead() {
  std::printf("| problem | chosen | options | auto | chosen backend directly | overhead |\n"
              "|---|---|---|---:|---:|---:|\n");
  struct Setting {
    const char* name;
    bool measure_time, polish;
  };
  // As `smcbench solve` times (the base's clock), as `smcbench bench` and the benchmarks do (timed from outside),
  // and the raw algorithm.
  const Setting settings[] = {{"timed, polish", true, true}, {"untimed, polish", false, true},
                              {"untimed, no polish", false, false}};
  for (auto [family, bounds, m] : std::vector<std::tuple<MatrixFamily, BoundKind, int>>{
           {MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kRelay, 1},
           {MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kRelay, 2},
           {MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kLCP, 64},
           {MatrixFamily::kNonsymmetricPMatrix, BoundKind::kLCP, 128},
           {MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kRelay, 256}}) {
    GeneratorOptions g;
    g.family = family;
    g.bounds = bounds;
    g.size = m;
    const BoxMLCP problem = GenerateProblem(g).problem;
    for (const Setting& setting : settings) {
      AutoSolver automatic;
      SolverOptions options;
      options.measure_time = setting.measure_time;
      options.polish = setting.polish;
      Solver* chosen = automatic.DelegateFor(problem, options);
      SolveResult a, d;
      const auto [ta, td] = FastestInTurnNs([&] { automatic.Solve(problem, options, &a); },
                                            [&] { chosen->Solve(problem, options, &d); });
      std::printf("| %s | %s | %s | %s | %s | %+.0f%% |\n", problem.name().c_str(),
                  std::string(chosen->info().name).c_str(), setting.name, Ns(ta).c_str(), Ns(td).c_str(),
                  100.0 * (ta - td) / td);
      std::fflush(stdout);
    }
  }
}

// One problem class of the `classes` table: a generator family with its bounds, degenerate rows and storage.
struct ProblemClass {
  MatrixFamily family;
  BoundKind bounds;
  double degenerate_fraction = 0.0;
  bool sparse = false;
};

std::string ClassName(const ProblemClass& c) {
  return ToString(c.family) + "-" + ToString(c.bounds) + (c.degenerate_fraction > 0.0 ? "-deg" : "") +
         (c.sparse ? "-sparse" : "");
}

// The class's problems of size m, seeds 1, 2, 3 (planted solutions).
std::vector<BoxMLCP> SeededProblems(const ProblemClass& c, int m) {
  std::vector<BoxMLCP> problems;
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    GeneratorOptions g;
    g.family = c.family;
    g.bounds = c.bounds;
    g.size = m;
    g.seed = seed;
    g.degenerate_fraction = c.degenerate_fraction;
    g.sparse = c.sparse;
    problems.push_back(GenerateProblem(g).problem);
  }
  return problems;
}

// A cold solve's time in ns: once when that first call took over 20 ms (not 7 × 2 ms of repeats), else MedianNs.
template <typename F>
double ColdSolveNs(F solve) {
  const auto start = Clock::now();
  solve();
  const double once = std::chrono::duration<double>(Clock::now() - start).count();
  return once > 0.02 ? once * 1e9 : MedianNs(solve);
}

// bpp's per-call safeguard: with max_single_pivots = c·m, a bpp that leaves its block phase hands the problem to
// lemke (what auto's chain does). Each cell: the chain's time over lemke alone (geometric mean over seeds 1–3 of
// the median), and how many of the three bpp answered itself; the last columns: bpp without a cap over lemke, and
// lemke's time.
void Handover(int max_m) {
  const double factors[] = {0.25, 0.5, 1.0, 2.0};
  constexpr int kFactors = 4;
  SolverOptions options = TimedOptions();
  options.time_limit_seconds = 0.5;
  LemkeSolver lemke;
  BppSolver uncapped;
  std::printf("Cold solves: bpp capped at c·m single pivots, then lemke if it handed over, over lemke alone "
              "(geometric mean over seeds 1-3 of the median; in brackets: solves bpp answered itself).\n\n"
              "| class | m |");
  for (double c : factors) std::printf(" c = %g |", c);
  std::printf(" bpp, no cap | lemke |\n|---|---:|");
  for (int k = 0; k < kFactors + 2; ++k) std::printf("---:|");
  std::printf("\n");
  for (MatrixFamily family : {MatrixFamily::kSymmetricPositiveDefinite, MatrixFamily::kNonsymmetricPMatrix,
                              MatrixFamily::kSkewPMatrix, MatrixFamily::kDiagonallyDominant,
                              MatrixFamily::kScaledPMatrix}) {
    for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay, BoundKind::kMixed}) {
      for (int m : {16, 32, 64, 128, 256}) {
        if (m > max_m) continue;
        const std::vector<BoxMLCP> problems = SeededProblems({family, bounds}, m);
        std::printf("| %s | %d |", ClassName({family, bounds}).c_str(), m);
        double lemke_log = 0.0;
        std::vector<double> lemke_ns;
        for (const BoxMLCP& p : problems) {
          SolveResult r;
          lemke_ns.push_back(ColdSolveNs([&] { lemke.Solve(p, options, &r); }));
          lemke_log += std::log(lemke_ns.back());
        }
        for (double c : factors) {
          BppOptions bo;
          bo.max_single_pivots = std::max(1, static_cast<int>(std::ceil(c * m)));
          BppSolver capped(bo);
          double log_ratio = 0.0;
          int answered = 0;
          for (std::size_t k = 0; k < problems.size(); ++k) {
            SolveResult r;
            bool bpp_answered = false;
            const double ns = ColdSolveNs([&] {
              capped.Solve(problems[k], options, &r);
              bpp_answered = r.solved();
              if (!bpp_answered) lemke.Solve(problems[k], options, &r);
            });
            answered += bpp_answered;
            log_ratio += std::log(ns / lemke_ns[k]);
          }
          std::printf(" %.2f (%d) |", std::exp(log_ratio / 3.0), answered);
        }
        double log_ratio = 0.0;
        for (std::size_t k = 0; k < problems.size(); ++k) {
          SolveResult r;
          const double ns = ColdSolveNs([&] { uncapped.Solve(problems[k], options, &r); });
          log_ratio += std::log(r.solved() ? ns / lemke_ns[k] : 0.5e9 / lemke_ns[k]);
        }
        std::printf(" %.2f | %s |\n", std::exp(log_ratio / 3.0), Ns(std::exp(lemke_log / 3.0)).c_str());
        std::fflush(stdout);
      }
    }
  }
}

// Every class × size: cold time of each candidate (geometric mean over seeds 1–3 of the median; "> 0.2 s" past the
// measurement's time limit; a failure names its status), the fastest that solved every seed, auto and auto over
// it. The rows the docs quote are the worst ratios and the classes the issue named.
void Classes(int max_m) {
  AutoSolver automatic;
  NewtonMinSolver newton_min;
  struct Column {
    const char* name;
    Solver* solver;
    int max_m;  // larger problems are not run (enum: 2^m sets)
  };
  const Column columns[] = {{"enum", &automatic.candidate(AutoCandidate::kEnum), 12},
                            {"psor", &automatic.candidate(AutoCandidate::kPsor), 1 << 20},
                            {"lemke", &automatic.candidate(AutoCandidate::kLemke), 1 << 20},
                            {"newton", &automatic.candidate(AutoCandidate::kNewton), 1 << 20},
                            {"newton-min", &newton_min, 1 << 20},
                            {"bpp", &automatic.candidate(AutoCandidate::kBpp), 1 << 20},
                            {"auto", &automatic, 1 << 20}};
  constexpr int kColumns = 7, kAuto = 6;
  std::vector<ProblemClass> classes;
  for (MatrixFamily family : {MatrixFamily::kSymmetricPositiveDefinite, MatrixFamily::kNonsymmetricPMatrix,
                              MatrixFamily::kSkewPMatrix, MatrixFamily::kDiagonallyDominant,
                              MatrixFamily::kScaledPMatrix}) {
    for (BoundKind bounds : {BoundKind::kLCP, BoundKind::kRelay, BoundKind::kMixed}) {
      classes.push_back({family, bounds});
    }
  }
  classes.push_back({MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kBox, 0.5});
  classes.push_back({MatrixFamily::kSkewPMatrix, BoundKind::kLCP, 0.5});
  classes.push_back({MatrixFamily::kDiagonallyDominant, BoundKind::kRelay, 0.0, true});
  classes.push_back({MatrixFamily::kSkewPMatrix, BoundKind::kRelay, 0.0, true});
  SolverOptions options = TimedOptions();
  options.time_limit_seconds = 0.2;
  std::printf("Cold solves, geometric mean over seeds 1, 2, 3 of the median time; a failure names its status.\n\n"
              "| class | m |");
  for (const Column& column : columns) std::printf(" %s |", column.name);
  std::printf(" fastest | auto / fastest | auto chose |\n|---|---:|");
  for (int k = 0; k < kColumns; ++k) std::printf("---:|");
  std::printf("---|---:|---|\n");
  for (const ProblemClass& c : classes) {
    for (int m : {4, 8, 16, 32, 64, 128, 256}) {
      if (m > max_m) continue;
      const std::vector<BoxMLCP> problems = SeededProblems(c, m);
      std::printf("| %s | %d |", ClassName(c).c_str(), m);
      double times[kColumns];
      std::string chose;
      for (int k = 0; k < kColumns; ++k) {
        times[k] = kInf;
        if (m > columns[k].max_m) {
          std::printf(" – |");
          continue;
        }
        double log_sum = 0.0;
        int solved = 0;
        std::string failure;
        for (const BoxMLCP& problem : problems) {
          SolveResult result;
          const double ns = ColdSolveNs([&] { columns[k].solver->Solve(problem, options, &result); });
          if (result.solved()) {
            log_sum += std::log(ns);
            ++solved;
          } else if (failure.empty()) {
            failure = result.status == SolveStatus::kTimeLimit ? "> 0.2 s" : std::string(ToString(result.status));
          }
          if (k == kAuto) {
            const std::optional<AutoCandidate> chosen = ChosenCandidateOf(result);
            const std::string name(chosen ? ToString(*chosen) : "?");
            if (chose.find(name) == std::string::npos) chose += (chose.empty() ? "" : ", ") + name;
          }
        }
        if (solved == static_cast<int>(problems.size())) times[k] = std::exp(log_sum / solved);
        std::printf(" %s |", failure.empty() ? Ns(times[k]).c_str() : failure.c_str());
      }
      int fastest = 0;
      for (int k = 1; k < kAuto; ++k) {
        if (times[k] < times[fastest]) fastest = k;
      }
      std::printf(" %s | %.2f | %s |\n", columns[fastest].name, times[kAuto] / times[fastest], chose.c_str());
      std::fflush(stdout);
    }
  }
}

}  // namespace
}  // namespace smcbench

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "sizes") {
    smcbench::Sizes();
  } else if (mode == "condition") {
    smcbench::Condition();
  } else if (mode == "spd-test") {
    smcbench::SpdTest();
  } else if (mode == "overhead") {
    smcbench::Overhead();
  } else if (mode == "handover") {
    smcbench::Handover(argc > 2 ? std::atoi(argv[2]) : 256);
  } else if (mode == "classes") {
    const int max_m = argc > 2 ? std::atoi(argv[2]) : 256;
    if (max_m < 4) {
      std::fprintf(stderr, "%s classes: MAX_M must be an integer >= 4 (the smallest size measured), got '%s'\n",
                   argv[0], argv[2]);
      return 2;
    }
    smcbench::Classes(max_m);
  } else {
    std::fprintf(stderr, "usage: %s sizes|condition|spd-test|overhead|handover|classes [MAX_M] (docs/auto.md)\n", argv[0]);
    return 2;
  }
  return 0;
}

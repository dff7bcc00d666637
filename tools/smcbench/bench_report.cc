#include "tools/smcbench/bench_report.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "tools/smcbench/simulate.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
constexpr double kInfTime = std::numeric_limits<double>::infinity();

std::string G(double v, int digits = 3) {
  if (std::isnan(v)) return "–";
  if (std::isinf(v)) return "∞";
  char b[40];
  std::snprintf(b, sizeof b, "%.*g", digits, v);
  return b;
}

std::string Seconds(double s) {
  if (std::isnan(s) || std::isinf(s)) return G(s);
  char b[40];
  if (s < 1e-6) {
    std::snprintf(b, sizeof b, "%.0f ns", s * 1e9);
  } else if (s < 1e-3) {
    std::snprintf(b, sizeof b, "%.2f µs", s * 1e6);
  } else if (s < 1.0) {
    std::snprintf(b, sizeof b, "%.2f ms", s * 1e3);
  } else {
    std::snprintf(b, sizeof b, "%.2f s", s);
  }
  return b;
}

bool Correct(const ReplayRecord& r) {
  return r.verdict == Verdict::kSolved || r.verdict == Verdict::kCorrectlyRefused;
}

std::vector<std::string> Solvers(const std::vector<ReplayRecord>& records) {
  std::vector<std::string> out;
  for (const auto& r : records) {
    if (std::find(out.begin(), out.end(), r.solver) == out.end()) out.push_back(r.solver);
  }
  return out;
}

double Slope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const std::size_t n = x.size();
  if (n < 2) return std::nan("");
  for (std::size_t i = 0; i < n; ++i) {
    const double a = std::log(x[i]), b = std::log(y[i]);
    sx += a, sy += b, sxx += a * a, sxy += a * b;
  }
  const double d = n * sxx - sx * sx;
  return d > 0 ? (n * sxy - sx * sy) / d : std::nan("");
}

// gnuplot data file in the temporary folder, removed with the object.
struct DataFile {
  fs::path path;
  explicit DataFile(const std::string& stem)
      : path(fs::temp_directory_path() / ("smcbench-report-" + std::to_string(::getpid()) + "-" + stem + ".dat")) {}
  ~DataFile() {
    std::error_code ec;
    fs::remove(path, ec);
  }
};

std::string Safe(const std::string& text) {
  std::string out;
  for (char c : text) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '-';
  return out;
}

}  // namespace

std::vector<BackendSummary> SummarizeSuite(const SuiteResults& suite, double time_limit_seconds) {
  const auto& records = suite.replay.records;
  // Slowest correct time per problem.
  std::map<std::string, double> slowest;
  for (const auto& r : records) {
    if (Correct(r)) slowest[r.problem] = std::max(slowest[r.problem], r.time_median);
  }
  std::vector<BackendSummary> out;
  for (const std::string& solver : Solvers(records)) {
    BackendSummary b;
    b.solver = solver;
    double log_sum = 0.0;
    constexpr double kShift = 1e-6;
    for (const auto& r : records) {
      if (r.solver != solver) continue;
      ++b.problems;
      switch (r.verdict) {
        case Verdict::kSolved:
          ++b.solved;
          b.worst_residual = std::max(b.worst_residual, r.residual_rel);
          break;
        case Verdict::kCorrectlyRefused:
          ++b.correctly_refused;
          break;
        case Verdict::kFailed:
          ++b.failed;
          break;
        case Verdict::kWronglyClaimed:
          ++b.wrongly_claimed;
          break;
      }
      const auto it = slowest.find(r.problem);
      const double t = Correct(r) ? r.time_median : (it != slowest.end() ? 10.0 * it->second : time_limit_seconds);
      log_sum += std::log(t + kShift);
    }
    b.success_rate = b.problems ? static_cast<double>(b.solved + b.correctly_refused) / b.problems : 0.0;
    b.shifted_geomean = b.problems ? std::exp(log_sum / b.problems) - kShift : 0.0;
    out.push_back(b);
  }
  return out;
}

std::vector<std::pair<std::string, std::vector<double>>> PerformanceRatios(const SuiteResults& suite) {
  const auto& records = suite.replay.records;
  std::map<std::string, double> best;
  for (const auto& r : records) {
    if (r.verdict != Verdict::kSolved) continue;
    auto [it, inserted] = best.emplace(r.problem, r.time_median);
    if (!inserted) it->second = std::min(it->second, r.time_median);
  }
  std::vector<std::pair<std::string, std::vector<double>>> out;
  for (const std::string& solver : Solvers(records)) {
    std::vector<double> ratios;
    for (const auto& r : records) {
      if (r.solver != solver || !best.count(r.problem)) continue;  // problems nobody solves are left out
      ratios.push_back(r.verdict == Verdict::kSolved ? r.time_median / best.at(r.problem) : kInfTime);
    }
    std::sort(ratios.begin(), ratios.end());
    out.emplace_back(solver, std::move(ratios));
  }
  return out;
}

double GrowthExponent(const SuiteResults& suite, const std::string& solver) {
  std::map<int, std::vector<double>> by_size;
  for (const auto& r : suite.replay.records) {
    if (r.solver == solver && r.verdict == Verdict::kSolved) by_size[r.size].push_back(r.time_median);
  }
  std::vector<double> x, y;
  for (auto& [m, times] : by_size) {
    std::sort(times.begin(), times.end());
    x.push_back(m);
    y.push_back(times[times.size() / 2]);
  }
  return Slope(x, y);
}

std::string WriteBenchReport(const std::string& dir, bool plots) {
  json env;
  const BenchResults results = ReadBenchResults(dir, &env);
  if (plots && !GnuplotAvailable()) {
    throw InvalidInputError("report: the plots need gnuplot (Debian package gnuplot-nox); install it or pass --no-plots");
  }
  std::ostringstream md;
  md << "# smcbench benchmark report\n\n"
     << "Made by `smcbench report " << dir << "` from `" << dir << "/results.json`, produced by\n\n    "
     << results.command << "\n\n"
     << "Environment: git " << env.value("git_sha", std::string("?")).substr(0, 12)
     << (env.value("git_dirty", false) ? " (dirty tree)" : "") << ", " << env.value("compiler", std::string("?"))
     << " " << env.value("build_type", std::string("")) << ", " << env.value("cpu", std::string("?")) << " ("
     << env.value("cores", 0) << " cores), " << env.value("date", std::string("")) << ".\n\n"
     << "Success = the backend says solved AND the merit function (the natural residual, recomputed from the returned "
        "z) is at or below the tolerance, or — on a problem known to have no solution — any non-solved status "
        "('correctly refused'). **Wrongly claimed** = status solved where the recomputed residual says otherwise or "
        "no solution exists; it must be 0. Times are medians over repeated cold solves (each sample repeats the "
        "solve until it lasts ≥ 0.2 ms); SGM is the shifted geometric mean (shift 1 µs) with a wrong or failed "
        "problem counted at 10× the slowest correct time on it.\n\n";

  for (const SuiteResults& suite : results.suites) {
    md << "## Suite `" << suite.suite << "`: " << suite.description << "\n\n"
       << suite.problems << " problems.\n\n"
       << "| backend | solved | correctly refused | failed | **wrongly claimed** | success | SGM time | worst "
          "residual (solved) |\n|---|---|---|---|---|---|---|---|\n";
    for (const BackendSummary& b : SummarizeSuite(suite)) {
      md << "| " << b.solver << " | " << b.solved << " | " << b.correctly_refused << " | " << b.failed << " | "
         << (b.wrongly_claimed ? "**" + std::to_string(b.wrongly_claimed) + "**" : std::string("0")) << " | "
         << G(100.0 * b.success_rate, 3) << "% | " << Seconds(b.shifted_geomean) << " | " << G(b.worst_residual)
         << " |\n";
    }
    md << "\n";

    // The paper suite against the generic sparse path (bench adds it: newton on sparse copies).
    {
      std::map<std::string, double> best, generic;
      std::map<std::string, int> sizes;
      for (const auto& r : suite.replay.records) {
        if (r.verdict != Verdict::kSolved) continue;
        if (r.solver == "newton-sparse-path") {
          generic[r.problem] = r.time_median;
        } else {
          auto [it, inserted] = best.emplace(r.problem, r.time_median);
          if (!inserted) it->second = std::min(it->second, r.time_median);
          sizes[r.problem] = r.size;
        }
      }
      std::vector<double> ratios, floors;
      for (const auto& [problem, t] : generic) {
        if (!best.count(problem)) continue;
        ratios.push_back(t / best.at(problem));
        // Arithmetic floor: one m×m factorization and two mat-vecs, m³/3 + 4m² flops, at one flop per
        // nanosecond (scalar code at ~1–3 GHz).
        const double m = sizes.at(problem);
        floors.push_back(best.at(problem) / ((m * m * m / 3.0 + 4.0 * m * m) * 1e-9));
      }
      if (!ratios.empty()) {
        std::sort(ratios.begin(), ratios.end());
        std::sort(floors.begin(), floors.end());
        md << "Fastest backend against the generic sparse path (the same problems with M stored sparse, solved by "
              "`newton` with its UMFPACK sparse LU forced, `newton.linear_solver=2`): speed-up median "
           << G(ratios[ratios.size() / 2]) << "×, min " << G(ratios.front()) << "×, max " << G(ratios.back())
           << "× over " << ratios.size() << " problems (goal ≥ 10×). Distance from the arithmetic alone (m³/3 + 4m² "
              "flops at 1 flop/ns): the fastest solve takes median "
           << G(floors[floors.size() / 2]) << "× that floor — the rest is the fixed cost of a call (option checks, "
              "cold start, the merit function).\n\n";
      }
    }

    // Ours against the external adapters (siconos-*), per size: best of each side per problem.
    {
      std::map<std::string, double> ours, theirs;
      std::map<std::string, int> sizes;
      for (const auto& r : suite.replay.records) {
        if (r.verdict != Verdict::kSolved || r.solver == "newton-sparse-path") continue;
        auto& side = r.solver.rfind("siconos-", 0) == 0 ? theirs : ours;
        auto [it, inserted] = side.emplace(r.problem, r.time_median);
        if (!inserted) it->second = std::min(it->second, r.time_median);
        sizes[r.problem] = r.size;
      }
      std::map<int, std::vector<double>> by_size;
      for (const auto& [problem, t] : theirs) {
        if (ours.count(problem)) by_size[sizes.at(problem)].push_back(t / ours.at(problem));
      }
      if (!by_size.empty()) {
        md << "Our best backend against Siconos' best (`siconos-*`, each solve in its worker process: ≈ 7 µs of "
              "IPC per solve, see `solvers/siconos/README.md`), on the problems both solve — Siconos time / our "
              "time:\n\n| m | problems | median ratio | min | max |\n|---|---|---|---|---|\n";
        for (auto& [m, ratios] : by_size) {
          std::sort(ratios.begin(), ratios.end());
          md << "| " << m << " | " << ratios.size() << " | " << G(ratios[ratios.size() / 2]) << "× | "
             << G(ratios.front()) << "× | " << G(ratios.back()) << "× |\n";
        }
        md << "\n";
      }
    }

    // Performance profile.
    const auto ratios = PerformanceRatios(suite);
    if (plots && !ratios.empty()) {
      DataFile data("profile-" + Safe(suite.suite));
      std::ofstream out(data.path);
      double tau_max = 2.0;
      for (const auto& [solver, r] : ratios) {
        for (double v : r) {
          if (std::isfinite(v)) tau_max = std::max(tau_max, v);
        }
      }
      tau_max = std::min(tau_max * 1.5, 1e6);
      std::ostringstream g;
      const std::string png = "profile-" + Safe(suite.suite) + ".png";
      g << GnuplotPngPreamble(900, 600, (fs::path(dir) / png).string())
        << "set logscale x 2\nset grid\nset key bottom right\nset xlabel 'tau (time / best time)'\n"
        << "set ylabel 'fraction of problems'\nset yrange [0:1.02]\nset xrange [1:" << tau_max << "]\n"
        << "set title " << GnuplotQuote("Performance profile, suite " + suite.suite) << "\nplot ";
      int index = 0;
      for (const auto& [solver, r] : ratios) {
        // Step function: (τ_i, i/N), extended to τ_max.
        const double n = static_cast<double>(r.size());
        out << "1 0\n";
        int k = 0;
        for (double v : r) {
          if (!std::isfinite(v)) break;
          ++k;
          out << v << ' ' << k / n << '\n';
        }
        out << tau_max << ' ' << k / n << "\n\n\n";
        g << (index ? ", " : "") << GnuplotQuote(data.path.string()) << " index " << index
          << " using 1:2 with steps lw 2 title " << GnuplotQuote(solver);
        ++index;
      }
      out.close();
      g << "\n";
      RunGnuplot(g.str(), (fs::path(dir) / png).string(), "report");
      md << "![performance profile, " << suite.suite << "](" << png << ")\n\n";
    }

    // Speed against error: the tolerance sweep.
    if (!suite.replay.sweep.empty()) {
      md << "Speed against error (iterative backends, tolerance 1e-2 … 1e-12, median over the swept problems):\n\n"
         << "| backend | tolerance | achieved residual (median) | time (median) | solved |\n|---|---|---|---|---|\n";
      // Keyed by (backend, −tolerance): loosest tolerance first.
      std::map<std::pair<std::string, double>, std::vector<const ReplayRecord*>> groups;
      for (const auto& r : suite.replay.sweep) groups[{r.solver, -r.tolerance}].push_back(&r);
      std::map<std::string, std::vector<std::pair<double, double>>> curves;
      for (auto& [key, rs] : groups) {
        std::vector<double> res, t;
        int solved = 0;
        for (const auto* r : rs) {
          res.push_back(std::isfinite(r->residual_rel) ? r->residual_rel : 1e300);
          t.push_back(r->time_median);
          solved += r->verdict == Verdict::kSolved;
        }
        std::sort(res.begin(), res.end());
        std::sort(t.begin(), t.end());
        const double mres = res[res.size() / 2], mt = t[t.size() / 2];
        md << "| " << key.first << " | " << G(-key.second) << " | " << G(mres) << " | " << Seconds(mt) << " | "
           << solved << "/" << rs.size() << " |\n";
        curves[key.first].emplace_back(std::max(mres, 1e-17), mt);
      }
      md << "\n";
      if (plots) {
        DataFile data("sweep-" + Safe(suite.suite));
        std::ofstream out(data.path);
        std::ostringstream g;
        const std::string png = "speed-error-" + Safe(suite.suite) + ".png";
        g << GnuplotPngPreamble(900, 600, (fs::path(dir) / png).string())
          << "set logscale xy\nset grid\nset key top right\nset xlabel 'achieved relative residual'\n"
          << "set ylabel 'time per solve [s]'\nset title "
          << GnuplotQuote("Speed against error, suite " + suite.suite) << "\nplot ";
        int index = 0;
        for (auto& [solver, pts] : curves) {
          std::sort(pts.begin(), pts.end());
          for (auto [x, y] : pts) out << x << ' ' << y << '\n';
          out << "\n\n";
          g << (index ? ", " : "") << GnuplotQuote(data.path.string()) << " index " << index
            << " using 1:2 with linespoints pt 7 lw 2 title " << GnuplotQuote(solver);
          ++index;
        }
        out.close();
        g << "\n";
        RunGnuplot(g.str(), (fs::path(dir) / png).string(), "report");
        md << "![speed against error, " << suite.suite << "](" << png << ")\n\n";
      }
    }

    // Scale: time against m with the fitted exponent.
    std::set<int> sizes;
    for (const auto& r : suite.replay.records) sizes.insert(r.size);
    if (sizes.size() >= 3 && suite.suite == "scale") {
      md << "| backend | fitted exponent of time in m | ";
      for (int m : sizes) md << "m = " << m << " | ";
      md << "\n|---|---|";
      for (std::size_t i = 0; i < sizes.size(); ++i) md << "---|";
      md << "\n";
      for (const std::string& solver : Solvers(suite.replay.records)) {
        md << "| " << solver << " | " << G(GrowthExponent(suite, solver)) << " | ";
        for (int m : sizes) {
          std::string cell = "–";
          for (const auto& r : suite.replay.records) {
            if (r.solver == solver && r.size == m) {
              cell = r.verdict == Verdict::kSolved ? Seconds(r.time_median) : std::string(ToString(r.status));
            }
          }
          md << cell << " | ";
        }
        md << "\n";
      }
      md << "\n";
    }
  }

  if (results.has_stepper) {
    const StepperStudy& st = results.stepper;
    md << "## Time-stepper: warm against cold starts\n\n"
       << "Each scene's own run (SCENES.md settings), every step's one-step problem started from the previous s "
          "(warm) or from Π(0) (cold).\n\n| scene | backend | warm: time/step | cold: time/step | cold/warm | "
          "iterations/step warm | cold |\n|---|---|---|---|---|---|---|\n";
    for (std::size_t i = 0; i + 1 < st.warm_start.size(); i += 2) {
      const auto& w = st.warm_start[i];
      const auto& c = st.warm_start[i + 1];
      md << "| " << w.scene << " | " << w.solver << (w.ok && c.ok ? "" : " (failed steps)") << " | "
         << Seconds(w.seconds_per_step) << " | " << Seconds(c.seconds_per_step) << " | "
         << G(c.seconds_per_step / w.seconds_per_step) << " | " << G(w.iterations_per_step) << " | "
         << G(c.iterations_per_step) << " |\n";
    }
    md << "\n## Time-stepper: work-precision\n\nRun time (set-up included, median of repeats) against the max-norm "
          "error of x on the grid, against implicit Euler (lemke) at the smallest h / "
       << G(st.reference_h_factor) << ", h halved " << "from the scene's own.\n\n";
    std::map<std::string, std::map<std::string, std::vector<const WorkPrecisionRecord*>>> by_scene;
    for (const auto& r : st.work_precision) {
      by_scene[r.scene][r.method == "explicit" ? std::string("explicit Euler") : "implicit, " + r.solver].push_back(&r);
    }
    for (const auto& [scene, lines] : by_scene) {
      md << "**" << scene << "**: ";
      for (const auto& [label, rs] : lines) {
        md << label << ": error " << G(rs.front()->error) << " → " << G(rs.back()->error) << " in "
           << Seconds(rs.front()->seconds) << " → " << Seconds(rs.back()->seconds) << "; ";
      }
      md << "\n\n";
      if (plots) {
        DataFile data("wp-" + Safe(scene));
        std::ofstream out(data.path);
        std::ostringstream g;
        const std::string png = "work-precision-" + Safe(scene) + ".png";
        g << GnuplotPngPreamble(900, 600, (fs::path(dir) / png).string())
          << "set logscale xy\nset grid\nset key top right\nset xlabel 'max error of x'\nset ylabel 'run time [s]'\n"
          << "set title " << GnuplotQuote("Work-precision, " + scene) << "\nplot ";
        int index = 0;
        for (const auto& [label, rs] : lines) {
          for (const auto* r : rs) out << std::max(r->error, 1e-17) << ' ' << r->seconds << '\n';
          out << "\n\n";
          g << (index ? ", " : "") << GnuplotQuote(data.path.string()) << " index " << index
            << " using 1:2 with linespoints pt 7 lw 2 title " << GnuplotQuote(label);
          ++index;
        }
        out.close();
        g << "\n";
        RunGnuplot(g.str(), (fs::path(dir) / png).string(), "report");
        md << "![work-precision, " << scene << "](" << png << ")\n\n";
      }
    }
  }

  const std::string text = md.str();
  std::ofstream out(fs::path(dir) / "report.md");
  out << text;
  if (!out) throw InvalidInputError("report: cannot write " + (fs::path(dir) / "report.md").string());
  return text;
}

}  // namespace smcbench

// `solve` on an AVI file (avi_solve.h).
#include "tools/smcbench/avi_solve.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ostream>

#include "solvers/core/number_text.h"
#include "tools/smcbench/solve_report.h"

namespace smcbench {
namespace {

// JSON has no infinity or NaN: write them as null.
nlohmann::json Number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json VectorJson(const Vector& v) {
  nlohmann::json array = nlohmann::json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) array.push_back(Number(v[i]));
  return array;
}

// "1 1.05" (shortest round-trip form), "(none)" when empty.
std::string VectorText(const Vector& v) {
  if (v.size() == 0) return "(none)";
  std::string text;
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (i > 0) text += ' ';
    AppendNumberText(&text, v[i]);
  }
  return text;
}

}  // namespace

AviSolveRecord TimedAviSolve(const AffineVI& avi, Solver& solver, const SolverOptions& options, int repeat) {
  using Clock = std::chrono::steady_clock;
  AviSolveRecord record;
  record.problem = avi.name();
  record.solver = std::string(solver.info().name);
  record.repeats = std::max(1, repeat);
  std::vector<double> samples;
  samples.reserve(static_cast<std::size_t>(record.repeats));
  for (int k = 0; k < record.repeats; ++k) {
    if (k > 0) record.cached = solver.ForgetWarmState() == WarmStateReset::kCannotForget || record.cached;
    const Clock::time_point t0 = Clock::now();
    record.result = SolveAvi(avi, solver, options);
    samples.push_back(std::chrono::duration<double, std::nano>(Clock::now() - t0).count());
  }
  std::sort(samples.begin(), samples.end());
  const std::size_t n = samples.size();
  record.time_ns_median = n % 2 ? samples[n / 2] : 0.5 * (samples[n / 2 - 1] + samples[n / 2]);
  record.time_ns_min = samples.front();
  record.time_ns_max = samples.back();
  return record;
}

std::string FormatAviRecord(const AviSolveRecord& record) {
  const AviResult& r = record.result;
  const AviJudgement& j = r.judgement;
  char buffer[320];
  std::snprintf(buffer, sizeof buffer,
                "%-8s %-18s iters %-7d res %.2e rel / %.2e scaled   primal %.2e   compl %.2e   %s",
                record.solver.c_str(), std::string(ToString(r.status)).c_str(), r.iterations, j.residual.rel,
                j.residual.scaled, j.primal_infeasibility, j.complementarity,
                FormatDuration(record.time_ns_median).c_str());
  std::string text = buffer;
  if (record.judged_against_reference) {
    if (j.forward_error_applicable) {
      std::snprintf(buffer, sizeof buffer, "   fwd err %.2e (rel %.2e, allowed %.2e)", j.forward_error,
                    j.forward_error_rel, j.forward_allowance);
      text += buffer;
    } else {
      text += "   fwd err n/a";
    }
  }
  text += "   verdict " + std::string(ToString(j.verdict));
  if (record.cached) text += "   [cached: the backend cannot forget between repeats, so they may not start cold]";
  if (!r.solved() && !r.message.empty()) text += "   (" + r.message + ")";
  text += "\n    lambda " + VectorText(r.solution.lambda);
  text += "\n    mu     " + VectorText(r.solution.mu);
  text += "\n    nu     " + VectorText(r.solution.nu);
  return text;
}

nlohmann::json AviRecordToJson(const AviSolveRecord& record) {
  const AviResult& r = record.result;
  const AviJudgement& j = r.judgement;
  nlohmann::json out;
  out["problem"] = record.problem;
  out["solver"] = record.solver;
  out["status"] = std::string(ToString(r.status));
  out["message"] = r.message;
  out["verdict"] = std::string(ToString(j.verdict));
  out["iterations"] = r.iterations;
  out["residual_rel"] = Number(j.residual.rel);
  out["residual_scaled"] = Number(j.residual.scaled);
  out["primal_infeasibility"] = Number(j.primal_infeasibility);
  out["complementarity"] = Number(j.complementarity);
  out["forward_error"] = Number(j.forward_error);
  out["forward_error_rel"] = Number(j.forward_error_rel);
  out["forward_allowance"] = Number(j.forward_allowance);
  out["lambda"] = VectorJson(r.solution.lambda);
  out["mu"] = VectorJson(r.solution.mu);
  out["nu"] = VectorJson(r.solution.nu);
  out["time_ns_median"] = record.time_ns_median;
  out["time_ns_min"] = record.time_ns_min;
  out["time_ns_max"] = record.time_ns_max;
  out["repeats"] = record.repeats;
  out["cached"] = record.cached;
  // The backend's own view of the reduction: a detail, never the verdict (STYLE.md, "Judge peers like ourselves").
  nlohmann::json reduced;
  reduced["status"] = std::string(ToString(r.reduced.status));
  reduced["iterations"] = r.reduced.iterations;
  reduced["size"] = r.reduced.z.size();
  nlohmann::json details = nlohmann::json::object();
  for (int i = 0; i < r.reduced.num_details; ++i) {
    const std::string_view code = SolveResult::CodeText(r.reduced.details[i]);
    details[r.reduced.details[i].name] =
        code.empty() ? Number(r.reduced.details[i].value) : nlohmann::json(std::string(code));
  }
  reduced["details"] = std::move(details);
  out["reduced"] = std::move(reduced);
  return out;
}

namespace {

// Every backend on one AVI, then judged by expected and, with reference, against a certified λ*: stored (a set's
// verified reference, used as it is) or certified here by CertifyAvi from known (a file's "solution") and the
// answers.
struct SolvedAvi {
  std::vector<AviSolveRecord> records;
  std::optional<AviReference> certified;
};

SolvedAvi SolveAndJudgeAvi(const AffineVI& avi, ExpectedOutcome expected, const AviReference* stored,
                           const Vector& known, std::vector<std::unique_ptr<Solver>>& solvers,
                           const SolverOptions& options, int repeat, bool reference) {
  SolvedAvi solved;
  for (auto& solver : solvers) solved.records.push_back(TimedAviSolve(avi, *solver, options, repeat));
  if (reference) {
    if (stored != nullptr && stored->verified()) {
      solved.certified = *stored;
    } else {
      std::vector<AviSolution> candidates;
      if (known.size() > 0) candidates.push_back(AviMultipliersAt(avi, known));
      for (const AviSolveRecord& r : solved.records) {
        if (r.result.solution.lambda.size() == avi.size()) candidates.push_back(r.result.solution);
      }
      solved.certified = CertifyAvi(avi, candidates);
    }
  }
  // SolveAvi assumed ExpectedAviOutcome: the file's or the set's expected outcome decides instead.
  for (AviSolveRecord& r : solved.records) {
    r.result.judgement = JudgeAvi(avi, expected, solved.certified ? &*solved.certified : nullptr, r.result.status,
                                  r.result.solution, options.tolerance);
    r.judged_against_reference = solved.certified.has_value();
  }
  return solved;
}

nlohmann::json AviReferenceToJson(const AviReference& certified) {
  nlohmann::json ref;
  ref["certificate"] = std::string(ToString(certified.reduced.certificate));
  ref["condition"] = Number(certified.reduced.condition);
  ref["lambda_unique"] = certified.lambda_unique;
  ref["lambda"] = VectorJson(certified.solution.lambda);
  ref["mu"] = VectorJson(certified.solution.mu);
  ref["nu"] = VectorJson(certified.solution.nu);
  return ref;
}

// "ID (AVI: n = 2, m = 4, p = 0, P bounded, expected solvable)", the reference line, one record per backend.
void PrintSolvedAvi(const std::string& title, const AffineVI& avi, ExpectedOutcome expected, const SolvedAvi& solved,
                    std::ostream& out) {
  out << title << " (AVI: n = " << avi.size() << ", m = " << avi.inequality_count()
      << ", p = " << avi.equality_count() << ", P " << ToString(avi.boundedness()) << ", expected "
      << ToString(expected) << ")\n";
  if (solved.certified) {
    const AviReference& certified = *solved.certified;
    char line[200];
    std::snprintf(line, sizeof line, "reference: certificate %s, condition %.3g, |lambda*|inf %.3g",
                  std::string(ToString(certified.reduced.certificate)).c_str(), certified.reduced.condition,
                  certified.solution.lambda.size() ? certified.solution.lambda.cwiseAbs().maxCoeff() : 0.0);
    out << line << (certified.lambda_unique ? "" : " (forward error not defined: lambda* not proven unique)")
        << "\n";
  }
  for (const AviSolveRecord& r : solved.records) out << "  " << FormatAviRecord(r) << "\n";
}

}  // namespace

int RunSolveAvi(const std::string& path, std::optional<ProblemFormat> format,
                std::vector<std::unique_ptr<Solver>>& solvers, const SolverOptions& options, int repeat, bool json,
                bool reference, std::ostream& out) {
  const AviFile file = ReadAviProblemFile(path, format);
  const SolvedAvi solved = SolveAndJudgeAvi(file.avi, file.expected, nullptr, file.solution, solvers, options,
                                            repeat, reference);
  if (!json) {
    PrintSolvedAvi(file.avi.name(), file.avi, file.expected, solved, out);
    return 0;
  }
  nlohmann::json array = nlohmann::json::array();
  for (const AviSolveRecord& r : solved.records) array.push_back(AviRecordToJson(r));
  if (!solved.certified) {
    out << array.dump(2) << "\n";
    return 0;
  }
  out << nlohmann::json{{"reference", AviReferenceToJson(*solved.certified)}, {"results", std::move(array)}}.dump(2)
      << "\n";
  return 0;
}

int RunSolveAviSet(const std::string& path, const std::vector<std::string>& ids,
                   std::vector<std::unique_ptr<Solver>>& solvers, const SolverOptions& options, int repeat, bool json,
                   bool reference, std::ostream& out) {
  const std::vector<AviLibraryProblem> problems = ReadAviProblemSetById(path, ids);
  nlohmann::json all = nlohmann::json::array();
  for (const AviLibraryProblem& p : problems) {
    const AffineVI& avi = *p.problem;
    SolvedAvi solved = SolveAndJudgeAvi(avi, p.expected, &p.reference, Vector(), solvers, options, repeat, reference);
    if (!json) {
      PrintSolvedAvi(p.id, avi, p.expected, solved, out);
      continue;
    }
    nlohmann::json array = nlohmann::json::array();
    for (AviSolveRecord& r : solved.records) {
      r.problem = p.id;
      array.push_back(AviRecordToJson(r));
    }
    nlohmann::json entry{{"problem", p.id},
                         {"n", avi.size()},
                         {"m", avi.inequality_count()},
                         {"p", avi.equality_count()},
                         {"expected", std::string(ToString(p.expected))},
                         {"results", std::move(array)}};
    if (solved.certified) entry["reference"] = AviReferenceToJson(*solved.certified);
    all.push_back(std::move(entry));
  }
  if (json) out << all.dump(2) << "\n";
  return 0;
}

}  // namespace smcbench

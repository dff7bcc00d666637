#include "tools/smcbench/solve_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "solvers/auto/auto_solver.h"

namespace smcbench {

SolveRecord TimedSolve(Solver& solver, const BoxMLCP& problem, const SolverOptions& options, int repeat,
                       bool warm) {
  SolveRecord record;
  record.warm = warm;
  record.problem = problem.name();
  record.solver = std::string(solver.info().name);
  record.repeats = std::max(1, repeat);
  std::vector<double> times;
  times.reserve(record.repeats);
  // Which path answered (detail "in_process", NaN for our backends): one answer from the worker taints the times.
  const auto time_it = [&] {
    times.push_back(record.result.solve_seconds * 1e9);
    record.timed_in_worker = record.timed_in_worker || record.result.GetDetail("in_process") == 0.0;
  };
  std::optional<SolveSession> session;
  Vector start;
  const auto solve = [&] {
    if (!session) return solver.Solve(problem, options, &record.result);
    session->Solve(problem.q(), &record.result, &start);
    if (record.result.solved()) start = record.result.z;
  };
  if (warm) {
    session.emplace(solver.Prepare(problem, options));
    start = options.warm_start;
  }
  if (record.repeats > 1) {  // untimed warm-up: the workspace, and a siconos-* backend's probe
    solve();
    if (record.result.status == SolveStatus::kTimeLimit) {  // not repeated: its time is the limit
      record.repeats = 1;
      time_it();
    }
  }
  while (static_cast<int>(times.size()) < record.repeats) {
    solve();
    time_it();
  }
  std::sort(times.begin(), times.end());
  const int n = record.repeats;
  record.time_ns_median = n % 2 ? times[n / 2] : 0.5 * (times[n / 2 - 1] + times[n / 2]);
  record.time_ns_min = times.front();
  record.time_ns_max = times.back();
  return record;
}

std::string FormatDuration(double ns) {
  char buffer[32];
  if (ns < 1e3) {
    std::snprintf(buffer, sizeof buffer, "%.0f ns", ns);
  } else if (ns < 1e6) {
    std::snprintf(buffer, sizeof buffer, "%.3g us", ns / 1e3);
  } else if (ns < 1e9) {
    std::snprintf(buffer, sizeof buffer, "%.3g ms", ns / 1e6);
  } else {
    std::snprintf(buffer, sizeof buffer, "%.3g s", ns / 1e9);
  }
  return buffer;
}

std::string FormatRecordLine(const SolveRecord& record) {
  char buffer[256];
  if (!record.error.empty()) {
    std::snprintf(buffer, sizeof buffer, "%-8s error: %s", record.solver.c_str(), record.error.c_str());
    return buffer;
  }
  const SolveResult& r = record.result;
  std::snprintf(buffer, sizeof buffer, "%-8s %-18s iters %-7d res %.2e abs / %.2e rel / %.2e eq   %s",
                record.solver.c_str(), std::string(ToString(r.status)).c_str(), r.iterations, r.residual_abs,
                r.residual_rel, r.residual_scaled, FormatDuration(record.time_ns_median).c_str());
  std::string line = buffer;
  if (record.has_judgement) {
    const Judgement& j = record.judgement;
    if (std::isnan(j.forward_error)) {
      std::snprintf(buffer, sizeof buffer, "   fwd err n/a   %s", std::string(ToString(j.verdict)).c_str());
    } else {
      std::snprintf(buffer, sizeof buffer, "   fwd err %.2e (rel %.2e, allowed %.2e)   %s", j.forward_error,
                    j.forward_error_rel, j.forward_allowance, std::string(ToString(j.verdict)).c_str());
    }
    line += buffer;
  }
  if (const double chosen = r.GetDetail("chosen"); record.solver == "auto" && !std::isnan(chosen)) {
    line += "   chose " + std::string(AutoCandidateName(static_cast<int>(chosen)));
  }
  if (record.warm) line += "   [warm: session, from the previous answer]";
  if (record.timed_in_worker) line += "   [timed through the isolation worker: IPC included]";
  if (!r.solved() && !r.message.empty()) line += "   (" + r.message + ")";
  return line;
}

namespace {
// JSON has no infinity or NaN: write them as null.
nlohmann::json Number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }
}  // namespace

nlohmann::json RecordToJson(const SolveRecord& record) {
  const SolveResult& r = record.result;
  nlohmann::json j;
  j["problem"] = record.problem;
  j["solver"] = record.solver;
  if (!record.error.empty()) {
    j["status"] = "error";
    j["message"] = record.error;
    return j;
  }
  j["status"] = std::string(ToString(r.status));
  j["message"] = r.message;
  j["iterations"] = r.iterations;
  j["residual_abs"] = Number(r.residual_abs);
  j["residual_rel"] = Number(r.residual_rel);
  j["residual_scaled"] = Number(r.residual_scaled);
  if (record.has_judgement) {
    j["forward_error"] = Number(record.judgement.forward_error);
    j["forward_error_rel"] = Number(record.judgement.forward_error_rel);
    j["forward_allowance"] = Number(record.judgement.forward_allowance);
    j["verdict"] = std::string(ToString(record.judgement.verdict));
  }
  j["time_ns_median"] = record.time_ns_median;
  j["time_ns_min"] = record.time_ns_min;
  j["time_ns_max"] = record.time_ns_max;
  j["repeats"] = record.repeats;
  j["timed_in_worker"] = record.timed_in_worker;
  nlohmann::json z = nlohmann::json::array();
  for (Eigen::Index i = 0; i < r.z.size(); ++i) z.push_back(Number(r.z[i]));
  j["z"] = std::move(z);
  nlohmann::json details = nlohmann::json::object();
  for (int i = 0; i < r.num_details; ++i) details[r.details[i].name] = Number(r.details[i].value);
  j["details"] = std::move(details);
  if (const double chosen = r.GetDetail("chosen"); record.solver == "auto" && !std::isnan(chosen)) {
    j["chosen"] = std::string(AutoCandidateName(static_cast<int>(chosen)));
  }
  j["warm"] = record.warm;
  return j;
}

nlohmann::json ReferenceToJson(const ReferenceSolution& reference) {
  nlohmann::json j;
  j["certificate"] = std::string(ToString(reference.certificate));
  j["condition"] = Number(reference.condition);
  nlohmann::json z = nlohmann::json::array();
  for (Eigen::Index i = 0; i < reference.z.size(); ++i) z.push_back(Number(reference.z[i]));
  j["z"] = std::move(z);
  return j;
}

}  // namespace smcbench

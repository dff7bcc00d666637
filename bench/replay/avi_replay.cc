#include "bench/replay/avi_replay.h"

#include <cstdint>

#include "bench/replay/jobs.h"
#include "bench/replay/sample_times.h"
#include "solvers/registry/backend_settings.h"
#include "solvers/registry/registry.h"

namespace smcbench {
namespace {

ReplayRecord Describe(const AviProblemSet& set, const AviLibraryProblem& p, const std::string& solver,
                      double tolerance) {
  ReplayRecord r;
  r.suite = set.name;
  r.problem = p.id;
  r.solver = solver;
  r.size = p.size();
  r.sparse = false;  // an AffineVI is dense
  for (const auto& t : p.tags) r.tags += (r.tags.empty() ? "" : ",") + t;
  r.expected = p.expected;
  r.certificate = std::string(ToString(p.reference.reduced.certificate));
  r.reference_radius = p.reference.reduced.proved_radius;
  r.reference_proved_unique = p.reference.reduced.proved_unique;
  r.tolerance = tolerance;
  r.mode = "cold";
  return r;
}

// The checksum's input: every field as bytes, lengths first (FNV-1a 64 over it: StableHashHex's function).
class ChecksumText {
 public:
  void Text(const std::string& s) {
    Count(s.size());
    bytes_ += s;
  }
  void Count(std::uint64_t n) { Raw(&n, sizeof n); }
  void Number(double v) { Raw(&v, sizeof v); }
  void Numbers(const DenseMatrix& A) {
    Count(static_cast<std::uint64_t>(A.rows()));
    Count(static_cast<std::uint64_t>(A.cols()));
    for (Eigen::Index j = 0; j < A.cols(); ++j) {
      for (Eigen::Index i = 0; i < A.rows(); ++i) Number(A(i, j));
    }
  }
  std::string Hex() const { return StableHashHex(bytes_); }

 private:
  void Raw(const void* data, std::size_t n) { bytes_.append(static_cast<const char*>(data), n); }
  std::string bytes_;
};

}  // namespace

void TimeAviSolves(Solver* solver, const AffineVI& avi, const SolverOptions& options, const ReplayOptions& replay,
                   AviResult* result, ReplayRecord* record) {
  // No reference in the timed call: the verdict against it is computed once, after the timing (ReplayAviOne).
  replay_internal::SampleSolveTimes([&] { *result = SolveAvi(avi, *solver, options); }, &result->reduced, replay,
                                    record, [&] { return solver->ForgetWarmState(); });
}

ReplayRecord ReplayAviOne(const AviProblemSet& set, const AviLibraryProblem& p, Solver* solver,
                          const std::string& solver_name, const ReplayOptions& options, double tolerance) {
  if (!p.problem) throw InvalidInputError("bench: AVI " + p.id + " has no problem");
  ReplayRecord r = Describe(set, p, solver_name, tolerance);
  const SolverOptions o = ReplaySolverOptions(options, tolerance);
  AviResult result;
  if (!solver->info().box) {
    result.status = SolveStatus::kNotApplicable;
    result.message = "backend does not solve box-MLCPs (SolverInfo::box is false): it cannot solve the reduction";
  } else {
    TimeAviSolves(solver, *p.problem, o, options, &result, &r);
  }
  // The verdict recomputes everything from (λ, μ, ν); the backend's own residuals are never read.
  const AviJudgement j = JudgeAvi(*p.problem, p.expected, &p.reference, result.status, result.solution, tolerance);
  r.status = result.status;
  r.message = result.message;
  r.iterations = result.iterations;
  r.residual_abs = j.residual.abs;
  r.residual_rel = j.residual.rel;
  r.residual_scaled = j.residual.scaled;
  r.forward_error = j.forward_error;
  r.forward_error_rel = j.forward_error_rel;
  r.forward_allowance = j.forward_allowance;
  r.verdict = j.verdict;
  r.backend_code = result.reduced.backend_code;
  return r;
}

ReplayResults ReplayAviProblemSet(const AviProblemSet& set, const ReplayOptions& options) {
  const std::vector<std::string> names = BackendsWith(options.solvers, &SolverInfo::box);
  std::vector<std::unique_ptr<Solver>> solvers;
  for (const std::string& name : names) {
    ReplayOptions one = options;
    one.settings = SettingsReaching(name, options.settings);
    std::vector<std::string> single{name};
    solvers.push_back(std::move(CreateReplaySolvers(one, &single).front()));
  }
  ReplayResults out;
  const std::size_t total = set.problems.size() * solvers.size();
  std::size_t done = 0;
  for (const AviLibraryProblem& p : set.problems) {
    for (std::size_t b = 0; b < solvers.size(); ++b) {
      out.records.push_back(ReplayAviOne(set, p, solvers[b].get(), names[b], options, options.tolerance));
      if (options.progress) options.progress(++done, total, set.name + " " + p.id + " " + names[b]);
    }
  }
  return out;
}

std::string AviProblemSetChecksum(const AviProblemSet& set) {
  ChecksumText c;
  c.Text(set.name);
  c.Count(set.problems.size());
  for (const AviLibraryProblem& p : set.problems) {
    c.Text(p.id);
    c.Text(p.source);
    c.Count(p.tags.size());
    for (const auto& t : p.tags) c.Text(t);
    c.Text(std::string(ToString(p.expected)));
    c.Count(p.problem ? 1 : 0);
    if (p.problem) {
      const AffineVI& a = *p.problem;
      for (const DenseMatrix* A : {&a.M(), &a.H(), &a.E()}) c.Numbers(*A);
      for (const Vector* v : {&a.q(), &a.K(), &a.f()}) c.Numbers(*v);
    }
    c.Text(std::string(ToString(p.reference.reduced.certificate)));
    c.Number(p.reference.reduced.condition);
    c.Count(p.reference.lambda_unique ? 1 : 0);
    c.Numbers(p.reference.reduced.z);
  }
  return c.Hex();
}

ReplayRecord AviNotRunRecord(const AviProblemSet& set, const AviLibraryProblem& p, const std::string& solver_name,
                             double tolerance, const std::string& message) {
  ReplayRecord r = Describe(set, p, solver_name, tolerance);
  r.status = SolveStatus::kTimeLimit;
  r.message = message;
  r.verdict = Verdict::kFailed;  // not run is no answer, even on an AVI with no solution
  r.residual_abs = r.residual_rel = r.residual_scaled = kInf;
  return r;
}

}  // namespace smcbench

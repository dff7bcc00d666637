// The conformance checks (conformance.h), moved here from tests/conformance_test.cc so that users run the same ones.
#include "solvers/conformance/conformance.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <memory>
#include <random>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "solvers/core/sanitized_build.h"  // a sanitizer build times its allocator, not the solve (CheckColdRepeat)
#include "solvers/core/verdict.h"
#include "solvers/enumerative/enumerative_solver.h"

namespace smcbench {
namespace {

// Collects failures of one check in the form the report keeps.
class Findings {
 public:
  Findings(std::string check, ConformanceReport* report) : check_(std::move(check)), report_(report) {}
  void Fail(const std::string& problem, const std::string& message) {
    report_->failures.push_back({check_, problem, message});
  }

 private:
  std::string check_;
  ConformanceReport* report_;
};

std::string Num(double x) {
  std::ostringstream s;
  s.precision(3);
  s << x;
  return s.str();
}

// The independent check: natural residual recomputed here from M, q, l, u, relative to 1 + ‖q‖∞.
double IndependentResidual(const BoxMLCP& p, const Vector& z) {
  const DenseMatrix M = p.ToDense();
  const Vector w = M * z + p.q();
  double r = 0;
  for (int i = 0; i < p.size(); ++i) {
    const double proj = std::min(std::max(z[i] - w[i], p.l()[i]), p.u()[i]);
    r = std::max(r, std::abs(z[i] - proj));
  }
  return r / (1.0 + p.q().cwiseAbs().maxCoeff());
}

std::unique_ptr<Solver> Make(const SolverFactory& create) {
  std::unique_ptr<Solver> solver = create();
  if (!solver) throw InvalidInputError("CheckConformance: the factory returned no backend");
  return solver;
}

void CheckKnownSolutions(const SolverFactory& create, const ConformanceOptions& options, ConformanceReport* report) {
  Findings findings("known-solution", report);
  const std::unique_ptr<Solver> solver = Make(create);
  EnumerativeSolver reference;
  const ConformanceCase cases[] = {
      {MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kLCP, 0.0, 0},
      {MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kRelay, 0.0, 0},
      {MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kMixed, 0.0, 0},
      {MatrixFamily::kNonsymmetricPMatrix, BoundKind::kLCP, 0.0, 0},
      {MatrixFamily::kNonsymmetricPMatrix, BoundKind::kBox, 0.0, 0},
      {MatrixFamily::kNonsymmetricPMatrix, BoundKind::kMixed, 0.0, 0},
      {MatrixFamily::kDiagonallyDominant, BoundKind::kRelay, 0.0, 0},
      {MatrixFamily::kDiagonallyDominant, BoundKind::kMixed, 0.0, 0},
      // Degenerate: z* at a bound with w* = 0 on a third (half) of the rows.
      {MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kLCP, 0.34, 0},
      {MatrixFamily::kNonsymmetricPMatrix, BoundKind::kRelay, 0.34, 0},
      {MatrixFamily::kDiagonallyDominant, BoundKind::kBox, 0.5, 0},
  };
  int solved = 0;
  for (ConformanceCase c : cases) {
    for (int n : {1, 2, 3, 5, 8, 10, 30}) {
      if (n > options.max_size) continue;
      c.size = n;
      for (std::uint64_t seed : {1u, 2u}) {
        GeneratorOptions g;
        g.family = c.family;
        g.bounds = c.bounds;
        g.degenerate_fraction = c.degenerate_fraction;
        g.size = n;
        g.seed = seed;
        const GeneratedProblem gen = GenerateProblem(g);
        const BoxMLCP& p = gen.problem;
        SolverOptions solve_options;
        solve_options.tolerance = options.tolerance;
        solve_options.time_limit_seconds = options.time_limit_seconds;
        const SolveResult r = solver->Solve(p, solve_options);
        ++report->solves;
        const bool must_solve = !options.must_solve || options.must_solve(c);
        if (!r.solved()) {
          if (must_solve) {
            findings.Fail(p.name(), "not solved: " + std::string(ToString(r.status)) + " " + r.message + " (residual " +
                                        Num(r.residual_rel) + ")");
          }
          continue;
        }
        // The invariant for every backend and every problem: "solved" is true.
        ++solved;
        ++report->solved_checked;
        const double residual = IndependentResidual(p, r.z);
        if (!(residual <= options.tolerance)) {
          findings.Fail(p.name(), "claimed solved, but the recomputed natural residual is " + Num(residual) +
                                      " > tolerance " + Num(options.tolerance));
        }
        // P-matrices have a unique solution: it must be z*, and the enumerative one.
        const double scale = 1.0 + gen.z_star.cwiseAbs().maxCoeff();
        const double error = (r.z - gen.z_star).cwiseAbs().maxCoeff();
        if (!(error <= 1e-6 * scale)) findings.Fail(p.name(), "z differs from the planted z* by " + Num(error));
        if (n <= 10) {
          const SolveResult e = reference.Solve(p, solve_options);
          if (!e.solved()) {
            findings.Fail(p.name(), "the enumerative reference did not solve it: " + e.message);
          } else if (const double gap = (r.z - e.z).cwiseAbs().maxCoeff(); !(gap <= 1e-6 * scale)) {
            findings.Fail(p.name(), "z differs from the enumerative backend's answer by " + Num(gap));
          }
        }
      }
    }
  }
  if (solved == 0) findings.Fail("(all)", "solved no problem");
}

// A seeded symmetric positive definite problem of n rows with the given bounds (a unique solution: a P-matrix).
BoxMLCP SpdProblem(BoundKind bounds, int n, int seed) {
  GeneratorOptions g;
  g.family = MatrixFamily::kSymmetricPositiveDefinite;
  g.bounds = bounds;
  g.size = n;
  g.seed = seed;
  return GenerateProblem(g).problem;
}

// A session without the warm active-set path (the time-stepper's path, the backend's own algorithm) is Solve
// without the per-call re-checks: over a sequence of one-step problems (q replaced, warm start = the previous
// answer) two instances of the backend, one driven by each, must return the same bits (the session adds only the
// detail "path").
void CheckSessionBits(const SolverFactory& create, const ConformanceOptions& options, ConformanceReport* report) {
  Findings findings("session-bits", report);
  std::unique_ptr<Solver> plain = Make(create);
  const std::unique_ptr<Solver> prepared = Make(create);
  for (BoundKind bounds : {BoundKind::kRelay, BoundKind::kLCP, BoundKind::kBox}) {
    for (int n : {1, 2, 3, 4, 6}) {
      BoxMLCP p = SpdProblem(bounds, n, 7);
      const Vector q0 = p.q();
      SolverOptions solve_options;
      solve_options.tolerance = options.tolerance;
      SessionOptions no_reuse;
      no_reuse.reuse_active_set = false;
      SolveSession session = prepared->Prepare(p, solve_options, no_reuse);
      // A meta-backend's session calls its choice directly: compare with that backend's own Solve.
      if (prepared->DelegateFor(p, solve_options) != nullptr) plain = CreateSolver(session.backend().info().name);
      SolveResult a, b;
      Vector warm_a, warm_b;
      for (int k = 0; k < 12; ++k) {
        // A slowly turning right side, as along a trajectory.
        Vector q = q0;
        for (int i = 0; i < n; ++i) q[i] *= std::cos(0.4 * k + i);
        p.set_q(q);
        solve_options.warm_start = warm_a;
        plain->Solve(p, solve_options, &a);
        session.Solve(q, &b, &warm_b);
        report->solves += 2;
        const std::string where = p.name() + ", step " + std::to_string(k);
        if (a.status != b.status) {
          findings.Fail(where, "status " + std::string(ToString(b.status)) + " from the session, " + std::string(ToString(a.status)) +
                                   " from Solve");
          break;
        }
        std::string differs;
        if (a.message != b.message) differs += " message";
        if (a.solver != b.solver) differs += " solver";
        if (a.z != b.z) differs += " z";
        if (a.w != b.w) differs += " w";
        if (a.residual_abs != b.residual_abs || a.residual_rel != b.residual_rel ||
            a.residual_scaled != b.residual_scaled) {
          differs += " residuals";
        }
        if (a.iterations != b.iterations) differs += " iterations";
        if (SessionPathOf(b) != SessionPath::kBackend) differs += " path";
        if (a.num_details + 1 != b.num_details) {
          differs += " details(count)";
        } else {
          for (int d = 0; d < a.num_details; ++d) {
            if (std::string_view(a.details[d].name) != b.details[d].name || a.details[d].value != b.details[d].value) {
              differs += std::string(" detail:") + a.details[d].name;
            }
          }
        }
        if (!differs.empty()) findings.Fail(where, "the session's result differs from Solve's in:" + differs);
        if (a.solved()) {
          warm_a = a.z;
          warm_b = b.z;
        }
      }
    }
  }
}

// With the warm active-set path on (the default), every answer still satisfies the verdict and agrees with the
// backend's own answer to rounding, and along a slowly moving q most calls are answered by the reused set.
void CheckSessionReuse(const SolverFactory& create, const ConformanceOptions& options, ConformanceReport* report) {
  Findings findings("session-reuse", report);
  const std::unique_ptr<Solver> plain = Make(create);
  const std::unique_ptr<Solver> prepared = Make(create);
  int reused = 0, calls = 0;
  for (BoundKind bounds : {BoundKind::kRelay, BoundKind::kLCP, BoundKind::kBox}) {
    for (int n : {1, 2, 4, 8}) {
      BoxMLCP p = SpdProblem(bounds, n, 11);
      const Vector q0 = p.q();
      SolverOptions solve_options;
      solve_options.tolerance = options.tolerance;
      SolveSession session = prepared->Prepare(p, solve_options);
      SolveResult a, b;
      for (int k = 0; k < 40; ++k) {
        Vector q = q0;
        for (int i = 0; i < n; ++i) q[i] *= 1.0 + 0.3 * std::sin(0.05 * k + i);
        p.set_q(q);
        plain->Solve(p, solve_options, &a);
        session.Solve(q, &b);
        report->solves += 2;
        ++calls;
        if (!a.solved()) continue;
        const std::string where = p.name() + ", step " + std::to_string(k);
        if (!b.solved()) {
          findings.Fail(where, "Solve solved it, the session did not: " + b.message);
          break;
        }
        if (!PassesBoxMlcpTolerance(b.residual(), options.tolerance)) {
          findings.Fail(where, "the session's solved answer has residuals " + Num(b.residual_rel) + " / " +
                                   Num(b.residual_scaled) + " above the tolerance");
        }
        const double gap = (a.z - b.z).lpNorm<Eigen::Infinity>();
        if (!(gap <= 1e-9 * (1.0 + a.z.lpNorm<Eigen::Infinity>()))) {
          findings.Fail(where, "the session's z differs from Solve's by " + Num(gap));
        }
        if (SessionPathOf(b) == SessionPath::kReusedActiveSet) {
          if (b.iterations != 0) findings.Fail(where, "a reused active set reports iterations");
          ++reused;
        }
      }
    }
  }
  if (!(reused > calls / 2)) {
    findings.Fail("(all)", "the reused active set answered " + std::to_string(reused) + " of " +
                               std::to_string(calls) + " calls (expected more than half)");
  }
}

// A strongly monotone MCP with a planted solution: F(z) = A z + κ∘z³ + b, A = BᵀB/n + skew + I/2 (positive definite
// symmetric part), κ > 0, so z* is its only solution; rows cycle through an LCP row, a box, a free row and an
// upper-bounded one; b is derived from z* and an F(z*) complementary to it.
struct PlantedMcpData {
  DenseMatrix A;
  Vector kappa, b, l, u, z_star;
};

PlantedMcpData MakePlantedMcpData(int n, int seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  PlantedMcpData p;
  DenseMatrix B(n, n), K(n, n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      B(i, j) = normal(rng);
      K(i, j) = normal(rng);
    }
  }
  p.A = B.transpose() * B / n + (K - K.transpose()) * 0.5;
  p.A.diagonal().array() += 0.5;
  p.kappa.resize(n);
  p.l.resize(n);
  p.u.resize(n);
  p.z_star.resize(n);
  Vector F_star(n);
  for (int i = 0; i < n; ++i) {
    p.kappa[i] = 0.2 + unit(rng);
    const int kind = (i + seed) % 4;
    p.l[i] = kind == 0 ? 0.0 : (kind == 1 ? -1.0 - unit(rng) : -kInf);
    p.u[i] = kind == 1 ? 1.0 + unit(rng) : (kind == 3 ? 2.0 * unit(rng) : kInf);
    const double pick = unit(rng);
    if (std::isfinite(p.l[i]) && pick < 0.4) {
      p.z_star[i] = p.l[i];
      F_star[i] = 0.1 + unit(rng);
    } else if (std::isfinite(p.u[i]) && pick > 0.6) {
      p.z_star[i] = p.u[i];
      F_star[i] = -0.1 - unit(rng);
    } else {
      const double lo = std::isfinite(p.l[i]) ? p.l[i] : -2.0, hi = std::isfinite(p.u[i]) ? p.u[i] : 2.0;
      p.z_star[i] = lo + (hi - lo) * (0.1 + 0.8 * unit(rng));
      F_star[i] = 0.0;
    }
  }
  p.b = F_star - p.A * p.z_star - (p.kappa.array() * p.z_star.array().cube()).matrix();
  return p;
}

// The planted MCP; its Jacobian can be made malformed (of the wrong size, or throwing).
class PlantedMcp final : public MCP {
 public:
  enum class Jacobian { kRight, kWrongSize, kThrows };

  PlantedMcp(int n, int seed, Jacobian jacobian = Jacobian::kRight)
      : PlantedMcp(MakePlantedMcpData(n, seed), "planted-mcp-n" + std::to_string(n) + "-seed" + std::to_string(seed),
                   jacobian) {}
  const Vector& z_star() const { return data_.z_star; }

  void Evaluate(const Vector& z, Vector* F) const override {
    F->noalias() = data_.A * z;
    F->array() += data_.kappa.array() * z.array().cube() + data_.b.array();
  }
  void JacobianDense(const Vector& z, DenseMatrix* J) const override {
    if (jacobian_ == Jacobian::kThrows) throw std::runtime_error("this Jacobian always throws");
    *J = data_.A;
    J->diagonal().array() += 3.0 * data_.kappa.array() * z.array().square();
    if (jacobian_ == Jacobian::kWrongSize) J->conservativeResize(J->rows() + 1, J->cols());
  }

 private:
  PlantedMcp(PlantedMcpData data, std::string name, Jacobian jacobian)
      : MCP(data.l, data.u, std::move(name)), data_(std::move(data)), jacobian_(jacobian) {}
  PlantedMcpData data_;
  Jacobian jacobian_;
};

// μ = ‖(D_F⁻¹ J_FF)⁻¹‖∞ at z* (verdict.h), in double: these Jacobians are well conditioned.
ReferenceSolution PlantedReference(const PlantedMcp& mcp) {
  const Vector& z = mcp.z_star();
  const int n = mcp.size();
  DenseMatrix J(n, n);
  mcp.JacobianDense(z, &J);
  std::vector<int> free_rows;
  for (int i = 0; i < n; ++i) {
    if (z[i] > mcp.l()[i] && z[i] < mcp.u()[i]) free_rows.push_back(i);
  }
  ReferenceSolution reference;
  reference.certificate = Certificate::kUnique;
  reference.z = z;
  const int nf = static_cast<int>(free_rows.size());
  if (nf > 0) {
    DenseMatrix block(nf, nf);
    for (int a = 0; a < nf; ++a) {
      const double d = J.row(free_rows[a]).cwiseAbs().maxCoeff();
      for (int b = 0; b < nf; ++b) block(a, b) = J(free_rows[a], free_rows[b]) / d;
    }
    reference.condition = DenseMatrix(block.inverse()).cwiseAbs().rowwise().sum().maxCoeff();
  }
  return reference;
}

constexpr int kMcpSizes[] = {1, 2, 3, 5, 8, 10};

void CheckMcpKnownSolutions(const SolverFactory& create, const ConformanceOptions& options,
                            ConformanceReport* report) {
  const std::unique_ptr<Solver> solver = Make(create);
  if (!solver->info().mcp) return;
  Findings findings("mcp-known-solution", report);
  int solved = 0;
  for (int n : kMcpSizes) {
    if (n > options.max_size) continue;
    for (int seed : {1, 2}) {
      const PlantedMcp mcp(n, seed);
      SolverOptions solve_options;
      solve_options.tolerance = options.tolerance;
      solve_options.time_limit_seconds = options.time_limit_seconds;
      const SolveResult r = solver->Solve(mcp, solve_options);
      ++report->mcp_solves;
      Vector F(n);
      mcp.Evaluate(r.z, &F);
      if (r.z.size() != n || r.w != F) findings.Fail(mcp.name(), "w is not F(z) on return");
      if (!r.solved()) {
        if (options.mcp_must_solve) {
          findings.Fail(mcp.name(), "not solved: " + std::string(ToString(r.status)) + " " + r.message +
                                        " (scale-free residual " + Num(r.residual_scaled) + ")");
        }
        continue;
      }
      ++solved;
      ++report->mcp_solved_checked;
      const Judgement j = JudgeMCP(mcp, ExpectedOutcome::kSolvable, {PlantedReference(mcp)}, false, r.status, r.z,
                                   options.tolerance);
      if (j.verdict != Verdict::kSolved) {
        findings.Fail(mcp.name(), "claimed solved, JudgeMCP says " + std::string(ToString(j.verdict)) +
                                      " (scale-free residual " + Num(j.residual.scaled) + ", forward error " +
                                      Num(j.forward_error) + ", allowance " + Num(j.forward_allowance) + ")");
      }
    }
  }
  if (solved == 0) findings.Fail("(all)", "solved no MCP");
}

void CheckMcpMalformedJacobian(const SolverFactory& create, const ConformanceOptions& options,
                               ConformanceReport* report) {
  const std::unique_ptr<Solver> solver = Make(create);
  if (!solver->info().mcp) return;
  Findings findings("mcp-malformed-jacobian", report);
  for (PlantedMcp::Jacobian kind : {PlantedMcp::Jacobian::kWrongSize, PlantedMcp::Jacobian::kThrows}) {
    const PlantedMcp mcp(3, 5, kind);
    const std::string what = mcp.name() + (kind == PlantedMcp::Jacobian::kThrows ? " (throwing Jacobian)"
                                                                                 : " (Jacobian of the wrong size)");
    SolverOptions solve_options;
    solve_options.tolerance = options.tolerance;
    solve_options.time_limit_seconds = options.time_limit_seconds;
    SolveResult r;
    try {
      solver->Solve(mcp, solve_options, &r);
    } catch (const std::exception& e) {
      findings.Fail(what, std::string("Solve threw: ") + e.what());
      continue;
    }
    ++report->mcp_solves;
    if (r.solved()) findings.Fail(what, "reported solved although its Jacobian cannot be evaluated");
    if (r.message.empty()) findings.Fail(what, "status " + std::string(ToString(r.status)) + " without a message");
  }
}

void CheckMcpNotApplicable(const SolverFactory& create, const ConformanceOptions& options,
                           ConformanceReport* report) {
  const std::unique_ptr<Solver> solver = Make(create);
  if (solver->info().mcp) return;
  Findings findings("mcp-not-applicable", report);
  for (int n : {1, 3}) {
    const PlantedMcp mcp(n, 1);
    SolverOptions solve_options;
    solve_options.tolerance = options.tolerance;
    const SolveResult r = solver->Solve(mcp, solve_options);
    ++report->mcp_solves;
    if (r.status != SolveStatus::kNotApplicable) {
      findings.Fail(mcp.name(), "a backend without info().mcp answered " + std::string(ToString(r.status)) +
                                    " instead of not_applicable");
    }
  }
}

// ---- cold-repeat (conformance.h, CheckColdRepeat) ----

// A first solve that refuses the problem leaves nothing to compare a repeat with.
bool Refused(SolveStatus status) {
  return status == SolveStatus::kNotApplicable || status == SolveStatus::kSizeLimit ||
         status == SolveStatus::kInvalidOptions;
}

double MedianOf(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n == 0 ? 0.0 : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double SecondsOfSolve(Solver* solver, const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) {
  const auto start = std::chrono::steady_clock::now();
  solver->Solve(problem, options, result);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A first solve, then `repeats` solves each after ForgetWarmState on the same instance; a failure for each repeat
// that did less work than the first or answered differently. The repeats' times go to *times. False when the
// first solve refused the problem.
bool CompareColdRepeats(Solver* solver, const BoxMLCP& problem, const SolverOptions& options, int repeats,
                        const std::string& label, Findings* findings, ColdRepeatReport* report,
                        std::vector<double>* times) {
  SolveResult first, repeat;
  solver->Solve(problem, options, &first);
  ++report->solves;
  if (Refused(first.status)) return false;
  for (int k = 1; k <= repeats; ++k) {
    solver->ForgetWarmState();
    times->push_back(SecondsOfSolve(solver, problem, options, &repeat));
    ++report->solves;
    const std::string where = label + ", cold repeat " + std::to_string(k);
    if (repeat.status != first.status) {
      findings->Fail(where, std::string(ToString(repeat.status)) + " where the first solve was " +
                                std::string(ToString(first.status)));
    } else if (repeat.iterations < first.iterations) {
      findings->Fail(where, std::to_string(repeat.iterations) + " iterations where the first solve took " +
                                std::to_string(first.iterations) +
                                ": answered from what an earlier solve left behind (ForgetWarmState)");
    } else if (first.solved() && repeat.z.size() == first.z.size() &&
               !((repeat.z - first.z).lpNorm<Eigen::Infinity>() <= 1e-8 * (1.0 + first.z.lpNorm<Eigen::Infinity>()))) {
      findings->Fail(where, "z differs from the first solve's by " +
                                Num((repeat.z - first.z).lpNorm<Eigen::Infinity>()));
    }
  }
  return true;
}

// The external library in this process (its option isolate=never), so that a first solve is timed as a solve, not
// as its isolation worker's start-up; a backend without the option keeps its defaults.
std::unique_ptr<Solver> InProcess(const SolverFactory& create) {
  std::unique_ptr<Solver> solver = Make(create);
  std::string ignored;
  if (solver->info().external) solver->SetOption("isolate", "never", &ignored);
  return solver;
}

// other: a problem of the same shape (another seed), which each fresh instance solves before its timed first solve
// of problem: what is paid once per instance (workspace sizes, a /dev/null opened for an external library's
// output) is then paid, as it is on the instance that repeats, and a cache of problem is not.
void CheckColdRepeatOn(const SolverFactory& create, const ColdRepeatOptions& options, const BoxMLCP& problem,
                       const BoxMLCP& other, Findings* findings, ColdRepeatReport* report) {
  SolverOptions o;
  o.tolerance = options.tolerance;
  o.time_limit_seconds = options.time_limit_seconds;
  o.measure_time = false;
  std::vector<double> ignored_times, repeat_times;
  const std::unique_ptr<Solver> by_default = Make(create);
  if (!CompareColdRepeats(by_default.get(), problem, o, options.repeats, problem.name(), findings, report,
                          &ignored_times)) {
    return;
  }
  ++report->problems_checked;
  const std::unique_ptr<Solver> in_process = InProcess(create);
  CompareColdRepeats(in_process.get(), problem, o, options.repeats, problem.name() + " (in process)", findings,
                     report, &repeat_times);
  if (kSanitizedBuild) return;
  std::vector<double> fresh_times;
  for (int i = 0; i < options.fresh_instances; ++i) {
    const std::unique_ptr<Solver> fresh = InProcess(create);
    SolveResult result;
    fresh->Solve(other, o, &result);
    fresh_times.push_back(SecondsOfSolve(fresh.get(), problem, o, &result));
    report->solves += 2;
  }
  // A loaded machine only adds time (preemption): the least disturbed first solve is the fastest one, while the
  // repeats' median only passes more easily for it.
  const double fresh = *std::min_element(fresh_times.begin(), fresh_times.end());
  if (fresh < options.min_timed_seconds || repeat_times.empty()) return;
  ++report->problems_timed;
  const double repeated = MedianOf(repeat_times);
  if (repeated < fresh / options.time_factor) {
    findings->Fail(problem.name(), "a cold repeat took " + Num(repeated) + " s (median) where another instance's "
                                   "first solve took " + Num(fresh) + " s (least): more than " +
                                   Num(options.time_factor) +
                                   " times faster, as if answered from what an earlier solve left behind");
  }
}

}  // namespace

ColdRepeatReport CheckColdRepeat(const SolverFactory& create, const ColdRepeatOptions& options) {
  if (!create) throw InvalidInputError("CheckColdRepeat: the factory is empty");
  Make(create);  // a null backend is a usage error, not a failed check
  ColdRepeatReport report;
  report.time_test_on = !kSanitizedBuild;
  ConformanceReport failures;  // Findings' sink, moved into the report at the end
  Findings findings("cold-repeat", &failures);
  struct Shape {
    MatrixFamily family;
    BoundKind bounds;
    int size;
  };
  // A 6-row relay is 12 variables in LCP form (within an enumeration's reach); the mixed rows include free ones
  // (what siconos-mlcp-lemke needs).
  const Shape shapes[] = {{MatrixFamily::kNonsymmetricPMatrix, BoundKind::kRelay, 20},
                          {MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kLCP, 20},
                          {MatrixFamily::kNonsymmetricPMatrix, BoundKind::kRelay, 6},
                          {MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kLCP, 8},
                          {MatrixFamily::kNonsymmetricPMatrix, BoundKind::kMixed, 10}};
  for (const Shape& shape : shapes) {
    GeneratorOptions g;
    g.size = shape.size;
    g.family = shape.family;
    g.bounds = shape.bounds;
    g.seed = 7;
    const GeneratedProblem generated = GenerateProblem(g);
    g.seed = 8;
    const GeneratedProblem other = GenerateProblem(g);
    try {
      CheckColdRepeatOn(create, options, generated.problem, other.problem, &findings, &report);
    } catch (const std::exception& e) {
      findings.Fail(generated.problem.name(), std::string("threw: ") + e.what());
    }
  }
  report.failures = std::move(failures.failures);
  return report;
}

ColdRepeatReport CheckColdRepeat(std::string_view registered_name, const ColdRepeatOptions& options) {
  CreateSolver(registered_name);  // unknown name: InvalidInputError listing the known ones
  const std::string name(registered_name);
  return CheckColdRepeat(SolverFactory([name] { return CreateSolver(name); }), options);
}

std::string ToString(const ColdRepeatReport& report) {
  if (report.passed()) {
    return "passed (" + std::to_string(report.solves) + " solves, " + std::to_string(report.problems_checked) +
           " problems compared, " + std::to_string(report.problems_timed) + " timed)";
  }
  std::string text;
  for (const ConformanceFailure& f : report.failures) text += f.check + ": " + f.problem + ": " + f.message + "\n";
  return text;
}

ConformanceReport CheckConformance(const SolverFactory& create, const ConformanceOptions& options) {
  if (!create) throw InvalidInputError("CheckConformance: the factory is empty");
  Make(create);  // a null backend is a usage error, not a failed check
  ConformanceReport report;
  using Check = void (*)(const SolverFactory&, const ConformanceOptions&, ConformanceReport*);
  const std::pair<const char*, Check> checks[] = {
      {"known-solution", &CheckKnownSolutions},
      {"session-bits", &CheckSessionBits},
      {"session-reuse", &CheckSessionReuse},
      {"mcp-known-solution", &CheckMcpKnownSolutions},
      {"mcp-malformed-jacobian", &CheckMcpMalformedJacobian},
      {"mcp-not-applicable", &CheckMcpNotApplicable},
  };
  for (const auto& [name, check] : checks) {
    try {
      check(create, options, &report);
    } catch (const std::exception& e) {
      report.failures.push_back({name, "(during the check)", std::string("threw: ") + e.what()});
    }
  }
  return report;
}

ConformanceReport CheckConformance(std::string_view registered_name, const ConformanceOptions& options) {
  CreateSolver(registered_name);  // unknown name: InvalidInputError listing the known ones
  const std::string name(registered_name);
  return CheckConformance(SolverFactory([name] { return CreateSolver(name); }), options);
}

std::string ToString(const ConformanceReport& report) {
  if (report.passed()) {
    std::string text = "passed (" + std::to_string(report.solves) + " solves, " +
                       std::to_string(report.solved_checked) + " solved answers checked against the planted solution";
    if (report.mcp_solved_checked > 0) {
      text += "; " + std::to_string(report.mcp_solves) + " MCP solves, " +
              std::to_string(report.mcp_solved_checked) + " solved MCP answers judged";
    }
    return text + ")";
  }
  std::string text;
  for (const ConformanceFailure& f : report.failures) text += f.check + ": " + f.problem + ": " + f.message + "\n";
  return text;
}

}  // namespace smcbench

// The Siconos MCP adapters (see siconos_mcp_solver.h): the rewriting's callbacks and the in-process call.
#include "solvers/siconos/siconos_mcp_solver.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <limits>
#include <sstream>
#include <string>

// Siconos Numerics C API (include directories: /usr/include/siconos and /usr/include/siconos/numerics).
#include "MCP_Solvers.h"
#include "MCP_cst.h"
#include "MixedComplementarityProblem.h"
#include "NumericsMatrix.h"
#include "NumericsVerbose.h"
#include "SolverOptions.h"
#include "solvers/isolation/child_process.h"
#include "solvers/siconos/mcp_standard_form.h"
#include "solvers/isolation/swapped_stdio.h"

namespace smcbench {
namespace {

// What Siconos' callbacks reach through `env`: the rewritten problem and the scratch to call it with.
struct CallbackEnv {
  const McpStandardForm* form = nullptr;
  Vector x, F;
  DenseMatrix J;
  std::exception_ptr error;  // the first exception from F or J, rethrown once Siconos returned
};

void EvaluateCallback(void* env, int n, double* x, double* F) {
  auto* e = static_cast<CallbackEnv*>(env);
  try {
    e->x = Eigen::Map<const Vector>(x, n);
    e->form->Evaluate(e->x, &e->F);
    std::copy(e->F.data(), e->F.data() + n, F);
  } catch (...) {  // never through Siconos' C frames: NaN there (its line search rejects it), rethrown after
    if (!e->error) e->error = std::current_exception();
    std::fill(F, F + n, std::numeric_limits<double>::quiet_NaN());
  }
}

void JacobianCallback(void* env, int n, double* x, NumericsMatrix* J) {
  auto* e = static_cast<CallbackEnv*>(env);
  try {
    e->x = Eigen::Map<const Vector>(x, n);
    e->form->JacobianDense(e->x, &e->J);
    std::memcpy(J->matrix0, e->J.data(), sizeof(double) * static_cast<std::size_t>(n) * n);  // both column-major
  } catch (...) {
    if (!e->error) e->error = std::current_exception();
    std::fill(J->matrix0, J->matrix0 + static_cast<std::size_t>(n) * n, std::numeric_limits<double>::quiet_NaN());
  }
}

const SolverInfo& InfoOf(SiconosMcpMethod method) {
  static const SolverInfo kFb{
      "siconos-mcp-newton-fb",
      "Siconos mcp_newton_FB_FBLSA: nonsmooth Newton on the Fischer-Burmeister reformulation with a line search on "
      "its merit function (Facchinei & Pang's FBLSA), on the exact rewriting of the box MCP into Siconos' form; "
      "runs in process",
      "Siconos Numerics 4.4 mcp_newton_FB_FBLSA; Facchinei & Pang 2003, Finite-Dimensional Variational "
      "Inequalities and Complementarity Problems, sec. 9.1",
      /*dense=*/true, /*sparse=*/false, /*symmetric_only=*/false, /*exact=*/false, /*mcp=*/true,
      /*default_size_limit=*/0, /*equilibrate=*/false, /*delegates=*/false, /*external=*/true,
      /*allocation_free=*/false, /*solves_every_p_matrix=*/false, /*practical_size_limit=*/0, /*box=*/false};
  static const SolverInfo kMin{
      "siconos-mcp-newton-min",
      "Siconos mcp_newton_min_FBLSA: Newton directions from the min reformulation, line search on the "
      "Fischer-Burmeister merit function, on the exact rewriting of the box MCP into Siconos' form; runs in process",
      "Siconos Numerics 4.4 mcp_newton_min_FBLSA; Facchinei & Pang 2003, sec. 9.1",
      /*dense=*/true, /*sparse=*/false, /*symmetric_only=*/false, /*exact=*/false, /*mcp=*/true,
      /*default_size_limit=*/0, /*equilibrate=*/false, /*delegates=*/false, /*external=*/true,
      /*allocation_free=*/false, /*solves_every_p_matrix=*/false, /*practical_size_limit=*/0, /*box=*/false};
  return method == SiconosMcpMethod::kNewtonFb ? kFb : kMin;
}

// The verdict's measure at z (J evaluated there); +∞ when F or J fails.
double ScaledResidual(const MCP& p, const Vector& z, Vector* F) {
  const int n = p.size();
  if (F->size() != n) F->resize(n);
  p.Evaluate(z, F);
  Vector d;
  if (p.jacobian_kind() == MCP::JacobianKind::kSparse) {
    SparseMatrix J;
    p.JacobianSparse(z, &J);
    if (J.rows() != n || J.cols() != n) return kInf;
    McpRowScales(J, p.variable_scale(), &d);
  } else {
    DenseMatrix J(n, n);
    p.JacobianDense(z, &J);
    if (J.rows() != n || J.cols() != n) return kInf;
    McpRowScales(J, p.variable_scale(), &d);
  }
  return McpScaledResidual(z, *F, p.l(), p.u(), d, p.variable_scale());
}

}  // namespace

bool SiconosMcpOptions::IsValid(std::string* why) const {
  if (max_size < 1) {
    *why = "max_size must be >= 1, got " + std::to_string(max_size);
    return false;
  }
  return true;
}

SiconosMcpSolver::SiconosMcpSolver(SiconosMcpMethod method) : method_(method) {}
SiconosMcpSolver::~SiconosMcpSolver() {
  if (stdio_sink_ != nullptr) std::fclose(stdio_sink_);
}

const SolverInfo& SiconosMcpSolver::info() const { return InfoOf(method_); }

void SiconosMcpSolver::BindOptions(OptionBinder* binder) {
  binder->Add("max_size", &options_.max_size, "largest rewritten MCP (a box row counts 2) sent to Siconos");
}

bool SiconosMcpSolver::ValidateBackendOptions(std::string* why) const { return options_.IsValid(why); }

void SiconosMcpSolver::DoSolve(const BoxMLCP&, const SolverOptions&, SolveResult* result) {
  result->status = SolveStatus::kNotApplicable;
  result->message = "solves nonlinear MCPs only (box-MLCPs: siconos-mlcp-fb, siconos-lcp-newton-fb, ...)";
}

void SiconosMcpSolver::DoSolveMCP(const MCP& problem, const SolverOptions& options, SolveResult* result) {
  const int n = problem.size();
  kAnswerProcessDetail.Set(result, AnswerProcess::kThisProcess);
  // F and J at the start: a failure there is a status before Siconos runs.
  Vector F(n);
  problem.Evaluate(result->z, &F);
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(F[i])) {
      std::ostringstream msg;
      msg << "F is NaN or Inf at the starting point: F[" << i << "] = " << F[i];
      result->status = SolveStatus::kNumericalFailure;
      result->message = msg.str();
      return;
    }
  }
  const McpStandardForm form(problem);
  const int N = form.size();
  if (N > options_.max_size) {
    result->status = SolveStatus::kSizeLimit;
    result->message = "the rewritten MCP has " + std::to_string(N) + " unknowns > max_size " +
                      std::to_string(options_.max_size) + " (Siconos' MCP methods are dense)";
    return;
  }
  CallbackEnv env;
  env.form = &form;
  env.F.resize(N);
  Vector x;
  form.FromOriginal(result->z, &x);
  form.JacobianDense(x, &env.J);
  if (!form.jacobian_error().empty()) {
    result->status = SolveStatus::kNumericalFailure;
    result->message = form.jacobian_error();
    return;
  }
  if (N == 0) {  // every row fixed: z = l is the only point, the base judges it
    form.ToOriginal(x, &result->z);
    result->status = SolveStatus::kSolved;
    return;
  }
  x_.assign(x.data(), x.data() + N);
  F_.assign(N, 0.0);

  MixedComplementarityProblem mcp{};
  mcp.n1 = form.num_equations();
  mcp.n2 = form.num_complementarity();
  mcp.compute_Fmcp = &EvaluateCallback;
  mcp.compute_nabla_Fmcp = &JacobianCallback;
  mcp.nabla_Fmcp = NM_create(NM_DENSE, N, N);
  mcp.env = &env;
  const int id = method_ == SiconosMcpMethod::kNewtonFb ? SICONOS_MCP_NEWTON_FB_FBLSA : SICONOS_MCP_NEWTON_MIN_FBLSA;
  ::SolverOptions* so = solver_options_create(id);  // Siconos' option struct, not ours
  const int budget = options.max_iterations > 0 ? options.max_iterations : so->iparam[SICONOS_IPARAM_MAX_ITER];
  so->iparam[SICONOS_IPARAM_MAX_ITER] = budget;
  so->iparam[SICONOS_IPARAM_ITER_DONE] = 0;
  const double floor = 10.0 * N * std::numeric_limits<double>::epsilon();
  so->dparam[SICONOS_DPARAM_TOL] = std::max(options.tolerance / std::sqrt(static_cast<double>(N)), floor);
  so->dparam[SICONOS_DPARAM_RESIDU] = NAN;
  numerics_set_verbose(options.verbosity >= 2 ? 1 : 0);
  int info = -1;
  // Some of Siconos' messages are unconditional printf (a failed LU): silenced unless the caller asked for them.
  if (options.verbosity < 2 && stdio_sink_ == nullptr) stdio_sink_ = std::fopen("/dev/null", "we");
  if (!TimeLimitReached()) {
    const SwappedStdio swapped(options.verbosity < 2 ? stdio_sink_ : nullptr);
    if (method_ == SiconosMcpMethod::kNewtonFb) {
      mcp_newton_FB_FBLSA(&mcp, x_.data(), F_.data(), &info, so);
    } else {
      mcp_newton_min_FBLSA(&mcp, x_.data(), F_.data(), &info, so);
    }
  }
  const int iterations = so->iparam[SICONOS_IPARAM_ITER_DONE];
  const double error = so->dparam[SICONOS_DPARAM_RESIDU];
  solver_options_delete(so);
  NM_free(mcp.nabla_Fmcp);
  numerics_set_verbose(0);
  if (env.error) std::rethrow_exception(env.error);

  result->iterations = iterations;
  result->SetDetail("siconos_info", info);
  result->backend_code = info;
  result->SetDetail("siconos_error", error);
  result->SetDetail("standard_size", N);
  if (info == -1) {
    result->status = SolveStatus::kTimeLimit;
    result->message = "time limit reached before the Siconos call";
    return;
  }
  x = Eigen::Map<const Vector>(x_.data(), N);
  form.ToOriginal(x, &result->z);
  std::ostringstream msg;
  msg.precision(3);
  if (!result->z.allFinite()) {
    result->status = SolveStatus::kNumericalFailure;
    msg << "Siconos returned a non-finite z (info " << info << ")";
  } else if (!form.jacobian_error().empty()) {
    result->status = SolveStatus::kNumericalFailure;
    msg << form.jacobian_error();
  } else {
    Vector Fz;
    double r = ScaledResidual(problem, result->z, &Fz);
    // Siconos' iterates need not lie in the box (its FB iterates approach it from outside): the answer is returned
    // projected onto [l, u] when the projection does not break the tolerance or is no worse (docs/problem.md,
    // "Starts outside the box").
    const Vector projected = result->z.cwiseMax(problem.l()).cwiseMin(problem.u());
    if (projected != result->z) {
      Vector Fp;
      const double rp = ScaledResidual(problem, projected, &Fp);
      if (rp <= std::max(r, options.tolerance)) {
        result->z = projected;
        r = rp;
      }
    }
    if (r <= options.tolerance) {
      result->status = SolveStatus::kSolved;
      return;
    }
    if (TimeLimitReached()) {
      result->status = SolveStatus::kTimeLimit;
      msg << "time limit passed during the Siconos call (in process, it cannot be interrupted)";
    } else if (info == 0) {
      result->status = SolveStatus::kInaccurate;
      msg << "Siconos reported success (info 0, its error " << error << ")";
    } else if (info == 1) {
      result->status = iterations >= budget ? SolveStatus::kIterationLimit : SolveStatus::kStalled;
      msg << (iterations >= budget ? "Siconos reached its iteration budget" : "Siconos' line search gave up")
          << " (info 1, its error " << error << ", " << iterations << " iterations)";
    } else {
      result->status = SolveStatus::kNumericalFailure;
      msg << "Siconos failed (info " << info << ", its error " << error << ")";
    }
    msg << "; scale-free residual " << r << " > tolerance " << options.tolerance;
  }
  result->message = msg.str();
}

namespace {

template <SiconosMcpMethod kMethod>
std::unique_ptr<Solver> MakeSiconosMcp() {
  return std::make_unique<SiconosMcpSolver>(kMethod);
}

}  // namespace

void AppendSiconosMcpBackends(std::vector<ExternalBackend>* backends) {
  backends->push_back({InfoOf(SiconosMcpMethod::kNewtonFb).name, &MakeSiconosMcp<SiconosMcpMethod::kNewtonFb>});
  backends->push_back({InfoOf(SiconosMcpMethod::kNewtonMin).name, &MakeSiconosMcp<SiconosMcpMethod::kNewtonMin>});
}

}  // namespace smcbench

// siconos-avi-caoferris (see siconos_avi_solver.h): the vertex, Cao–Ferris' change of variables and the map back
// are ours; stage 3 runs in Siconos through a SiconosSolver of method kAviCaoFerrisStage3.
#include "solvers/siconos/siconos_avi_solver.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <utility>

#include "solvers/avi/polytope.h"

namespace smcbench {

namespace {

// A slack of the vertex below zero by this much (in units of λ, relative) is rounding: stage 3 needs q̄_I ≥ 0.
constexpr double kVertexSlackTolerance = 1e-9;

// The details of stage 3's result that describe Siconos' run (its code, which process answered, the problem size).
bool IsSiconosDetail(const char* name) {
  return std::strncmp(name, "siconos_", 8) == 0 || std::strcmp(name, "in_process") == 0 ||
         std::strcmp(name, "standard_size") == 0;
}

}  // namespace

SiconosAviSolver::SiconosAviSolver() : SiconosAviSolver(SiconosOptions{}) {}

SiconosAviSolver::SiconosAviSolver(const SiconosOptions& options)
    : BackendWithOptions(options), stage3_(SiconosMethod::kAviCaoFerrisStage3, options) {}

const SolverInfo& SiconosAviSolver::info() const {
  static const SolverInfo kInfo{
      "siconos-avi-caoferris",
      "Cao & Ferris' pivotal method for AVIs: our vertex of P and change of variables, then Siconos' "
      "avi_caoferris_stage3 (Lemke with the covering vector on the vertex's rows); a box is the polytope "
      "l <= z <= u; needs a vertex (no free rows)",
      "Cao & Ferris 1996, A pivotal method for affine variational inequalities, Math. Oper. Res. 21(1); Siconos "
      "Numerics 4.4 avi_caoferris_stage3",
      true, false, false, true, false, 0, /*equilibrate=*/false, /*delegates=*/false, /*external=*/true};
  return kInfo;
}

void SiconosAviSolver::BindOptions(OptionBinder* binder) {
  binder->Add("isolate", &options_.isolate,
              {{"first", static_cast<int>(IsolationPolicy::kFirst)},
               {"always", static_cast<int>(IsolationPolicy::kAlways)},
               {"never", static_cast<int>(IsolationPolicy::kNever)}},
              {"never", "always"},  // the old boolean spelling, as every siconos-* adapter
              "where Siconos' stage 3 runs: first (default: a problem's first solve in this backend's worker "
              "process, later solves of the same problem in process), always (in the worker), never (in process)");
  binder->Add("default_time_limit", &options_.default_time_limit,
              "seconds a solve in the worker may take when no time limit is given; then the worker is killed");
  binder->Add("remembered_problems", &options_.remembered_problems,
              "isolate=first: how many probed problems are remembered (the latest); others are probed again");
  binder->Add("remembered_megabytes", &options_.remembered_megabytes,
              "isolate=first: memory for the copies of the remembered problems (8(N^2+4N) bytes each)");
  binder->Add("max_size", &options_.max_size,
              "largest number of rows of P (stage 3's LCP size; a fixed or equality row counts 2) sent to Siconos");
  binder->Add("quiet", &options_.quiet,
              "in process: silence Siconos' console around each call (as the other siconos-* adapters); 0 = bare call");
}

bool SiconosAviSolver::ValidateBackendOptions(std::string* why) const { return options_.IsValid(why); }

void SiconosAviSolver::SolveAtVertex(const DenseMatrix& M, const Vector& q, const DenseMatrix& G, const Vector& b,
                                     const std::vector<int>& vertex_rows, const SolverOptions& options,
                                     Vector* lambda, Vector* multipliers, SolveResult* result) {
  const Eigen::Index n = M.rows(), rows = G.rows(), inactive = rows - n;
  // Stage 3's order of the constraints: the vertex's rows A first (its covered rows), then the others I.
  std::vector<int> order(vertex_rows);
  std::vector<bool> in_vertex(static_cast<std::size_t>(rows), false);
  for (int r : vertex_rows) in_vertex[static_cast<std::size_t>(r)] = true;
  for (Eigen::Index r = 0; r < rows; ++r) {
    if (!in_vertex[static_cast<std::size_t>(r)]) order.push_back(static_cast<int>(r));
  }
  DenseMatrix B(n, n), G_I(inactive, n);
  Vector b_A(n), b_I(inactive);
  for (Eigen::Index k = 0; k < rows; ++k) {
    const int r = order[static_cast<std::size_t>(k)];
    if (k < n) {
      B.row(k) = G.row(r);
      b_A[k] = b[r];
    } else {
      G_I.row(k - n) = G.row(r);
      b_I[k - n] = b[r];
    }
  }
  // A box's vertex rows are ±e_i in order (B diagonal): every product below is then a scaling, O(n²) instead of
  // O(n³), with no sum whose rounding could turn an exact 0 into a pivot.
  bool diagonal = true;
  for (Eigen::Index j = 0; j < n && diagonal; ++j) {
    for (Eigen::Index i = 0; i < n && diagonal; ++i) diagonal = i == j ? B(i, j) != 0.0 : B(i, j) == 0.0;
  }
  DenseMatrix B_inverse, C, T;  // B⁻¹, G_I B⁻¹, B⁻ᵀMB⁻¹
  Vector vertex;                // B⁻¹ b_A
  if (diagonal) {
    const Vector d = B.diagonal().cwiseInverse();
    B_inverse = d.asDiagonal();
    vertex = d.cwiseProduct(b_A);
    C = G_I * d.asDiagonal();
    T = d.asDiagonal() * M * d.asDiagonal();
  } else {
    const Eigen::PartialPivLU<DenseMatrix> lu(B);
    const double rcond = lu.rcond();
    if (!(rcond > static_cast<double>(n) * std::numeric_limits<double>::epsilon())) {
      result->status = SolveStatus::kSingular;
      result->message = "the vertex's " + std::to_string(n) + " rows are numerically dependent (reciprocal " +
                        "condition " + std::to_string(rcond) + "), so Cao-Ferris' change of variables cannot be built";
      return;
    }
    B_inverse = lu.inverse();
    vertex = lu.solve(b_A);
    // Stage 3 pivots on any entry > 0, without a tolerance: an entry that is rounding of an exact 0 (the row
    // −Eλ ≥ −f against its pair's column) would be taken as a pivot and blow the answer up to 1e17. So entries of
    // G_IB⁻¹ and B⁻ᵀMB⁻¹ within their own rounding bound (products of absolute values times 4(n + 1)ε) are set
    // to 0 exactly.
    const double noise = 4.0 * static_cast<double>(n + 1) * std::numeric_limits<double>::epsilon();
    const DenseMatrix B_inverse_abs = B_inverse.cwiseAbs();
    const auto clean = [noise](const DenseMatrix& value, const DenseMatrix& magnitude) {
      return DenseMatrix((value.array().abs() <= noise * magnitude.array()).select(0.0, value.array()));
    };
    C = clean(G_I * B_inverse, G_I.cwiseAbs() * B_inverse_abs);
    T = clean(B_inverse.transpose() * M * B_inverse, B_inverse_abs.transpose() * M.cwiseAbs() * B_inverse_abs);
  }
  // w = (u_A, s_I) = M̄ (u_I, s_A) + q̄ (siconos_avi_solver.h).
  DenseMatrix M_bar = DenseMatrix::Zero(rows, rows);
  M_bar.topLeftCorner(n, inactive) = -C.transpose();
  M_bar.topRightCorner(n, n) = T;
  M_bar.bottomRightCorner(inactive, n) = C;
  Vector q_bar(rows);
  q_bar.head(n) = B_inverse.transpose() * (M * vertex + q);
  const double vertex_norm = vertex.cwiseAbs().maxCoeff();
  for (Eigen::Index k = 0; k < inactive; ++k) {
    const double slack = G_I.row(k).dot(vertex) - b_I[k];
    const double scale = G_I.row(k).cwiseAbs().maxCoeff();
    if (slack < -kVertexSlackTolerance * scale * (1.0 + vertex_norm + std::abs(b_I[k]) / scale)) {
      result->status = SolveStatus::kNumericalFailure;
      result->message = "the vertex is outside P by " + std::to_string(-slack / scale) + " on row " +
                        std::to_string(order[static_cast<std::size_t>(n + k)]) + " (rounding in its rows)";
      return;
    }
    q_bar[n + k] = std::max(slack, 0.0);  // ≥ 0 at a vertex of P: a rounding-sized negative is its 0
  }
  if (!M_bar.allFinite() || !q_bar.allFinite()) {
    result->status = SolveStatus::kNumericalFailure;
    result->message = "Cao-Ferris' change of variables overflowed (the vertex's rows are badly conditioned)";
    return;
  }
  const BoxMLCP lcp = BoxMLCP::LCP(std::move(M_bar), std::move(q_bar), "cao-ferris-stage3");
  SolverOptions inner = options;
  inner.warm_start.resize(0);  // stage 3 starts at the vertex
  inner.polish = false;        // Siconos' own answer: our rule judges λ, not stage 3's LCP
  stage3_.set_options(options_);
  stage3_.set_covering_rows(static_cast<int>(n));
  stage3_.Solve(lcp, inner, &stage3_result_);
  for (int i = 0; i < stage3_result_.num_details; ++i) {
    const SolveResult::Detail& d = stage3_result_.details[static_cast<std::size_t>(i)];
    if (!IsSiconosDetail(d.name)) continue;
    if (d.code_name != nullptr) {
      result->SetCodeDetail(d.name, static_cast<int>(d.value), d.code_name);
    } else {
      result->SetDetail(d.name, d.value);
    }
  }
  result->backend_code = stage3_result_.backend_code;
  result->iterations = stage3_result_.iterations;
  const Vector& z = stage3_result_.z;
  const bool answered = z.size() == rows && z.allFinite();
  if (answered) {
    const Vector w = lcp.dense_matrix() * z + lcp.q();
    *lambda = vertex + B_inverse * z.tail(n);  // B⁻¹(s_A + b_A)
    multipliers->setZero(rows);
    for (Eigen::Index k = 0; k < n; ++k) (*multipliers)[order[static_cast<std::size_t>(k)]] = w[k];
    for (Eigen::Index k = 0; k < inactive; ++k) (*multipliers)[order[static_cast<std::size_t>(n + k)]] = z[k];
  }
  // Siconos' info 0 is a claim, judged by the caller's rule on λ (the stage-3 LCP's own residual does not decide).
  if (stage3_result_.backend_code == 0 && answered) {
    result->status = SolveStatus::kSolved;
  } else {
    result->status = stage3_result_.status == SolveStatus::kSolved ? SolveStatus::kNumericalFailure
                                                                   : stage3_result_.status;
    result->message = stage3_result_.status == SolveStatus::kSolved
                          ? "Siconos' stage 3 returned a non-finite answer"
                          : stage3_result_.message;
  }
}

void SiconosAviSolver::DoSolve(const BoxMLCP& problem, const SolverOptions& options, SolveResult* result) {
  const int n = problem.size();
  const Vector& l = problem.l();
  const Vector& u = problem.u();
  int fixed = 0, rows = 0;
  for (int i = 0; i < n; ++i) {
    const bool lower = std::isfinite(l[i]), upper = std::isfinite(u[i]);
    if (!lower && !upper) {
      result->status = SolveStatus::kNotApplicable;
      result->message = "row " + std::to_string(i) + " has no finite bound: the box has no vertex, which Cao-Ferris' "
                        "method starts from";
      return;
    }
    fixed += l[i] == u[i] ? 1 : 0;
    rows += (lower ? 1 : 0) + (upper ? 1 : 0);
  }
  if (fixed == n) {  // every row fixed: z = l is the solution, nothing to ask Siconos
    result->z = l;
    result->iterations = 0;
    result->status = SolveStatus::kSolved;
    return;
  }
  // P = {z : z_i ≥ l_i, −z_i ≥ −u_i on the finite bounds}; the vertex puts each z_i at its lower bound if finite.
  DenseMatrix G = DenseMatrix::Zero(rows, n);
  Vector b(rows);
  std::vector<int> vertex_rows;
  vertex_rows.reserve(static_cast<std::size_t>(n));
  int r = 0;
  for (int i = 0; i < n; ++i) {
    vertex_rows.push_back(r);
    if (std::isfinite(l[i])) {
      G(r, i) = 1.0;
      b[r++] = l[i];
    }
    if (std::isfinite(u[i])) {
      G(r, i) = -1.0;
      b[r++] = -u[i];
    }
  }
  Vector lambda, multipliers;
  SolveAtVertex(problem.dense_matrix(), problem.q(), G, b, vertex_rows, options, &lambda, &multipliers, result);
  if (lambda.size() == n) result->z = lambda;
}

void SiconosAviSolver::SolveAviDirect(const AffineVI& avi, const SolverOptions& options, AviSolution* solution,
                                      SolveResult* result) {
  const int m = avi.inequality_count(), p = avi.equality_count(), n = avi.size();
  solution->lambda.resize(0);
  solution->mu.resize(0);
  solution->nu.resize(0);
  const PolytopeVertex vertex = FindPolytopeVertex(avi.H(), avi.K(), avi.E(), avi.f(), &avi.feasible_point());
  if (!vertex.found) {
    result->status = vertex.contains_line ? SolveStatus::kNotApplicable : SolveStatus::kNumericalFailure;
    result->message = "Cao-Ferris' method starts at a vertex of P: " + vertex.why;
    return;
  }
  // P = {λ : Hλ ≥ K, Eλ ≥ f, −Eλ ≥ −f}; the vertex's rows of E are the first of each pair.
  DenseMatrix G(m + 2 * p, n);
  Vector b(m + 2 * p);
  G.topRows(m) = avi.H();
  b.head(m) = avi.K();
  if (p > 0) {
    G.middleRows(m, p) = avi.E();
    G.bottomRows(p) = -avi.E();
    b.segment(m, p) = avi.f();
    b.tail(p) = -avi.f();
  }
  Vector lambda, multipliers;
  SolveAtVertex(avi.M(), avi.q(), G, b, vertex.rows, options, &lambda, &multipliers, result);
  if (lambda.size() != n) return;
  solution->lambda = std::move(lambda);
  solution->mu = multipliers.head(m);
  solution->nu = multipliers.segment(m, p) - multipliers.tail(p);
}

}  // namespace smcbench

#include "bench/replay/floor.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>

#include "bench/replay/sample_times.h"
#include "solvers/avi/avi_reduction.h"

namespace smcbench {
namespace {

std::string JoinTags(const std::vector<std::string>& tags) {
  std::string out;
  for (const auto& t : tags) out += (out.empty() ? "" : ",") + t;
  return out;
}

bool HasTag(std::string_view tags, std::string_view tag) {
  std::size_t begin = 0;
  while (begin <= tags.size()) {
    const std::size_t end = std::min(tags.find(',', begin), tags.size());
    if (tags.substr(begin, end - begin) == tag) return true;
    begin = end + 1;
  }
  return false;
}

ReplayRecord FloorRecord(const std::string& suite, const std::string& problem, int size, bool sparse,
                         const std::string& tags, ExpectedOutcome expected, const ReplayOptions& options) {
  ReplayRecord r;
  r.suite = suite;
  r.problem = problem;
  r.solver = kFloorSolver;
  r.mode = kFloorSolver;
  r.size = size;
  r.sparse = sparse;
  r.tags = tags;
  r.expected = expected;
  r.tolerance = options.tolerance;
  return r;
}

// The message of a floor record: "dense Cholesky of a 64×64 matrix", with the fallback when there was one.
std::string FloorMessage(FloorMethod asked, FloorMethod timed, Eigen::Index rows) {
  std::string text = std::string(ToString(timed)) + " of a " + std::to_string(rows) + "×" + std::to_string(rows) +
                     " matrix";
  if (asked != timed) text += " (" + std::string(ToString(asked)) + " failed: not positive definite)";
  return text;
}

// Whether the last factorization completed: Eigen's info() for the Cholesky and sparse ones; a dense LU always
// runs to the end, so there every pivot of U must be finite and nonzero (else M is singular).
template <typename Factor>
bool Completed(const Factor& factor) {
  return factor.info() == Eigen::Success;
}
template <>
bool Completed(const Eigen::PartialPivLU<DenseMatrix>& lu) {
  const auto pivots = lu.matrixLU().diagonal().array();
  return pivots.allFinite() && (pivots != 0.0).all();
}

// Times factor.compute(M) with the cold protocol; returns whether the last one completed.
template <typename Factor, typename Matrix>
bool TimeCompute(Factor* factor, const Matrix& M, const ReplayOptions& replay, ReplayRecord* record) {
  SolveResult result;  // SampleSolveTimes reads the status (a time-limit stop is not repeated) and the process
  result.status = SolveStatus::kSolved;
  replay_internal::SampleSolveTimes([&] { factor->compute(M); }, &result, replay, record);
  return Completed(*factor);
}

}  // namespace

std::string_view ToString(FloorMethod method) {
  switch (method) {
    case FloorMethod::kDenseCholesky: return "dense Cholesky";
    case FloorMethod::kDenseLu: return "dense LU (partial pivoting)";
    case FloorMethod::kSparseCholesky: return "sparse Cholesky";
    case FloorMethod::kSparseLu: return "sparse LU (COLAMD)";
  }
  return "?";
}

bool TagsSaySpd(std::string_view tags) {
  return HasTag(tags, "spd") || (HasTag(tags, "symmetric") && HasTag(tags, "positive_definite"));
}

FloorMethod ChooseFloorMethod(bool sparse, bool spd) {
  if (sparse) return spd ? FloorMethod::kSparseCholesky : FloorMethod::kSparseLu;
  return spd ? FloorMethod::kDenseCholesky : FloorMethod::kDenseLu;
}

FloorMethod TimeFactorization(const DenseMatrix& M, FloorMethod method, const ReplayOptions& replay,
                              ReplayRecord* record) {
  FloorMethod timed = FloorMethod::kDenseLu;
  bool completed = true;
  if (method == FloorMethod::kDenseCholesky || method == FloorMethod::kSparseCholesky) {
    Eigen::LLT<DenseMatrix> llt(M.rows());
    if (TimeCompute(&llt, M, replay, record)) {
      timed = FloorMethod::kDenseCholesky;
    } else {
      Eigen::PartialPivLU<DenseMatrix> lu(M.rows());
      completed = TimeCompute(&lu, M, replay, record);
    }
  } else {
    Eigen::PartialPivLU<DenseMatrix> lu(M.rows());
    completed = TimeCompute(&lu, M, replay, record);
  }
  record->status = completed ? SolveStatus::kSolved : SolveStatus::kSingular;
  record->verdict = completed ? Verdict::kSolved : Verdict::kFailed;
  record->message = FloorMessage(method == FloorMethod::kSparseCholesky ? FloorMethod::kDenseCholesky : method,
                                 timed, M.rows());
  if (!completed) record->message += ": the factorization failed (singular matrix)";
  return timed;
}

FloorMethod TimeFactorization(const SparseMatrix& M, FloorMethod method, const ReplayOptions& replay,
                              ReplayRecord* record) {
  SparseMatrix compressed = M;
  compressed.makeCompressed();
  FloorMethod timed = FloorMethod::kSparseLu;
  bool completed = false;
  if (method == FloorMethod::kSparseCholesky || method == FloorMethod::kDenseCholesky) {
    Eigen::SimplicialLLT<SparseMatrix> llt;
    if (TimeCompute(&llt, compressed, replay, record)) {
      timed = FloorMethod::kSparseCholesky;
      completed = true;
    }
  }
  if (timed == FloorMethod::kSparseLu) {
    Eigen::SparseLU<SparseMatrix, Eigen::COLAMDOrdering<int>> lu;
    completed = TimeCompute(&lu, compressed, replay, record);
  }
  record->status = completed ? SolveStatus::kSolved : SolveStatus::kSingular;
  record->verdict = completed ? Verdict::kSolved : Verdict::kFailed;
  record->message = FloorMessage(method == FloorMethod::kDenseCholesky ? FloorMethod::kSparseCholesky : method,
                                 timed, M.rows());
  if (!completed) record->message += ": the factorization failed (singular matrix)";
  return timed;
}

ReplayRecord ReplayFloor(const ProblemSet& set, const LibraryProblem& p, const ReplayOptions& options) {
  ReplayRecord r = FloorRecord(set.name, p.id, p.size(), p.sparse(), JoinTags(p.tags), p.expected, options);
  const FloorMethod method = ChooseFloorMethod(p.sparse(), TagsSaySpd(r.tags));
  if (p.problem.is_sparse()) {
    TimeFactorization(p.problem.sparse_matrix(), method, options, &r);
  } else {
    TimeFactorization(p.problem.dense_matrix(), method, options, &r);
  }
  return r;
}

ReplayRecord ReplayMcpFloor(const McpProblemSet& set, const McpLibraryProblem& p, std::size_t start,
                            const ReplayOptions& options) {
  if (start >= p.starts.size() || !p.problem) {
    throw InvalidInputError("floor: problem '" + p.id + "' has no start " + std::to_string(start + 1));
  }
  ReplayRecord r = FloorRecord(set.name, p.id, p.size(), p.sparse(), JoinTags(p.tags), p.expected, options);
  r.start = start < p.start_labels.size() ? p.start_labels[start] : "";
  if (p.sparse()) {
    SparseMatrix J;
    p.problem->JacobianSparse(p.starts[start], &J);
    TimeFactorization(J, FloorMethod::kSparseLu, options, &r);
  } else {
    DenseMatrix J;
    p.problem->JacobianDense(p.starts[start], &J);
    TimeFactorization(J, FloorMethod::kDenseLu, options, &r);
  }
  r.message = "Jacobian at the start: " + r.message;
  return r;
}

ReplayRecord ReplayAviFloor(const AviProblemSet& set, const AviLibraryProblem& p, const ReplayOptions& options) {
  ReplayRecord r = FloorRecord(set.name, p.id, p.size(), false, JoinTags(p.tags), p.expected, options);
  if (!p.problem) throw InvalidInputError("floor: AVI problem '" + p.id + "' has no data");
  const AviReduction reduction = ReduceToBoxMlcp(*p.problem);
  if (reduction.problem.is_sparse()) {
    TimeFactorization(reduction.problem.sparse_matrix(), FloorMethod::kSparseLu, options, &r);
  } else {
    TimeFactorization(reduction.problem.dense_matrix(), FloorMethod::kDenseLu, options, &r);
  }
  r.message = "reduced box-MLCP: " + r.message;
  return r;
}

}  // namespace smcbench

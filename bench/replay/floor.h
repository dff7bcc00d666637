// The floor of a benchmark problem: the time of one factorization of its matrix, measured in the same run and with
// the same protocol as a cold solve (SampleSolveTimes: an untimed warm-up, then the run's repetitions of samples
// lasting at least min_sample_seconds, the median reported), so the report can say how close each backend is to
// what any direct method must pay at least once (issue 34: "our best cold within 1.5× one factorization of M").
//
// Which factorization: a dense Cholesky (LLᵀ) when the problem's tags say M is symmetric positive definite, else a
// dense LU with partial pivoting; for a sparse M the sparse counterparts (simplicial LLᵀ, or LU with COLAMD
// ordering). An MCP's floor is the factorization of its Jacobian at the start, an AVI's that of the matrix of its
// reduced box-MLCP (the system SolveAvi hands a backend). A floor record is a ReplayRecord with solver kFloorSolver
// and mode "floor", kept apart from the backends' records (ReplayResults::floor): it is never a backend.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "bench/replay/replay.h"
#include "problems/avi_library/avi_library.h"
#include "problems/mcp/mcp_library.h"

namespace smcbench {

// The name and mode floor records carry (ReplayRecord::solver, ::mode).
inline constexpr const char* kFloorSolver = "floor";

enum class FloorMethod {
  kDenseCholesky = 0,   // Eigen::LLT
  kDenseLu = 1,         // Eigen::PartialPivLU
  kSparseCholesky = 2,  // Eigen::SimplicialLLT
  kSparseLu = 3,        // Eigen::SparseLU with COLAMD ordering
};
// "dense Cholesky", "dense LU (partial pivoting)", "sparse Cholesky", "sparse LU (COLAMD)".
std::string_view ToString(FloorMethod method);

// True when comma-separated tags (ReplayRecord::tags) say M is symmetric positive definite: "spd", or both
// "symmetric" and "positive_definite".
bool TagsSaySpd(std::string_view tags);

// The factorization that is the floor of a matrix stored sparse or dense, SPD or not.
FloorMethod ChooseFloorMethod(bool sparse, bool spd);

// Times factorizations of M by method with the cold protocol of replay (median, min, max, mad, samples and
// solves_per_sample of *record). When a Cholesky fails (M not positive definite after all) the LU of the same
// storage is timed instead. Writes *record's status (solved: the factorization completed) and message (the method
// and the size, and the fallback if there was one). Returns the method timed.
FloorMethod TimeFactorization(const DenseMatrix& M, FloorMethod method, const ReplayOptions& replay,
                              ReplayRecord* record);
FloorMethod TimeFactorization(const SparseMatrix& M, FloorMethod method, const ReplayOptions& replay,
                              ReplayRecord* record);

// The floor record of a box-MLCP problem of set: its M, Cholesky when its tags say SPD (TagsSaySpd).
ReplayRecord ReplayFloor(const ProblemSet& set, const LibraryProblem& problem, const ReplayOptions& options);
// The floor record of an MCP problem × start: its Jacobian at that start (LU, dense or sparse as the problem
// stores it). InvalidInputError if start is not one of the problem's.
ReplayRecord ReplayMcpFloor(const McpProblemSet& set, const McpLibraryProblem& problem, std::size_t start,
                            const ReplayOptions& options);
// The floor record of an AVI problem: the matrix of its normalized reduction (ReduceToBoxMlcp), a dense LU.
ReplayRecord ReplayAviFloor(const AviProblemSet& set, const AviLibraryProblem& problem, const ReplayOptions& options);

}  // namespace smcbench

// A box-MLCP (M, q, l, u) as Matrix Market files, the exchange format of SuiteSparse, Matrix Market and Eigen's
// MarketIO, so a problem can go to and come from MATLAB, SciPy (scipy.io.mmread) or Julia without our code.
// The convention (docs/formats.md): PROBLEM.mtx holds M; PROBLEM_q.mtx, PROBLEM_l.mtx, PROBLEM_u.mtx hold the
// vectors (array format, n x 1). Infinite bounds are written "inf" / "-inf".
#pragma once

#include <string>
#include <string_view>

#include "solvers/core/problem.h"

namespace smcbench {

// The four file names of one problem: matrix = "DIR/P.mtx" gives DIR/P_q.mtx, DIR/P_l.mtx, DIR/P_u.mtx.
// Throws InvalidInputError if matrix_path does not end in ".mtx" (the names of the others derive from it).
struct MatrixMarketFiles {
  std::string matrix, q, l, u;
};
MatrixMarketFiles MatrixMarketFileNames(const std::string& matrix_path);

// Reads the problem named by its matrix file. M: "coordinate" (stored sparse; "general" or "symmetric", the latter
// with the lower triangle only, mirrored) or "array" (stored dense, column-major; "array symmetric", as SciPy's
// mmwrite writes a symmetric dense M: the lower triangle column by column, mirrored), field "real" or
// "integer". q is required; a missing l file means l = 0 and a missing u file means u = +inf (an LCP needs only M
// and q). Every defect is an InvalidInputError "Matrix Market '<file>': line L: <what>": a missing or unknown
// banner, complex/pattern/skew/Hermitian data, a non-square M, indices out of range or repeated, entries above the
// diagonal of a symmetric matrix, fewer or more entries than declared, non-numeric tokens, a non-finite entry of M
// or q, NaN bounds, l = +inf, u = -inf, l > u, vector lengths other than n. The problem's name is the matrix
// file's stem. Input per file is capped at 1 GiB.
BoxMLCP ReadMatrixMarketProblem(const std::string& matrix_path);

// Writes the four files. A dense M is written "array real general" (every entry, column-major) and a sparse M
// "coordinate real general" (its stored entries, explicit zeros included), so reading back restores the storage
// and every number bit for bit (the shortest round-trip form, std::to_chars). Throws InvalidInputError naming the
// file if one cannot be written.
void WriteMatrixMarketProblem(const BoxMLCP& problem, const std::string& matrix_path);

// The reader's core on text already in memory (for tests and fuzzing); file_name is used in messages.
struct MatrixMarketMatrix {
  bool is_dense = false;  // "array" files; "coordinate" files are stored sparse
  DenseMatrix dense;
  SparseMatrix sparse;
};
MatrixMarketMatrix ParseMatrixMarketMatrix(std::string_view text, const std::string& file_name);
// An n x 1 "array" file's values (any n >= 1), infinities included.
Vector ParseMatrixMarketVector(std::string_view text, const std::string& file_name);

}  // namespace smcbench

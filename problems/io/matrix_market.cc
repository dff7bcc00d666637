// Matrix Market reader and writer of a box-MLCP. Not Eigen's MarketIO (unsupported/Eigen/SparseExtra): its
// loadMarket reports a bad line only on std::cerr and goes on without the entry, ignores the "symmetric" qualifier
// (half of M silently lost), reads no "array" matrix, and its vector reader cannot read "inf" (iostreams) and
// asserts on a bad size line. A problem read wrong is a wrong benchmark, so this reader checks every line; the
// tests use Eigen's MarketIO as the independent implementation both ways (matrix_market_test.cc).
#include "problems/io/matrix_market.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <system_error>
#include <tuple>
#include <vector>

#include "problems/io/read_text.h"
#include "solvers/core/number_text.h"

namespace smcbench {
namespace {

constexpr std::int64_t kMaxDimension = 10'000'000;  // 10⁷ rows: 40 MB of column starts for an empty sparse M
constexpr double kInfinity = std::numeric_limits<double>::infinity();

[[noreturn]] void Fail(const std::string& file, int line, const std::string& what) {
  throw InvalidInputError("Matrix Market '" + file + "': " + (line > 0 ? "line " + std::to_string(line) + ": " : "") +
                          what);
}

std::string Lower(std::string_view text) {
  std::string s(text);
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Splits text into lines and each line into whitespace-separated tokens; skips comments ('%') and blank lines
// after the banner, keeping the 1-based line number of each for messages.
class Lines {
 public:
  Lines(std::string_view text, std::string file) : text_(text), file_(std::move(file)) {}

  const std::string& file() const { return file_; }
  int line() const { return line_; }

  // The next line, raw (for the banner).
  bool NextRaw(std::string_view* out) {
    if (pos_ >= text_.size()) return false;
    const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
    *out = text_.substr(pos_, end - pos_);
    if (!out->empty() && out->back() == '\r') out->remove_suffix(1);
    pos_ = end + 1;
    ++line_;
    return true;
  }

  // The tokens of the next line that is neither blank nor a comment; false at the end of the text.
  bool NextData(std::vector<std::string_view>* tokens) {
    std::string_view raw;
    while (NextRaw(&raw)) {
      tokens->clear();
      std::size_t i = 0;
      while (i < raw.size()) {
        while (i < raw.size() && std::isspace(static_cast<unsigned char>(raw[i]))) ++i;
        const std::size_t start = i;
        while (i < raw.size() && !std::isspace(static_cast<unsigned char>(raw[i]))) ++i;
        if (i > start) tokens->push_back(raw.substr(start, i - start));
      }
      if (tokens->empty() || (*tokens)[0][0] == '%') continue;
      return true;
    }
    return false;
  }

  [[noreturn]] void Fail(const std::string& what) const { smcbench::Fail(file_, line_, what); }

 private:
  std::string_view text_;
  std::string file_;
  std::size_t pos_ = 0;
  int line_ = 0;
};

std::string Quote(std::string_view token) {
  std::string s(token.substr(0, 40));
  for (char& c : s) {
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
  }
  return "'" + s + (token.size() > 40 ? "...'" : "'");
}

double ParseNumber(const Lines& lines, std::string_view token, const std::string& field) {
  std::string_view digits = token;
  if (!digits.empty() && digits[0] == '+') digits.remove_prefix(1);  // from_chars takes no '+'
  double value = 0.0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (ec == std::errc::result_out_of_range) lines.Fail(field + ": " + Quote(token) + " is out of double range");
  if (ec != std::errc() || end != digits.data() + digits.size()) {
    lines.Fail(field + ": expected a number, got " + Quote(token));
  }
  return value;
}

std::int64_t ParseIndex(const Lines& lines, std::string_view token, const std::string& field, std::int64_t low,
                        std::int64_t high) {
  std::int64_t value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size()) {
    lines.Fail(field + ": expected an integer, got " + Quote(token));
  }
  if (value < low || value > high) {
    lines.Fail(field + " = " + std::to_string(value) + " is outside " + std::to_string(low) + " ... " +
               std::to_string(high));
  }
  return value;
}

struct Banner {
  bool coordinate = false;
  bool symmetric = false;
};

Banner ReadBanner(Lines& lines) {
  std::string_view raw;
  if (!lines.NextRaw(&raw)) lines.Fail("empty file (expected the banner %%MatrixMarket matrix ...)");
  std::vector<std::string> words;
  std::string word;
  for (char c : std::string(raw) + " ") {
    if (std::isspace(static_cast<unsigned char>(c))) {
      if (!word.empty()) words.push_back(Lower(word));
      word.clear();
    } else {
      word.push_back(c);
    }
  }
  if (words.size() != 5 || words[0] != "%%matrixmarket" || words[1] != "matrix") {
    lines.Fail("expected the banner '%%MatrixMarket matrix <coordinate|array> <real|integer> <general|symmetric>', "
               "got " + Quote(raw));
  }
  Banner banner;
  if (words[2] != "coordinate" && words[2] != "array") {
    lines.Fail("format '" + words[2] + "' is not 'coordinate' or 'array'");
  }
  banner.coordinate = words[2] == "coordinate";
  if (words[3] != "real" && words[3] != "integer") {
    lines.Fail("field '" + words[3] + "' is not supported (a box-MLCP is real: 'real' or 'integer')");
  }
  if (words[4] != "general" && words[4] != "symmetric") {
    lines.Fail("symmetry '" + words[4] + "' is not supported ('general' or 'symmetric')");
  }
  banner.symmetric = words[4] == "symmetric";
  return banner;
}

void CheckEnd(Lines& lines, const std::string& after) {
  std::vector<std::string_view> tokens;
  if (lines.NextData(&tokens)) lines.Fail("trailing data " + Quote(tokens[0]) + " after " + after);
}

std::string ReadFile(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) Fail(path, 0, "is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) Fail(path, 0, "cannot open file: " + std::generic_category().message(errno));
  return ReadBoundedText(in, "Matrix Market '" + path + "'");
}

bool FileExists(const std::string& path) {
  std::error_code ec;
  return std::filesystem::exists(path, ec);
}

}  // namespace

MatrixMarketFiles MatrixMarketFileNames(const std::string& matrix_path) {
  const std::string extension = ".mtx";
  if (matrix_path.size() <= extension.size() ||
      Lower(matrix_path.substr(matrix_path.size() - extension.size())) != extension) {
    throw InvalidInputError("Matrix Market '" + matrix_path + "': the matrix file's name must end in .mtx (q, l and "
                            "u are read from NAME_q.mtx, NAME_l.mtx, NAME_u.mtx beside NAME.mtx)");
  }
  const std::string base = matrix_path.substr(0, matrix_path.size() - extension.size());
  return {matrix_path, base + "_q.mtx", base + "_l.mtx", base + "_u.mtx"};
}

MatrixMarketMatrix ParseMatrixMarketMatrix(std::string_view text, const std::string& file_name) {
  Lines lines(text, file_name);
  const Banner banner = ReadBanner(lines);
  std::vector<std::string_view> tokens;
  if (!lines.NextData(&tokens)) lines.Fail("no size line");
  if (tokens.size() != (banner.coordinate ? 3u : 2u)) {
    lines.Fail(std::string("size line: expected ") + (banner.coordinate ? "'rows columns entries'" : "'rows columns'"));
  }
  const std::int64_t rows = ParseIndex(lines, tokens[0], "rows", 1, kMaxDimension);
  const std::int64_t cols = ParseIndex(lines, tokens[1], "columns", 1, kMaxDimension);
  if (rows != cols) {
    lines.Fail("M is " + std::to_string(rows) + " x " + std::to_string(cols) + ": a box-MLCP's M is square");
  }
  const auto n = static_cast<Eigen::Index>(rows);
  MatrixMarketMatrix result;
  if (!banner.coordinate) {
    // 'array general': every entry, column by column. 'array symmetric' (SciPy's mmwrite of a symmetric dense M):
    // the lower triangle, column by column (column j from row j down), mirrored above the diagonal.
    const std::int64_t count = banner.symmetric ? rows * (rows + 1) / 2 : rows * cols;
    // Bytes bound the entries: each takes at least two characters, so a huge declared size fails before allocating.
    if (count > static_cast<std::int64_t>(text.size() / 2 + 1)) {
      lines.Fail("declares " + std::to_string(count) + " entries, more than the file can hold");
    }
    result.is_dense = true;
    result.dense.resize(n, n);
    std::int64_t k = 0;
    Eigen::Index i = 0, j = 0;  // the entry k is (i, j)
    while (k < count && lines.NextData(&tokens)) {
      for (std::string_view token : tokens) {
        if (k == count) lines.Fail("more entries than the " + std::to_string(count) + " declared");
        const std::string field = "M(" + std::to_string(i + 1) + "," + std::to_string(j + 1) + ")";
        const double value = ParseNumber(lines, token, field);
        if (!std::isfinite(value)) lines.Fail(field + " is " + NumberText(value) + " (M must be finite)");
        result.dense(i, j) = value;
        if (banner.symmetric) result.dense(j, i) = value;
        ++k;
        if (++i == n) {
          ++j;
          i = banner.symmetric ? j : 0;
        }
      }
    }
    if (k < count) {
      lines.Fail("only " + std::to_string(k) + " of the " + std::to_string(count) + " entries declared" +
                 (banner.symmetric ? " (an 'array symmetric' file holds the lower triangle, n(n+1)/2 entries)" : ""));
    }
    CheckEnd(lines, "the last entry");
    return result;
  }
  const std::int64_t declared = ParseIndex(lines, tokens[2], "entries", 0, rows * cols);
  if (declared > static_cast<std::int64_t>(text.size() / 6 + 1)) {  // "i j v\n" takes at least 6 bytes
    lines.Fail("declares " + std::to_string(declared) + " entries, more than the file can hold");
  }
  struct Entry {
    int row, col, line;
    double value;
  };
  std::vector<Entry> entries;
  entries.reserve(static_cast<std::size_t>(declared) * (banner.symmetric ? 2 : 1));
  std::int64_t read = 0;
  while (lines.NextData(&tokens)) {
    if (read == declared) lines.Fail("more entries than the " + std::to_string(declared) + " declared");
    if (tokens.size() != 3) lines.Fail("expected 'row column value', got " + std::to_string(tokens.size()) + " tokens");
    const auto i = static_cast<int>(ParseIndex(lines, tokens[0], "row", 1, rows) - 1);
    const auto j = static_cast<int>(ParseIndex(lines, tokens[1], "column", 1, cols) - 1);
    const std::string field = "M(" + std::to_string(i + 1) + "," + std::to_string(j + 1) + ")";
    const double value = ParseNumber(lines, tokens[2], field);
    if (!std::isfinite(value)) lines.Fail(field + " is " + NumberText(value) + " (M must be finite)");
    if (banner.symmetric && i < j) {
      lines.Fail(field + " is above the diagonal: a symmetric file holds the lower triangle only");
    }
    entries.push_back({i, j, lines.line(), value});
    if (banner.symmetric && i != j) entries.push_back({j, i, lines.line(), value});
    ++read;
  }
  if (read < declared) {
    lines.Fail("only " + std::to_string(read) + " of the " + std::to_string(declared) + " entries declared");
  }
  // Matrix Market allows no repeated entry; summing them (as Eigen's setFromTriplets would) hides a broken file.
  std::vector<std::size_t> order(entries.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::tie(entries[a].col, entries[a].row) < std::tie(entries[b].col, entries[b].row);
  });
  for (std::size_t k = 1; k < order.size(); ++k) {
    const Entry& a = entries[order[k - 1]];
    const Entry& b = entries[order[k]];
    if (a.row == b.row && a.col == b.col) {
      Fail(file_name, std::max(a.line, b.line),
           "M(" + std::to_string(a.row + 1) + "," + std::to_string(a.col + 1) + ") is given twice (lines " +
               std::to_string(std::min(a.line, b.line)) + " and " + std::to_string(std::max(a.line, b.line)) + ")");
    }
  }
  std::vector<Eigen::Triplet<double, int>> triplets;
  triplets.reserve(entries.size());
  for (std::size_t k : order) triplets.emplace_back(entries[k].row, entries[k].col, entries[k].value);
  result.sparse.resize(n, n);
  result.sparse.setFromTriplets(triplets.begin(), triplets.end());
  result.sparse.makeCompressed();
  return result;
}

Vector ParseMatrixMarketVector(std::string_view text, const std::string& file_name) {
  Lines lines(text, file_name);
  const Banner banner = ReadBanner(lines);
  if (banner.coordinate || banner.symmetric) {
    lines.Fail("a vector file is 'array real general' with one column");
  }
  std::vector<std::string_view> tokens;
  if (!lines.NextData(&tokens)) lines.Fail("no size line");
  if (tokens.size() != 2) lines.Fail("size line: expected 'rows 1'");
  const std::int64_t rows = ParseIndex(lines, tokens[0], "rows", 1, kMaxDimension);
  ParseIndex(lines, tokens[1], "columns", 1, 1);
  if (rows > static_cast<std::int64_t>(text.size() / 2 + 1)) {
    lines.Fail("declares " + std::to_string(rows) + " entries, more than the file can hold");
  }
  Vector values(static_cast<Eigen::Index>(rows));
  std::int64_t k = 0;
  while (k < rows && lines.NextData(&tokens)) {
    for (std::string_view token : tokens) {
      if (k == rows) lines.Fail("more entries than the " + std::to_string(rows) + " declared");
      values[static_cast<Eigen::Index>(k)] = ParseNumber(lines, token, "entry " + std::to_string(k + 1));
      ++k;
    }
  }
  if (k < rows) lines.Fail("only " + std::to_string(k) + " of the " + std::to_string(rows) + " entries declared");
  CheckEnd(lines, "the last entry");
  return values;
}

namespace {

// A vector file of the problem: its length must be n, and check(i, value) names what is wrong with an entry.
template <typename Check>
Vector ReadVectorFile(const std::string& path, Eigen::Index n, const char* name, Check check) {
  const Vector v = ParseMatrixMarketVector(ReadFile(path), path);
  if (v.size() != n) {
    Fail(path, 0, std::string(name) + " has " + std::to_string(v.size()) + " entries but M is " + std::to_string(n) +
                      " x " + std::to_string(n));
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    const std::string what = check(v[i]);
    if (!what.empty()) Fail(path, 0, std::string(name) + "[" + std::to_string(i) + "] = " + NumberText(v[i]) + what);
  }
  return v;
}

}  // namespace

BoxMLCP ReadMatrixMarketProblem(const std::string& matrix_path) {
  const MatrixMarketFiles files = MatrixMarketFileNames(matrix_path);
  MatrixMarketMatrix M = ParseMatrixMarketMatrix(ReadFile(files.matrix), files.matrix);
  const Eigen::Index n = M.is_dense ? M.dense.rows() : M.sparse.rows();
  if (!FileExists(files.q)) Fail(files.q, 0, "missing: the q of '" + files.matrix + "' is required");
  Vector q = ReadVectorFile(files.q, n, "q", [](double x) {
    return std::isfinite(x) ? std::string() : std::string(" (q must be finite)");
  });
  Vector l = Vector::Zero(n);
  Vector u = Vector::Constant(n, kInfinity);
  if (FileExists(files.l)) {
    l = ReadVectorFile(files.l, n, "l", [](double x) {
      if (std::isnan(x)) return std::string(" (a bound is never NaN)");
      return x == kInfinity ? std::string(" (no feasible point)") : std::string();
    });
  }
  if (FileExists(files.u)) {
    u = ReadVectorFile(files.u, n, "u", [](double x) {
      if (std::isnan(x)) return std::string(" (a bound is never NaN)");
      return x == -kInfinity ? std::string(" (no feasible point)") : std::string();
    });
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    if (l[i] > u[i]) {
      Fail(files.l, 0, "l[" + std::to_string(i) + "] = " + NumberText(l[i]) + " > u[" + std::to_string(i) +
                           "] = " + NumberText(u[i]) + " (u from '" + files.u + "')");
    }
  }
  const std::string name = std::filesystem::path(files.matrix).stem().string();
  try {
    if (M.is_dense) return BoxMLCP(std::move(M.dense), std::move(q), std::move(l), std::move(u), name);
    return BoxMLCP(std::move(M.sparse), std::move(q), std::move(l), std::move(u), name);
  } catch (const InvalidInputError& e) {
    throw InvalidInputError("Matrix Market '" + files.matrix + "': " + e.what());
  }
}

namespace {

void WriteText(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) Fail(path, 0, "cannot open for writing: " + std::generic_category().message(errno));
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.close();
  if (!out) Fail(path, 0, "writing failed");
}

std::string VectorText(const Vector& v, const std::string& comment) {
  std::string text = "%%MatrixMarket matrix array real general\n% " + comment + "\n";
  text += std::to_string(v.size()) + " 1\n";
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    AppendNumberText(&text, v[i]);
    text.push_back('\n');
  }
  return text;
}

}  // namespace

void WriteMatrixMarketProblem(const BoxMLCP& problem, const std::string& matrix_path) {
  const MatrixMarketFiles files = MatrixMarketFileNames(matrix_path);
  const Eigen::Index n = problem.size();
  const std::string stem = std::filesystem::path(files.matrix).stem().string();
  const std::string about = "smcbench box-MLCP '" + problem.name() + "': M z + q = w - v, l <= z <= u; ";
  std::string text;
  if (problem.is_sparse()) {
    const SparseMatrix& M = problem.sparse_matrix();
    std::int64_t stored = 0;
    for (int j = 0; j < M.outerSize(); ++j) {
      for (SparseMatrix::InnerIterator it(M, j); it; ++it) ++stored;
    }
    text = "%%MatrixMarket matrix coordinate real general\n% " + about + "M here, q, l, u in " + stem + "_q.mtx, " +
           stem + "_l.mtx, " + stem + "_u.mtx\n" + std::to_string(n) + " " + std::to_string(n) + " " +
           std::to_string(stored) + "\n";
    for (int j = 0; j < M.outerSize(); ++j) {
      for (SparseMatrix::InnerIterator it(M, j); it; ++it) {
        text += std::to_string(it.row() + 1) + " " + std::to_string(j + 1) + " ";
        AppendNumberText(&text, it.value());
        text.push_back('\n');
      }
    }
  } else {
    const DenseMatrix& M = problem.dense_matrix();
    text = "%%MatrixMarket matrix array real general\n% " + about + "M here (column-major), q, l, u in " + stem +
           "_q.mtx, " + stem + "_l.mtx, " + stem + "_u.mtx\n" + std::to_string(n) + " " + std::to_string(n) + "\n";
    for (Eigen::Index j = 0; j < n; ++j) {
      for (Eigen::Index i = 0; i < n; ++i) {
        AppendNumberText(&text, M(i, j));
        text.push_back('\n');
      }
    }
  }
  WriteText(files.matrix, text);
  WriteText(files.q, VectorText(problem.q(), about + "q"));
  WriteText(files.l, VectorText(problem.l(), about + "l (lower bounds, -inf: none)"));
  WriteText(files.u, VectorText(problem.u(), about + "u (upper bounds, inf: none)"));
}

}  // namespace smcbench

// Siconos Numerics text formats (tests/data/siconos/README.md; Siconos' own readers are
// linearComplementarity_newFromFile, relay_newFromFile, mixedLinearComplementarity_newFromFile and
// NM_new_from_file / SBM_new_from_file). We read whitespace-separated numbers, never lines, like their fscanf
// calls, but unlike them we check everything: a corrupt or hostile file is an InvalidInputError, never a crash,
// a giant allocation or a silently wrong problem.
#include "problems/io/siconos_format.h"

#include "problems/io/read_text.h"
#include "solvers/core/number_text.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <istream>
#include <limits>
#include <ostream>
#include <sstream>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

namespace smcbench {
namespace {

// The largest peer file is 3.2 MB; 1 GiB leaves room for real problems while refusing to slurp a device.
// Caps every declared dimension so that products of two sizes fit in int64 and Eigen::Index. The real guard
// against a corrupt size is Parser::Reserve, which compares the declared count with the bytes left.
constexpr std::int64_t kMaxDimension = std::int64_t{1} << 28;

const char* KindName(SiconosKind kind) {
  switch (kind) {
    case SiconosKind::kLCP:
      return "LCP";
    case SiconosKind::kRelay:
      return "Relay";
    case SiconosKind::kMLCP:
      return "MLCP";
  }
  return "unknown-kind";
}

// Names the value being read ("q[3]", "M(2,5)", "blocksRows[1]"); formatted only when an error is reported,
// so the hot loop over a 221x221 matrix builds no strings.
struct Field {
  const char* name;
  std::int64_t i = -1;
  std::int64_t j = -1;
};

std::string Format(const Field& f) {
  std::string s = f.name;
  if (f.i >= 0 && f.j >= 0) {
    s += "(" + std::to_string(f.i) + "," + std::to_string(f.j) + ")";
  } else if (f.i >= 0) {
    s += "[" + std::to_string(f.i) + "]";
  }
  return s;
}

// A token quoted for an error message: printable, at most 32 characters (fuzzed input may hold anything).
std::string Quote(std::string_view token) {
  std::string s = "'";
  const std::size_t shown = std::min<std::size_t>(token.size(), 32);
  for (std::size_t k = 0; k < shown; ++k) {
    const unsigned char c = static_cast<unsigned char>(token[k]);
    if (std::isprint(c)) {
      s += static_cast<char>(c);
    } else {
      static const char kHex[] = "0123456789abcdef";
      s += "\\x";
      s += kHex[c >> 4];
      s += kHex[c & 15];
    }
  }
  if (shown < token.size()) s += "...";
  return s + "'";
}

bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

enum class NumberStatus { kOk, kNotANumber };

// Locale-independent (std::from_chars) parse of a whole token. Accepts what C's strtod accepts in the "C"
// locale except hexadecimal: an optional sign (a leading '+' too), decimal or exponent form, inf, infinity, nan.
// Out-of-range values become ±inf (overflow) or ±0 (underflow below the subnormals), as strtod does.
NumberStatus ParseDouble(std::string_view token, double* value) {
  const char* first = token.data();
  const char* last = token.data() + token.size();
  if (first != last && *first == '+') {
    ++first;
    if (first == last || *first == '+' || *first == '-') return NumberStatus::kNotANumber;
  }
  if (first == last) return NumberStatus::kNotANumber;
  double v = 0.0;
  const auto result = std::from_chars(first, last, v, std::chars_format::general);
  if (result.ptr != last) return NumberStatus::kNotANumber;
  if (result.ec == std::errc::result_out_of_range) {
    // Decimal magnitude of the token: integer digits after leading zeros (or minus the zeros after the point)
    // plus the exponent. Positive means overflow (|x| > 1.8e308), otherwise underflow (|x| < 4.9e-324).
    const bool negative = *first == '-';
    const char* p = negative ? first + 1 : first;
    std::int64_t magnitude = 0;
    bool seen_nonzero = false;
    bool after_point = false;
    for (; p != last && *p != 'e' && *p != 'E'; ++p) {
      if (*p == '.') {
        after_point = true;
      } else if (!seen_nonzero) {
        if (*p != '0') {
          seen_nonzero = true;
          if (!after_point) ++magnitude;
        } else if (after_point) {
          --magnitude;
        }
      } else if (!after_point) {
        ++magnitude;
      }
    }
    if (p != last) {
      std::int64_t exponent = 0;
      ++p;
      const bool negative_exponent = p != last && *p == '-';
      if (p != last && (*p == '-' || *p == '+')) ++p;
      for (; p != last; ++p) exponent = std::min<std::int64_t>(exponent * 10 + (*p - '0'), 1'000'000'000);
      magnitude += negative_exponent ? -exponent : exponent;
    }
    v = magnitude > 0 ? kInf : 0.0;
    if (negative) v = -v;
  } else if (result.ec != std::errc()) {
    return NumberStatus::kNotANumber;
  }
  *value = v;
  return NumberStatus::kOk;
}

// Tokenizer over the whole file held in memory. '#' starts a comment to the end of the line wherever a token
// could start. Every failure throws InvalidInputError "<source>: <field>: <what> (line L)".
class Parser {
 public:
  Parser(std::string_view text, std::string source) : text_(text), source_(std::move(source)) {}

  [[noreturn]] void Fail(const Field& field, const std::string& what) const {
    throw InvalidInputError(source_ + ": " + Format(field) + ": " + what + " (line " +
                            std::to_string(LineOf(token_pos_)) + ")");
  }

  // Next token, skipping whitespace and comments; false at the end of the input.
  bool Next(std::string_view* token) {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (IsSpace(c)) {
        ++pos_;
      } else if (c == '#') {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
      } else {
        break;
      }
    }
    token_pos_ = pos_;
    if (pos_ >= text_.size()) return false;
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !IsSpace(text_[pos_])) ++pos_;
    *token = text_.substr(start, pos_ - start);
    return true;
  }

  std::int64_t ReadInt(const Field& field, std::int64_t min, std::int64_t max) {
    std::string_view token;
    if (!Next(&token)) Fail(field, "unexpected end of file (truncated data)");
    std::int64_t v = 0;
    const char* first = token.data();
    const char* last = token.data() + token.size();
    if (first != last && *first == '+') {
      ++first;
      if (first != last && *first == '-') first = last;  // "+-3" is not an integer
    }
    const auto result = std::from_chars(first, last, v);
    if (result.ptr != last || first == last) {
      Fail(field, "expected an integer, found " + Quote(token));
    }
    if (result.ec != std::errc() || v < min || v > max) {
      Fail(field, "value " + Quote(token) + " out of range [" + std::to_string(min) + ", " + std::to_string(max) +
                      "]");
    }
    return v;
  }

  // Any double, including ±inf and NaN (bounds may be infinite; the caller checks NaN).
  double ReadDouble(const Field& field) {
    std::string_view token;
    if (!Next(&token)) Fail(field, "unexpected end of file (truncated data)");
    double v = 0.0;
    if (ParseDouble(token, &v) != NumberStatus::kOk) Fail(field, "expected a number, found " + Quote(token));
    return v;
  }

  // Matrix and vector data: NaN and ±inf (including overflowing literals such as 1e999) are rejected.
  double ReadFinite(const Field& field) {
    const double v = ReadDouble(field);
    if (std::isnan(v)) Fail(field, "is NaN");
    if (std::isinf(v)) Fail(field, "is infinite");
    return v;
  }

  // Before allocating storage for `count` numbers, check that the rest of the input could hold them: every
  // number takes at least one character plus a separator. A corrupt size therefore fails here instead of
  // allocating gigabytes.
  void Reserve(std::int64_t count, const Field& field) {
    const std::int64_t remaining = static_cast<std::int64_t>(text_.size() - pos_);
    if (count > 0 && 2 * count - 1 > remaining) {
      token_pos_ = pos_;
      Fail(field, "the sizes declare " + std::to_string(count) + " more numbers but only " +
                      std::to_string(remaining) + " bytes remain (truncated file or corrupt size)");
    }
  }

  // After the last field: only whitespace, '#' comments, up to `allowed_numbers` numbers (the reference
  // solutions Siconos' MLCP files carry, which its reader ignores) and free-text notes that start a line after
  // an empty line (lcp_CPS_*.dat end with "Remark 4.1.14 CPS 2009 ..."). Anything else means the declared
  // sizes do not match the data, or the file is damaged.
  void CheckEnd(std::int64_t allowed_numbers, const char* last_field) {
    std::size_t previous_end = pos_;
    std::int64_t numbers = 0;
    std::string_view token;
    while (Next(&token)) {
      double ignored = 0.0;
      if (ParseDouble(token, &ignored) == NumberStatus::kOk) {
        if (numbers < allowed_numbers) {
          ++numbers;
          previous_end = pos_;
          continue;
        }
        Fail(Field{"trailing data"},
             "unexpected number " + Quote(token) + " after " + last_field +
                 (allowed_numbers > 0 ? " (more than the " + std::to_string(allowed_numbers) +
                                            " trailing reference-solution values allowed)"
                                      : std::string()) +
                 ": the declared sizes do not match the data");
      }
      if (StartsLine(token_pos_) && HasEmptyLine(previous_end, token_pos_)) return;  // a free-text note
      Fail(Field{"trailing data"}, "unexpected text " + Quote(token) + " after " + last_field +
                                       "; after the data a file may hold only '#' comment lines or free-text "
                                       "notes that follow an empty line");
    }
  }

 private:
  std::size_t LineOf(std::size_t pos) const {
    pos = std::min(pos, text_.size());
    const auto end = text_.begin() + static_cast<std::ptrdiff_t>(pos);
    return 1 + static_cast<std::size_t>(std::count(text_.begin(), end, '\n'));
  }

  bool StartsLine(std::size_t pos) const {
    while (pos > 0 && text_[pos - 1] != '\n') {
      if (!IsSpace(text_[pos - 1])) return false;
      --pos;
    }
    return true;
  }

  // True if [begin, end) contains a line holding only whitespace.
  bool HasEmptyLine(std::size_t begin, std::size_t end) const {
    bool line_blank = false;  // the first partial line (after the data) does not count
    for (std::size_t k = begin; k < end; ++k) {
      const char c = text_[k];
      if (c == '\n') {
        if (line_blank) return true;
        line_blank = true;
      } else if (!IsSpace(c)) {
        line_blank = false;
      }
    }
    return false;
  }

  std::string_view text_;
  std::string source_;
  std::size_t pos_ = 0;
  std::size_t token_pos_ = 0;
};

// A matrix block as stored: dense (storage 0) or, from sparse-block storage 1, a SparseMatrix.
struct MatrixBlock {
  bool is_sparse = false;
  DenseMatrix dense;
  SparseMatrix sparse;
};

// Storage 1 (SparseBlockStructuredMatrix, SBM_new_from_file): nbblocks, blocknumber0, blocknumber1, the
// cumulative row and column block sizes, filled1 (= blocknumber0 + 1), filled2 (= nbblocks), the block-row
// pointers index1_data, the block-column indices index2_data, then each block as its number followed by its
// values in column-major order.
SparseMatrix ReadSparseBlock(Parser& p, std::int64_t rows, std::int64_t cols) {
  const std::int64_t nbblocks = p.ReadInt(Field{"M nbblocks"}, 0, kMaxDimension);
  SparseMatrix M(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
  if (nbblocks == 0) return M;  // Siconos stops here: an all-zero matrix
  const std::int64_t blocknumber0 = p.ReadInt(Field{"M blocknumber0"}, 1, rows);
  const std::int64_t blocknumber1 = p.ReadInt(Field{"M blocknumber1"}, 1, cols);
  if (nbblocks > blocknumber0 * blocknumber1) {
    p.Fail(Field{"M nbblocks"}, std::to_string(nbblocks) + " blocks do not fit a " + std::to_string(blocknumber0) +
                                    "x" + std::to_string(blocknumber1) + " block grid");
  }
  p.Reserve(blocknumber0 + blocknumber1, Field{"M blocksize0"});
  const auto read_sizes = [&](const char* name, std::int64_t count, std::int64_t total) {
    std::vector<std::int64_t> sizes(static_cast<std::size_t>(count));
    for (std::int64_t k = 0; k < count; ++k) {
      const std::int64_t previous = k == 0 ? 0 : sizes[static_cast<std::size_t>(k - 1)];
      sizes[static_cast<std::size_t>(k)] = p.ReadInt(Field{name, k}, previous + 1, total);
    }
    if (sizes.back() != total) {
      p.Fail(Field{name, count - 1}, "cumulative block sizes end at " + std::to_string(sizes.back()) +
                                         " but the matrix has " + std::to_string(total));
    }
    return sizes;
  };
  const std::vector<std::int64_t> blocksize0 = read_sizes("M blocksize0", blocknumber0, rows);
  const std::vector<std::int64_t> blocksize1 = read_sizes("M blocksize1", blocknumber1, cols);
  p.ReadInt(Field{"M filled1"}, blocknumber0 + 1, blocknumber0 + 1);
  p.ReadInt(Field{"M filled2"}, nbblocks, nbblocks);
  p.Reserve(blocknumber0 + 1 + nbblocks, Field{"M index1_data"});
  std::vector<std::int64_t> index1(static_cast<std::size_t>(blocknumber0 + 1));
  for (std::int64_t k = 0; k <= blocknumber0; ++k) {
    const std::int64_t low = k == 0 ? 0 : index1[static_cast<std::size_t>(k - 1)];
    const std::int64_t high = k == 0 ? 0 : nbblocks;
    index1[static_cast<std::size_t>(k)] = p.ReadInt(Field{"M index1_data", k}, low, high);
  }
  if (index1.back() != nbblocks) {
    p.Fail(Field{"M index1_data", blocknumber0},
           "block-row pointers end at " + std::to_string(index1.back()) + " but nbblocks = " +
               std::to_string(nbblocks));
  }
  std::vector<std::int64_t> index2(static_cast<std::size_t>(nbblocks));
  for (std::int64_t r = 0; r < blocknumber0; ++r) {
    for (std::int64_t b = index1[static_cast<std::size_t>(r)]; b < index1[static_cast<std::size_t>(r + 1)]; ++b) {
      // Block columns strictly increase along a block row, so no block is given twice.
      const bool first_in_row = b == index1[static_cast<std::size_t>(r)];
      const std::int64_t low = first_in_row ? 0 : index2[static_cast<std::size_t>(b - 1)] + 1;
      index2[static_cast<std::size_t>(b)] = p.ReadInt(Field{"M index2_data", b}, low, blocknumber1 - 1);
    }
  }
  std::vector<Eigen::Triplet<double, int>> entries;
  for (std::int64_t r = 0; r < blocknumber0; ++r) {
    const std::int64_t row0 = r == 0 ? 0 : blocksize0[static_cast<std::size_t>(r - 1)];
    const std::int64_t nrows = blocksize0[static_cast<std::size_t>(r)] - row0;
    for (std::int64_t b = index1[static_cast<std::size_t>(r)]; b < index1[static_cast<std::size_t>(r + 1)]; ++b) {
      const std::int64_t c = index2[static_cast<std::size_t>(b)];
      const std::int64_t col0 = c == 0 ? 0 : blocksize1[static_cast<std::size_t>(c - 1)];
      const std::int64_t ncols = blocksize1[static_cast<std::size_t>(c)] - col0;
      p.ReadInt(Field{"M block number", b}, b, b);
      p.Reserve(nrows * ncols, Field{"M block", b});
      for (std::int64_t jj = 0; jj < ncols; ++jj) {
        for (std::int64_t ii = 0; ii < nrows; ++ii) {
          const double v = p.ReadFinite(Field{"M", row0 + ii, col0 + jj});
          entries.emplace_back(static_cast<int>(row0 + ii), static_cast<int>(col0 + jj), v);
        }
      }
    }
  }
  M.setFromTriplets(entries.begin(), entries.end());
  return M;
}

// A Siconos matrix block (NM_new_from_file) that must be rows x cols: storage type, size0, size1, then for
// dense storage the two sizes again and size0*size1 numbers in column-major order.
MatrixBlock ReadMatrix(Parser& p, std::int64_t rows, std::int64_t cols, const std::string& context) {
  const std::int64_t storage = p.ReadInt(Field{"M storage type"}, std::numeric_limits<std::int64_t>::min(),
                                         std::numeric_limits<std::int64_t>::max());
  if (storage != 0 && storage != 1 && storage != 2) {
    p.Fail(Field{"M storage type"},
           "unknown storage type " + std::to_string(storage) + " (0 dense, 1 sparse-block, 2 sparse)");
  }
  const std::int64_t size0 = p.ReadInt(Field{"M size0 (rows)"}, 0, kMaxDimension);
  const std::int64_t size1 = p.ReadInt(Field{"M size1 (columns)"}, 0, kMaxDimension);
  if (size0 != rows || size1 != cols) {
    p.Fail(Field{"M"}, "matrix is " + std::to_string(size0) + "x" + std::to_string(size1) + " but a " +
                           std::to_string(rows) + "x" + std::to_string(cols) + " matrix is required (" + context +
                           ")");
  }
  MatrixBlock block;
  if (storage == 2) {
    p.Fail(Field{"M storage type"},
           "storage type 2 (sparse, CSparse) is not supported; write the matrix with dense storage 0");
  }
  if (storage == 1) {
    block.is_sparse = true;
    block.sparse = ReadSparseBlock(p, rows, cols);
    return block;
  }
  p.ReadInt(Field{"M size0 (repeated)"}, size0, size0);
  p.ReadInt(Field{"M size1 (repeated)"}, size1, size1);
  p.Reserve(rows * cols, Field{"M"});
  block.dense.resize(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
  for (std::int64_t j = 0; j < cols; ++j) {
    for (std::int64_t i = 0; i < rows; ++i) {
      block.dense(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = p.ReadFinite(Field{"M", i, j});
    }
  }
  return block;
}

Vector ReadFiniteVector(Parser& p, const char* name, std::int64_t n) {
  p.Reserve(n, Field{name});
  Vector v(static_cast<Eigen::Index>(n));
  for (std::int64_t i = 0; i < n; ++i) v[static_cast<Eigen::Index>(i)] = p.ReadFinite(Field{name, i});
  return v;
}

Vector ReadBoundVector(Parser& p, const char* name, std::int64_t n, double forbidden_infinity) {
  p.Reserve(n, Field{name});
  Vector v(static_cast<Eigen::Index>(n));
  for (std::int64_t i = 0; i < n; ++i) {
    const double x = p.ReadDouble(Field{name, i});
    if (std::isnan(x)) p.Fail(Field{name, i}, "is NaN");
    if (x == forbidden_infinity) p.Fail(Field{name, i}, "is " + NumberText(x) + " (no feasible point)");
    v[static_cast<Eigen::Index>(i)] = x;
  }
  return v;
}

BoxMLCP MakeProblem(const std::string& source, MatrixBlock M, Vector q, Vector l, Vector u,
                    const std::string& name) {
  // Everything BoxMLCP validates was checked above with file positions; this is a last line of defence.
  try {
    if (M.is_sparse) return BoxMLCP(std::move(M.sparse), std::move(q), std::move(l), std::move(u), name);
    return BoxMLCP(std::move(M.dense), std::move(q), std::move(l), std::move(u), name);
  } catch (const InvalidInputError& e) {
    throw InvalidInputError(source + ": " + e.what());
  }
}

BoxMLCP ParseLCP(Parser& p, const std::string& source, const std::string& name) {
  const std::int64_t n = p.ReadInt(Field{"n"}, 1, kMaxDimension);
  MatrixBlock M = ReadMatrix(p, n, n, "n = " + std::to_string(n));
  Vector q = ReadFiniteVector(p, "q", n);
  p.CheckEnd(0, "q");
  const auto size = static_cast<Eigen::Index>(n);
  return MakeProblem(source, std::move(M), std::move(q), Vector::Zero(size), Vector::Constant(size, kInf), name);
}

BoxMLCP ParseRelay(Parser& p, const std::string& source, const std::string& name) {
  const std::int64_t n = p.ReadInt(Field{"n"}, 1, kMaxDimension);
  MatrixBlock M = ReadMatrix(p, n, n, "n = " + std::to_string(n));
  Vector q = ReadFiniteVector(p, "q", n);
  Vector lb = ReadBoundVector(p, "lb", n, kInf);
  Vector ub = ReadBoundVector(p, "ub", n, -kInf);
  for (std::int64_t i = 0; i < n; ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    if (lb[k] > ub[k]) {
      p.Fail(Field{"lb", i}, "lb[" + std::to_string(i) + "] = " + NumberText(lb[k]) + " > ub[" + std::to_string(i) +
                                 "] = " + NumberText(ub[k]));
    }
  }
  p.CheckEnd(0, "ub");
  return MakeProblem(source, std::move(M), std::move(q), std::move(lb), std::move(ub), name);
}

// Entries written from the same double by the same %32.24e agree exactly; a few ulps of slack accept a file
// whose two storages were printed at different (round-tripping) precisions.
bool Agree(double a, double b) {
  return a == b || std::abs(a - b) <= 4.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(a), std::abs(b));
}

// MLCP (mixedLinearComplementarity_newFromFile). Unknowns z = (u, v) with u free (n) and v >= 0 (m).
BoxMLCP ParseMLCP(Parser& p, const std::string& source, const std::string& name) {
  const bool type1 = p.ReadInt(Field{"isStorageType1"}, 0, 1) == 1;
  const bool type2 = p.ReadInt(Field{"isStorageType2"}, 0, 1) == 1;
  if (!type1 && !type2) p.Fail(Field{"isStorageType2"}, "neither storage type 1 (M, q) nor type 2 (A..D, a, b)");
  const std::int64_t n = p.ReadInt(Field{"n"}, 0, kMaxDimension);
  const std::int64_t m = p.ReadInt(Field{"m"}, 0, kMaxDimension);
  const std::int64_t N = n + m;
  if (N == 0) p.Fail(Field{"m"}, "n + m = 0: a problem needs at least one unknown");
  if (N > kMaxDimension) p.Fail(Field{"m"}, "n + m = " + std::to_string(N) + " is too large");
  p.Reserve(N, Field{"n + m"});  // either storage holds at least n + m more numbers (q, or a and b)

  // Per row: true on complementarity rows. Type 2 fixes the layout: n equality rows, then m complementarity.
  std::vector<bool> complementarity(static_cast<std::size_t>(N), false);
  for (std::int64_t i = n; i < N; ++i) complementarity[static_cast<std::size_t>(i)] = true;

  MatrixBlock M1;
  Vector q1;
  if (type1) {
    std::vector<std::int64_t> starts;
    starts.push_back(p.ReadInt(Field{"blocksRows", 0}, 0, 0));
    while (starts.back() < N) {  // strictly increasing up to n + m, so at most n + m + 1 entries
      const auto k = static_cast<std::int64_t>(starts.size());
      starts.push_back(p.ReadInt(Field{"blocksRows", k}, starts.back() + 1, N));
    }
    std::int64_t equality_rows = 0;
    std::vector<bool> from_blocks(static_cast<std::size_t>(N), false);
    for (std::size_t b = 0; b + 1 < starts.size(); ++b) {
      const bool comp = p.ReadInt(Field{"blocksIsComp", static_cast<std::int64_t>(b)}, 0, 1) == 1;
      for (std::int64_t i = starts[b]; i < starts[b + 1]; ++i) from_blocks[static_cast<std::size_t>(i)] = comp;
      if (!comp) equality_rows += starts[b + 1] - starts[b];
    }
    if (equality_rows != n) {
      p.Fail(Field{"blocksIsComp"}, "the blocks mark " + std::to_string(equality_rows) +
                                        " equality rows but n = " + std::to_string(n));
    }
    if (type2 && from_blocks != complementarity) {
      p.Fail(Field{"blocksIsComp"},
             "the type-1 blocks do not put the n equality rows first, which disagrees with the type-2 layout "
             "(A, C rows then D, B rows)");
    }
    complementarity = from_blocks;
    // Siconos' Rectangular_mlcp.dat has a 3x2 M for n = m = 1 (and a q sized by the columns); its own test
    // collection leaves it out. A box-MLCP pairs each unknown with one row, so such a file is rejected here.
    M1 = ReadMatrix(p, N, N,
                    "n + m = " + std::to_string(N) +
                        "; a rectangular MLCP, with a row count different from the unknown count, has no box-MLCP "
                        "form");
    q1 = ReadFiniteVector(p, "q", N);
  }

  DenseMatrix M2;
  Vector q2;
  if (type2) {
    p.Reserve(n * n + m * m + 2 * n * m + n + m, Field{"A"});
    M2.resize(static_cast<Eigen::Index>(N), static_cast<Eigen::Index>(N));
    // Written row after row (unlike the column-major matrix blocks); M = [A C; D B].
    const auto read_rows = [&](const char* block, std::int64_t rows, std::int64_t cols, std::int64_t row0,
                               std::int64_t col0) {
      for (std::int64_t i = 0; i < rows; ++i) {
        for (std::int64_t j = 0; j < cols; ++j) {
          M2(static_cast<Eigen::Index>(row0 + i), static_cast<Eigen::Index>(col0 + j)) =
              p.ReadFinite(Field{block, i, j});
        }
      }
    };
    read_rows("A", n, n, 0, 0);
    read_rows("B", m, m, n, n);
    read_rows("C", n, m, 0, n);
    read_rows("D", m, n, n, 0);
    q2.resize(static_cast<Eigen::Index>(N));
    for (std::int64_t i = 0; i < n; ++i) q2[static_cast<Eigen::Index>(i)] = p.ReadFinite(Field{"a", i});
    for (std::int64_t i = 0; i < m; ++i) q2[static_cast<Eigen::Index>(n + i)] = p.ReadFinite(Field{"b", i});
  }

  if (type1 && type2) {
    const DenseMatrix dense1 = M1.is_sparse ? DenseMatrix(M1.sparse) : DenseMatrix();
    const DenseMatrix& D1 = M1.is_sparse ? dense1 : M1.dense;
    for (Eigen::Index j = 0; j < N; ++j) {
      for (Eigen::Index i = 0; i < N; ++i) {
        if (Agree(D1(i, j), M2(i, j))) continue;
        const bool top = i < n;
        const bool left = j < n;
        const char* block = top ? (left ? "A" : "C") : (left ? "D" : "B");
        const Eigen::Index bi = top ? i : i - n;
        const Eigen::Index bj = left ? j : j - n;
        p.Fail(Field{"M", i, j}, "the storages disagree: type 1 has M(" + std::to_string(i) + "," +
                                     std::to_string(j) + ") = " + NumberText(D1(i, j)) + " but type 2 has " + block +
                                     "(" + std::to_string(bi) + "," + std::to_string(bj) + ") = " +
                                     NumberText(M2(i, j)));
      }
    }
    for (Eigen::Index i = 0; i < N; ++i) {
      if (Agree(q1[i], q2[i])) continue;
      const std::string other = i < n ? "a[" + std::to_string(i) + "]" : "b[" + std::to_string(i - n) + "]";
      p.Fail(Field{"q", i}, "the storages disagree: type 1 has q[" + std::to_string(i) + "] = " + NumberText(q1[i]) +
                                " but type 2 has " + other + " = " + NumberText(q2[i]));
    }
  }
  // Older Siconos tools appended a reference solution (printed with %f) that Siconos' reader never reads; we
  // skip up to 2(n + m) such values (room for z and w) and reject more.
  p.CheckEnd(2 * N, type2 ? "b" : "q");

  const auto size = static_cast<Eigen::Index>(N);
  Vector l(size);
  Vector u = Vector::Constant(size, kInf);
  for (Eigen::Index i = 0; i < size; ++i) l[i] = complementarity[static_cast<std::size_t>(i)] ? 0.0 : -kInf;
  if (type1) return MakeProblem(source, std::move(M1), std::move(q1), std::move(l), std::move(u), name);
  MatrixBlock block;
  block.dense = std::move(M2);
  return MakeProblem(source, std::move(block), std::move(q2), std::move(l), std::move(u), name);
}

BoxMLCP Parse(std::string_view text, SiconosKind kind, const std::string& source, const std::string& name) {
  Parser p(text, source);
  switch (kind) {
    case SiconosKind::kLCP:
      return ParseLCP(p, source, name);
    case SiconosKind::kRelay:
      return ParseRelay(p, source, name);
    case SiconosKind::kMLCP:
      return ParseMLCP(p, source, name);
  }
  throw InvalidInputError(source + ": unknown SiconosKind " + std::to_string(static_cast<int>(kind)));
}

std::string Source(SiconosKind kind, const std::string& where) {
  return std::string("Siconos ") + KindName(kind) + " '" + where + "'";
}


std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

BoxMLCP ReadSiconosStream(std::istream& in, SiconosKind kind, const std::string& name) {
  const std::string source = Source(kind, name);
  const std::string text = ReadBoundedText(in, source);
  return Parse(text, kind, source, name);
}

BoxMLCP ReadSiconosFile(const std::string& path, SiconosKind kind) {
  const std::string source = Source(kind, path);
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InvalidInputError(source + ": is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InvalidInputError(source + ": cannot open file: " + std::generic_category().message(errno));
  }
  const std::string text = ReadBoundedText(in, source);
  return Parse(text, kind, source, std::filesystem::path(path).stem().string());
}

BoxMLCP ReadSiconosFile(const std::string& path) {
  const std::filesystem::path p(path);
  const std::string folder = Lower(p.parent_path().filename().string());
  const std::string file = Lower(p.filename().string());
  SiconosKind kind = SiconosKind::kLCP;
  if (folder == "lcp") {
    kind = SiconosKind::kLCP;
  } else if (folder == "relay") {
    kind = SiconosKind::kRelay;
  } else if (folder == "mlcp" || file.find("mlcp") != std::string::npos) {  // "relay2_mlcp.dat" is an MLCP
    kind = SiconosKind::kMLCP;
  } else if (file.find("relay") != std::string::npos) {
    kind = SiconosKind::kRelay;
  }
  return ReadSiconosFile(path, kind);
}

namespace {

void AppendVector(std::string* out, const Vector& v) {
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (i) out->push_back(' ');
    AppendNumberText(out, v[i]);
  }
  out->push_back('\n');
}

}  // namespace

void WriteSiconosRelay(const BoxMLCP& problem, std::ostream& out) {
  const Eigen::Index n = problem.size();
  DenseMatrix converted;
  if (problem.is_sparse()) converted = problem.ToDense();
  const DenseMatrix& M = problem.is_sparse() ? converted : problem.dense_matrix();
  std::string text;
  const std::string ns = std::to_string(n);
  text += ns + "\n0\n" + ns + "\n" + ns + "\n" + ns + "\t" + ns + "\n";
  // Column-major, one column per line, as Siconos' NM_write_in_file does.
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::Index i = 0; i < n; ++i) {
      if (i) text.push_back(' ');
      AppendNumberText(&text, M(i, j));
    }
    text.push_back('\n');
  }
  AppendVector(&text, problem.q());
  AppendVector(&text, problem.l());
  AppendVector(&text, problem.u());
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.flush();
  if (!out) throw InvalidInputError("WriteSiconosRelay: writing problem '" + problem.name() + "' failed");
}

void WriteSiconosRelayFile(const BoxMLCP& problem, const std::string& path) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) {
    throw InvalidInputError("WriteSiconosRelayFile: cannot open '" + path +
                            "' for writing: " + std::generic_category().message(errno));
  }
  WriteSiconosRelay(problem, out);
  out.close();
  if (!out) throw InvalidInputError("WriteSiconosRelayFile: closing '" + path + "' failed");
}

}  // namespace smcbench

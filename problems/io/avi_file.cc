// The AVI file (docs/formats.md, "AVI files"): a strict reader (every key known, every number finite, every size
// consistent) and a writer whose numbers read back bit for bit.
#include "problems/io/avi_file.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <utility>

#include "problems/io/read_text.h"
#include "solvers/avi/avi_solver.h"
#include "solvers/avi/avi_verdict.h"
#include "solvers/core/number_text.h"
#include "solvers/core/problem.h"

namespace smcbench {
namespace {

using nlohmann::json;

constexpr const char* kKnownKeys[] = {"format", "version", "name", "M", "q", "H", "K", "E", "f", "solution",
                                     "expected"};

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string Index(Eigen::Index i) { return "[" + std::to_string(i) + "]"; }

// Control bytes as \xNN (a key of the file in a one-line message).
std::string Escaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u != 0x7f) {
      out += c;
    } else {
      static const char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[u >> 4];
      out += kHex[u & 15];
    }
  }
  return out;
}

// Every message starts with the file and the field, so a user with many files knows where to look.
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  // field may be a key taken from the file: its control bytes are escaped, since a message must stay one line.
  [[noreturn]] void Fail(const std::string& field, const std::string& what) const {
    throw InvalidInputError("AVI file '" + source_ + "': " + (field.empty() ? "" : "\"" + Escaped(field) + "\": ") +
                            what);
  }

  double Number(const json& value, const std::string& field) const {
    // JSON has no NaN or infinity: a string such as "nan" is refused here as a wrong type (the parser itself
    // refuses a literal that overflows a double, 1e400).
    if (!value.is_number()) Fail(field, "expected a number, got " + Describe(value));
    const double x = value.get<double>();
    if (!std::isfinite(x)) Fail(field, "is not finite (" + NumberText(x) + ")");
    return x;
  }

  const json& Array(const json& value, const std::string& field) const {
    if (!value.is_array()) Fail(field, "expected an array, got " + Describe(value));
    return value;
  }

  // A vector; expected_size < 0: any size.
  Vector ReadVector(const json& value, const std::string& field, Eigen::Index expected_size,
                    const std::string& size_meaning) const {
    const json& array = Array(value, field);
    const auto size = static_cast<Eigen::Index>(array.size());
    if (expected_size >= 0 && size != expected_size) {
      Fail(field, "has " + std::to_string(size) + " entries, expected " + std::to_string(expected_size) + " (" +
                      size_meaning + ")");
    }
    Vector v(size);
    for (Eigen::Index i = 0; i < size; ++i) v[i] = Number(array[static_cast<std::size_t>(i)], field + Index(i));
    return v;
  }

  // A matrix as an array of rows, each of cols entries; expected_rows < 0: any row count.
  DenseMatrix ReadMatrix(const json& value, const std::string& field, Eigen::Index expected_rows,
                         Eigen::Index cols, const std::string& size_meaning) const {
    const json& rows = Array(value, field);
    const auto row_count = static_cast<Eigen::Index>(rows.size());
    if (expected_rows >= 0 && row_count != expected_rows) {
      Fail(field, "has " + std::to_string(row_count) + " rows, expected " + std::to_string(expected_rows) + " (" +
                      size_meaning + ")");
    }
    // Every row's length before the allocation: rows of empty brackets would otherwise claim rows × cols doubles
    // with a few bytes of text each.
    for (Eigen::Index i = 0; i < row_count; ++i) {
      const std::string row_field = field + Index(i);
      const json& row = Array(rows[static_cast<std::size_t>(i)], row_field);
      if (static_cast<Eigen::Index>(row.size()) != cols) {
        Fail(row_field, "has " + std::to_string(row.size()) + " entries, expected " + std::to_string(cols) +
                            " (n = the size of q): a ragged matrix");
      }
    }
    DenseMatrix A(row_count, cols);
    for (Eigen::Index i = 0; i < row_count; ++i) {
      const json& row = rows[static_cast<std::size_t>(i)];
      for (Eigen::Index j = 0; j < cols; ++j) {
        A(i, j) = Number(row[static_cast<std::size_t>(j)], field + Index(i) + Index(j));
      }
    }
    return A;
  }

  // An array or object is named by its size, never dumped: dump() recurses once per nesting level, and a file of
  // nested brackets would overflow the stack.
  static std::string Describe(const json& value) {
    if (value.is_array() || value.is_object()) {
      return std::string(value.type_name()) + " of " + std::to_string(value.size()) + " entries";
    }
    std::string text = value.dump();
    if (text.size() > 40) text = text.substr(0, 37) + "...";
    return std::string(value.type_name()) + " " + text;
  }

 private:
  std::string source_;
};

// "-0" would read back as the integer 0 and lose its sign; every other double's shortest form reads back exactly.
void AppendJsonNumber(std::string* out, double value) {
  if (value == 0.0 && std::signbit(value)) {
    out->append("-0.0");
    return;
  }
  AppendNumberText(out, value);
}

void AppendVector(std::string* out, const Vector& v) {
  out->push_back('[');
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (i > 0) out->append(", ");
    AppendJsonNumber(out, v[i]);
  }
  out->push_back(']');
}

void AppendMatrix(std::string* out, const DenseMatrix& A) {
  if (A.rows() == 0) {
    out->append("[]");
    return;
  }
  out->append("[\n");
  for (Eigen::Index i = 0; i < A.rows(); ++i) {
    out->append("    ");
    AppendVector(out, A.row(i).transpose());
    out->append(i + 1 < A.rows() ? ",\n" : "\n");
  }
  out->append("  ]");
}

std::string DefaultName(const std::string& path) {
  std::string file = std::filesystem::path(path).filename().string();
  for (const char* suffix : {kAviFileExtension, ".json"}) {
    const std::string s(suffix);
    if (file.size() > s.size() && Lower(file.substr(file.size() - s.size())) == s) {
      return file.substr(0, file.size() - s.size());
    }
  }
  return file;
}

}  // namespace

AviFile ParseAviText(const std::string& text, const std::string& source, const std::string& default_name) {
  const Reader reader(source);
  json doc;
  // A key given twice would silently keep the last value: refused, as a hand-edited file's slip.
  std::set<std::string> top_level_keys;
  const json::parser_callback_t refuse_repeated_keys = [&](int depth, json::parse_event_t event, json& parsed) {
    if (event == json::parse_event_t::key && depth == 1 && !top_level_keys.insert(parsed.get<std::string>()).second) {
      reader.Fail(parsed.get<std::string>(), "given twice");
    }
    return true;
  };
  try {
    doc = json::parse(text, refuse_repeated_keys);
  } catch (const json::exception& e) {
    reader.Fail("", std::string("not valid JSON: ") + e.what());
  }
  if (!doc.is_object()) reader.Fail("", "expected a JSON object, got " + Reader::Describe(doc));
  // The kind first: a scene file or another JSON document is named as such rather than by its first odd key.
  if (!doc.contains("format")) reader.Fail("format", "missing (expected \"" + std::string(kAviFileFormat) + "\")");
  if (!doc["format"].is_string() || doc["format"].get<std::string>() != kAviFileFormat) {
    reader.Fail("format", "expected \"" + std::string(kAviFileFormat) + "\", got " + Reader::Describe(doc["format"]));
  }
  if (!doc.contains("version")) reader.Fail("version", "missing (expected " + std::to_string(kAviFileVersion) + ")");
  if (!doc["version"].is_number_integer() || doc["version"].get<long long>() != kAviFileVersion) {
    reader.Fail("version", "unsupported version " + Reader::Describe(doc["version"]) + " (this reader knows " +
                               std::to_string(kAviFileVersion) + ")");
  }
  for (const auto& item : doc.items()) {
    const std::string& key = item.key();
    if (std::find_if(std::begin(kKnownKeys), std::end(kKnownKeys), [&](const char* k) { return key == k; }) ==
        std::end(kKnownKeys)) {
      std::string known;
      for (const char* k : kKnownKeys) known += (known.empty() ? "" : ", ") + std::string(k);
      reader.Fail(key, "unknown key (known: " + known + ")");
    }
  }
  for (const char* key : {"M", "q", "H", "K"}) {
    if (!doc.contains(key)) reader.Fail(key, "missing (M, q, H and K are required; H and K may be [])");
  }
  if (doc.contains("E") != doc.contains("f")) {
    reader.Fail(doc.contains("E") ? "f" : "E", std::string("missing: E and f come together (") +
                                                   (doc.contains("E") ? "E" : "f") + " is given)");
  }
  std::string name = default_name;
  if (doc.contains("name")) {
    if (!doc["name"].is_string()) reader.Fail("name", "expected a string, got " + Reader::Describe(doc["name"]));
    name = doc["name"].get<std::string>();
  }

  Vector q = reader.ReadVector(doc["q"], "q", -1, "");
  const Eigen::Index n = q.size();
  if (n == 0) reader.Fail("q", "is empty: an AVI has at least one unknown (n = the size of q)");
  DenseMatrix M = reader.ReadMatrix(doc["M"], "M", n, n, "M is n×n, n = the size of q");
  DenseMatrix H = reader.ReadMatrix(doc["H"], "H", -1, n, "");
  Vector K = reader.ReadVector(doc["K"], "K", H.rows(), "one per row of H");
  DenseMatrix E(0, n);
  Vector f(0);
  if (doc.contains("E")) {
    E = reader.ReadMatrix(doc["E"], "E", -1, n, "");
    f = reader.ReadVector(doc["f"], "f", E.rows(), "one per row of E");
  }
  Vector solution;
  if (doc.contains("solution")) solution = reader.ReadVector(doc["solution"], "solution", n, "n = the size of q");
  std::optional<ExpectedOutcome> expected;
  if (doc.contains("expected")) {
    const json& value = doc["expected"];
    if (value.is_string()) expected = ExpectedOutcomeFromString(value.get<std::string>());
    if (!expected) {
      reader.Fail("expected", "expected \"solvable\", \"infeasible\" or \"unknown\", got " + Reader::Describe(value));
    }
    if (*expected == ExpectedOutcome::kInfeasible && solution.size() > 0) {
      reader.Fail("expected", "\"infeasible\" contradicts the \"solution\" the file gives");
    }
  }

  std::optional<AffineVI> avi;
  try {
    avi.emplace(std::move(M), std::move(q), std::move(H), std::move(K), std::move(E), std::move(f), std::move(name));
  } catch (const InvalidInputError& e) {
    reader.Fail("", e.what());  // the constructor's own checks (a zero row, P empty) with the file named
  }
  if (solution.size() > 0) {
    // The reference is checked as any answer is judged: the AVI rule at multipliers recovered for it.
    const AviSolution answer = AviMultipliersAt(*avi, solution);
    const AviJudgement j = JudgeAvi(*avi, ExpectedOutcome::kUnknown, nullptr, SolveStatus::kSolved, answer,
                                    kAviFileSolutionTolerance);
    if (!PassesAviTolerance(j, kAviFileSolutionTolerance)) {
      reader.Fail("solution", "does not solve the AVI: primal infeasibility " + NumberText(j.primal_infeasibility) +
                                  ", complementarity " + NumberText(j.complementarity) + ", residual " +
                                  NumberText(j.residual.rel) + " rel / " + NumberText(j.residual.scaled) +
                                  " scaled (tolerance " + NumberText(kAviFileSolutionTolerance) + ")");
    }
  }
  if (expected == ExpectedOutcome::kInfeasible && avi->boundedness() == PolytopeBoundedness::kBounded) {
    reader.Fail("expected", "\"infeasible\", but P is bounded, so the AVI has a solution (Hartman–Stampacchia)");
  }
  const ExpectedOutcome outcome = expected ? *expected : ExpectedAviOutcome(*avi);
  return AviFile{std::move(*avi), std::move(solution), outcome};
}

AviFile ReadAviFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidInputError("AVI file '" + path + "': cannot open");
  const std::string text = ReadBoundedText(in, "AVI file '" + path + "'");
  return ParseAviText(text, path, DefaultName(path));
}

std::string AviFileText(const AffineVI& avi, const Vector& solution, std::optional<ExpectedOutcome> expected) {
  if (solution.size() != 0) {
    if (solution.size() != avi.size()) {
      throw InvalidInputError("WriteAviFile: solution has " + std::to_string(solution.size()) +
                              " entries, expected n = " + std::to_string(avi.size()));
    }
    for (Eigen::Index i = 0; i < solution.size(); ++i) {
      if (!std::isfinite(solution[i])) {
        throw InvalidInputError("WriteAviFile: solution" + Index(i) + " is not finite (" + NumberText(solution[i]) +
                                ")");
      }
    }
  }
  std::string out = "{\n  \"format\": \"" + std::string(kAviFileFormat) + "\",\n  \"version\": " +
                    std::to_string(kAviFileVersion) + ",\n  \"name\": " + json(avi.name()).dump() + ",\n";
  out += "  \"M\": ";
  AppendMatrix(&out, avi.M());
  out += ",\n  \"q\": ";
  AppendVector(&out, avi.q());
  out += ",\n  \"H\": ";
  AppendMatrix(&out, avi.H());
  out += ",\n  \"K\": ";
  AppendVector(&out, avi.K());
  if (avi.equality_count() > 0) {
    out += ",\n  \"E\": ";
    AppendMatrix(&out, avi.E());
    out += ",\n  \"f\": ";
    AppendVector(&out, avi.f());
  }
  if (solution.size() != 0) {
    out += ",\n  \"solution\": ";
    AppendVector(&out, solution);
  }
  if (expected) out += ",\n  \"expected\": \"" + std::string(ToString(*expected)) + "\"";
  out += "\n}\n";
  return out;
}

void WriteAviFile(const AffineVI& avi, const std::string& path, const Vector& solution,
                  std::optional<ExpectedOutcome> expected) {
  const std::string text = AviFileText(avi, solution, expected);
  std::ofstream out(path, std::ios::binary);
  if (!out) throw InvalidInputError("WriteAviFile: cannot write '" + path + "'");
  out << text;
  out.flush();
  if (!out) throw InvalidInputError("WriteAviFile: error writing '" + path + "'");
}

bool HasAviFileExtension(const std::string& path) {
  const std::string s(kAviFileExtension);
  return path.size() > s.size() && Lower(path.substr(path.size() - s.size())) == s;
}

}  // namespace smcbench

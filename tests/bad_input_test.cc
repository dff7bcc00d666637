// The bad-input table: every kind of bad input a user can give, through the entry points a user meets (the
// smcbench command line run in-process, and the library API), and what they get back. Each case asserts no crash,
// a one-line error naming the defect, and the exit code; with SMCBENCH_BAD_INPUT_TABLE=<path> the table checked
// here is also written as markdown (the table of docs/bad-input.md is this output).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "problems/io/siconos_format.h"
#include "problems/scenes/registry.h"
#include "solvers/registry/registry.h"
#include "tools/smcbench/cli_test_runner.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// What the user got: how ("exit 1", "InvalidInputError", ...) and the first line of the message.
struct Outcome {
  std::string how;
  std::string message;
  int lines = 0;  // lines of error output (CLI) or of the message (API)
};

int CountLines(const std::string& text) {
  int lines = 0;
  for (char c : text) lines += c == '\n';
  if (!text.empty() && text.back() != '\n') ++lines;
  return lines;
}

std::string FirstLine(const std::string& text) { return text.substr(0, text.find('\n')); }

// The folder holding this test's input files; paths under it are shown relative in the table.
const fs::path& Dir() {
  static const fs::path dir = fs::temp_directory_path() / ("smcbench_bad_input_" + std::to_string(::getpid()));
  return dir;
}

std::string Write(const std::string& name, const std::string& text) {
  fs::create_directories(Dir());
  const fs::path path = Dir() / name;
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

Outcome Cli(std::vector<std::string> args) {
  const test_support::CliRun r = test_support::RunSmcbench(std::move(args));
  return {"exit " + std::to_string(r.code), FirstLine(r.err), CountLines(r.err)};
}

template <typename Fn>
Outcome Throws(Fn fn) {
  try {
    fn();
  } catch (const InvalidInputError& e) {
    return {"InvalidInputError", FirstLine(e.what()), CountLines(e.what())};
  } catch (const std::exception& e) {
    return {std::string("unexpected exception: ") + e.what(), "", 0};
  }
  return {"no error", "", 0};
}

Outcome SetOptionOutcome(const std::string& backend, const std::string& name, const std::string& value) {
  std::string error;
  const bool ok = CreateSolver(backend)->SetOption(name, value, &error);
  return {ok ? "accepted" : "SetOption returns false", error, CountLines(error)};
}

Outcome SolveOutcome(const SolverOptions& options) {
  const BoxMLCP problem = BoxMLCP::LCP(DenseMatrix::Identity(2, 2), Vector::Constant(2, -1.0));
  const SolveResult result = CreateSolver("lemke")->Solve(problem, options);
  return {"status " + std::string(ToString(result.status)), result.message, CountLines(result.message)};
}

DenseMatrix Mat(int rows, int cols, double fill = 1.0) { return DenseMatrix::Constant(rows, cols, fill); }
Vector Vec(int n, double fill = 0.0) { return Vector::Constant(n, fill); }

// A valid relay file for n = 2 with one field replaced.
std::string Relay(const std::string& q, const std::string& lb, const std::string& ub) {
  return "2\n0\n2 2\n2 2\n2 1\n1 2\n" + q + "\n" + lb + "\n" + ub + "\n";
}

// A valid scene file (S1) with one field replaced.
std::string Scene(const std::string& simulation) {
  return R"({"format": "smcbench-scene/1", "name": "bad", "description": "d", "system": {"type": "sign", "E": [[0]], "B": [[1]],
             "C": [[1]]}, "simulation": )" +
         simulation + "}";
}

struct Case {
  const char* id;    // test name
  const char* kind;  // the kind of bad input (first column of the table)
  std::string tried;
  std::function<Outcome()> run;
  std::string expected_how;
  std::vector<std::string> keywords;  // all in the first line of the message
};

// Every bad input and the error it must get, as one table (docs/bad-input.md is written from it): a long function
// on purpose, since splitting a table would only scatter its rows.
std::vector<Case> AllCases() {
  return {
      // Files.
      {"TruncatedFileCli", "truncated file", "`smcbench solve truncated_lcp.dat` (file ends inside q)",
       [] { return Cli({"solve", Write("truncated_lcp.dat", "3\n0 3 3 3 3\n2 0 0 0 2 0 0 0 2\n-1 -1\n")}); },
       "exit 1", {"truncated_lcp.dat", "q[2]", "unexpected end of file (truncated data)", "(line 5)"}},
      {"EmptyFileCli", "truncated file", "`smcbench solve empty.dat` (0 bytes)",
       [] { return Cli({"solve", Write("empty.dat", "")}); }, "exit 1", {"empty.dat", "n: unexpected end of file"}},
      {"WrongSizesFile", "wrong sizes", "`smcbench solve wrong_size_lcp.dat` (n = 3, M 2x2)",
       [] { return Cli({"solve", Write("wrong_size_lcp.dat", "3\n0 2 2 2 2\n1 0 0 1\n-1 -1 -1\n")}); }, "exit 1",
       {"wrong_size_lcp.dat", "matrix is 2x2 but a 3x3 matrix is required"}},
      {"WrongSizesApi", "wrong sizes", "`BoxMLCP(M 2x2, q of size 3, l, u)`",
       [] { return Throws([] { BoxMLCP(Mat(2, 2), Vec(3), Vec(2), Vec(2, 1.0)); }); }, "InvalidInputError",
       {"BoxMLCP", "q has size 3 but M is 2x2"}},
      {"TrailingDataFile", "wrong sizes", "`smcbench solve extra_lcp.dat` (n = 2 but three q values)",
       [] { return Cli({"solve", Write("extra_lcp.dat", "2\n0 2 2 2 2\n1 0 0 1\n-1 -1 -1\n")}); }, "exit 1",
       {"extra_lcp.dat", "trailing data", "unexpected number '-1' after q"}},
      {"NanInMatrixFile", "NaN/Inf in M or q", "`smcbench solve nan_relay.dat` (an M entry is `nan`)",
       [] { return Cli({"solve", Write("nan_relay.dat", "2\n0\n2 2\n2 2\n2 nan\n1 2\n1 1\n-1 -1\n1 1\n")}); },
       "exit 1", {"nan_relay.dat", "M(1,0): is NaN"}},
      {"InfInQFile", "NaN/Inf in M or q", "`smcbench solve inf_relay.dat` (q[1] is `1e999`)",
       [] { return Cli({"solve", Write("inf_relay.dat", Relay("1 1e999", "-1 -1", "1 1"))}); }, "exit 1",
       {"inf_relay.dat", "q[1]: is infinite"}},
      {"NanInMatrixApi", "NaN/Inf in M or q", "`BoxMLCP::LCP(M with M(0,1) = NaN, q)`",
       [] {
         return Throws([] {
           DenseMatrix M = Mat(2, 2);
           M(0, 1) = std::nan("");
           BoxMLCP::LCP(M, Vec(2));
         });
       },
       "InvalidInputError", {"BoxMLCP", "M(0,1) is NaN"}},
      {"InfInQApi", "NaN/Inf in M or q", "`BoxMLCP::LCP(M, q with q[1] = inf)`",
       [] {
         return Throws([] {
           Vector q = Vec(2);
           q[1] = kInf;
           BoxMLCP::LCP(Mat(2, 2), q);
         });
       },
       "InvalidInputError", {"BoxMLCP", "q[1] is infinite"}},
      {"LowerAboveUpperFile", "l > u", "`smcbench solve crossed_relay.dat` (lb = 1, ub = -1 on row 0)",
       [] { return Cli({"solve", Write("crossed_relay.dat", Relay("1 1", "1 -1", "-1 1"))}); }, "exit 1",
       {"crossed_relay.dat", "lb[0] = 1 > ub[0] = -1"}},
      {"LowerAboveUpperApi", "l > u", "`BoxMLCP(M, q, l = (0, 2), u = (1, 1))`",
       [] {
         return Throws([] {
           Vector l(2);
           l << 0, 2;
           BoxMLCP(Mat(2, 2), Vec(2), l, Vec(2, 1.0));
         });
       },
       "InvalidInputError", {"BoxMLCP", "l[1] = 2 > u[1] = 1"}},
      {"NanBoundFile", "NaN bound", "`smcbench solve nan_bound_relay.dat` (ub[1] is `nan`)",
       [] { return Cli({"solve", Write("nan_bound_relay.dat", Relay("1 1", "-1 -1", "1 nan"))}); }, "exit 1",
       {"nan_bound_relay.dat", "ub[1]: is NaN"}},
      {"NanBoundApi", "NaN bound", "`BoxMLCP::Relay(M, q, lower = NaN)`",
       [] { return Throws([] { BoxMLCP::Relay(Mat(2, 2), Vec(2), std::nan("")); }); }, "InvalidInputError",
       {"BoxMLCP", "l[0] is NaN"}},
      {"InfiniteLowerBoundFile", "NaN bound", "`smcbench solve inf_bound_relay.dat` (lb[0] is `inf`)",
       [] { return Cli({"solve", Write("inf_bound_relay.dat", Relay("1 1", "inf -1", "inf 1"))}); }, "exit 1",
       {"inf_bound_relay.dat", "lb[0]: is inf (no feasible point)"}},
      {"NonSquareApi", "non-square M", "`BoxMLCP(M 2x3, q, l, u of size 2)`",
       [] { return Throws([] { BoxMLCP(Mat(2, 3), Vec(2), Vec(2), Vec(2, 1.0)); }); }, "InvalidInputError",
       {"BoxMLCP", "M is 2x3 but must be square"}},
      {"NonSquareFile", "non-square M", "`smcbench solve rect_lcp.dat` (n = 2, M declared 2x3)",
       [] { return Cli({"solve", Write("rect_lcp.dat", "2\n0 2 3 2 3\n1 0 0 1 1 1\n-1 -1\n")}); }, "exit 1",
       {"rect_lcp.dat", "matrix is 2x3 but a 2x2 matrix is required"}},
      {"EmptyProblemApi", "empty problem (n = 0)", "`BoxMLCP(M 0x0, empty q, l, u)`",
       [] { return Throws([] { BoxMLCP(DenseMatrix(0, 0), Vector(0), Vector(0), Vector(0)); }); },
       "InvalidInputError", {"BoxMLCP", "empty problem (M is 0x0)"}},
      {"EmptyProblemFile", "empty problem (n = 0)", "`smcbench solve zero_lcp.dat` (n = 0)",
       [] { return Cli({"solve", Write("zero_lcp.dat", "0\n0 0 0 0 0\n")}); }, "exit 1",
       {"zero_lcp.dat", "n: value '0' out of range [1,"}},
      {"EmptyMlcpFile", "empty problem (n = 0)", "`smcbench solve zero_mlcp.dat` (MLCP with n = m = 0)",
       [] { return Cli({"solve", Write("zero_mlcp.dat", "1 0\n0 0\n")}); }, "exit 1",
       {"zero_mlcp.dat", "n + m = 0: a problem needs at least one unknown"}},
      {"MissingFileCli", "unreadable or missing file", "`smcbench solve /nonexistent/problem.dat`",
       [] { return Cli({"solve", "/nonexistent/problem.dat"}); }, "exit 1",
       {"/nonexistent/problem.dat", "cannot open file: No such file or directory"}},
      {"DirectoryApi", "unreadable or missing file", "`ReadSiconosFile(\"<a folder>\")`",
       [] {
         fs::create_directories(Dir() / "lcp");
         return Throws([] { ReadSiconosFile((Dir() / "lcp").string()); });
       },
       "InvalidInputError", {"is a directory, not a file"}},
      {"MissingSceneFileCli", "unreadable or missing file", "`smcbench simulate missing.json`",
       [] { return Cli({"simulate", "missing.json"}); }, "exit 1", {"scene file 'missing.json': cannot be read"}},
      {"UnknownSolverCli", "unknown solver", "`smcbench solve relay.dat --solver simplex`",
       [] { return Cli({"solve", Write("relay.dat", Relay("1 1", "-1 -1", "1 1")), "--solver", "simplex"}); },
       "exit 1", {"unknown solver 'simplex' (known: lemke, psor, newton, enum, ipopt"}},
      {"UnknownSolverApi", "unknown solver", "`CreateSolver(\"simplex\")`",
       [] { return Throws([] { CreateSolver("simplex"); }); }, "InvalidInputError",
       {"unknown solver 'simplex' (known: lemke"}},
      {"UnknownSceneCli", "unknown scene", "`smcbench simulate nosuchscene`",
       [] { return Cli({"simulate", "nosuchscene"}); }, "exit 1",
       {"unknown scene 'nosuchscene' (known: sign, galias-yu-2007", "or give the path of a scene file"}},
      {"UnknownSceneApi", "unknown scene", "`LoadScene(\"nosuchscene\")`",
       [] { return Throws([] { LoadScene("nosuchscene"); }); }, "InvalidInputError", {"unknown scene 'nosuchscene'"}},
      {"NegativeToleranceCli", "invalid options", "`smcbench solve relay.dat --tol -1`",
       [] { return Cli({"solve", Write("relay.dat", Relay("1 1", "-1 -1", "1 1")), "--tol", "-1"}); }, "exit 2",
       {"--tol", "-1"}},
      {"NegativeToleranceApi", "invalid options", "`Solve(problem, options with tolerance = -1)`",
       [] {
         SolverOptions options;
         options.tolerance = -1.0;
         return SolveOutcome(options);
       },
       "status invalid_options", {"tolerance must be a positive finite number, got -1"}},
      {"OmegaOutOfRangeCli", "invalid options", "`smcbench solve relay.dat --solver psor --set psor.omega=3`",
       [] {
         return Cli({"solve", Write("relay.dat", Relay("1 1", "-1 -1", "1 1")), "--solver", "psor", "--set",
                     "psor.omega=3"});
       },
       "exit 1", {"psor: invalid value for option 'omega'", "omega must lie in the open interval (0, 2)"}},
      {"OmegaOutOfRangeApi", "invalid options", "`CreateSolver(\"psor\")->SetOption(\"omega\", \"0\")`",
       [] { return SetOptionOutcome("psor", "omega", "0"); }, "SetOption returns false",
       {"invalid value for option 'omega'"}},
      {"UnknownOptionCli", "invalid options", "`smcbench solve relay.dat --set psor.nosuchoption=1`",
       [] {
         return Cli({"solve", Write("relay.dat", Relay("1 1", "-1 -1", "1 1")), "--set", "psor.nosuchoption=1"});
       },
       "exit 1", {"psor: unknown option 'nosuchoption' (known: omega"}},
      {"UnknownOptionApi", "invalid options", "`CreateSolver(\"lemke\")->SetOption(\"omega\", \"1\")`",
       [] { return SetOptionOutcome("lemke", "omega", "1"); }, "SetOption returns false",
       {"unknown option 'omega' (known: pivot_tolerance"}},
      {"NonNumericOptionCli", "invalid options", "`smcbench solve relay.dat --set psor.omega=fast`",
       [] {
         return Cli({"solve", Write("relay.dat", Relay("1 1", "-1 -1", "1 1")), "--set", "psor.omega=fast"});
       },
       "exit 1", {"option 'omega' expects a number, got 'fast'"}},
      {"MalformedSetCli", "invalid options", "`smcbench solve relay.dat --set omega=1.5`",
       [] { return Cli({"solve", Write("relay.dat", Relay("1 1", "-1 -1", "1 1")), "--set", "omega=1.5"}); },
       "exit 1", {"--set expects BACKEND.OPTION=VALUE, got 'omega=1.5'"}},
      {"UnknownSubcommandCli", "invalid options", "`smcbench frobnicate`", [] { return Cli({"frobnicate"}); },
       "exit 2", {"unknown command 'frobnicate'", "known: list, solve"}},
      {"StepNotPositiveCli", "h <= 0", "`smcbench simulate sign --h 0`",
       [] { return Cli({"simulate", "sign", "--h", "0"}); }, "exit 1",
       {"simulate sign", "h must be a positive finite time step, got 0"}},
      {"StepNotPositiveSceneFile", "h <= 0", "`smcbench simulate h0.json` (`\"h\": -0.1` in the file)",
       [] {
         return Cli({"simulate", Write("h0.json", Scene(R"({"method": "implicit", "h": -0.1, "T": 1, "x0": [1]})"))});
       },
       "exit 1", {"h0.json", "simulation.h: must be > 0, got -0.1"}},
      {"ThetaOutsideCli", "theta outside [0, 1]", "`smcbench simulate sign --theta 1.5`",
       [] { return Cli({"simulate", "sign", "--theta", "1.5"}); }, "exit 1",
       {"simulate sign", "theta must lie in [0, 1], got 1.5"}},
      {"ThetaOutsideSceneFile", "theta outside [0, 1]", "`smcbench simulate theta.json` (`\"theta\": -1`)",
       [] {
         return Cli({"simulate",
                     Write("theta.json", Scene(R"({"method": "implicit", "theta": -1, "h": 0.1, "T": 1, "x0": [1]})"))});
       },
       "exit 1", {"theta.json", "simulation.theta: must lie in [0, 1], got -1"}},
      {"MalformedSceneJsonCli", "malformed scene JSON", "`smcbench simulate broken.json` (JSON cut short)",
       [] { return Cli({"simulate", Write("broken.json", R"({"name": "x",)")}); }, "exit 1",
       {"broken.json", "not valid JSON"}},
      {"SceneWrongShapeCli", "malformed scene JSON", "`smcbench simulate shape.json` (B has 2 rows, n = 1)",
       [] {
         return Cli({"simulate", Write("shape.json", R"({"format": "smcbench-scene/1", "name": "shape", "description": "d",
             "system": {"type": "sign", "E": [[0]], "B": [[1], [1]], "C": [[1]]},
             "simulation": {"method": "implicit", "h": 0.1, "T": 1, "x0": [1]}})")});
       },
       "exit 1", {"shape.json", "system.B"}},
      {"SceneBadExpressionCli", "malformed scene JSON", "`smcbench simulate expr.json` (an entry of E is `\"1/\"`)",
       [] {
         return Cli({"simulate", Write("expr.json", R"({"format": "smcbench-scene/1", "name": "expr", "description": "d",
             "system": {"type": "sign", "E": [["1/"]], "B": [[1]], "C": [[1]]},
             "simulation": {"method": "implicit", "h": 0.1, "T": 1, "x0": [1]}})")});
       },
       "exit 1", {"expr.json", "system.E[0][0]", "expression '1/': expression ends early"}},
  };
}

// Paths under Dir() shown relative, lists of known names cut to three (the list depends on the optional backends
// built in), markdown table cells escaped, at most 150 characters.
std::string ForTable(std::string text) {
  const std::string prefix = Dir().string() + "/";
  for (std::size_t at; (at = text.find(prefix)) != std::string::npos;) text.erase(at, prefix.size());
  const std::size_t known = text.find("(known: ");
  const std::size_t close = known == std::string::npos ? known : text.find_first_of(");", known);
  if (close != std::string::npos) {
    std::size_t cut = known;
    for (int names = 0; names < 3 && cut != std::string::npos && cut < close; ++names) cut = text.find(", ", cut + 1);
    if (cut != std::string::npos && cut < close) text.replace(cut, close - cut, ", ...");
  }
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  if (out.size() > 150) out = out.substr(0, 147) + "...";
  return out;
}

void Check(const Case& c, const Outcome& o) {
  EXPECT_EQ(o.how, c.expected_how) << c.tried << ": " << o.message;
  for (const std::string& keyword : c.keywords) EXPECT_THAT(o.message, HasSubstr(keyword)) << c.tried;
  if (o.how == "exit 1" || o.how == "InvalidInputError" || o.how.rfind("status", 0) == 0 ||
      o.how.rfind("SetOption", 0) == 0) {
    EXPECT_EQ(o.lines, 1) << c.tried << ": the error is one line";
  }
  if (o.how == "exit 1") {
    EXPECT_THAT(o.message, ::testing::StartsWith("smcbench: ")) << c.tried;
  }
  if (o.how == "exit 2") {
    EXPECT_GE(o.lines, 1) << c.tried << ": a usage error says something";
  }
}

// The kinds of bad input, in the table's order; one test each (a test process per case would cost more than the
// cases themselves).
struct Kind {
  const char* id;
  const char* text;
};
constexpr Kind kKinds[] = {
    {"TruncatedFile", "truncated file"},
    {"WrongSizes", "wrong sizes"},
    {"NanOrInfInMOrQ", "NaN/Inf in M or q"},
    {"LowerAboveUpper", "l > u"},
    {"NanBound", "NaN bound"},
    {"NonSquareM", "non-square M"},
    {"EmptyProblem", "empty problem (n = 0)"},
    {"UnreadableOrMissingFile", "unreadable or missing file"},
    {"UnknownSolver", "unknown solver"},
    {"UnknownScene", "unknown scene"},
    {"InvalidOptions", "invalid options"},
    {"StepNotPositive", "h <= 0"},
    {"ThetaOutsideUnitInterval", "theta outside [0, 1]"},
    {"MalformedSceneJson", "malformed scene JSON"},
};

// gtest prints a failing parameter with this.
void PrintTo(const Kind& k, std::ostream* out) { *out << k.text; }

class BadInput : public ::testing::TestWithParam<Kind> {
 protected:
  static void TearDownTestSuite() { fs::remove_all(Dir()); }
};

TEST_P(BadInput, IsAClearErrorNeverACrash) {
  int cases = 0;
  for (const Case& c : AllCases()) {
    if (std::string(c.kind) != GetParam().text) continue;
    SCOPED_TRACE(c.id);
    Check(c, c.run());
    ++cases;
  }
  EXPECT_GT(cases, 0);
}

INSTANTIATE_TEST_SUITE_P(Table, BadInput, ::testing::ValuesIn(kKinds),
                         [](const ::testing::TestParamInfo<Kind>& info) { return std::string(info.param.id); });

TEST(BadInputTable, EveryCaseHasAKnownKind) {
  for (const Case& c : AllCases()) {
    bool known = false;
    for (const Kind& k : kKinds) known = known || std::string(c.kind) == k.text;
    EXPECT_TRUE(known) << c.id << ": kind '" << c.kind << "' is not in kKinds";
  }
}

// Runs every case and, if SMCBENCH_BAD_INPUT_TABLE names a file, writes the table of docs/bad-input.md there.
TEST(BadInputTable, WritesTheMarkdownTableWhenAsked) {
  const char* path = std::getenv("SMCBENCH_BAD_INPUT_TABLE");
  if (!path || !*path) GTEST_SKIP() << "set SMCBENCH_BAD_INPUT_TABLE=<file> to write the table";
  std::string table =
      "| kind of bad input | what was tried | what the user gets |\n|---|---|---|\n";
  for (const Case& c : AllCases()) {
    const Outcome o = c.run();
    Check(c, o);
    table += "| " + std::string(c.kind) + " | " + ForTable(c.tried) + " | " + o.how +
             (o.message.empty() ? "" : ": `" + ForTable(o.message) + "`") + " |\n";
  }
  fs::remove_all(Dir());
  std::ofstream out(path);
  out << table;
  ASSERT_TRUE(out.good()) << "cannot write " << path;
}

}  // namespace
}  // namespace smcbench

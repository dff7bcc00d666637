// The gnuplot writer: quoting, the terminal lines, a figure gnuplot really draws (and redraws from its own script),
// and every failure as an InvalidInputError that says what failed.
#include "bench/figures/gnuplot_figure.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "solvers/core/problem.h"

namespace smcbench {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

// A fresh folder, removed afterwards; its name holds a quote and a space, which the scripts must quote.
class GnuplotFigure : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("smcbench-figure-test-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name() + " it's");
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path dir_;
};

bool IsPng(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[8] = {};
  in.read(magic, 8);
  return in && std::string(magic + 1, 3) == "PNG";
}

// Restores PATH when it goes out of scope.
struct PathGuard {
  std::string saved = std::getenv("PATH") ? std::getenv("PATH") : "";
  ~PathGuard() { ::setenv("PATH", saved.c_str(), 1); }
};

TEST(GnuplotQuote, DoublesQuotesAndRefusesNewlines) {
  EXPECT_EQ(GnuplotQuote("plain"), "'plain'");
  EXPECT_EQ(GnuplotQuote("it's a 'test'"), "'it''s a ''test'''");
  EXPECT_EQ(GnuplotQuote(""), "''");
  EXPECT_THROW(GnuplotQuote("two\nlines"), InvalidInputError);
}

TEST(GnuplotPngPreamble, SelectsASizedTerminalAndQuotesTheOutput) {
  const std::string preamble = GnuplotPngPreamble(640, 480, "/tmp/a 'b'.png");
  EXPECT_THAT(preamble, HasSubstr("set terminal pngcairo size 640,480"));
  EXPECT_THAT(preamble, HasSubstr("set terminal png size 640,480"));  // the fallback without cairo
  EXPECT_THAT(preamble, HasSubstr("set output '/tmp/a ''b''.png'\n"));
}

TEST_F(GnuplotFigure, MissingGnuplotIsAnInvalidInputErrorNamingTheCaller) {
  PathGuard guard;
  ::setenv("PATH", "/nonexistent", 1);
  EXPECT_FALSE(GnuplotAvailable());
  try {
    RunGnuplot("plot x\n", (dir_ / "x.png").string(), "report");
    FAIL() << "no error without gnuplot";
  } catch (const InvalidInputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("report needs gnuplot (Debian package gnuplot-nox), which is not on PATH"));
  }
  EXPECT_THROW(WriteGnuplotFigure(dir_.string(), "f", "1 1\n", "plot 'f.dat'\n", 300, 200, "smc-sweep"),
               InvalidInputError);
  EXPECT_FALSE(fs::exists(dir_ / "f.png"));
}

TEST_F(GnuplotFigure, WritesDataScriptPngAndSvgThatTheScriptRemakes) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot not installed (Debian package gnuplot-nox)";
  const std::string body = "set title " + GnuplotQuote("squares, 'quoted'") +
                           "\nplot 'f.dat' index 0 using 1:2 with lines title 'x^2', 'f.dat' index 1 using 1:2 "
                           "with points title 'x'\n";
  WriteGnuplotFigure(dir_.string(), "f", "1 1\n2 4\n3 9\n\n\n1 1\n2 2\n", body, 400, 300, "test");
  for (const char* name : {"f.dat", "f.gp", "f.png", "f.svg"}) EXPECT_TRUE(fs::is_regular_file(dir_ / name)) << name;
  EXPECT_TRUE(IsPng(dir_ / "f.png"));
  std::ifstream gp(dir_ / "f.gp");
  std::string first;
  std::getline(gp, first);
  EXPECT_THAT(first, HasSubstr("Made by `smcbench test`"));
  // The script stands alone: run in its folder it redraws both files.
  fs::remove(dir_ / "f.png");
  fs::remove(dir_ / "f.svg");
  const std::string command = "cd '" + dir_.string().replace(dir_.string().find('\''), 1, "'\\''") +
                              "' && gnuplot f.gp 2>/dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0);
  EXPECT_TRUE(IsPng(dir_ / "f.png"));
  EXPECT_GT(fs::file_size(dir_ / "f.svg"), 0u);
}

TEST_F(GnuplotFigure, AFailingScriptReportsGnuplotsLastErrorLine) {
  if (!GnuplotAvailable()) GTEST_SKIP() << "gnuplot not installed (Debian package gnuplot-nox)";
  const std::string png = (dir_ / "bad.png").string();
  try {
    RunGnuplot(GnuplotPngPreamble(300, 200, png) + "plot 'no-such-file.dat' using 1:2\n", png, "--plot");
    FAIL() << "gnuplot accepted a missing data file";
  } catch (const InvalidInputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("--plot: gnuplot failed to write '" + png + "'"));
    EXPECT_THAT(e.what(), HasSubstr("No data in plot"));  // gnuplot's own last line
  }
}

}  // namespace
}  // namespace smcbench

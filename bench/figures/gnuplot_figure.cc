#include "bench/figures/gnuplot_figure.h"

#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "solvers/core/problem.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;

// POSIX shell single-quoted word.
std::string ShellQuote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// A fresh path in the temporary folder (the caller removes it): distinct per process and per call.
fs::path TempPath(const std::string& stem, const std::string& extension) {
  static std::atomic<int> counter{0};
  return fs::temp_directory_path() /
         ("smcbench-" + stem + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + extension);
}

// Removes a file when it goes out of scope.
struct TempFile {
  fs::path path;
  ~TempFile() {
    std::error_code ec;
    if (!path.empty()) fs::remove(path, ec);
  }
};

}  // namespace

bool GnuplotAvailable() {
  const char* path = std::getenv("PATH");
  if (!path) return false;
  std::stringstream ss(path);
  for (std::string dir; std::getline(ss, dir, ':');) {
    if (dir.empty()) dir = ".";
    const std::string candidate = dir + "/gnuplot";
    std::error_code ec;
    if (::access(candidate.c_str(), X_OK) == 0 && fs::is_regular_file(candidate, ec)) return true;
  }
  return false;
}

std::string GnuplotPngPreamble(int width, int height, const std::string& png_path) {
  const std::string size = " size " + std::to_string(width) + "," + std::to_string(height);
  return "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) { set terminal pngcairo" + size +
         " noenhanced font ',10' } else { set terminal png" + size + " noenhanced }\nset output " +
         GnuplotQuote(png_path) + "\n";
}

std::string GnuplotQuote(const std::string& text) {
  if (text.find('\n') != std::string::npos) throw InvalidInputError("gnuplot: text contains a newline: " + text);
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

void WriteGnuplotFigure(const std::string& dir, const std::string& stem, const std::string& data,
                        const std::string& body, int width, int height, const std::string& made_by) {
  const fs::path folder(dir);
  const auto write = [&](const fs::path& path, const std::string& text) {
    std::ofstream out(path);
    out << text;
    if (!out) throw InvalidInputError(made_by + ": cannot write '" + path.string() + "'");
  };
  write(folder / (stem + ".dat"), data);
  const std::string size = std::to_string(width) + "," + std::to_string(height);
  std::ostringstream script;
  script << "# Made by `smcbench " << made_by << "`; remake " << stem << ".png and " << stem << ".svg with `gnuplot "
         << stem << ".gp` in this folder.\n# Data: " << stem << ".dat (one block per curve, in the order of the plot "
         << "command).\n"
         << GnuplotPngPreamble(width, height, stem + ".png") << body << "unset output\nset terminal svg size " << size
         << " dynamic noenhanced font 'sans,11'\nset output " << GnuplotQuote(stem + ".svg") << "\n"
         << body << "unset output\n";  // the body again, not replot: replot cannot redo a multiplot
  write(folder / (stem + ".gp"), script.str());
  RunGnuplot("cd " + GnuplotQuote(fs::absolute(folder).string()) + "\n" + script.str(),
             (folder / (stem + ".png")).string(), made_by);
  std::error_code ec;
  if (!fs::is_regular_file(folder / (stem + ".svg"), ec)) {
    throw InvalidInputError(made_by + ": gnuplot wrote no '" + (folder / (stem + ".svg")).string() + "'");
  }
}

void RunGnuplot(const std::string& script_text, const std::string& png_path, const std::string& what) {
  if (!GnuplotAvailable()) {
    throw InvalidInputError(what + " needs gnuplot (Debian package gnuplot-nox), which is not on PATH");
  }
  TempFile script{TempPath("plot", ".gp")};
  TempFile log{TempPath("plot", ".log")};
  {
    std::ofstream out(script.path);
    out << script_text;
    if (!out) throw InvalidInputError(what + ": cannot write the gnuplot script " + script.path.string());
  }
  const std::string command = "gnuplot " + ShellQuote(script.path.string()) + " 2> " + ShellQuote(log.path.string());
  const int rc = std::system(command.c_str());
  std::error_code ec;
  if (rc != 0 || !fs::is_regular_file(png_path, ec) || fs::file_size(png_path, ec) == 0) {
    std::ifstream in(log.path);
    std::string line, last;
    while (std::getline(in, line)) {
      if (!line.empty()) last = line;
    }
    throw InvalidInputError(what + ": gnuplot failed to write '" + png_path + "' (exit status " + std::to_string(rc) +
                            (last.empty() ? ")" : "): " + last));
  }
}

}  // namespace smcbench

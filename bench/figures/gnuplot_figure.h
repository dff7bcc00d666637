// The project's one gnuplot writer: every figure of `simulate --plot`, `report`, `report --history`, `paper` and
// `smc-sweep` is a gnuplot script run here, so quoting, terminals and error messages are the same everywhere.
#pragma once

#include <string>

namespace smcbench {

// True if an executable named gnuplot is on PATH.
bool GnuplotAvailable();

// Runs a gnuplot script that writes png_path. InvalidInputError starting with `what` if gnuplot is missing
// ("--plot needs gnuplot (Debian package gnuplot-nox), which is not on PATH"), fails or writes nothing
// ("--plot: gnuplot failed to write 'x.png' (exit status 1): <its last error line>").
void RunGnuplot(const std::string& script, const std::string& png_path, const std::string& what);

// The lines that select a PNG terminal (pngcairo when available) of this size writing png_path.
std::string GnuplotPngPreamble(int width, int height, const std::string& png_path);

// A gnuplot single-quoted string ('' for a quote); InvalidInputError if text holds a newline (gnuplot has no
// escape for it inside single quotes).
std::string GnuplotQuote(const std::string& text);

// A figure a user can restyle: dir/STEM.dat (data), dir/STEM.gp (the gnuplot script: reads STEM.dat, writes STEM.png
// and STEM.svg; `cd DIR && gnuplot STEM.gp` remakes both), then runs it. body: the settings and the plot command,
// naming the data file 'STEM.dat'. made_by names the command in the script's first line and in errors
// ("smc-sweep: gnuplot wrote no 'x.svg'").
void WriteGnuplotFigure(const std::string& dir, const std::string& stem, const std::string& data,
                        const std::string& body, int width, int height, const std::string& made_by);

}  // namespace smcbench

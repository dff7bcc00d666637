#include "problems/stepper/trajectory.h"

#include <charconv>
#include <fstream>
#include <ostream>

#include "solvers/core/number_text.h"
#include "solvers/core/problem.h"

namespace smcbench {
namespace {

// Appends value in shortest round-trip form (no locale, no allocation).
void Append(double value, std::string* line) { AppendNumberText(line, value); }

void Append(long long value, std::string* line) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  line->append(buffer, result.ptr);
}

}  // namespace

void WriteTrajectoryCsv(const Trajectory& trajectory, std::ostream& out) {
  const Trajectory& tr = trajectory;
  if (!tr.recorded) {
    throw InvalidInputError("WriteTrajectoryCsv: the trajectory was not recorded (StepperOptions::record = false)");
  }
  std::string line = "t";
  for (int i = 1; i <= tr.n; ++i) line += ",x" + std::to_string(i);
  for (int i = 1; i <= tr.m; ++i) line += ",s" + std::to_string(i);
  for (int i = 1; i <= tr.m; ++i) line += ",y" + std::to_string(i);
  line += ",iterations,residual\n";
  out << line;
  const std::int64_t rows = tr.steps_taken + 1;
  for (std::int64_t k = 0; k < rows; ++k) {
    line.clear();
    Append(tr.t[k], &line);
    for (int i = 0; i < tr.n; ++i) line.push_back(','), Append(tr.x(i, k), &line);
    for (int i = 0; i < tr.m; ++i) line.push_back(','), Append(tr.s(i, k), &line);
    for (int i = 0; i < tr.m; ++i) line.push_back(','), Append(tr.y(i, k), &line);
    line.push_back(',');
    Append(static_cast<long long>(tr.iterations[k]), &line);
    line.push_back(',');
    Append(tr.residual[k], &line);
    line.push_back('\n');
    out << line;
  }
  if (!out) throw InvalidInputError("WriteTrajectoryCsv: writing to the stream failed");
}

void WriteTrajectoryCsvFile(const Trajectory& trajectory, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw InvalidInputError("WriteTrajectoryCsvFile: cannot open '" + path + "' for writing");
  WriteTrajectoryCsv(trajectory, out);
  out.flush();
  if (!out) throw InvalidInputError("WriteTrajectoryCsvFile: writing '" + path + "' failed");
}

}  // namespace smcbench

#include "bench/perf/callgrind_dump.h"

#include <cstdlib>

#include "solvers/core/problem.h"

namespace smcbench {
namespace {

bool StartsWith(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }

}  // namespace

CallgrindDump ParseCallgrindDump(std::string_view text, const std::string& where) {
  constexpr std::string_view kTrigger = "desc: Trigger: Client Request: ";
  CallgrindDump dump;
  bool has_totals = false, has_summary = false, ir_first = false;
  double summary = 0.0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    if (StartsWith(line, kTrigger)) {
      dump.trigger = std::string(line.substr(kTrigger.size()));
    } else if (StartsWith(line, "events:")) {
      std::string_view events = line.substr(7);
      events.remove_prefix(std::min(events.find_first_not_of(' '), events.size()));
      ir_first = StartsWith(events, "Ir") && (events.size() == 2 || events[2] == ' ');
    } else if (StartsWith(line, "totals:") || StartsWith(line, "summary:")) {
      const bool totals = line[0] == 't';
      const std::string number(line.substr(totals ? 7 : 8));
      char* stop = nullptr;
      const double value = std::strtod(number.c_str(), &stop);
      if (stop == number.c_str()) throw InvalidInputError(where + ": unreadable '" + std::string(line) + "'");
      if (totals) {
        dump.instructions = value;
        has_totals = true;
      } else {
        summary = value;
        has_summary = true;
      }
    }
  }
  if (!has_totals && !has_summary) {
    throw InvalidInputError(where + ": no 'totals:' or 'summary:' line (not a callgrind dump?)");
  }
  if (!ir_first) throw InvalidInputError(where + ": the first event is not Ir (run callgrind with its default events)");
  if (!has_totals) dump.instructions = summary;
  return dump;
}

}  // namespace smcbench

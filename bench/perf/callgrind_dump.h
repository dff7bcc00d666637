// Reads the two numbers the perf gate needs from one callgrind output file: the dump's trigger (the figure id
// given to CALLGRIND_DUMP_STATS_AT) and its instruction count (the Ir of "totals:", else "summary:").
#pragma once

#include <string>
#include <string_view>

namespace smcbench {

struct CallgrindDump {
  std::string trigger;  // "Client Request: <id>" without the prefix; empty for other dumps (program end)
  double instructions = 0.0;
};

// Throws InvalidInputError naming `where` if the text has no instruction count or its event list does not start
// with Ir (a dump made with other --event options).
CallgrindDump ParseCallgrindDump(std::string_view text, const std::string& where);

}  // namespace smcbench

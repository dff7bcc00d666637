#!/usr/bin/env python3
"""Self instructions per machine instruction of the functions matching a pattern, per unit, beside the disassembly.

callgrind_self.py gives a function's total; this shows where inside it the instructions go (which branch ran, how
often each instruction ran), for a Release build without debug information.
Usage: callgrind_instr.py DUMP BINARY REGEX [UNITS]
Make the dump with --dump-instr=yes --compress-strings=no --compress-pos=no (docs/auto.md, "Issue 34.3").
"""
import collections
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from callgrind_self import self_cost_lines  # noqa: E402  the dump's own-cost lines, read as callgrind_self reads them


def instruction_costs(path, pattern):
    costs = collections.Counter()
    for fn, fields in self_cost_lines(path):
        if fields[0].startswith("0x") and fn is not None and re.search(pattern, fn):
            costs[int(fields[0], 16)] += int(fields[-1])
    return costs


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    dump, binary, pattern = sys.argv[1:4]
    units = float(sys.argv[4]) if len(sys.argv) > 4 else 1.0
    costs = instruction_costs(dump, pattern)
    if not costs:
        sys.exit("no function matches " + pattern)
    disassembly = subprocess.run(
        ["objdump", "-d", "--no-show-raw-insn", "-C", "--start-address=%#x" % min(costs),
         "--stop-address=%#x" % (max(costs) + 16), binary], capture_output=True, text=True, check=True).stdout
    total = 0.0
    for line in disassembly.splitlines():
        m = re.match(r"\s*([0-9a-f]+):\s*(.*)", line)
        if m and costs.get(int(m.group(1), 16)):
            count = costs[int(m.group(1), 16)] / units
            total += count
            print("%7.1f  %s  %s" % (count, m.group(1), m.group(2)[:100]))
    print("%7.1f  total per unit" % total)


if __name__ == "__main__":
    main()

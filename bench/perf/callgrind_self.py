#!/usr/bin/env python3
"""Self instructions per function of one callgrind dump, divided by the figure's units (solves).

callgrind_annotate folds a Release build without debug information into one line (every function has file ???),
so this reads the dump itself: the cost lines of each fn= block, without the inclusive cost that follows calls=.
Usage: callgrind_self.py DUMP [UNITS] (UNITS: solves per measured run, 64 for a solve/* figure of the perf gate).
Make the dumps with --compress-strings=no (docs/auto.md, "What a cold call costs").
"""
import collections
import sys


def self_cost_lines(path):
    """(function, fields) of every cost line of the dump that is the function's own (position(s), then cost)."""
    fn = None
    after_call = False
    with open(path) as f:
        for line in f:
            if line.startswith("fn="):
                fn = line[3:].rstrip("\n")
            elif line.startswith("calls="):
                after_call = True
            elif line[:1] in "0123456789+-*" and line.strip():
                fields = line.split()
                if after_call:
                    after_call = False  # the callee's inclusive cost, not this function's own
                elif len(fields) >= 2:
                    yield fn, fields


def self_costs(path):
    costs = collections.Counter()
    for fn, fields in self_cost_lines(path):
        costs[fn] += int(fields[-1])
    return costs


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    units = float(sys.argv[2]) if len(sys.argv) == 3 else 64.0
    costs = self_costs(sys.argv[1])
    print(f"{sum(costs.values()) / units:8.1f}  total per unit")
    for fn, c in costs.most_common():
        if c / units >= 0.5:
            print(f"{c / units:8.1f}  {fn[:140]}")


if __name__ == "__main__":
    main()

#!/usr/bin/env bash
# The README's main-job command: install dependencies, build Release, then
#   1. the benchmark suites (paper, families, hard, siconos) on every backend → results/bench/ (results.json, .csv,
#      report.md with plots; extra arguments go to `smcbench bench`, e.g. --suite all for the large scale runs),
#   2. the Siconos collection table → results/siconos-collection.{md,json},
#   3. the paper's claims re-measured → results/paper/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)" --target smcbench
smcbench=./build/release/tools/smcbench
"$smcbench" bench --out results/bench --report "$@"
"$smcbench" collection ../shared/peer-data/siconos --time-limit 10 --markdown results/siconos-collection.md \
  --json results/siconos-collection.json >/dev/null
"$smcbench" paper --out results/paper
echo "report: results/bench/report.md, results/siconos-collection.md, results/paper/README.md"

#!/usr/bin/env bash
# The README's main-job command: install dependencies, build Release, then
#   1. the benchmark suites (paper, families, hard, siconos on every backend; mcp, the nonlinear MCPs, on every backend
#      that solves MCPs; avi, the AVIs over polytopes, on every box backend through their reduction) → results/bench/
#      (results.json, .csv, report.md with plots; extra arguments go to `smcbench bench`, e.g. --suite all for the
#      large scale runs, or --full for the full campaign without time budgets),
#   2. the Siconos collection table → results/siconos-collection.{md,json},
#   3. the paper's claims re-measured → results/paper/.
# Exit status 3 (after all three steps) when `smcbench bench` found a wrong answer (wrongly claimed, inaccurate or
# wrongly refused) from one of our backends.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)" --target smcbench
smcbench=./build/release/tools/smcbench
# --allow-wrong external: the external codes' wrong answers are reported (report.md, results.csv, one line on
# stderr) but are not a failure of this job; a wrong answer from one of our backends is (status 3). The other two
# steps still run, so the job's results are complete either way.
# --out results/bench --overwrite: `bench` writes to a fresh folder unless told otherwise; the main job's results are
# the committed ones. The budgets are `bench`'s defaults, chosen so this job fits in 10 min on a 2-core machine:
# --job-budget 1 (a cold job's solves under 1 s), --sequence-budget 1 (a warm sequence x backend kept within 1 s),
# --backend-budget 60 (one backend on one suite); a job they cut is recorded as cut (no verdict) and listed in the
# report. `bash tools/bench.sh --full` passes --full to `bench`: no budget, the full campaign (about 40 min).
# Any other extra argument goes to `bench` too.
# --siconos-dir: the collection vendored in this repository (tests/data/siconos), so the job needs nothing outside
# the checkout.
bench_status=0
"$smcbench" bench --out results/bench --overwrite --report --allow-wrong external \
  --siconos-dir tests/data/siconos "$@" ||
  bench_status=$?
if [ "$bench_status" -ne 0 ] && [ "$bench_status" -ne 3 ]; then exit "$bench_status"; fi
"$smcbench" collection tests/data/siconos --time-limit 3 --markdown results/siconos-collection.md \
  --json results/siconos-collection.json >/dev/null
"$smcbench" paper --out results/paper
echo "report: results/bench/report.md, results/siconos-collection.md, results/paper/README.md"
if [ "$bench_status" -eq 3 ]; then
  echo "bench.sh: our backends gave wrong answers (see results/bench/report.md); exit status 3" >&2
fi
exit "$bench_status"

#!/usr/bin/env bash
# The README's main-job command: install dependencies, build Release, solve the whole Siconos collection with
# every backend and print the backend × file table (also written to results/siconos-collection.md).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)" --target smcbench
./build/release/tools/smcbench collection ../shared/peer-data/siconos --markdown results/siconos-collection.md "$@"

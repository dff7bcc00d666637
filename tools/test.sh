#!/usr/bin/env bash
# The README's test command: install dependencies, build the Release preset (-Werror), run every test but the
# `slow` label. `tools/test.sh asan` does the same with the ASan+UBSan Debug preset.
set -euo pipefail
cd "$(dirname "$0")/.."
preset=${1:-release}
bash tools/install-deps.sh
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset" -j "$(nproc)"
ctest --preset "$preset"

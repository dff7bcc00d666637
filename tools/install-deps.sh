#!/usr/bin/env bash
# Installs smcbench's dependencies from Debian 12 packages (as root), skipping what is already there.
#   tools/install-deps.sh        what the build and the main job need
#   tools/install-deps.sh test   also what the test gates need: valgrind (perf gate), clang, its sanitizer and
#                                libFuzzer runtimes and lld (the asan preset and the fuzz targets), and what
#                                `pip install .` into a virtual environment needs offline (the ctest
#                                python_pip_install*, docs/python.md)
set -euo pipefail
# libsiconos-numerics-dev, libbullet-dev and libdart-dev are optional for the build (without them the siconos-*,
# bullet-* and dart-* backends are not built) but are installed so that the default report compares against them.
packages=(cmake make g++ pkg-config libeigen3-dev libsuitesparse-dev coinor-libipopt-dev libbenchmark-dev
          libgtest-dev libgmock-dev nlohmann-json3-dev libcli11-dev gnuplot-nox libsiconos-numerics-dev
          libbullet-dev libdart-dev
          pybind11-dev python3-dev python3-numpy python3-scipy python3-pandas python3-pytest)
case "${1:-}" in
  "") ;;
  test) packages+=(valgrind clang libclang-rt-14-dev lld python3-venv python3-pip python3-setuptools python3-wheel) ;;
  *) echo "install-deps: unknown argument '$1' (none, or 'test')" >&2; exit 2 ;;
esac
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  if [[ $(id -u) -ne 0 ]]; then
    echo "install-deps: need root to apt-get install: ${missing[*]}" >&2
    exit 1
  fi
  echo "install-deps: installing ${missing[*]}" >&2
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

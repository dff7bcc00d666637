#!/usr/bin/env bash
# Installs smcbench's build dependencies from Debian 12 packages (as root), skipping what is already there.
set -euo pipefail
# libsiconos-numerics-dev is optional for the build (without it the siconos-* backends are not built) but is
# installed so that the default report compares against Siconos.
packages=(cmake make g++ pkg-config libeigen3-dev libsuitesparse-dev coinor-libipopt-dev libbenchmark-dev
          libgtest-dev libgmock-dev nlohmann-json3-dev libcli11-dev gnuplot-nox libsiconos-numerics-dev)
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

#!/usr/bin/env bash
# The installed package end to end (docs/install.md): install smcbench to a temporary prefix, then — against that
# prefix alone — build the smallest consumer (examples/consumer) and the out-of-tree backend
# (examples/custom-backend), run the consumer, the backend's conformance checks and a small `bench` that shows
# the backend beside ours; check that no installed text file names the source or build tree, and that the installed
# program, started from an empty folder after the prefix is moved, reads its own scenes and Siconos collection
# (`simulate` of a named scene, `collection` and `bench --suite hard` with their default folders).
#
#   bash tools/install-check.sh [BUILD_DIR]
# BUILD_DIR: an existing build tree to install from (only what is installed gets built in it); without it a
# library-only build is configured in the temporary directory. Set KEEP=1 to keep the temporary directory.
# JOBS (default 2) is the build parallelism.
set -euo pipefail

source_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
jobs=${JOBS:-2}
work=$(mktemp -d "${TMPDIR:-/tmp}/smcbench-install-check.XXXXXX")
if [[ "${KEEP:-0}" != 1 ]]; then trap 'rm -rf "$work"' EXIT; fi
step() { echo "== install-check: $*"; }
fail() { echo "install-check: FAILED: $*" >&2; exit 1; }

if [[ $# -ge 1 && -n "$1" ]]; then
  build_dir=$(cd "$1" && pwd)
else
  build_dir="$work/build"
  step "configuring a library-only build in $build_dir"
  cmake -S "$source_dir" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DSMCBENCH_BUILD_TESTS=OFF \
    -DSMCBENCH_BUILD_BENCHMARKS=OFF -DSMCBENCH_BUILD_PYTHON=OFF >/dev/null
fi

step "building what is installed (target smcbench_installables) in $build_dir"
cmake --build "$build_dir" --target smcbench_installables -j "$jobs" >"$work/build.log" 2>&1 ||
  { tail -40 "$work/build.log"; fail "build"; }

prefix="$work/prefix"
step "cmake --install $build_dir --prefix $prefix"
cmake --install "$build_dir" --prefix "$prefix" >"$work/install.log" || fail "install"
for f in bin/smcbench include/smcbench/smcbench.h include/smcbench/solvers/core/solver.h \
         lib/cmake/smcbench/smcbenchConfig.cmake lib/cmake/smcbench/smcbenchTargets.cmake \
         share/smcbench/scenes/galias-yu-2007.json share/smcbench/siconos/README.md share/smcbench/siconos/LICENSE \
         share/smcbench/siconos/SOURCE_COMMIT share/smcbench/siconos/lcp/lcp_CPS_3.dat share/doc/smcbench/LICENSE; do
  [[ -e "$prefix/$f" ]] || fail "not installed: $f"
done
if compgen -G "$prefix/bin/*_test" >/dev/null || compgen -G "$prefix/lib/*test_support*" >/dev/null; then
  fail "tests were installed: $(ls "$prefix/bin" "$prefix/lib")"
fi

step "the installed headers are the public ones (cmake/SmcbenchPublicHeaders.cmake) and include only each other"
# The list's entries as paths under P/include: smcbench/X for X, Y for include/Y.
public_list="$source_dir/cmake/SmcbenchPublicHeaders.cmake"
printf '%s\n' 'include(${LIST})' 'foreach(h IN LISTS SMCBENCH_PUBLIC_HEADERS)' 'message("${h}")' 'endforeach()' \
  >"$work/print-public-headers.cmake"
expected=$(cmake -DLIST="$public_list" -P "$work/print-public-headers.cmake" 2>&1 |
  sed -E '/^include\//!s|^|smcbench/|; s|^include/||' | sort)
[[ -n "$expected" ]] || fail "no public header read from $public_list"
installed_headers=$(cd "$prefix/include" && find . -type f | sed 's|^\./||' | sort)
if [[ "$expected" != "$installed_headers" ]]; then
  diff <(echo "$expected") <(echo "$installed_headers") >&2 || true
  fail "the installed headers differ from the public list (<: listed, not installed; >: installed, not listed)"
fi
for internal in solvers/core/dense_lu.h solvers/core/polish.h solvers/core/active_set.h \
                problems/suites/generation_detail.h; do
  [[ ! -e "$prefix/include/smcbench/$internal" ]] || fail "an internal header was installed: $internal"
done
# A quoted include of an installed header must name another installed header (paths from include/smcbench, or
# from include/ for "smcbench/...").
while read -r header; do
  while read -r included; do
    [[ -f "$prefix/include/smcbench/$included" || -f "$prefix/include/$included" ]] ||
      fail "installed $header includes \"$included\", which is not installed"
  done < <(sed -nE 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*"([^"]+)".*/\1/p' "$prefix/include/$header")
done <<<"$installed_headers"

step "each installed header compiles alone against the prefix (-Wall -Wextra -Werror)"
# One translation unit per header, in a project that sees nothing but the prefix: a header that needs another one
# it does not include, or an internal one, fails here.
alone="$work/headers-alone"
mkdir -p "$alone"
count=0
while read -r header; do
  count=$((count + 1))
  name=${header#smcbench/}
  # As a user writes it: "solvers/core/solver.h" for the tree's headers, <smcbench/smcbench.h> for the top ones.
  if [[ "$name" == */* ]]; then printf '#include "%s"\n' "$name"; else printf '#include <%s>\n' "$header"; fi \
    >"$alone/h$count.cc"
done <<<"$installed_headers"
cat >"$alone/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.25)
project(smcbench_headers_alone LANGUAGES CXX)
set(CMAKE_CXX_STANDARD 17)
find_package(smcbench 0.1 CONFIG REQUIRED)
file(GLOB sources ${CMAKE_CURRENT_SOURCE_DIR}/*.cc)
add_library(headers_alone OBJECT ${sources})
target_compile_options(headers_alone PRIVATE -Wall -Wextra -Werror)
target_link_libraries(headers_alone PRIVATE smcbench::smcbench smcbench::cli smcbench::compare smcbench::scene_runs)
CMAKE
cmake -S "$alone" -B "$alone/build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release \
  >"$work/headers-alone-configure.log" 2>&1 || { cat "$work/headers-alone-configure.log"; fail "configure headers-alone"; }
cmake --build "$alone/build" -j "$jobs" >"$work/headers-alone-build.log" 2>&1 ||
  { grep -m 40 -E "error:|fatal" "$work/headers-alone-build.log" || true; fail "an installed header does not compile alone"; }
echo "$count installed headers, each compiled alone"

step "no installed text file names the source or build tree"
if leaks=$(grep -rIl -e "$source_dir" -e "$build_dir" "$prefix"); then
  echo "$leaks" >&2
  fail "installed text files name $source_dir or $build_dir"
fi

# Every default data folder must resolve from the prefix alone: run from an empty folder, with the variables that
# override the data folders unset.
moved="$work/moved-prefix"
cp -a "$prefix" "$moved"
empty="$work/empty"
mkdir "$empty"
installed() { (cd "$empty" && env -u SMCBENCH_SCENES_DIR -u SMCBENCH_SICONOS_DIR "$moved/bin/smcbench" "$@"); }

step "from an empty folder, a moved prefix: simulate galias-yu-2007 (its own scenes)"
installed simulate galias-yu-2007 --T 0.01 >"$work/simulate.txt" || fail "moved prefix: smcbench simulate galias-yu-2007"
grep -q "^galias-yu-2007: " "$work/simulate.txt" || { cat "$work/simulate.txt"; fail "simulate printed no outcome"; }
# Proof that the scene came from the moved prefix and not from the source tree: a scene file changed there only
# is what the program reads.
sed -i 's/"name": *"sign"/"name": "changed-in-the-moved-prefix"/' "$moved/share/smcbench/scenes/sign.json"
if installed simulate sign --T 0.01 >/dev/null 2>"$work/sign.err"; then
  fail "moved prefix: the changed sign.json was not read (the scenes came from somewhere else)"
fi
grep -q "changed-in-the-moved-prefix" "$work/sign.err" || { cat "$work/sign.err"; fail "unexpected error"; }

step "from an empty folder, a moved prefix: collection and bench --suite hard (its own Siconos collection)"
# collection reads every file of the default collection; the hard suite's Siconos cases come from it too. The
# quickest bench that reads the collection (one backend, one sample, no stepper studies): the default suites of
# `bench --quick` take minutes, most of it certifying references.
installed collection --solver lemke --repeat 1 >"$work/collection.txt" 2>&1 || { tail -20 "$work/collection.txt"; fail "collection"; }
grep -q "lcp/lcp_CPS_3.dat" "$work/collection.txt" || { tail -20 "$work/collection.txt"; fail "collection read no file"; }
installed bench --suite hard --quick --solver lemke --repetitions 1 --no-stepper --report --no-plots \
  --out "$work/bench-hard" >"$work/bench-hard.log" 2>&1 || { tail -20 "$work/bench-hard.log"; fail "bench --suite hard"; }
grep -q "^hard,hard/siconos/lcp_CPS_3,lemke," "$work/bench-hard/results.csv" ||
  fail "bench --suite hard: no Siconos case in results.csv"
[[ -z "$(ls -A "$empty")" ]] || fail "the installed program wrote into the working folder: $(ls -A "$empty")"
# Proof that the collection came from the moved prefix: a file removed there only is missed, by its moved path.
rm "$moved/share/smcbench/siconos/lcp/lcp_CPS_3.dat"
if installed bench --suite hard --quick --solver lemke --repetitions 1 --no-stepper --out "$work/bench-hard-2" \
     >"$work/bench-hard-2.log" 2>&1; then
  fail "moved prefix: the removed lcp_CPS_3.dat was not missed (the collection came from somewhere else)"
fi
grep -qF "$moved/share/smcbench/siconos/lcp/lcp_CPS_3.dat' not found" "$work/bench-hard-2.log" ||
  { cat "$work/bench-hard-2.log"; fail "unexpected error"; }
"$prefix/bin/smcbench" --version

# The examples are copied out of the checkout, so that nothing but the prefix can supply a header or a library.
cp -r "$source_dir/examples" "$work/examples"
configure_example() {  # NAME
  cmake -S "$work/examples/$1" -B "$work/$1-build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_EXPORT_COMPILE_COMMANDS=ON >"$work/$1-configure.log" 2>&1 || { cat "$work/$1-configure.log"; fail "configure $1"; }
  cmake --build "$work/$1-build" -j "$jobs" >"$work/$1-build.log" 2>&1 || { tail -40 "$work/$1-build.log"; fail "build $1"; }
  if grep -l -e "$source_dir" -e "$build_dir" "$work/$1-build/compile_commands.json" "$work/$1-build/CMakeCache.txt"; then
    fail "$1 was built with paths into the source or build tree"
  fi
}

step "examples/consumer against the prefix: CreateSolver(\"lemke\")->Solve(BoxMLCP::Relay(M, q))"
configure_example consumer
"$work/consumer-build/consumer" || fail "consumer"

step "examples/custom-backend against the prefix: conformance checks of the projected Jacobi backend"
configure_example custom-backend
"$work/custom-backend-build/pjacobi-conformance" || fail "pjacobi conformance"

step "pjacobi in smcbench list and in a small bench run beside lemke"
# Into a file, then grep: `list | grep -q` under pipefail fails when grep stops reading at its first match while
# the program is still writing (SIGPIPE), which the listing's 40 KB made happen.
"$work/custom-backend-build/pjacobi-smcbench" list >"$work/list.txt" || { cat "$work/list.txt"; fail "list"; }
grep -q "pjacobi" "$work/list.txt" || fail "pjacobi not listed"
(cd "$work" && env -u SMCBENCH_SCENES_DIR "$work/custom-backend-build/pjacobi-smcbench" bench --suite tiny \
  --solver pjacobi --solver lemke --out "$work/bench" --report) >"$work/bench.log" 2>&1 ||
  { tail -30 "$work/bench.log"; fail "bench with pjacobi"; }
grep -q "pjacobi" "$work/bench/results.csv" || fail "pjacobi missing from results.csv"
grep -q "pjacobi" "$work/bench/report.md" || fail "pjacobi missing from report.md"
grep -m 5 "pjacobi" "$work/bench/report.md"
echo "install-check: passed (prefix $prefix)"

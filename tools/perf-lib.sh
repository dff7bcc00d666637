# Shared by tools/perf-check and tools/perf-update (sourced, not run): builds perf_probe in the Release preset and
# measures the perf gate's figures — natively for wall-clock (information), then under callgrind for instruction
# counts (the gated figure) — into "$perf_dir/current.json".
# Uses: root (the checkout), perf_dir (work folder), wallclock (1/0), filter (regex, may be empty).

perf_measure() {
  command -v valgrind >/dev/null || { echo "perf: valgrind is not installed (bash tools/install-deps.sh)" >&2; exit 2; }
  (cd "$root" && cmake --preset release >/dev/null && cmake --build --preset release -j "$(nproc)" --target perf_probe >/dev/null)
  local probe="$root/build/release/bench/perf_probe"
  local filter_args=()
  [[ -n "$filter" ]] && filter_args=(--filter "$filter")
  rm -rf "$perf_dir"
  mkdir -p "$perf_dir/callgrind"
  # One BLAS thread: a second thread spinning inside a measured region would make the counts vary run to run. And
  # one OpenBLAS kernel on every AVX2 machine (valgrind hides AVX-512), so the counts of the backends that call BLAS
  # (ipopt through MUMPS, UMFPACK) do not depend on which CPU model the gate runs on.
  export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
  grep -qw avx2 /proc/cpuinfo 2>/dev/null && export OPENBLAS_CORETYPE=Haswell
  local merge=()
  if (( wallclock )); then
    echo "perf: wall-clock run (information only)" >&2
    "$probe" measure --out "$perf_dir/wallclock.json" "${filter_args[@]}" 2>"$perf_dir/wallclock.log" ||
      { cat "$perf_dir/wallclock.log" >&2; exit 2; }
    merge=(--wallclock "$perf_dir/wallclock.json")
  fi
  echo "perf: callgrind run (instruction counts; about a minute)" >&2
  valgrind --tool=callgrind --collect-atstart=no --callgrind-out-file="$perf_dir/callgrind/callgrind.out.%p" \
    "$probe" measure --out "$perf_dir/units.json" "${filter_args[@]}" >"$perf_dir/callgrind.log" 2>&1 ||
    { tail -n 30 "$perf_dir/callgrind.log" >&2; exit 2; }
  "$probe" collect --units "$perf_dir/units.json" --callgrind "$perf_dir/callgrind" "${merge[@]}" \
    --out "$perf_dir/current.json"
  probe_binary=$probe
}

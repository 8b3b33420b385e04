#!/usr/bin/env bash
# Runs libFuzzer targets: fuzz/run.sh TARGET|all SECONDS
# TARGET: scene_json, rig_json, probe, mesh or image. Builds the targets in
# build-asan/ (the `asan` preset) when needed, runs each for SECONDS from its
# seed corpus fuzz/corpus/TARGET (new inputs go to build-asan/fuzzing/corpus/TARGET),
# JOBS targets at a time (default: the number of cores). A crash leaves its
# input in build-asan/fuzzing/artifacts/TARGET/ and makes the script fail: copy it to
# fuzz/regressions/TARGET/, where ctest replays it, and fix the bug.
set -euo pipefail
cd "$(dirname "$0")/.."
all=(scene_json rig_json probe mesh image)
if [ $# -ne 2 ] || ! [[ "$2" =~ ^[0-9]+$ ]]; then
  echo "usage: fuzz/run.sh TARGET|all SECONDS   (TARGET: ${all[*]})" >&2
  exit 2
fi
if [ "$1" = all ]; then targets=("${all[@]}"); else targets=("$1"); fi
for t in "${targets[@]}"; do
  [[ " ${all[*]} " == *" $t "* ]] || { echo "fuzz/run.sh: unknown target '$t' (${all[*]})" >&2; exit 2; }
done
seconds="$2"
jobs="${JOBS:-$(nproc)}"

cmake --preset asan >/dev/null  # (again: a build-asan/ configured before it built the fuzz targets)
cmake --build --preset asan --target fuzz_targets -j "$jobs"
out=build-asan/fuzzing

export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizers/lsan.supp:print_suppressions=0"

run_one() {
  local t="$1" work="$out/corpus/$1" artifacts="$out/artifacts/$1/" log="$out/logs/$1.log"
  mkdir -p "$work" "$artifacts" "$(dirname "$log")"
  local dict=()
  [[ "$t" == *_json ]] && dict=(-dict=fuzz/json.dict)
  # libFuzzer watches its own process's memory, not the mesh reader's child
  # (which has a limit of its own, src/io/mesh_io.h: a header claiming
  # millions of elements runs into it and is refused, as in use). What the
  # child hands back is held here: one allocation of 512 MB from an input of
  # a few kilobytes is a memory bomb, and a finding.
  local memory=(-rss_limit_mb=3072)
  [ "$t" = mesh ] && memory+=(-malloc_limit_mb=512)
  local status=0
  "build-asan/fuzz/fuzz_$t" -max_total_time="$seconds" -timeout=30 "${memory[@]}" -print_final_stats=1 \
    -artifact_prefix="$artifacts" "${dict[@]}" "$work" "fuzz/corpus/$t" >"$log" 2>&1 || status=$?
  local runs rate
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  printf 'fuzz %-10s %3ss: %s runs, %s exec/s, corpus %s files, status %s\n' "$t" "$seconds" "${runs:-?}" \
    "${rate:-?}" "$(ls "$work" | wc -l)" "$status" >>"$out/logs/summary"
  if [ "$status" -ne 0 ]; then
    echo "fuzz $t: FAILED (status $status); the input is in $artifacts, the log in $log:" >&2
    grep -E 'ERROR|SUMMARY|fuzz:|#[0-9]+ 0x' "$log" | head -20 >&2 || true
  fi
  return "$status"
}

mkdir -p "$out/logs"
: >"$out/logs/summary"
failed=0
pids=()
for t in "${targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do sleep 1; done
  run_one "$t" &
  pids+=($!)
done
for pid in "${pids[@]}"; do wait "$pid" || failed=1; done
cat "$out/logs/summary"
exit "$failed"

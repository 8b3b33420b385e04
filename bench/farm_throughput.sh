#!/usr/bin/env bash
# docs/benchmarks.md "Frame sequences": relight farm through a Slurm of one
# node started on this machine (tests/local_slurm.sh; as root), with 1 and
# then 2 CPU slots: FRAMES frames of bench/frame_sequence.sh's animated rig
# in chunks of CHUNK, from submission until the queue is empty.
#   bench/farm_throughput.sh [SCENE_DIR] [FRAMES] [CHUNK]
# Run bench/frame_sequence.sh first (its analysis and rig are used).
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-../shared/scenes/studio}
frames=${2:-24}
chunk=${3:-6}
relight=$(realpath "${RELIGHT:-build/src/cli/relight}")
out=$(realpath -m out/bench/farm_throughput)
sequence=out/bench/frame_sequence
[ -f "$sequence/rig.json" ] || { echo "run bench/frame_sequence.sh first"; exit 1; }
source tests/local_slurm.sh
for slots in 1 2; do
  start_local_slurm "$out/slurm" "$slots"
  rm -rf "$out/frames$slots"
  start=$(date +%s.%N)
  job=$("$relight" farm "$scene/scene.json" --rig "$sequence/rig.json" --analysis "$sequence/analysis" \
    --frames "1-$frames" --chunk "$chunk" -o "$out/frames$slots/relit.####.exr" --job "$out/job$slots" --submit |
    sed -n 's/^submitted job \([0-9]*\).*/\1/p')
  wait_for_job "$job" 3600
  "$relight" farm-check "$out/job$slots" >/dev/null
  awk -v a="$start" -v b="$(date +%s.%N)" -v n="$frames" -v s="$slots" -v c="$chunk" 'BEGIN {
    printf "%d slot(s): %d frames in tasks of %d in %.0f s, %.1f frames a minute\n", s, n, c, b - a, n * 60 / (b - a) }'
  stop_local_slurm
  trap - EXIT
done

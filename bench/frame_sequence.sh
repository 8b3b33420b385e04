#!/usr/bin/env bash
# docs/benchmarks.md "Frame sequences": an animated rig of four lights on a
# scene (the studio by default) — its softbox, a key spot and a fill light
# held still, a small warm point light carried across the room and dimmed
# and brightened over FRAMES frames (bench/moving_light_rig.py) — rendered
# with `relight render --frames`, against rendering a frame by itself
# (`relight render` of the rig, all four lights in one render: what every
# frame cost before), timed STILLS times.
#   bench/frame_sequence.sh [SCENE_DIR] [FRAMES] [STILLS]
# RELIGHT names the binary (default the build's).
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-../shared/scenes/studio}
frames=${2:-120}
stills=${3:-3}
relight=${RELIGHT:-build/src/cli/relight}
out=out/bench/frame_sequence
mkdir -p "$out"
/usr/bin/python3 bench/moving_light_rig.py "$scene/scene.json" "$out/rig.json" "$frames"
"$relight" analyze "$scene/scene.json" -o "$out/analysis" >/dev/null 2>&1
start=$(date +%s.%N)
"$relight" render "$scene/scene.json" --analysis "$out/analysis" --rig "$out/rig.json" --frames "1-$frames" \
  -o "$out/frames/relit.####.exr" 2>/dev/null | grep -E "^frame (1|2|$frames) |frames written"
sequence=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
start=$(date +%s.%N)
for i in $(seq "$stills"); do
  "$relight" render "$scene/scene.json" --analysis "$out/analysis" --rig "$out/rig.json" -o "$out/still.exr" \
    >/dev/null 2>&1
done
still=$(awk -v a="$start" -v b="$(date +%s.%N)" -v n="$stills" 'BEGIN { print (b - a) / n }')
awk -v n="$frames" -v s="$sequence" -v f="$still" 'BEGIN {
  printf "sequence: %d frames in %.0f s, %.1f frames a minute\n", n, s, n * 60 / s
  printf "each frame by itself: %.1f s a frame, %.1f frames a minute\n", f, 60 / f
  printf "speed-up: %.1fx\n", f * n / s }'

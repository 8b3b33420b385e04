#!/usr/bin/env bash
# Radiosity against path tracing for the initial illumination (docs/
# benchmarks.md, "Radiosity against path tracing"): the whole `relight
# analyze` (interreflection on), its wall time and albedo PSNR, for
# --method radiosity with the lights' direct light per pixel (the default)
# or from the nodes (the thesis), and --method path at the fewest paths
# (9: one per G-buffer sample) and at 32 per pixel.
#   bench/radiosity_vs_path.sh [SCENES_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
scenes=${1:-../shared/scenes}
relight=build/src/cli/relight
out=out/bench/radiosity
run() {
  local scene=$1 name=$2
  shift 2
  mkdir -p "$out/$(basename "$scene")"
  local folder="$out/$(basename "$scene")/$name" start
  start=$(date +%s%N)
  $relight analyze "$scene/scene.json" -o "$folder" "$@" >/dev/null
  printf '%s %s: %.1f s, albedo %s\n' "$(basename "$scene")" "$name" \
    "$(( ($(date +%s%N) - start) / 1000000 ))e-3" \
    "$($relight compare "$folder/albedo.exr" "$scene/albedo_gt.exr" --mask "$scene/mask.exr")"
}
for scene in "$scenes"/*/; do
  scene=${scene%/}
  run "$scene" radiosity --method radiosity --spp 9
  run "$scene" radiosity-nodes --method radiosity --direct-light nodes
  run "$scene" path-9 --spp 9
  run "$scene" path-32 --spp 32
done

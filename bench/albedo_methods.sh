#!/usr/bin/env bash
# The analysis methods compared on the reference scenes (docs/benchmarks.md,
# "Analysis methods"): albedo PSNR per render of the interreflection
# iteration (render 1 is the thesis's white-diffuse albedo), and the final
# albedo of each initial-illumination strategy.
#   bench/albedo_methods.sh [SCENES_DIR] [SPP]
set -euo pipefail
cd "$(dirname "$0")/.."
scenes=${1:-../shared/scenes}
spp=${2:-32}
relight=build/src/cli/relight
out=out/bench/methods
psnr() { $relight compare "$1" "$2/albedo_gt.exr" --mask "$2/mask.exr"; }
for scene in "$scenes"/*/; do
  name=$(basename "$scene")
  mkdir -p "$out/$name"
  $relight analyze "$scene/scene.json" -o "$out/$name/iterations" --spp "$spp" --save-renders >/dev/null
  for render in "$out/$name"/iterations/albedo_render*.exr; do
    printf '%s interreflection %s: albedo %s\n' "$name" "$(basename "$render" .exr)" "$(psnr "$render" "$scene")"
  done
  for strategy in lights probe combined; do
    start=$(date +%s%N)
    $relight analyze "$scene/scene.json" -o "$out/$name/$strategy" --spp "$spp" --strategy "$strategy" >/dev/null
    t=$(( ($(date +%s%N) - start) / 1000000 ))
    printf '%s strategy %s: %d ms, albedo %s\n' "$name" "$strategy" "$t" \
      "$(psnr "$out/$name/$strategy/albedo.exr" "$scene")"
  done
done

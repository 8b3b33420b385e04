#!/usr/bin/env bash
# End-to-end figures for docs/benchmarks.md: for each reference scene, the
# analysis time and albedo PSNR, then each rig's render time and re-lit PSNR.
#   bench/end_to_end.sh [SCENES_DIR] [SPP]
set -euo pipefail
cd "$(dirname "$0")/.."
scenes=${1:-../shared/scenes}
spp=${2:-64}
relight=build/src/cli/relight
out=out/bench
for scene in "$scenes"/*/; do
  name=$(basename "$scene")
  mkdir -p "$out/$name"
  start=$(date +%s%N)
  $relight analyze "$scene/scene.json" -o "$out/$name/analysis" --spp "$spp" >/dev/null
  t=$(( ($(date +%s%N) - start) / 1000000 ))
  printf '%s analyze: %d ms, albedo %s\n' "$name" "$t" \
    "$($relight compare "$out/$name/analysis/albedo.exr" "$scene/albedo_gt.exr" --mask "$scene/mask.exr")"
  for rig in "$scene"/rigs/*.json; do
    r=$(basename "$rig" .json)
    start=$(date +%s%N)
    $relight render "$scene/scene.json" --rig "$rig" --analysis "$out/$name/analysis" -o "$out/$name/$r.exr" --spp "$spp" >/dev/null
    t=$(( ($(date +%s%N) - start) / 1000000 ))
    printf '%s render %s: %d ms, re-lit %s\n' "$name" "$r" "$t" \
      "$($relight compare "$out/$name/$r.exr" "$scene/relit/$r.exr" --tonemap)"
  done
done

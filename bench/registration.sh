#!/usr/bin/env bash
# Camera registration on the reference scenes (docs/benchmarks.md, "Camera
# registration"): each camera perturbed as tests/registration_test.cpp does
# (turned 1 degree, vfov 3 % wide, principal point 1 % of the width off, all
# together), registered (time, edge mismatch), and the albedo of the exact,
# the perturbed and the registered camera against albedo_gt.exr.
#   bench/registration.sh [SCENES_DIR] [SPP]
set -euo pipefail
cd "$(dirname "$0")/.."
scenes=${1:-../shared/scenes}
spp=${2:-16}
relight=build/src/cli/relight
out=out/bench/registration
mkdir -p "$out"
psnr() { $relight compare "$1/albedo.exr" "$2/albedo_gt.exr" --mask "$2/mask.exr"; }
for scene in "$scenes"/*/; do
  name=$(basename "$scene")
  bench/perturb_camera.py "$scene/scene.json" "$out/$name-perturbed.json" --turn 1 --fov-scale 1.03 --shift 0.01
  start=$(date +%s%N)
  $relight register "$out/$name-perturbed.json" -o "$out/$name-registered.json" 2>/dev/null | sed "s/^/$name: /"
  printf '%s: registration %d ms\n' "$name" $(( ($(date +%s%N) - start) / 1000000 ))
  for camera in exact perturbed registered; do
    json="$out/$name-$camera.json"
    [ "$camera" = exact ] && json="$scene/scene.json"
    $relight analyze "$json" -o "$out/$name-$camera" --spp "$spp" >/dev/null 2>&1
    printf '%s: albedo with the %s camera: %s\n' "$name" "$camera" "$(psnr "$out/$name-$camera" "$scene")"
  done
done

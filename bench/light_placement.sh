#!/usr/bin/env bash
# Lights placed from the photo on the reference scenes (docs/benchmarks.md,
# "Lights placed from the photo"): every light moved 20 cm sideways (a sun
# turned 3 degrees; bench/perturb_lights.py), one at a time and all together,
# then `relight fit --refine-placement` (time, how far each light ends from
# the truth) and the albedo of the true, the given and the fitted lights
# against albedo_gt.exr.
#   bench/light_placement.sh [SCENES_DIR] [SPP]
set -euo pipefail
cd "$(dirname "$0")/.."
scenes=${1:-../shared/scenes}
spp=${2:-16}
relight=build/src/cli/relight
out=out/bench/light_placement
mkdir -p "$out"
albedo() {  # albedo SCENE.json FOLDER TRUTH_DIR: the albedo's PSNR
  $relight analyze "$1" -o "$2" --spp "$spp" >/dev/null 2>&1
  $relight compare "$2/albedo.exr" "$3/albedo_gt.exr" --mask "$3/mask.exr"
}
off() {  # off TRUE.json FITTED.json: each light's distance (or turn) from the truth
  python3 - "$1" "$2" <<'PY'
import json, math, sys
true = {l["name"]: l for l in json.load(open(sys.argv[1]))["lights"]}
for l in json.load(open(sys.argv[2]))["lights"]:
    t = true[l["name"]]
    if l["type"] == "directional":
        a, b = l["direction"], t["direction"]
        c = sum(x * y for x, y in zip(a, b)) / math.sqrt(sum(x * x for x in a) * sum(x * x for x in b))
        print(f'{l["name"]} {math.degrees(math.acos(min(1.0, c))):.3f} deg off', end="; ")
    else:
        print(f'{l["name"]} {100 * math.dist(l["position"], t["position"]):.1f} cm off', end="; ")
print()
PY
}
for scene in "$scenes"/*/; do
  name=$(basename "$scene")
  printf '%s: true lights: albedo %s\n' "$name" "$(albedo "$scene/scene.json" "$out/$name-true" "$scene")"
  lights=$(python3 -c "import json,sys; print(' '.join(l['name'] for l in json.load(open(sys.argv[1]))['lights']))" "$scene/scene.json")
  sets=$lights
  [ "$(wc -w <<<"$lights")" -gt 1 ] && sets="$sets all"
  for moved in $sets; do
    case=$out/$name-$moved
    if [ "$moved" = all ]; then bench/perturb_lights.py "$scene/scene.json" "$case-given.json"
    else bench/perturb_lights.py "$scene/scene.json" "$case-given.json" --light "$moved"; fi
    printf '%s, %s moved: given: %s albedo %s\n' "$name" "$moved" "$(off "$scene/scene.json" "$case-given.json")" \
      "$(albedo "$case-given.json" "$case-given" "$scene")"
    start=$(date +%s%N)
    $relight fit "$case-given.json" --refine-placement -o "$case-fitted.json" >/dev/null 2>&1
    ms=$(( ($(date +%s%N) - start) / 1000000 ))
    printf '%s, %s moved: fitted in %d ms: %s albedo %s\n' "$name" "$moved" "$ms" \
      "$(off "$scene/scene.json" "$case-fitted.json")" "$(albedo "$case-fitted.json" "$case-fitted" "$scene")"
  done
done

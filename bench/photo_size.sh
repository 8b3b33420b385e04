#!/usr/bin/env bash
# docs/benchmarks.md "Photo size": a reference scene's photo upsampled to
# camera sizes (bench/upsample_scene.py) and analysed at the defaults, one
# size after another in one run: wall-clock, peak resident memory (bytes
# per pixel beside it) and albedo PSNR against the upsampled true albedo.
#   bench/photo_size.sh [SCENE_DIR] [FACTORS...]
# Default: ../shared/scenes/bookcase at 1 2.55 4 5.1 8.84 (0.3, 2, 4.9, 8
# and 24 Mpixel from 640x480). RELIGHT names the binary (default the build's).
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-../shared/scenes/bookcase}
shift || true
factors=("$@")
[ ${#factors[@]} -gt 0 ] || factors=(1 2.55 4 5.1 8.84)
relight=${RELIGHT:-build/src/cli/relight}
out=out/bench/photo_size
mkdir -p "$out"
printf '| photo | Mpixel | analysis | peak memory | bytes per pixel | albedo PSNR |\n|---|---|---|---|---|---|\n'
for f in "${factors[@]}"; do
  sized=$out/$(basename "$scene")-$f
  [ -f "$sized/scene.json" ] || /usr/bin/python3 bench/upsample_scene.py "$scene" "$sized" "$f"
  size=$(/usr/bin/python3 -c "import OpenImageIO as o; s=o.ImageInput.open('$sized/photo.exr').spec(); print(s.width, s.height)")
  read -r w h <<<"$size"
  /usr/bin/time -f "%e %M" -o "$out/time.txt" "$relight" analyze "$sized/scene.json" -o "$sized/analysis" --force \
    >/dev/null 2>"$out/log.txt"
  read -r seconds kib <"$out/time.txt"
  psnr=$("$relight" compare "$sized/analysis/albedo.exr" "$sized/albedo_gt.exr" --mask "$sized/mask.exr")
  awk -v w="$w" -v h="$h" -v s="$seconds" -v k="$kib" -v p="$psnr" 'BEGIN {
    printf "| %dx%d | %.1f | %.0f s | %.2f GiB | %.0f | %s |\n", w, h, w * h / 1e6, s, k / 1048576, k * 1024 / (w * h), p }'
done

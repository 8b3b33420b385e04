#!/usr/bin/env bash
# relight farm through a real Slurm on this machine: munged, slurmctld and
# slurmd started here on localhost (two CPU slots, private ports and
# folders), an animated rig's frames submitted as a job array of chunks,
# checked back in, and compared with a local `relight render --frames` of
# the same frames: bit-identical. Then two frames deleted: farm-check lists
# them (exit 3), --resubmit renders their chunk again, and they come back
# the same. And a tracked shot's frames the same way, bit-identical too.
# Skipped (77) without Slurm and munge, or when not root
# (tests/local_slurm.sh).
#   farm_slurm_test.sh RELIGHT SOURCE_DIR WORK
set -euo pipefail
relight=$1 src=$2 work=$3
command -v idiff >/dev/null || { echo "skipped: idiff is not installed (scripts/install-deps.sh)"; exit 77; }

source "$src/tests/local_slurm.sh"
start_local_slurm "$work" 2

# An analysis and an animated rig of the example room.
scene="$src/examples/room/scene.json"
"$relight" analyze "$scene" -o "$work/analysis" --spp 2 --interreflection off >/dev/null 2>&1
cat >"$work/rig.json" <<'RIG'
{"format": "relight-rig/1", "environment_scale": 0.5, "lights": [
  {"name": "still", "type": "point", "position": [0, -1, 2.2], "power": 60},
  {"name": "lamp", "type": "point", "position": [-1, -1.2, 2], "power": 250, "radius": 0.05,
   "keys": [{"frame": 1, "position": [-1, -1.2, 2], "interpolation": "linear"},
            {"frame": 6, "position": [1, -1.2, 2], "power": 100}]}]}
RIG
"$relight" render "$scene" --rig "$work/rig.json" --analysis "$work/analysis" --frames 1-6 \
  -o "$work/local/relit.##.exr" >/dev/null

same_frames() {  # every pixel equal (the files differ in their DateTime)
  for f in 01 02 03 04 05 06; do
    idiff -q -fail 0 -warn 0 "$work/local/relit.$f.exr" "$work/farm/relit.$f.exr" >/dev/null ||
      { echo "frame $f differs from the local render"; exit 1; }
  done
}

# Runs COMMAND (one that submits JOB_DIR's job, or part of it), waits for the
# job Slurm gives it, and checks JOB_DIR's frames in.
submit_and_check() {  # JOB_DIR COMMAND...
  local job_dir=$1 job
  shift
  "$@" | tee "$job_dir.submitted.txt"
  job=$(sed -n 's/^submitted job \([0-9]*\).*/\1/p' "$job_dir.submitted.txt")
  [ -n "$job" ] || { echo "no job id from: $*"; exit 1; }
  wait_for_job "$job" 300
  "$relight" farm-check "$job_dir"
}
submit_and_check "$work/job" "$relight" farm "$scene" --rig "$work/rig.json" --analysis "$work/analysis" \
  -o "$work/farm/relit.##.exr" --chunk 2 --job "$work/job" --submit
same_frames

rm "$work/farm/relit.03.exr" "$work/farm/relit.04.png"
set +e
"$relight" farm-check "$work/job" >"$work/check.txt" 2>&1
status=$?
set -e
cat "$work/check.txt"
[ "$status" = 3 ] || { echo "farm-check with frames missing exited $status, not 3"; exit 1; }
grep -q "2 of 6 frames missing: 3-4 (tasks 1;" "$work/check.txt" || { echo "farm-check did not list frames 3-4"; exit 1; }
submit_and_check "$work/job" "$relight" farm-check "$work/job" --resubmit
same_frames
# A tracked shot through the farm: four frames (the example photo from its
# own camera, each frame's copy), analysed frame by frame with the albedo
# fused, rendered by the job array and locally: bit-identical.
mkdir -p "$work/shot"
python3 - "$scene" "$work/shot" <<'SHOT'
import json, os, shutil, sys
scene, out = sys.argv[1], sys.argv[2]
doc = json.load(open(scene))
folder = os.path.dirname(scene)
for key in ("photo", "geometry"):
    doc[key] = os.path.join(folder, doc[key])
for frame in range(1, 5):
    shutil.copyfile(doc["photo"], os.path.join(out, "photo.%04d.exr" % frame))
doc["shot"] = {"photo": "photo.####.exr", "cameras": [doc["camera"]] * 4}
json.dump(doc, open(os.path.join(out, "scene.json"), "w"))
SHOT
shot="$work/shot/scene.json"
"$relight" analyze "$shot" -o "$work/shot_analysis" --spp 2 --interreflection off >/dev/null 2>&1
"$relight" render "$shot" --rig "$work/rig.json" --analysis "$work/shot_analysis" -o "$work/shot_local/relit.####.exr" >/dev/null
submit_and_check "$work/shot_job" "$relight" farm "$shot" --rig "$work/rig.json" --analysis "$work/shot_analysis" \
  -o "$work/shot_farm/relit.####.exr" --chunk 2 --job "$work/shot_job" --submit
for f in 0001 0002 0003 0004; do
  idiff -q -fail 0 -warn 0 "$work/shot_local/relit.$f.exr" "$work/shot_farm/relit.$f.exr" >/dev/null ||
    { echo "shot frame $f differs from the local render"; exit 1; }
done
echo "farm: 6 frames through Slurm in 3 tasks, bit-identical to the local render; 2 lost frames re-rendered;"
echo "      a 4-frame shot in 2 tasks, bit-identical to its local render"

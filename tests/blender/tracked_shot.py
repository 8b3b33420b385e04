# A tracked shot from Blender: the example scene's camera dollied sideways
# (0.3 m) over frames 1-3, each frame rendered by Cycles (8 samples),
# exported with the exporter's --shot: scene.json's shot must hold the
# camera of every frame as Blender has it there, the frames' photos beside
# it, and the still (photo and camera) the first frame. Longer and cleaner
# shots for the figures with --frames and --samples (docs/benchmarks.md,
# "A tracked shot").
#   blender -b SCENE.blend --python-exit-code 1 --python tracked_shot.py -- EXPORTER OUTDIR [--frames N] [--samples S]
import argparse
import importlib.util
import json
import os
import sys

import bpy

parser = argparse.ArgumentParser()
parser.add_argument("exporter")
parser.add_argument("outdir")
parser.add_argument("--frames", type=int, default=3)
parser.add_argument("--samples", type=int, default=8)
args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:])
exporter_path, outdir, frames = args.exporter, args.outdir, list(range(1, args.frames + 1))
spec = importlib.util.spec_from_file_location("relight_export", exporter_path)
exporter = importlib.util.module_from_spec(spec)
spec.loader.exec_module(exporter)

scene = bpy.context.scene
scene.frame_start, scene.frame_end = frames[0], frames[-1]
camera = scene.camera
camera.keyframe_insert("location", frame=frames[0])
camera.location.x += 0.3
camera.keyframe_insert("location", frame=frames[-1])

scene.render.engine = 'CYCLES'
scene.cycles.samples = args.samples
scene.cycles.use_denoising = False
scene.view_settings.view_transform = 'Standard'
scene.render.image_settings.file_format = 'OPEN_EXR'
scene.render.image_settings.color_depth = '32'
pattern = os.path.abspath("render/photo.####.exr")
for frame in frames:
    scene.frame_set(frame)
    scene.render.filepath = exporter.frame_file(pattern, frame)
    bpy.ops.render.render(write_still=True)

target = exporter.export_scene(scene, os.path.abspath(outdir), shot=pattern)
with open(target) as f:
    shot = json.load(f)["shot"]
assert shot["photo"] == "photo.####.exr" and shot["first_frame"] == 1, shot
assert len(shot["cameras"]) == len(frames), shot
for frame, block in zip(frames, shot["cameras"]):
    scene.frame_set(frame)
    where = camera.matrix_world.translation
    assert all(abs(a - b) < 1e-4 for a, b in zip(block["position"], where)), (frame, block["position"], where)
    assert os.path.isfile(os.path.join(outdir, "photo.%04d.exr" % frame)), frame
with open(target) as f:
    still = json.load(f)["camera"]
assert still == shot["cameras"][0], "the still is the first frame"
moved = shot["cameras"][-1]["position"][0] - shot["cameras"][0]["position"][0]
assert abs(moved - 0.3) < 1e-4, moved
print("tracked_shot: %d frames exported, the camera moved %.2f m" % (len(frames), moved))

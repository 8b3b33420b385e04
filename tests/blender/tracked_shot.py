# A tracked shot from Blender: the example scene's camera dollied sideways
# over frames 1-3, each frame rendered by Cycles (8 samples), exported with
# the exporter's --shot: scene.json's shot must hold the camera of every
# frame as Blender has it there, and the frames' photos beside it.
#   blender -b SCENE.blend --python-exit-code 1 --python tracked_shot.py -- EXPORTER OUTDIR
import importlib.util
import json
import os
import sys

import bpy

exporter_path, outdir = sys.argv[sys.argv.index("--") + 1:][:2]
spec = importlib.util.spec_from_file_location("relight_export", exporter_path)
exporter = importlib.util.module_from_spec(spec)
spec.loader.exec_module(exporter)

scene = bpy.context.scene
scene.frame_start, scene.frame_end = 1, 3
camera = scene.camera
camera.keyframe_insert("location", frame=1)
camera.location.x += 0.3
camera.keyframe_insert("location", frame=3)

scene.render.engine = 'CYCLES'
scene.cycles.samples = 8
scene.cycles.use_denoising = False
scene.view_settings.view_transform = 'Standard'
scene.render.image_settings.file_format = 'OPEN_EXR'
scene.render.image_settings.color_depth = '32'
pattern = os.path.abspath("render/photo.####.exr")
for frame in (1, 2, 3):
    scene.frame_set(frame)
    scene.render.filepath = exporter.frame_file(pattern, frame)
    bpy.ops.render.render(write_still=True)

target = exporter.export_scene(scene, os.path.abspath(outdir), shot=pattern)
with open(target) as f:
    shot = json.load(f)["shot"]
assert shot["photo"] == "photo.####.exr" and shot["first_frame"] == 1, shot
assert len(shot["cameras"]) == 3, shot
for frame, block in zip((1, 2, 3), shot["cameras"]):
    scene.frame_set(frame)
    where = camera.matrix_world.translation
    assert all(abs(a - b) < 1e-4 for a, b in zip(block["position"], where)), (frame, block["position"], where)
    assert os.path.isfile(os.path.join(outdir, "photo.%04d.exr" % frame)), frame
moved = shot["cameras"][2]["position"][0] - shot["cameras"][0]["position"][0]
assert abs(moved - 0.3) < 1e-4, moved
print("tracked_shot: 3 frames exported, the camera moved %.2f m" % moved)

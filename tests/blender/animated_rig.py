# The exporter's animated rig: on the example scene, the lamp is carried
# across the room (Blender's default Bezier easing) and dimmed, the spot
# turned at a constant rate and hidden from frame 8, the panel slid at a
# constant speed (linear keyframes), the sun left still. Exported over
# frames 1-10, the rig's keys must give back, at every frame, what Blender
# has there, read the way relight reads them (linear between keys, held
# outside, on/off held); the panel's slide takes its two end keys only, the
# still sun none. Imported back, the keys become keyframes that give the
# same lights at every frame.
#   blender -b SCENE.blend --python-exit-code 1 --python animated_rig.py -- EXPORTER RIG
import importlib.util
import json
import math
import sys

import bpy

exporter_path, rig_path = sys.argv[sys.argv.index("--") + 1:][:2]
spec = importlib.util.spec_from_file_location("relight_export", exporter_path)
exporter = importlib.util.module_from_spec(spec)
spec.loader.exec_module(exporter)

scene = bpy.context.scene
scene.frame_start, scene.frame_end = 1, 10
lamp, spot, panel = bpy.data.objects["Lamp"], bpy.data.objects["Spot"], bpy.data.objects["Panel"]
lamp.keyframe_insert("location", frame=1)
lamp.data.keyframe_insert("energy", frame=1)
lamp.location.x += 2.0
lamp.data.energy = 50.0
lamp.keyframe_insert("location", frame=10)
lamp.data.keyframe_insert("energy", frame=10)
spot.keyframe_insert("rotation_euler", frame=1)
spot.rotation_euler.z += math.radians(30.0)
spot.keyframe_insert("rotation_euler", frame=10)
panel.keyframe_insert("location", frame=1)
panel.location.x -= 1.0
panel.keyframe_insert("location", frame=10)
for obj in (spot, panel):
    for curve in obj.animation_data.action.fcurves:
        for point in curve.keyframe_points:
            point.interpolation = 'LINEAR'
spot.hide_render = False
spot.keyframe_insert("hide_render", frame=1)
spot.hide_render = True
spot.keyframe_insert("hide_render", frame=8)

exporter.export_rig(scene, rig_path)
lights = {light["name"]: light for light in json.load(open(rig_path))["lights"]}


def relight_value(light, name, frame):
    """The value relight gives `name` at `frame` from linear keys (or the light's own)."""
    keys = [k for k in light.get("keys", []) if name in k]
    if not keys:
        return light.get(name, True if name == "enabled" else None)
    if frame <= keys[0]["frame"]:
        return keys[0][name]
    for a, b in zip(keys, keys[1:]):
        if a["frame"] <= frame < b["frame"]:
            if isinstance(a[name], bool):
                return a[name]
            t = (frame - a["frame"]) / (b["frame"] - a["frame"])
            if isinstance(a[name], list):
                return [x + (y - x) * t for x, y in zip(a[name], b[name])]
            return a[name] + (b[name] - a[name]) * t
    return keys[-1][name]


def close(a, b):
    if isinstance(a, list):
        return all(close(x, y) for x, y in zip(a, b))
    if isinstance(a, bool):
        return a == b
    return abs(a - b) <= 1e-4 * max(1.0, abs(a))


for frame in range(1, 11):
    scene.frame_set(frame)
    rendered = exporter.rendered_objects(scene)
    for obj in (lamp, spot, panel, bpy.data.objects["Sun"]):
        truth = exporter.light_entry(obj)
        truth["enabled"] = obj in rendered
        for name in ("position", "direction", "power", "enabled"):
            if name in truth:
                got = relight_value(lights[obj.name], name, frame)
                assert close(got, truth[name]), (obj.name, name, frame, got, truth[name])

assert "keys" not in lights["Sun"], lights["Sun"]
assert [k["frame"] for k in lights["Panel"]["keys"]] == [1, 10], lights["Panel"]["keys"]
# A turn at a constant rate is an arc: its direction bends at every frame.
assert len([k for k in lights["Spot"]["keys"] if "direction" in k]) == 10, lights["Spot"]["keys"]
assert [k["frame"] for k in lights["Spot"]["keys"] if "enabled" in k] == [1, 8, 10], lights["Spot"]["keys"]
assert len([k for k in lights["Lamp"]["keys"] if "position" in k]) == 10  # an eased move bends at every frame
# Back into Blender: the imported lights' keyframes give the rig's values at every frame.
imported = {obj.name.rsplit(".", 1)[0]: obj for obj in exporter.import_rig(rig_path)}
assert set(imported) == set(lights), (set(imported), set(lights))
for frame in range(1, 11):
    scene.frame_set(frame)
    for name, obj in imported.items():
        back = exporter.light_entry(obj)
        for value in ("position", "direction", "power"):
            if value in back:
                got = relight_value(lights[name], value, frame)
                assert close(back[value], got), (name, value, frame, back[value], got)
        assert (not obj.hide_render) == relight_value(lights[name], "enabled", frame), (name, frame)
print("animated_rig: the rig's keys give Blender's lights at every frame, and come back as keyframes")

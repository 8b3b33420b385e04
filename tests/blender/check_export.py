# Checks what tools/blender/relight_export.py wrote for make_example_scene.py's
# scene against the values that script set, and that a rig relight wrote from
# the exported scene comes back into Blender as the same lights.
# The albedo relight recovered in ANALYSIS (from the Cycles-rendered photo) must
# be the colours the materials were given.
# A rig with environment_scale and colours typed both ways comes into Blender as
# written. The exporter refuses what relight would: a photo of another shape, no
# photo, nothing visible to be geometry, writing nothing. Last, a world lit by an
# HDRI exports as an equirect probe that relight loads (its orientation is
# proven on rendered scenes by light_frames.py).
#   blender -b SCENE.blend --python-exit-code 1 --python check_export.py -- EXPORTER OUTDIR RIG ANALYSIS RELIGHT
import importlib.util
import json
import math
import os
import subprocess
import sys

import bpy

exporter_path, outdir, rig_path, analysis, relight = sys.argv[sys.argv.index("--") + 1:]
spec = importlib.util.spec_from_file_location("relight_export", exporter_path)
relight_export = importlib.util.module_from_spec(spec)
spec.loader.exec_module(relight_export)

with open(outdir + "/scene.json") as f:
    scene = json.load(f)


def near(a, b, tol=1e-4):
    a, b = (a, b) if isinstance(a, (list, tuple)) else ([a], [b])
    assert len(a) == len(b) and all(abs(x - y) <= tol for x, y in zip(a, b)), "%r != %r" % (a, b)


# The camera: 35 mm lens on a 36 mm sensor fitted to the 320 px width, lens shifted 0.05 widths.
camera = scene["camera"]
near(camera["vfov_deg"], math.degrees(2 * math.atan(18.0 / 35.0 * 240.0 / 320.0)))
near(camera["position"], [6.0, -5.0, 3.5])
near(camera["principal_point"], [0.45, 0.5])
near(camera["aspect"], 320.0 / 240.0)
forward = [a - b for a, b in zip(camera["look_at"], camera["position"])]
target = [0.0 - 6.0, 0.0 + 5.0, 0.6 - 3.5]
norm = math.sqrt(sum(t * t for t in target))
near(forward, [t / norm for t in target])

lights = {light["name"]: light for light in scene["lights"]}
assert sorted(lights) == ["Lamp", "Panel", "Spot", "Sun"], sorted(lights)
near(lights["Lamp"]["power"], 150.0)
near(lights["Lamp"]["radius"], 0.1)
near(lights["Lamp"]["color"], [1.0, 0.9, 0.8])
assert lights["Spot"]["type"] == "spot"
near(lights["Spot"]["spot_angle_deg"], 40.0)
near(lights["Spot"]["blend"], 0.2)
d = [2.0, 3.0, -3.0]  # from (-2, -3, 3) to the origin
near(lights["Spot"]["direction"], [x / math.sqrt(22.0) for x in d])
near(lights["Panel"]["size"], [1.0, 0.5])
near(lights["Panel"]["power"], 200.0)
assert lights["Sun"]["type"] == "directional"
near(lights["Sun"]["irradiance"], 1.0)
near(lights["Sun"]["angle_deg"], 0.5)
near(scene["background"], [0.05, 0.06, 0.08])

# The geometry stays in Blender's world frame (Z up): the box's top corner (1.1, 0.8, 1.0) is a vertex.
with open(outdir + "/geometry.obj") as f:
    vertices = [tuple(map(float, line.split()[1:4])) for line in f if line.startswith("v ")]
assert any(max(abs(a - b) for a, b in zip(v, (1.1, 0.8, 1.0))) < 1e-4 for v in vertices), "box corner missing"
assert all(v[2] > -1e-4 for v in vertices), "a vertex below the floor: the axes were converted"

# The albedo relight recovers on the box's top, the floor and the ball's side facing the camera.
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector
bscene = bpy.context.scene
albedo = bpy.data.images.load(analysis + "/albedo.exr")
width, height = albedo.size
pixels = albedo.pixels[:]
ball = Vector((-0.8, -0.4, 0.45))
facing = ball + 0.45 * (bscene.camera.location - ball).normalized()
for where, point, colour in [("box top", (0.6, 0.3, 1.0), (0.7, 0.25, 0.15)),
                             ("floor", (2.5, 0.5, 0.0), (0.6, 0.6, 0.6)),
                             ("ball", facing, (0.2, 0.4, 0.7))]:
    view = world_to_camera_view(bscene, bscene.camera, Vector(point))
    col, row = int(view.x * width), int(view.y * height)  # Blender's rows count from the bottom
    mean = [0.0, 0.0, 0.0]
    for r in range(row - 2, row + 3):
        for c in range(col - 2, col + 3):
            for k in range(3):
                mean[k] += pixels[(r * width + c) * 4 + k] / 25.0
    assert all(abs(m - t) < 0.06 * t + 0.005 for m, t in zip(mean, colour)), \
        "%s: albedo %s, material %s" % (where, mean, colour)
    print("check_export: %s albedo %.3f %.3f %.3f (material %.2f %.2f %.2f)" % (where, *mean, *colour))

# Rig (written by relight) -> Blender lights -> exporter: the same lights again.
made = relight_export.import_rig(rig_path, replace=True)  # replaced: the imported lights keep their names
assert len(made) == 4
for obj in made:
    again = relight_export.light_entry(obj)
    original = lights[obj.name]
    assert again["type"] == original["type"], obj.name
    for key, value in original.items():
        if key in ("name", "type", "enabled"):
            continue
        near(again[key], value, 1e-3)
print("check_export: camera, 4 lights, world and geometry as set; rig round trip exact")

# Everything a rig holds: environment_scale scales the world (from its strength before any rig,
# so a second rig does not compound), "#rrggbb" is sRGB, [r, g, b] linear, enabled false hides.
typed = {"format": "relight-rig/1", "environment_scale": 0.25, "lights": [
    {"name": "warm", "type": "point", "position": [1, 2, 3], "power": 80, "color": "#ff8000", "radius": 0.2},
    {"name": "off", "type": "directional", "direction": [0, 0, -1], "irradiance": 2, "color": [0.5, 0.25, 1],
     "enabled": False}]}
with open(outdir + "/typed.json", "w") as f:
    json.dump(typed, f)
background = bpy.context.scene.world.node_tree.nodes["Background"].inputs["Strength"]
strength = background.default_value
for _ in range(2):
    warm, off = relight_export.import_rig(outdir + "/typed.json", replace=True)
near(background.default_value, 0.25 * strength)
near(list(warm.data.color), [1.0, ((128 / 255 + 0.055) / 1.055) ** 2.4, 0.0])
near(list(off.data.color), [0.5, 0.25, 1.0])
assert (warm.name, warm.hide_render, off.name, off.hide_render) == ("warm", False, "off", True)
near(list(warm.location), [1.0, 2.0, 3.0])
near([warm.data.energy, warm.data.shadow_soft_size, off.data.energy], [80.0, 0.2, 2.0])
background.default_value = strength
# In a scene modelled in centimetres the rig's metres become 100 units, and the power what lights
# a surface so many units away as the rig's lamp does at so many metres; exported, the same again.
bpy.context.scene.unit_settings.scale_length = 0.01
warm, _ = relight_export.import_rig(outdir + "/typed.json", replace=True)
near(list(warm.location), [100.0, 200.0, 300.0])
near([warm.data.energy / 1e4, warm.data.shadow_soft_size], [80.0, 20.0])
again = relight_export.light_entry(warm, relight_export.metres_per_unit(bpy.context.scene))
near(again["position"] + [again["power"], again["radius"]], typed["lights"][0]["position"] + [80.0, 0.2])
bpy.context.scene.unit_settings.scale_length = 1.0
background.default_value = strength
# A rig with a bad entry changes nothing: the good light before it is not added either.
with open(outdir + "/bad.json", "w") as f:
    json.dump({"format": "relight-rig/1", "environment_scale": 0.5,
               "lights": [typed["lights"][0], {"type": "spot", "position": [0, 0, 1], "power": 5}]}, f)
before = sorted(o.name for o in bpy.context.scene.objects)
try:
    relight_export.import_rig(outdir + "/bad.json", replace=True)
    raise AssertionError("a spot without its cone and direction imported")
except relight_export.BridgeError as e:
    assert "/lights/1: the spot light has no" in str(e), e
assert sorted(o.name for o in bpy.context.scene.objects) == before
near(background.default_value, strength)
print("check_export: a rig's environment_scale, typed colours, switched-off lights and lengths (in a "
      "centimetre scene too) imported as written")


def refused(why, photo, expected):
    """export_scene must raise a BridgeError saying `expected`, writing nothing."""
    target = outdir + "/refused"
    try:
        relight_export.export_scene(bpy.context.scene, target, photo)
    except relight_export.BridgeError as e:
        assert expected in str(e), "%s: %s" % (why, e)
        assert not os.path.exists(target), "%s: %s written anyway" % (why, os.listdir(target))
        print("check_export: %s refused: %s" % (why, e))
        return
    raise AssertionError("%s: exported" % why)


square = bpy.data.images.new("square", 64, 64, float_buffer=True)
square.save_render(outdir + "/square.exr", scene=bpy.context.scene)
refused("a square photo for a 320x240 render", outdir + "/square.exr", "not the aspect ratio")
refused("no photo", None, "no photo")
refused("a photo that is not there", outdir + "/none.exr", "does not exist")
tree = bpy.context.scene.world.node_tree
sky = tree.nodes.new("ShaderNodeTexSky")
link = tree.links.new(sky.outputs["Color"], tree.nodes["Background"].inputs["Color"])
refused("a world lit by a Sky Texture", outdir + "/" + scene["photo"], "TEX_SKY")
tree.links.remove(link)
tree.nodes.remove(sky)
bpy.context.scene.render.pixel_aspect_x = 2.0
refused("non-square pixels", outdir + "/" + scene["photo"], "square pixels")
bpy.context.scene.render.pixel_aspect_x = 1.0
for obj in bpy.context.scene.objects:
    obj.hide_render = obj.type == 'MESH'
refused("no mesh rendered", outdir + "/" + scene["photo"], "no visible mesh")
for obj in bpy.context.scene.objects:
    obj.hide_render = False

# An HDRI world (a generated equirect image, packed): exported as a probe facing +X, Z up, at the camera.
hdri = bpy.data.images.new("sky", 64, 32, float_buffer=True)
hdri.pixels.foreach_set([0.5] * (64 * 32 * 4))
hdri.pack()
world = bpy.context.scene.world
texture = world.node_tree.nodes.new("ShaderNodeTexEnvironment")
texture.image = hdri
world.node_tree.links.new(texture.outputs["Color"], world.node_tree.nodes["Background"].inputs["Color"])
scene_path = relight_export.export_scene(bpy.context.scene, outdir + "/hdri", outdir + "/" + scene["photo"])
with open(scene_path) as f:
    probes = json.load(f)["probes"]
assert len(probes) == 1 and probes[0]["mapping"] == "equirect", probes
near(probes[0]["forward"], [1.0, 0.0, 0.0])
near(probes[0]["up"], [0.0, 0.0, 1.0])
near(probes[0]["position"], camera["position"])
loaded = subprocess.run([relight, "rig", scene_path, "-o", outdir + "/hdri/rig.json"], capture_output=True, text=True)
assert loaded.returncode == 0, loaded.stderr
print("check_export: HDRI world exported as an equirect probe relight loads")

# Materials: the example's Diffuse BSDFs export none; a Principled BSDF on the ball exports the ball
# as glossy by its object name (the OBJ's), with its roughness and specular, and relight loads it.
assert "materials" not in scene, scene.get("materials")
ball = bpy.data.objects["Ball"]
shiny = bpy.data.materials.new("Varnish")
shiny.use_nodes = True  # a new material's surface is a Principled BSDF
principled = shiny.node_tree.nodes["Principled BSDF"]
principled.inputs["Roughness"].default_value = 0.25
principled.inputs["Specular"].default_value = 0.6
ball.data.materials[0] = shiny
scene_path = relight_export.export_scene(bpy.context.scene, outdir + "/glossy", outdir + "/" + scene["photo"])
with open(scene_path) as f:
    materials = json.load(f)["materials"]
assert list(materials) == ["Ball"], materials
near(materials["Ball"]["roughness"], 0.25)
near(materials["Ball"]["specular"], 0.6)
loaded = subprocess.run([relight, "rig", scene_path, "-o", outdir + "/glossy/rig.json"], capture_output=True, text=True)
assert loaded.returncode == 0, loaded.stderr
print("check_export: a Principled BSDF exported as the object's gloss, which relight loads")

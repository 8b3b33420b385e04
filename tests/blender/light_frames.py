# Proves the exporter's frames on rendered scenes: for each case a white floor
# and a box are lit by one kind of light only (an HDRI world with one bright
# patch, a sun, a spot, an area light, a point light; a lens-shifted camera),
# Cycles renders the photo, tools/blender/relight_export.py exports the scene
# and `relight analyze` recovers the albedo. The floor is white (0.8) all over,
# so its albedo must come out flat: in the box's shadow as well as outside it.
# A light exported turned, or a camera shifted the wrong way, puts relight's
# shadow elsewhere than the photo's, and the floor's albedo there is far off.
#   blender -b --factory-startup --python-exit-code 1 --python light_frames.py -- \
#       EXPORTER RELIGHT WORKDIR CASE...
# CASE: hdri (an image made in Blender), hdri_rotated (an EXR file turned by a
# Mapping node, the world at strength 2), sun, spot, area, point, shift,
# shift_vertical (the sensor fitted to the height), centimetres (the point
# light's scene modelled in centimetres: Unit Scale 0.01), all (the turned HDRI,
# the spot, the area and the point light and the shifted lens at once; the
# scene's own lights rendered over the analysis must then give back the photo).
# The sun's scene also holds a box and a second sun that are not rendered
# (hide_render, and a collection disabled for rendering): exported, they would
# shade the floor where the photo shows it lit.
import array
import importlib.util
import json
import math
import os
import shutil
import subprocess
import sys

import bpy
from mathutils import Euler, Vector

exporter_path, relight, work, *cases = sys.argv[sys.argv.index("--") + 1:]
spec = importlib.util.spec_from_file_location("relight_export", exporter_path)
relight_export = importlib.util.module_from_spec(spec)
spec.loader.exec_module(relight_export)

WIDTH, HEIGHT = 96, 72
ALBEDO = 0.8
AMBIENT = 0.2  # the world's radiance besides the light: what lights the shadow
# Where the HDRI's bright patch and the sun shine from (azimuth from +X towards +Y, elevation).
AZIMUTH, ELEVATION = math.radians(35.0), math.radians(30.0)
TOWARDS_LIGHT = Vector((math.cos(ELEVATION) * math.cos(AZIMUTH), math.cos(ELEVATION) * math.sin(AZIMUTH),
                        math.sin(ELEVATION)))


def diffuse(name, albedo):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    nodes = material.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    bsdf = nodes.new("ShaderNodeBsdfDiffuse")
    bsdf.inputs["Color"].default_value = (albedo, albedo, albedo, 1.0)
    material.node_tree.links.new(bsdf.outputs["BSDF"], nodes["Material Output"].inputs["Surface"])
    return material


def look(obj, target):
    obj.rotation_euler = (Vector(target) - obj.location).to_track_quat('-Z', 'Y').to_euler()


def uniform_world(scene, radiance):
    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (radiance, radiance, radiance, 1.0)
    scene.world = world


def patch_sky(rotation_z, strength):
    """An equirect image, dim all over, with one bright disc (radius 5 degrees) where
    Cycles shows TOWARDS_LIGHT once a Mapping node turns the image by rotation_z; to be
    shown at `strength`."""
    w, h = 128, 64
    # Cycles looks direction d up at the texture direction R(rotation_z) d.
    lookup = Euler((0.0, 0.0, rotation_z)).to_matrix() @ TOWARDS_LIGHT
    cos_radius = math.cos(math.radians(5.0))
    solid_angle = 2.0 * math.pi * (1.0 - cos_radius)
    patch = 4.0 / (solid_angle * TOWARDS_LIGHT.z) / strength  # 4 W/m^2 on the floor
    ambient = AMBIENT / strength
    pixels = array.array('f', [0.0]) * (w * h * 4)
    for j in range(h):  # Blender's rows count from the bottom
        elevation = ((j + 0.5) / h - 0.5) * math.pi
        for i in range(w):
            # Blender's equirect: u = 0.5 - atan2(y, x) / 2pi, v = 0.5 + elevation / pi.
            azimuth = (0.5 - (i + 0.5) / w) * 2.0 * math.pi
            d = Vector((math.cos(elevation) * math.cos(azimuth), math.cos(elevation) * math.sin(azimuth),
                        math.sin(elevation)))
            value = patch if d.dot(lookup) > cos_radius else ambient
            pixels[(j * w + i) * 4:(j * w + i) * 4 + 4] = array.array('f', [value, value, value, 1.0])
    image = bpy.data.images.new("sky", w, h, float_buffer=True)
    image.pixels.foreach_set(pixels)
    return image


def hdri_world(scene, path=None, rotation_z=None, strength=1.0):
    """A world lit by patch_sky: the generated image itself, or (with `path`) an EXR file of it,
    shown at `strength` (the Background node's)."""
    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    tree = world.node_tree
    texture = tree.nodes.new("ShaderNodeTexEnvironment")
    texture.image = patch_sky(rotation_z or 0.0, strength)
    if path:
        scene.render.image_settings.file_format, scene.render.image_settings.color_depth = 'OPEN_EXR', '32'
        texture.image.save_render(path, scene=scene)  # linear floats (Image.save() of a generated image is not)
        texture.image = bpy.data.images.load(path)
    texture.interpolation = 'Closest'
    tree.links.new(texture.outputs["Color"], tree.nodes["Background"].inputs["Color"])
    tree.nodes["Background"].inputs["Strength"].default_value = strength
    if rotation_z is not None:  # as scenegen and most HDRI set-ups turn the sky
        coords = tree.nodes.new("ShaderNodeTexCoord")
        mapping = tree.nodes.new("ShaderNodeMapping")
        mapping.inputs["Rotation"].default_value = (0.0, 0.0, rotation_z)
        tree.links.new(coords.outputs["Generated"], mapping.inputs["Vector"])
        tree.links.new(mapping.outputs["Vector"], texture.inputs["Vector"])
    scene.world = world


def add_light(scene, kind, location, energy, target, **settings):
    data = bpy.data.lights.new(kind.lower(), kind)
    data.energy = energy
    for key, value in settings.items():
        setattr(data, key, value)
    obj = bpy.data.objects.new(kind.lower(), data)
    obj.location = location
    look(obj, target)
    scene.collection.objects.link(obj)
    return obj


def build(case, folder):
    """The scene of `case`; returns (floor object, the point each floor point is lit from:
    a position, or None with a direction)."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = WIDTH, HEIGHT, 100
    bpy.ops.mesh.primitive_plane_add(size=7.0, location=(0.0, 0.0, 0.0))
    floor = bpy.context.object
    floor.data.materials.append(diffuse("floor", ALBEDO))
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=(0.0, 0.0, 0.7))
    box = bpy.context.object
    box.scale = (0.8, 0.8, 1.4)
    box.data.materials.append(diffuse("box", 0.5))

    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.location = (0.5, -6.5, 5.0)
    look(camera, (0.0, 0.0, 0.2))
    camera.data.lens = 30.0
    if case in ("shift", "all"):
        camera.data.shift_x, camera.data.shift_y = 0.12, -0.08
    if case == "shift_vertical":  # the sensor fitted to the height: field of view and shift in heights
        camera.data.sensor_fit, camera.data.sensor_height, camera.data.lens = 'VERTICAL', 24.0, 24.0
        camera.data.shift_x, camera.data.shift_y = -0.1, 0.12
    scene.collection.objects.link(camera)
    scene.camera = camera

    light_at, light_towards = None, TOWARDS_LIGHT
    if case == "hdri":  # the image made in Blender, not saved: the exporter writes it
        hdri_world(scene)
    elif case in ("hdri_rotated", "all"):  # an EXR file, turned by a Mapping node, at strength 2
        hdri_world(scene, os.path.join(folder, "sky.exr"), math.radians(70.0), 2.0)
    else:
        uniform_world(scene, AMBIENT)
    if case in ("sun", "shift", "shift_vertical"):
        add_light(scene, 'SUN', (0.0, 0.0, 4.0), 4.0, -TOWARDS_LIGHT, angle=math.radians(2.0))
    if case == "sun":
        bpy.ops.mesh.primitive_cube_add(size=1.0, location=(1.5, -1.0, 1.5))
        bpy.context.object.hide_render = True
        unrendered = bpy.data.collections.new("not rendered")
        scene.collection.children.link(unrendered)
        unrendered.hide_render = True
        unrendered.objects.link(add_light(scene, 'SUN', (0.0, 0.0, 4.0), 4.0, -TOWARDS_LIGHT))
        scene.collection.objects.unlink(unrendered.objects[0])
    if case in ("spot", "all"):
        light_at = Vector((2.0, 1.5, 3.0))
        add_light(scene, 'SPOT', light_at, 1500.0, (-0.3, -0.6, 0.0), spot_size=math.radians(120.0),
                  spot_blend=0.05, shadow_soft_size=0.05)
    if case in ("area", "all"):
        light_at = Vector((-2.0, 1.0, 2.8))
        add_light(scene, 'AREA', light_at, 1500.0, (0.2, -0.6, 0.0), shape='RECTANGLE', size=0.4, size_y=0.2)
    if case in ("point", "centimetres", "all"):
        light_at = Vector((1.8, 2.2, 2.6))
        add_light(scene, 'POINT', light_at, 1200.0, (0.0, 0.0, 0.0), shadow_soft_size=0.05)
    if case == "centimetres":  # the same scene 100 times larger in Blender units of 1 cm
        scene.unit_settings.scale_length = 0.01
        for obj in scene.objects:
            obj.location *= 100.0
            obj.scale *= 100.0
            if obj.type == 'LIGHT':
                obj.data.energy *= 1e4  # Cycles has the light fall off with distance in Blender units
                obj.data.shadow_soft_size *= 100.0
        camera.data.clip_end = 1e5
        light_at *= 100.0
        bpy.context.view_layer.update()
    if case == "all":  # the floor classed by the sky's patch; the lamps' shadows fall elsewhere
        light_at = None
    return scene, floor, light_at, light_towards


def render(scene, path):
    scene.render.engine = 'CYCLES'
    cycles = scene.cycles
    cycles.device, cycles.samples, cycles.use_denoising = 'CPU', 48, False
    cycles.use_adaptive_sampling = False
    cycles.seed = 7
    cycles.pixel_filter_type, cycles.filter_width = 'BOX', 1.0
    cycles.max_bounces, cycles.diffuse_bounces = 4, 4
    cycles.sample_clamp_direct = cycles.sample_clamp_indirect = 0.0
    scene.view_settings.view_transform = 'Standard'
    scene.render.image_settings.file_format = 'OPEN_EXR'
    scene.render.image_settings.color_depth = '32'
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)


def pixel_rays(scene):
    """The world ray through each pixel centre (rows from the top), from Blender's own view frame
    (lens shift and sensor fit included), independent of the exporter's arithmetic."""
    camera = scene.camera
    top_right, bottom_right, bottom_left, top_left = camera.data.view_frame(scene=scene)
    rotation = camera.matrix_world.to_3x3()
    for row in range(HEIGHT):
        for col in range(WIDTH):
            x, y = (col + 0.5) / WIDTH, (row + 0.5) / HEIGHT
            local = top_left + x * (top_right - top_left) + y * (bottom_left - top_left)
            yield row, col, camera.matrix_world.translation, (rotation @ local).normalized()


def cast(scene, depsgraph, origin, direction):
    """The first rendered object along the ray (the viewport's ray_cast sees hide_render ones too), or None."""
    for _ in range(8):
        hit, point, _, _, obj, _ = scene.ray_cast(depsgraph, origin, direction)
        if not hit:
            return None, None
        if not obj.hide_render and not any(c.hide_render for c in obj.users_collection):
            return obj, point
        origin = point + 1e-3 * direction
    return None, None


def floor_classes(scene, floor, light_at, light_towards):
    """Per pixel: None (not the floor), True (floor lit by the light), False (floor in the box's shadow)."""
    depsgraph = bpy.context.evaluated_depsgraph_get()
    classes = [[None] * WIDTH for _ in range(HEIGHT)]
    for row, col, origin, direction in pixel_rays(scene):
        obj, point = cast(scene, depsgraph, origin, direction)
        if obj is None or obj.name != floor.name:
            continue
        towards = (light_at - point).normalized() if light_at is not None else light_towards
        blocker, _ = cast(scene, depsgraph, point + 1e-3 * towards, towards)
        classes[row][col] = blocker is None
    return classes


def interior(classes, row, col):
    """The pixel and its 8 neighbours are of one class (away from edges and penumbrae)."""
    value = classes[row][col]
    if value is None or row in (0, HEIGHT - 1) or col in (0, WIDTH - 1):
        return False
    return all(classes[r][c] == value for r in range(row - 1, row + 2) for c in range(col - 1, col + 2))


def albedo_rows(path):
    image = bpy.data.images.load(path)
    assert tuple(image.size) == (WIDTH, HEIGHT), "albedo.exr is %dx%d" % tuple(image.size)
    pixels = array.array('f', [0.0]) * (WIDTH * HEIGHT * 4)
    image.pixels.foreach_get(pixels)
    # Mean of the three channels; Blender's rows count from the bottom.
    return [[sum(pixels[((HEIGHT - 1 - row) * WIDTH + col) * 4 + k] for k in range(3)) / 3.0
             for col in range(WIDTH)] for row in range(HEIGHT)]


def metres_problem(scene_json):
    """The centimetre scene's export must be in metres: the camera 5 m up, the box 1.4 m tall."""
    with open(scene_json) as f:
        camera = json.load(f)["camera"]["position"]
    with open(os.path.join(os.path.dirname(scene_json), "geometry.obj")) as f:
        top = max(float(line.split()[3]) for line in f if line.startswith("v "))
    if abs(camera[2] - 5.0) > 1e-3 or abs(top - 1.4) > 1e-3:
        return "exported camera height %g m and box height %g m, not 5 and 1.4" % (camera[2], top)
    return ""


def round_trip_problem(scene_json, analysis, photo, folder):
    """export -> analyze -> render: the scene's own rig over its analysis gives back the photo."""
    rig, relit = os.path.join(folder, "same.json"), os.path.join(folder, "same.exr")
    for command in (["rig", scene_json, "-o", rig],
                    ["render", scene_json, "--rig", rig, "--analysis", analysis, "-o", relit],
                    ["compare", relit, photo, "--tonemap"]):
        done = subprocess.run([relight] + command, capture_output=True, text=True)
        if done.returncode != 0:
            return "relight %s failed: %s" % (command[0], done.stderr.strip())
    psnr = float(done.stdout.split()[1])
    print("light_frames: %-12s the scene's own lights re-rendered: %.2f dB against the photo (tone-mapped)"
          % ("all", psnr))
    # Both renders' noise at 96x72 and 32 paths a pixel keeps it near 43 dB.
    return "" if psnr > 35.0 else "the re-rendered photo is only %.2f dB from the photo" % psnr


def run(case):
    folder = os.path.join(work, case)
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    scene, floor, light_at, light_towards = build(case, folder)
    photo = os.path.join(folder, "photo.exr")
    render(scene, photo)
    scene_json = relight_export.export_scene(scene, os.path.join(folder, "export"), photo)
    analysis = os.path.join(folder, "analysis")
    done = subprocess.run([relight, "analyze", scene_json, "-o", analysis, "--spp", "32", "--bounces", "4"],
                          capture_output=True, text=True)
    if done.returncode != 0:
        return "relight analyze failed: " + done.stderr.strip()
    if case == "centimetres" and metres_problem(scene_json):
        return metres_problem(scene_json)
    classes = floor_classes(scene, floor, light_at, light_towards)
    albedo = albedo_rows(os.path.join(analysis, "albedo.exr"))
    lit = [albedo[r][c] for r in range(HEIGHT) for c in range(WIDTH) if interior(classes, r, c) and classes[r][c]]
    shade = [albedo[r][c] for r in range(HEIGHT) for c in range(WIDTH)
             if interior(classes, r, c) and classes[r][c] is False]
    assert len(lit) > 200 and len(shade) > 30, "%s: the scene shows %d lit and %d shadowed floor pixels" % (
        case, len(lit), len(shade))
    floor_all = lit + shade
    mean = sum(floor_all) / len(floor_all)
    std = math.sqrt(sum((a - mean) ** 2 for a in floor_all) / len(floor_all))
    lit_mean, shade_mean = sum(lit) / len(lit), sum(shade) / len(shade)
    print("light_frames: %-12s floor albedo %.3f (std/mean %.3f; lit %.3f over %d px, in the shadow %.3f over %d px)"
          % (case, mean, std / mean, lit_mean, len(lit), shade_mean, len(shade)))
    # 10% on the means, 25% on the spread: Cycles' and relight's noise at 48 and 32 paths a pixel.
    problems = ["%s %.3f, not %.2f" % (where, value, ALBEDO) for where, value in
                (("lit floor", lit_mean), ("shadowed floor", shade_mean))
                if abs(value - ALBEDO) > 0.1 * ALBEDO]
    if std / mean > 0.25:
        problems.append("std/mean %.3f" % (std / mean))
    if case == "all":
        problems.append(round_trip_problem(scene_json, analysis, photo, folder))
    return "; ".join(p for p in problems if p)


failures = []
for case in cases:
    problem = run(case)
    if problem:
        failures.append("%s: %s" % (case, problem))
if failures:
    print("light_frames: the floor's albedo is not flat:\n  " + "\n  ".join(failures), file=sys.stderr)
    sys.exit(1)
print("light_frames: the white floor's albedo flat in each of: " + ", ".join(cases))

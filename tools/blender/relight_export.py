# relight's bridge to Blender: export the scene for relight, import relight rigs.
#
# As an add-on (Edit > Preferences > Add-ons > Install..., this file):
#   File > Export > relight scene (scene.json + geometry.obj)
#   File > Export > relight rig (the lights as a rig.json, their animation as keys)
#   File > Import > relight rig (lights of a rig.json or scene.json)
# From the command line (exit 2 and one line on what is wrong with the scene or rig,
# 1 on any other error):
#   blender -b FILE.blend --python-exit-code 1 --python relight_export.py -- OUTDIR [--photo PHOTO]
#   blender -b FILE.blend --python-exit-code 1 --python relight_export.py -- OUTDIR --shot render/photo.####.exr [--frames A-B]
#   blender -b FILE.blend --python-exit-code 1 --python relight_export.py -- --export-rig RIG.json [--frames A-B]
#   blender -b FILE.blend --python-exit-code 1 --python relight_export.py -- --import-rig RIG.json [--replace] [--save OUT.blend]
#
# Coordinates stay Blender's world frame (Z up): the OBJ is written without an
# axis conversion, and the camera, lights and probe are given in the same
# frame, in metres (the scene's Unit Scale applied). Light units are Blender's
# own, which relight's scene format uses unchanged (docs/formats.md). Only what
# Cycles renders is exported: hide_render objects and collections disabled for
# rendering are left out of the geometry, and such lights are exported switched
# off. See docs/tutorial.md.

bl_info = {
    "name": "relight scene exporter",
    "description": "Export the camera, lights, world and geometry for relight; import relight rigs as lights",
    "blender": (3, 3, 0),
    "category": "Import-Export",
    "location": "File > Export > relight scene; File > Import > relight rig",
}

import array
import json
import math
import os
import re
import shutil
import sys
import tempfile

import bpy
import mathutils


class BridgeError(Exception):
    pass


def _vec(v):
    return [round(float(x), 7) for x in v]


def metres_per_unit(scene):
    """What one Blender unit is in metres: the scene's Unit Scale (a scene modelled in
    centimetres has 0.01). relight's scenes are in metres."""
    units = scene.unit_settings
    return units.scale_length if units.system != 'NONE' else 1.0


def _axes(obj):
    """World position, and the object's -Z (where a camera or light points) and +Y, unit."""
    m = obj.matrix_world
    rot = m.to_3x3().normalized()
    return m.translation.copy(), -rot.col[2], rot.col[1]


# ------------------------------------------------------------------ export

def camera_block(scene, metres=1.0):
    cam = scene.camera
    if cam is None or cam.type != 'CAMERA':
        raise BridgeError("the scene has no active camera")
    data = cam.data
    if data.type != 'PERSP':
        raise BridgeError("the active camera '%s' is not a perspective camera" % cam.name)
    render = scene.render
    if abs(render.pixel_aspect_x - render.pixel_aspect_y) > 1e-6 * render.pixel_aspect_x:
        raise BridgeError("the render's pixel aspect is %g:%g; relight's photos have square pixels"
                          % (render.pixel_aspect_x, render.pixel_aspect_y))
    width, height = render.resolution_x, render.resolution_y
    # Blender's sensor fit: the sensor spans the width (horizontal) or the height (vertical);
    # AUTO fits the longer side with sensor_width.
    fit = data.sensor_fit
    if fit == 'AUTO':
        fit = 'HORIZONTAL' if width >= height else 'VERTICAL'
        sensor = data.sensor_width
    else:
        sensor = data.sensor_width if fit == 'HORIZONTAL' else data.sensor_height
    tan_half = sensor / (2.0 * data.lens)
    if fit == 'HORIZONTAL':
        tan_half *= height / width
    position, forward, up = _axes(cam)
    block = {
        "position": _vec(position * metres),
        "look_at": _vec(position * metres + forward),
        "up": _vec(up),
        "vfov_deg": math.degrees(2.0 * math.atan(tan_half)),
        # The render's shape: relight refuses a photo of another (cropped to 16:9, say).
        "aspect": width / height,
    }
    # Lens shift is in units of the fitted side; relight's principal point is a
    # fraction of width and height from the top left.
    if data.shift_x != 0.0 or data.shift_y != 0.0:
        unit = width if fit == 'HORIZONTAL' else height
        block["principal_point"] = [0.5 - data.shift_x * unit / width, 0.5 + data.shift_y * unit / height]
    return block, (render.resolution_x, render.resolution_y)


def light_entry(obj, metres=1.0):
    """The light as relight's scene format has it; lengths in metres (`metres` per Blender unit).
    Cycles takes lengths in Blender units, so a lamp lights a surface d units away as one of
    power P at d metres would: in metres it has power P * metres^2 (a sun's irradiance stays)."""
    light = obj.data
    position, forward, up = _axes(obj)
    position, power = position * metres, light.energy * metres ** 2
    scale = obj.matrix_world.to_scale() * metres
    entry = {"name": obj.name, "color": _vec(light.color)}
    if light.type in ('POINT', 'SPOT'):
        entry.update(type=light.type.lower(), position=_vec(position), power=power)
        if light.shadow_soft_size > 0.0:
            entry["radius"] = light.shadow_soft_size * metres
        if light.type == 'SPOT':
            entry.update(direction=_vec(forward), spot_angle_deg=math.degrees(light.spot_size), blend=light.spot_blend)
    elif light.type == 'AREA':
        w = light.size * scale.x
        h = (light.size_y if light.shape in ('RECTANGLE', 'ELLIPSE') else light.size) * scale.y
        if light.shape in ('DISK', 'ELLIPSE'):
            # relight's area lights are rectangles: keep the area and the power.
            w, h = w * math.sqrt(math.pi) / 2.0, h * math.sqrt(math.pi) / 2.0
            print("relight_export: area light '%s' is a %s; exported as a rectangle of the same area"
                  % (obj.name, light.shape.lower()))
        entry.update(type="area", position=_vec(position), direction=_vec(forward), up=_vec(up),
                     size=[w, h], power=power)
    elif light.type == 'SUN':
        entry.update(type="directional", direction=_vec(forward), irradiance=light.energy)
        if light.angle > 0.0:
            entry["angle_deg"] = math.degrees(light.angle)
    else:
        raise BridgeError("light '%s' has type %s, which relight does not know" % (obj.name, light.type))
    return entry


def _world_background(world):
    """The Background node and its strength, or (None, 1)."""
    if world is None or not world.use_nodes:
        return None, 1.0
    for node in world.node_tree.nodes:
        if node.type == 'BACKGROUND':
            return node, node.inputs['Strength'].default_value
    return None, 1.0


def _environment_frame(texture):
    """relight's forward and up for an Environment Texture's equirect image.

    Cycles looks a direction d up at u = 0.5 - atan2(d.y, d.x)/2pi, v = 0.5 + asin(d.z)/pi
    (u from the left, v from the bottom): the image centre shows +X, the top row +Z and
    columns run towards -Y, which is relight's equirect with forward +X and up +Z.
    A Mapping node (fed by Texture Coordinate > Generated, the world direction) makes the
    lookup R d (Point, Vector, Normal) or R^-1 d (Texture): the frame turns by R^-1 or R."""
    forward, up = mathutils.Vector((1.0, 0.0, 0.0)), mathutils.Vector((0.0, 0.0, 1.0))
    vector = texture.inputs['Vector']
    if not vector.is_linked:
        return forward, up
    mapping = vector.links[0].from_node
    if mapping.type != 'MAPPING':
        raise BridgeError("the world's Environment Texture takes its vector from a %s node; relight takes "
                          "none, or a Mapping node fed by Texture Coordinate > Generated" % mapping.type)
    source = mapping.inputs['Vector'].links[0].from_socket if mapping.inputs['Vector'].is_linked else None
    if source is None or source.node.type != 'TEX_COORD' or source.name != 'Generated':
        raise BridgeError("the world's Mapping node is not fed by Texture Coordinate > Generated")
    scale = mapping.inputs['Scale'].default_value if 'Scale' in mapping.inputs else (1.0, 1.0, 1.0)
    if min(scale) <= 0.0 or max(scale) - min(scale) > 1e-6 * max(scale):
        raise BridgeError("the world's Mapping node scales the HDRI unevenly (%g, %g, %g); relight takes "
                          "an undistorted sky" % tuple(scale))
    if mapping.vector_type in ('POINT', 'TEXTURE') and mapping.inputs['Location'].default_value.length > 1e-6:
        raise BridgeError("the world's Mapping node moves the HDRI (Location); relight takes rotations only")
    rotation = mathutils.Euler(mapping.inputs['Rotation'].default_value, 'XYZ').to_matrix()
    turn = rotation if mapping.vector_type == 'TEXTURE' else rotation.transposed()
    return turn @ forward, turn @ up


def _write_linear_exr(image, path, scene):
    """The image's float pixels as a 32-bit EXR (Image.save() of a generated image writes them
    colour-managed; save_render with an EXR format writes them as they are)."""
    settings = scene.render.image_settings
    kept = settings.file_format, settings.color_depth
    settings.file_format, settings.color_depth = 'OPEN_EXR', '32'
    try:
        image.save_render(path, scene=scene)
    finally:
        settings.file_format, settings.color_depth = kept


def _write_scaled_exr(image, factor, path, scene):
    """The image's colour times `factor`, as a 32-bit EXR."""
    width, height = image.size
    pixels = array.array('f', [0.0]) * (width * height * 4)
    image.pixels.foreach_get(pixels)
    for channel in range(3):  # alpha stays
        pixels[channel::4] = array.array('f', (value * factor for value in pixels[channel::4]))
    copy = bpy.data.images.new("relight scaled " + image.name, width, height, float_buffer=True)
    try:
        copy.pixels.foreach_set(pixels)
        _write_linear_exr(copy, path, scene)
    finally:
        bpy.data.images.remove(copy)


def world_entries(scene, folder, probe_position):
    """background (constant colour) or probes (an equirect HDRI, written into `folder`) for the world."""
    world = scene.world
    node, strength = _world_background(world)
    if node is None:
        colour = world.color if world is not None else (0.0, 0.0, 0.0)
        return {"background": _vec(c for c in colour)}
    colour_input = node.inputs['Color']
    if not colour_input.is_linked:
        return {"background": _vec(c * strength for c in colour_input.default_value[:3])}
    texture = colour_input.links[0].from_node
    if texture.type != 'TEX_ENVIRONMENT' or texture.image is None:
        raise BridgeError("the world colour comes from a %s node; relight takes a colour or an "
                          "Environment Texture (equirectangular HDRI)" % texture.type)
    if texture.projection != 'EQUIRECTANGULAR':
        raise BridgeError("the world's Environment Texture uses %s projection; relight takes equirectangular"
                          % texture.projection)
    forward, up = _environment_frame(texture)
    image = texture.image
    source = bpy.path.abspath(image.filepath)
    scaled = abs(strength - 1.0) > 1e-6
    if scaled and not image.is_float:
        print("relight_export: warning: the world strength %.3g is not applied to the 8-bit image %s"
              % (strength, image.name))
        scaled = False
    if scaled:  # the probe is the light Cycles renders with: the image times the strength
        name = "%s_x%g.exr" % (bpy.path.clean_name(os.path.splitext(image.name)[0]), strength)
        _write_scaled_exr(image, strength, os.path.join(folder, name), scene)
    elif image.packed_file is None and image.source == 'FILE' and os.path.isfile(source):
        name = os.path.basename(source)
        target = os.path.join(folder, name)
        if os.path.abspath(source) != os.path.abspath(target):
            shutil.copyfile(source, target)
    else:  # packed or generated: write its float pixels
        name = bpy.path.clean_name(os.path.splitext(image.name)[0]) + ".exr"
        _write_linear_exr(image, os.path.join(folder, name), scene)
    return {"probes": [{"image": name, "mapping": "equirect", "position": _vec(probe_position),
                        "forward": _vec(forward), "up": _vec(up)}]}


def camera_photo(scene):
    """The camera's background image (where fSpy's importer puts the photo), if any."""
    cam = scene.camera
    for bg in (cam.data.background_images if cam is not None else []):
        if bg.image is not None and bg.image.filepath:
            return bpy.path.abspath(bg.image.filepath)
    return None


def rendered_objects(scene):
    """The objects Cycles renders: in no excluded or render-disabled collection, not hide_render."""
    found = set()

    def walk(layer_collection):
        if layer_collection.exclude or layer_collection.collection.hide_render:
            return
        found.update(o for o in layer_collection.collection.objects if not o.hide_render)
        for child in layer_collection.children:
            walk(child)

    walk(bpy.context.view_layer.layer_collection)
    return found


def _principled(material):
    """The Principled BSDF that is a material's surface, or None (any other shader: matte to relight)."""
    if not material or not material.use_nodes:
        return None
    for node in material.node_tree.nodes:
        if node.type == 'OUTPUT_MATERIAL' and node.is_active_output and node.inputs['Surface'].links:
            source = node.inputs['Surface'].links[0].from_node
            return source if source.type == 'BSDF_PRINCIPLED' else None
    return None


def materials_block(objects):
    """scene.json's "materials": each rendered mesh whose surface is a Principled BSDF that shines
    (specular above 0), by object name (the OBJ's `o` lines), with its roughness and specular. A
    texture driving either is taken at the input's own value, metallic as 0 (relight models dielectrics);
    both said. An object of several glossy materials takes the sharpest's, with a warning."""
    block = {}
    for obj in sorted(objects, key=lambda o: o.name):
        if obj.type != 'MESH':
            continue
        glosses = set()
        for slot in obj.material_slots:
            node = _principled(slot.material)
            if node is None:
                continue
            for name in ('Roughness', 'Specular', 'Metallic'):
                if node.inputs[name].is_linked:
                    print("relight_export: warning: '%s' (object '%s'): its %s is a texture; exported as %.3g"
                          % (slot.material.name, obj.name, name.lower(), node.inputs[name].default_value))
            if node.inputs['Metallic'].default_value > 0:
                print("relight_export: warning: '%s' (object '%s') is metallic, which relight does not model: "
                      "exported as a dielectric" % (slot.material.name, obj.name))
            roughness = round(min(max(node.inputs['Roughness'].default_value, 0.0), 1.0), 4)
            specular = round(min(max(node.inputs['Specular'].default_value, 0.0), 1.0), 4)
            if specular > 0:
                glosses.add((roughness, specular))
        if len(glosses) > 1:
            print("relight_export: warning: object '%s' has materials of %d glosses; exported with the "
                  "sharpest's" % (obj.name, len(glosses)))
        if glosses:
            roughness, specular = min(glosses)
            block[obj.name] = {"roughness": roughness, "specular": specular}
    return block


def write_geometry(path, metres):
    """Every mesh Cycles renders (hide_render objects and disabled collections left out) as one OBJ
    in world coordinates, metres, no axis change, triangulated. Refuses a scene without faces."""
    bpy.ops.wm.obj_export(filepath=path, export_selected_objects=False, export_eval_mode='DAG_EVAL_RENDER',
                          apply_modifiers=True, global_scale=metres, forward_axis='Y', up_axis='Z',
                          export_materials=False, export_uv=False, export_normals=True,
                          export_triangulated_mesh=True, export_animation=False)
    with open(path) as f:
        if not any(line.startswith("f ") for line in f):
            raise BridgeError("no visible mesh: the render shows nothing that could be relight's geometry")


def check_photo_size(photo, resolution):
    """Refuses a photo whose aspect ratio is not the render resolution's (the camera's field of
    view is worked out for that shape)."""
    image = bpy.data.images.load(photo, check_existing=False)
    try:
        width, height = image.size
    finally:
        bpy.data.images.remove(image)
    if width == 0 or height == 0:
        raise BridgeError("the photo %s cannot be read as an image" % photo)
    if abs(width * resolution[1] - height * resolution[0]) > max(resolution[0], resolution[1]) * 0.01 * height:
        raise BridgeError("the photo %s is %dx%d, not the aspect ratio of the render resolution %dx%d"
                          % (photo, width, height, resolution[0], resolution[1]))


def frame_file(pattern, frame):
    """PATTERN's last run of '#' replaced by FRAME, zero-padded to as many digits (relight's and
    Blender's convention: photo.####.exr, frame 7 -> photo.0007.exr)."""
    folder, name = os.path.split(pattern)
    runs = list(re.finditer("#+", name))
    if not runs:
        raise BridgeError("the shot's photos %s need '#'s for the frame number (photo.####.exr)" % pattern)
    run = runs[-1]
    return os.path.join(folder, name[:run.start()] + str(frame).zfill(run.end() - run.start()) + name[run.end():])


def shot_block(scene, pattern, frames, metres=1.0):
    """A tracked shot over FRAMES (first, last): the camera at each frame, and each frame's photo
    (PATTERN's '#'s its number), which must exist and have the render's aspect. Returns the
    scene.json's "shot" block and the photos' paths."""
    first, last = frames
    if last < first:
        raise BridgeError("the shot's frames %d-%d are empty" % (first, last))
    cameras, photos = [], []
    current = scene.frame_current
    try:
        for frame in range(first, last + 1):
            scene.frame_set(frame)
            camera, resolution = camera_block(scene, metres)
            photo = frame_file(pattern, frame)
            if not os.path.isfile(photo):
                raise BridgeError("frame %d's photo %s does not exist" % (frame, photo))
            check_photo_size(photo, resolution)
            cameras.append(camera)
            photos.append(photo)
    finally:
        scene.frame_set(current)
    block = {"photo": os.path.basename(pattern), "first_frame": first, "cameras": cameras}
    return block, photos


def export_scene(scene, outdir, photo=None, shot=None, frames=None):
    """Writes OUTDIR/scene.json, OUTDIR/geometry.obj and copies the photo (and HDRI) there; with
    SHOT (a photo pattern with '#'s), the camera of every frame of FRAMES (first, last; default the
    scene's range) as a tracked shot, its photos copied too, the first frame (its photo and camera)
    the scene's still. Checks first, so that a refused scene writes nothing."""
    shot_photos = []
    if shot:
        if photo:
            raise BridgeError("a shot's still is its first frame: give --shot or --photo, not both")
        frames = frames or (scene.frame_start, scene.frame_end)
        shot_doc, shot_photos = shot_block(scene, shot, frames, metres_per_unit(scene))
        photo = shot_photos[0]
    photo = photo or camera_photo(scene)
    if not photo:
        raise BridgeError("no photo: give one (--photo, or the exporter's Photo field) or set it as the "
                          "camera's background image")
    if not os.path.isfile(photo):
        raise BridgeError("the photo %s does not exist" % photo)
    metres = metres_per_unit(scene)
    camera, resolution = camera_block(scene, metres)
    if shot:
        camera = shot_doc["cameras"][0]
    check_photo_size(photo, resolution)
    rendered = rendered_objects(scene)
    lights = []
    for obj in scene.objects:
        if obj.type == 'LIGHT':
            lights.append(light_entry(obj, metres))
            if obj not in rendered:
                lights[-1]["enabled"] = False
    photo_name = os.path.basename(photo)
    doc = {"format": "relight-scene/1", "photo": photo_name, "geometry": "geometry.obj", "camera": camera,
           "lights": lights}
    if shot:
        doc["shot"] = shot_doc
    materials = materials_block(rendered)
    if materials:
        doc["materials"] = materials
    target = os.path.join(outdir, "scene.json")
    # Everything is made in a scratch folder first: a scene refused on the way writes nothing.
    with tempfile.TemporaryDirectory() as scratch:
        write_geometry(os.path.join(scratch, "geometry.obj"), metres)
        doc.update(world_entries(scene, scratch, mathutils.Vector(camera["position"])))
        with open(os.path.join(scratch, "scene.json"), "w") as f:
            json.dump(doc, f, indent=2)
            f.write("\n")
        os.makedirs(outdir, exist_ok=True)
        for source in [photo] + shot_photos:
            if os.path.abspath(os.path.dirname(source)) != os.path.abspath(outdir):
                shutil.copyfile(source, os.path.join(outdir, os.path.basename(source)))
        for name in os.listdir(scratch):
            if name != "scene.json":
                shutil.move(os.path.join(scratch, name), os.path.join(outdir, name))
        # scene.json last, renamed over: a reader never sees half a file, nor one whose files are missing.
        shutil.move(os.path.join(scratch, "scene.json"), target + ".part")
        os.replace(target + ".part", target)
    print("relight_export: wrote %s (%d lights, %g m per Blender unit%s)"
          % (target, len(lights), metres, ", a shot of %d frames" % len(shot_photos) if shot else ""))
    return target


# ------------------------------------------------------------------ an animated rig

# What a key of relight's animated rigs may set (docs/formats.md, "Animated rigs").
_KEYABLE = ("position", "direction", "color", "power", "irradiance", "enabled")
# What relight does not key: a light whose animation changes these is exported with its first frame's.
_UNKEYABLE = ("up", "size", "radius", "spot_angle_deg", "blend", "angle_deg")


def _differ(a, b, tol=1e-6):
    if isinstance(a, list):
        return any(_differ(x, y, tol) for x, y in zip(a, b))
    if isinstance(a, bool) or a is None or b is None:
        return a != b
    return abs(a - b) > tol * max(1.0, abs(a), abs(b))


def _bends(track, i, name):
    """Whether the value `name` at sample i is not on the straight line through its neighbours:
    its key is needed (the first and last always are; on/off wherever it changes)."""
    if i == 0 or i == len(track) - 1:
        return True
    before, here, after = (track[j][1][name] for j in (i - 1, i, i + 1))
    if isinstance(here, bool):
        return here != before
    if isinstance(here, list):
        return any(_differ(2 * h, b + a) for b, h, a in zip(before, here, after))
    return _differ(2 * here, before + after)


def light_samples(scene, lights, first, last, metres):
    """Each light's entry at every frame first..last (the scene's frame restored after)."""
    samples = {obj.name: [] for obj in lights}
    current = scene.frame_current
    try:
        for frame in range(first, last + 1):
            scene.frame_set(frame)
            rendered = rendered_objects(scene)
            for obj in lights:
                entry = light_entry(obj, metres)
                entry["enabled"] = obj in rendered
                samples[obj.name].append((frame, entry))
    finally:
        scene.frame_set(current)
    return samples


def animated_light(track):
    """A light's entry from its samples: the first frame's values, and keys for those that change,
    one where a value bends (the frames between follow linearly, as Blender's curves sampled at
    every frame do)."""
    light = dict(track[0][1])
    name = light["name"]
    for key in _UNKEYABLE:
        if any(_differ(entry.get(key), light.get(key)) for _, entry in track):
            print("relight_export: light '%s': its %s is animated, which relight does not key; exported "
                  "as at frame %d" % (name, key, track[0][0]))
    changing = [k for k in _KEYABLE if k in light and any(_differ(e[k], light[k]) for _, e in track)]
    if changing:
        keys = []
        for i, (frame, entry) in enumerate(track):
            key = {k: entry[k] for k in changing if _bends(track, i, k)}
            if key:
                keys.append(dict(frame=frame, interpolation="linear", **key))
        light["keys"] = keys
    if light["enabled"]:
        del light["enabled"]
    return light


def export_rig(scene, path, frames=None):
    """Writes the scene's lights as a relight rig at PATH, each light's animation over FRAMES
    (first, last; default the scene's frame range) as its keys. Returns the number of animated lights."""
    first, last = frames or (scene.frame_start, scene.frame_end)
    if first > last:
        raise BridgeError("the frames %d-%d run backwards" % (first, last))
    metres = metres_per_unit(scene)
    lights = [obj for obj in scene.objects if obj.type == 'LIGHT']
    samples = light_samples(scene, lights, first, last, metres)
    entries = [animated_light(samples[obj.name]) for obj in lights]
    doc = {"format": "relight-rig/1", "environment_scale": 1.0, "lights": entries}
    with open(path + ".part", "w") as f:
        json.dump(doc, f, indent=2)
        f.write("\n")
    os.replace(path + ".part", path)
    animated = sum(1 for e in entries if "keys" in e)
    print("relight_export: wrote %s (%d lights, %d animated over frames %d-%d)" % (path, len(entries), animated,
                                                                                first, last))
    return animated


# ------------------------------------------------------------------ import

def _linear_colour(value, where):
    """A rig colour as typed: [r, g, b] linear, or "#rrggbb" sRGB-encoded (linearised)."""
    if isinstance(value, str):
        if len(value) != 7 or value[0] != '#' or any(c not in "0123456789abcdefABCDEF" for c in value[1:]):
            raise BridgeError("%s: %r is not a colour \"#rrggbb\"" % (where, value))

        def lin(c):
            return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4
        return [lin(int(value[i:i + 2], 16) / 255.0) for i in (1, 3, 5)]
    if not isinstance(value, list) or len(value) != 3 or not all(isinstance(c, (int, float)) for c in value):
        raise BridgeError("%s: %r is not a colour [r, g, b]" % (where, value))
    return [float(c) for c in value]


def _orientation(direction, up=None):
    """A rotation whose -Z is `direction` and whose +Y is as close to `up` as can be."""
    back = -mathutils.Vector(direction).normalized()
    up = mathutils.Vector(up if up is not None else (0.0, 0.0, 1.0))
    if abs(up.normalized().dot(back)) > 0.999:
        up = mathutils.Vector((0.0, 1.0, 0.0))
    right = up.cross(back).normalized()
    return mathutils.Matrix((right, back.cross(right), back)).transposed()


def scale_world(scene, scale):
    """The world's strength (or colour) at `scale` times what it was before any rig was imported:
    a rig's environment_scale. The unscaled value is kept on the world, so importing rig after rig
    does not compound."""
    world = scene.world
    if world is None:
        if scale != 1.0:
            print("relight_export: the scene has no world to scale by %g" % scale)
        return
    node, strength = _world_background(world)
    base = world.get("relight_unscaled")
    if base is None:
        base = world["relight_unscaled"] = [strength] if node is not None else list(world.color)
    if node is not None:
        node.inputs['Strength'].default_value = base[0] * scale
    else:
        world.color = [c * scale for c in base]


def _light_from_entry(entry, where, metres):
    """(name, a Blender light object not yet in the scene) for one light of a rig."""
    def need(key):
        if key not in entry:
            raise BridgeError("%s: the %s light has no \"%s\"" % (where, entry.get("type"), key))
        return entry[key]

    kind = entry.get("type")
    blender_type = {"point": 'POINT', "spot": 'SPOT', "area": 'AREA', "directional": 'SUN'}.get(kind)
    if blender_type is None:
        raise BridgeError("%s/type: %r is not point, spot, area or directional" % (where, kind))
    name = entry.get("name", "%s %s" % (kind, where.rsplit("/", 1)[-1]))
    data = bpy.data.lights.new(name, blender_type)
    data.color = _linear_colour(entry.get("color", [1.0, 1.0, 1.0]), where + "/color")
    rotation = mathutils.Matrix.Identity(3)
    if kind == "directional":
        data.energy = need("irradiance")
        data.angle = math.radians(entry.get("angle_deg", 0.0))
        rotation = _orientation(need("direction"))
    else:  # Blender units and the power that lights a surface so many units away as the rig's does
        data.energy = need("power") / metres ** 2
    if kind in ("point", "spot"):
        data.shadow_soft_size = entry.get("radius", 0.0) / metres
    if kind == "spot":
        data.spot_size = math.radians(need("spot_angle_deg"))
        data.spot_blend = entry.get("blend", 0.0)
        rotation = _orientation(need("direction"))
    elif kind == "area":
        data.shape = 'RECTANGLE'
        data.size, data.size_y = (x / metres for x in need("size"))
        rotation = _orientation(need("direction"), need("up"))
    obj = bpy.data.objects.new(name, data)
    position = mathutils.Vector(entry.get("position", (0.0, 0.0, 0.0)) if kind == "directional"
                                else need("position")) / metres
    obj.matrix_world = mathutils.Matrix.Translation(position) @ rotation.to_4x4()
    obj.hide_render = not entry.get("enabled", True)
    return name, obj


_INTERPOLATION = {"constant": 'CONSTANT', "linear": 'LINEAR', "smooth": 'BEZIER'}


def _check_keys(entry, where):
    """Refuses keys _keyframe_light cannot make keyframes of, before anything changes."""
    keys = entry.get("keys", [])
    if not isinstance(keys, list) or not all(isinstance(key, dict) for key in keys):
        raise BridgeError("%s/keys is not a list of keys" % where)
    for i, key in enumerate(keys):
        if not isinstance(key.get("frame"), int):
            raise BridgeError("%s/keys/%d: a key needs a whole \"frame\"" % (where, i))
        if key.get("interpolation", "smooth") not in _INTERPOLATION:
            raise BridgeError("%s/keys/%d/interpolation: %r is not constant, linear or smooth"
                              % (where, i, key["interpolation"]))


def _keyframe_light(obj, entry, where, metres):
    """The keys of an animated rig's light as Blender keyframes on OBJ (in the scene): each value
    at its keys' frames, with their interpolation (relight's smooth as Blender's Bezier, whose
    auto-clamped handles are close to it but not the same curve)."""
    data, euler = obj.data, obj.rotation_euler.copy()
    for i, key in enumerate(entry.get("keys", [])):
        at = "%s/keys/%d" % (where, i)
        frame, interpolation = key["frame"], _INTERPOLATION[key.get("interpolation", "smooth")]
        keyed = []  # (ID, property)
        if "position" in key:
            obj.location = mathutils.Vector(key["position"]) / metres
            keyed.append((obj, "location"))
        if "direction" in key:
            euler = _orientation(key["direction"], entry.get("up")).to_euler('XYZ', euler)
            obj.rotation_euler = euler
            keyed.append((obj, "rotation_euler"))
        if "color" in key:
            data.color = _linear_colour(key["color"], at + "/color")
            keyed.append((data, "color"))
        power = key.get("irradiance" if entry.get("type") == "directional" else "power")
        if power is not None:
            data.energy = power if entry.get("type") == "directional" else power / metres ** 2
            keyed.append((data, "energy"))
        if "enabled" in key:
            obj.hide_render = not key["enabled"]
            keyed.append((obj, "hide_render"))
        for owner, prop in keyed:
            owner.keyframe_insert(prop, frame=frame)
            for curve in owner.animation_data.action.fcurves:
                if curve.data_path == prop:
                    for point in curve.keyframe_points:
                        if point.co.x == frame:
                            point.interpolation = interpolation


def import_rig(path, collection=None, replace=False):
    """Creates Blender lights for the lights of a rig.json (or scene.json), after deleting the
    scene's lights if `replace`, and scales the world by the rig's environment_scale; returns the
    lights. Lengths are turned into the scene's units (its Unit Scale). An animated rig's keys
    become keyframes."""
    with open(path) as f:
        doc = json.load(f)
    if not isinstance(doc, dict) or doc.get("format") not in ("relight-rig/1", "relight-scene/1"):
        raise BridgeError("%s: not a relight rig or scene (format %r)"
                          % (path, doc.get("format") if isinstance(doc, dict) else None))
    lights = doc.get("lights", [])
    if not isinstance(lights, list) or not all(isinstance(entry, dict) for entry in lights):
        raise BridgeError("%s: /lights is not a list of lights" % path)
    scale = doc.get("environment_scale", 1.0)
    if not isinstance(scale, (int, float)) or scale < 0.0:
        raise BridgeError("%s: /environment_scale %r is not a number >= 0" % (path, scale))
    scene = bpy.context.scene
    metres = metres_per_unit(scene)
    # Every light is made before anything in the scene changes: a bad entry changes nothing.
    for i, entry in enumerate(lights):
        _check_keys(entry, "%s: /lights/%d" % (path, i))
    made = [_light_from_entry(entry, "%s: /lights/%d" % (path, i), metres) for i, entry in enumerate(lights)]
    if replace:
        for obj in [o for o in scene.objects if o.type == 'LIGHT']:
            bpy.data.objects.remove(obj)
    collection = collection or scene.collection
    for i, ((name, obj), entry) in enumerate(zip(made, lights)):
        collection.objects.link(obj)
        obj.name = name  # the rig's name, now that a replaced light no longer holds it
        _keyframe_light(obj, entry, "%s: /lights/%d" % (path, i), metres)
    scale_world(scene, float(scale))
    return [obj for _, obj in made]


# ------------------------------------------------------------------ add-on UI

class RELIGHT_OT_export(bpy.types.Operator):
    """Export the active camera, the lights, the world and the geometry for relight"""
    bl_idname = "relight.export_scene"
    bl_label = "Export relight scene"

    directory: bpy.props.StringProperty(subtype='DIR_PATH')
    photo: bpy.props.StringProperty(name="Photo", subtype='FILE_PATH',
                                    description="The HDR photo (default: the camera's background image)")

    def execute(self, context):
        try:
            path = export_scene(context.scene, bpy.path.abspath(self.directory), bpy.path.abspath(self.photo) or None)
        except BridgeError as e:
            self.report({'ERROR'}, "relight export: " + str(e))
            return {'CANCELLED'}
        self.report({'INFO'}, "relight scene written to " + path)
        return {'FINISHED'}

    def invoke(self, context, event):
        context.window_manager.fileselect_add(self)
        return {'RUNNING_MODAL'}


class RELIGHT_OT_export_rig(bpy.types.Operator):
    """Export the scene's lights as a relight rig, their animation over the frame range as keys"""
    bl_idname = "relight.export_rig"
    bl_label = "Export relight rig"

    filepath: bpy.props.StringProperty(subtype='FILE_PATH')
    filter_glob: bpy.props.StringProperty(default="*.json", options={'HIDDEN'})

    def execute(self, context):
        try:
            export_rig(context.scene, bpy.path.abspath(self.filepath))
        except (BridgeError, OSError) as e:
            self.report({'ERROR'}, "relight rig export: %s" % e)
            return {'CANCELLED'}
        self.report({'INFO'}, "relight rig written to " + self.filepath)
        return {'FINISHED'}

    def invoke(self, context, event):
        if not self.filepath:
            self.filepath = "rig.json"
        context.window_manager.fileselect_add(self)
        return {'RUNNING_MODAL'}


class RELIGHT_OT_import_rig(bpy.types.Operator):
    """Create Blender lights from a relight rig.json or scene.json"""
    bl_idname = "relight.import_rig"
    bl_label = "Import relight rig"

    filepath: bpy.props.StringProperty(subtype='FILE_PATH')
    replace: bpy.props.BoolProperty(name="Replace the scene's lights", default=False)
    filter_glob: bpy.props.StringProperty(default="*.json", options={'HIDDEN'})

    def execute(self, context):
        try:
            made = import_rig(self.filepath, replace=self.replace)
        except (BridgeError, ValueError, OSError) as e:
            self.report({'ERROR'}, "relight import: %s" % e)
            return {'CANCELLED'}
        self.report({'INFO'}, "%d lights imported" % len(made))
        return {'FINISHED'}

    def invoke(self, context, event):
        context.window_manager.fileselect_add(self)
        return {'RUNNING_MODAL'}


def _export_menu(self, context):
    self.layout.operator(RELIGHT_OT_export.bl_idname, text="relight scene (scene.json)")
    self.layout.operator(RELIGHT_OT_export_rig.bl_idname, text="relight rig (.json, animated lights)")


def _import_menu(self, context):
    self.layout.operator(RELIGHT_OT_import_rig.bl_idname, text="relight rig (.json)")


def register():
    bpy.utils.register_class(RELIGHT_OT_export)
    bpy.utils.register_class(RELIGHT_OT_export_rig)
    bpy.utils.register_class(RELIGHT_OT_import_rig)
    bpy.types.TOPBAR_MT_file_export.append(_export_menu)
    bpy.types.TOPBAR_MT_file_import.append(_import_menu)


def unregister():
    bpy.types.TOPBAR_MT_file_import.remove(_import_menu)
    bpy.types.TOPBAR_MT_file_export.remove(_export_menu)
    bpy.utils.unregister_class(RELIGHT_OT_import_rig)
    bpy.utils.unregister_class(RELIGHT_OT_export_rig)
    bpy.utils.unregister_class(RELIGHT_OT_export)


# ------------------------------------------------------------------ command line

def main(argv):
    import argparse
    parser = argparse.ArgumentParser(prog="blender -b FILE.blend --python relight_export.py --")
    parser.add_argument("outdir", nargs="?", help="folder to write scene.json, geometry.obj and the photo to")
    parser.add_argument("--photo", help="the HDR photo (default: the camera's background image)")
    parser.add_argument("--export-rig", metavar="RIG", help="instead: write the lights as a rig, animated ones keyed")
    parser.add_argument("--shot", metavar="PHOTOS",
                        help="with OUTDIR: a tracked shot, each frame's photo PHOTOS with '#'s for the frame "
                             "number (render/photo.####.exr); the camera exported at every frame")
    parser.add_argument("--frames", metavar="A-B",
                        help="with --export-rig or --shot: the frames (default: the scene's range)")
    parser.add_argument("--import-rig", metavar="RIG", help="instead: create the lights of RIG as Blender lights")
    parser.add_argument("--replace", action="store_true", help="with --import-rig: delete the scene's lights first")
    parser.add_argument("--save", metavar="BLEND", help="with --import-rig: save the result as BLEND")
    args = parser.parse_args(argv)
    try:
        frames = None
        if args.frames:
            first, _, last = args.frames.partition("-")
            frames = (int(first), int(last or first))
        if args.export_rig:
            export_rig(bpy.context.scene, os.path.abspath(args.export_rig), frames)
        elif args.import_rig:
            made = import_rig(args.import_rig, replace=args.replace)
            print("relight_export: %d lights imported from %s" % (len(made), args.import_rig))
            if args.save:
                bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(args.save), check_existing=False)
        elif args.outdir:
            export_scene(bpy.context.scene, os.path.abspath(args.outdir), args.photo and os.path.abspath(args.photo),
                         args.shot and os.path.abspath(args.shot), frames)
        else:
            parser.error("give OUTDIR, --export-rig RIG or --import-rig RIG")
    except (BridgeError, ValueError, OSError) as e:
        print("relight_export: error: %s" % e, file=sys.stderr)
        sys.exit(2)
    except Exception:  # a bug: Blender without --python-exit-code would carry on and exit 0
        import traceback
        traceback.print_exc()
        sys.exit(1)


if __name__ == "__main__":
    main(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])

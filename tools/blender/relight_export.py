# relight's bridge to Blender: export the scene for relight, import relight rigs.
#
# As an add-on (Edit > Preferences > Add-ons > Install..., this file):
#   File > Export > relight scene (scene.json + geometry.obj)
#   File > Import > relight rig (lights of a rig.json or scene.json)
# From the command line:
#   blender -b FILE.blend --python relight_export.py -- OUTDIR [--photo PHOTO]
#   blender -b FILE.blend --python relight_export.py -- --import-rig RIG.json [--replace] [--save OUT.blend]
#
# Coordinates stay Blender's world frame (Z up): the OBJ is written without an
# axis conversion, and the camera, lights and probe are given in the same
# frame. Light units are Blender's own, which relight's scene format uses
# unchanged (docs/formats.md). See docs/tutorial.md.

bl_info = {
    "name": "relight scene exporter",
    "description": "Export the camera, lights, world and geometry for relight; import relight rigs as lights",
    "blender": (3, 3, 0),
    "category": "Import-Export",
    "location": "File > Export > relight scene; File > Import > relight rig",
}

import json
import math
import os
import shutil
import sys

import bpy
import mathutils


class BridgeError(Exception):
    pass


def _vec(v):
    return [round(float(x), 7) for x in v]


def _axes(obj):
    """World position, and the object's -Z (where a camera or light points) and +Y, unit."""
    m = obj.matrix_world
    rot = m.to_3x3().normalized()
    return m.translation.copy(), -rot.col[2], rot.col[1]


# ------------------------------------------------------------------ export

def camera_block(scene):
    cam = scene.camera
    if cam is None or cam.type != 'CAMERA':
        raise BridgeError("the scene has no active camera")
    data = cam.data
    if data.type != 'PERSP':
        raise BridgeError("the active camera '%s' is not a perspective camera" % cam.name)
    render = scene.render
    width = render.resolution_x * render.pixel_aspect_x
    height = render.resolution_y * render.pixel_aspect_y
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
        "position": _vec(position),
        "look_at": _vec(position + forward),
        "up": _vec(up),
        "vfov_deg": math.degrees(2.0 * math.atan(tan_half)),
    }
    # Lens shift is in units of the fitted side; relight's principal point is a
    # fraction of width and height from the top left.
    if data.shift_x != 0.0 or data.shift_y != 0.0:
        unit = width if fit == 'HORIZONTAL' else height
        block["principal_point"] = [0.5 - data.shift_x * unit / width, 0.5 + data.shift_y * unit / height]
    return block, (render.resolution_x, render.resolution_y)


def light_entry(obj):
    light = obj.data
    position, forward, up = _axes(obj)
    scale = obj.matrix_world.to_scale()
    entry = {"name": obj.name, "color": _vec(light.color)}
    if obj.hide_render:
        entry["enabled"] = False
    if light.type in ('POINT', 'SPOT'):
        entry.update(type=light.type.lower(), position=_vec(position), power=light.energy)
        if light.shadow_soft_size > 0.0:
            entry["radius"] = light.shadow_soft_size
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
                     size=[w, h], power=light.energy)
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


def world_entries(scene, outdir, probe_position):
    """background (constant colour) or probes (an equirect HDRI) for the world."""
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
    if abs(strength - 1.0) > 1e-6:
        print("relight_export: warning: the world strength %.3g is not applied to the probe image" % strength)
    # Blender looks direction d up at u = atan2(d.y, -d.x)/2pi + 0.5: the image centre faces -X with Z up,
    # which is relight's equirect probe with forward -X. A Mapping node's Z rotation turns that.
    forward = mathutils.Vector((-1.0, 0.0, 0.0))
    vector = texture.inputs['Vector']
    if vector.is_linked and vector.links[0].from_node.type == 'MAPPING':
        rotation = vector.links[0].from_node.inputs['Rotation'].default_value
        if abs(rotation[0]) > 1e-6 or abs(rotation[1]) > 1e-6:
            raise BridgeError("the world's Mapping node tilts the HDRI; relight takes rotations about Z only")
        forward = mathutils.Matrix.Rotation(-rotation[2], 3, 'Z') @ forward
    image = texture.image
    name = bpy.path.clean_name(os.path.splitext(image.name)[0]) + ".exr"
    target = os.path.join(outdir, name)
    source = bpy.path.abspath(image.filepath)
    if image.packed_file is None and os.path.isfile(source):
        name = os.path.basename(source)
        target = os.path.join(outdir, name)
        if os.path.abspath(source) != os.path.abspath(target):
            shutil.copyfile(source, target)
    else:  # packed or generated: write its float pixels
        image.filepath_raw = target
        image.file_format = 'OPEN_EXR'
        image.save()
    return {"probes": [{"image": name, "mapping": "equirect", "position": _vec(probe_position),
                        "forward": _vec(forward), "up": [0.0, 0.0, 1.0]}]}


def camera_photo(scene):
    """The camera's background image (where fSpy's importer puts the photo), if any."""
    cam = scene.camera
    for bg in (cam.data.background_images if cam is not None else []):
        if bg.image is not None and bg.image.filepath:
            return bpy.path.abspath(bg.image.filepath)
    return None


def write_geometry(path):
    """Every visible mesh as one OBJ in world coordinates (no axis change), triangulated."""
    if hasattr(bpy.ops.wm, "obj_export"):  # Blender 3.3+
        bpy.ops.wm.obj_export(filepath=path, export_selected_objects=False, apply_modifiers=True,
                              forward_axis='Y', up_axis='Z', export_materials=False, export_uv=False,
                              export_triangulated_mesh=True, export_animation=False)
    else:
        bpy.ops.export_scene.obj(filepath=path, use_selection=False, use_mesh_modifiers=True,
                                 axis_forward='Y', axis_up='Z', use_materials=False, use_uvs=False,
                                 use_triangles=True)


def export_scene(scene, outdir, photo=None):
    """Writes OUTDIR/scene.json, OUTDIR/geometry.obj and copies the photo (and HDRI) there."""
    os.makedirs(outdir, exist_ok=True)
    photo = photo or camera_photo(scene)
    if not photo:
        raise BridgeError("no photo: give one (--photo, or the exporter's Photo field) or set it as the "
                          "camera's background image")
    if not os.path.isfile(photo):
        raise BridgeError("the photo %s does not exist" % photo)
    camera, resolution = camera_block(scene)
    photo_name = os.path.basename(photo)
    if os.path.abspath(os.path.dirname(photo)) != os.path.abspath(outdir):
        shutil.copyfile(photo, os.path.join(outdir, photo_name))
    write_geometry(os.path.join(outdir, "geometry.obj"))
    lights = [light_entry(obj) for obj in scene.objects if obj.type == 'LIGHT']
    doc = {"format": "relight-scene/1", "photo": photo_name, "geometry": "geometry.obj", "camera": camera,
           "lights": lights}
    doc.update(world_entries(scene, outdir, mathutils.Vector(camera["position"])))
    # Written beside and renamed over, so a reader never sees half a file.
    target = os.path.join(outdir, "scene.json")
    with open(target + ".part", "w") as f:
        json.dump(doc, f, indent=2)
        f.write("\n")
    os.replace(target + ".part", target)
    print("relight_export: wrote %s (%d lights, render resolution %dx%d: the photo must have this aspect ratio)"
          % (target, len(lights), resolution[0], resolution[1]))
    return target


# ------------------------------------------------------------------ import

def _linear_colour(value):
    if isinstance(value, str):  # "#rrggbb", sRGB-encoded
        def lin(c):
            return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4
        return [lin(int(value[i:i + 2], 16) / 255.0) for i in (1, 3, 5)]
    return list(value)


def _orientation(direction, up=None):
    """A rotation whose -Z is `direction` and whose +Y is as close to `up` as can be."""
    back = -mathutils.Vector(direction).normalized()
    up = mathutils.Vector(up if up is not None else (0.0, 0.0, 1.0))
    if abs(up.normalized().dot(back)) > 0.999:
        up = mathutils.Vector((0.0, 1.0, 0.0))
    right = up.cross(back).normalized()
    return mathutils.Matrix((right, back.cross(right), back)).transposed()


def import_rig(path, collection=None, replace=False):
    """Creates Blender lights for the lights of a rig.json (or scene.json), after deleting the
    scene's lights if `replace`; returns them. A rig's environment_scale is reported, not applied."""
    with open(path) as f:
        doc = json.load(f)
    if doc.get("format") not in ("relight-rig/1", "relight-scene/1"):
        raise BridgeError("%s: not a relight rig or scene (format %r)" % (path, doc.get("format")))
    lights = doc.get("lights", [])
    if not isinstance(lights, list):
        raise BridgeError("%s: /lights is not a list of lights" % path)
    collection = collection or bpy.context.scene.collection
    if replace:
        for obj in [o for o in bpy.context.scene.objects if o.type == 'LIGHT']:
            bpy.data.objects.remove(obj)
    scale = doc.get("environment_scale", 1.0)
    if scale != 1.0:
        print("relight_export: the rig scales the environment by %g: scale the world's strength to match" % scale)
    made = []
    for i, entry in enumerate(lights):
        kind = entry["type"]
        blender_type = {"point": 'POINT', "spot": 'SPOT', "area": 'AREA', "directional": 'SUN'}[kind]
        name = entry.get("name", "%s %d" % (kind, i))
        data = bpy.data.lights.new(name, blender_type)
        data.color = _linear_colour(entry.get("color", [1.0, 1.0, 1.0]))
        obj = bpy.data.objects.new(name, data)
        collection.objects.link(obj)
        rotation = mathutils.Matrix.Identity(3)
        if kind in ("point", "spot"):
            data.energy = entry["power"]
            data.shadow_soft_size = entry.get("radius", 0.0)
        if kind == "spot":
            data.spot_size = math.radians(entry["spot_angle_deg"])
            data.spot_blend = entry.get("blend", 0.0)
            rotation = _orientation(entry["direction"])
        elif kind == "area":
            data.shape = 'RECTANGLE'
            data.size, data.size_y = entry["size"]
            data.energy = entry["power"]
            rotation = _orientation(entry["direction"], entry["up"])
        elif kind == "directional":
            data.energy = entry["irradiance"]
            data.angle = math.radians(entry.get("angle_deg", 0.0))
            rotation = _orientation(entry["direction"])
        position = mathutils.Vector(entry.get("position", (0.0, 0.0, 0.0)))
        obj.matrix_world = mathutils.Matrix.Translation(position) @ rotation.to_4x4()
        obj.hide_render = not entry.get("enabled", True)
        made.append(obj)
    return made


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
        except (BridgeError, KeyError, ValueError) as e:
            self.report({'ERROR'}, "relight import: %s" % e)
            return {'CANCELLED'}
        self.report({'INFO'}, "%d lights imported" % len(made))
        return {'FINISHED'}

    def invoke(self, context, event):
        context.window_manager.fileselect_add(self)
        return {'RUNNING_MODAL'}


def _export_menu(self, context):
    self.layout.operator(RELIGHT_OT_export.bl_idname, text="relight scene (scene.json)")


def _import_menu(self, context):
    self.layout.operator(RELIGHT_OT_import_rig.bl_idname, text="relight rig (.json)")


def register():
    bpy.utils.register_class(RELIGHT_OT_export)
    bpy.utils.register_class(RELIGHT_OT_import_rig)
    bpy.types.TOPBAR_MT_file_export.append(_export_menu)
    bpy.types.TOPBAR_MT_file_import.append(_import_menu)


def unregister():
    bpy.types.TOPBAR_MT_file_import.remove(_import_menu)
    bpy.types.TOPBAR_MT_file_export.remove(_export_menu)
    bpy.utils.unregister_class(RELIGHT_OT_import_rig)
    bpy.utils.unregister_class(RELIGHT_OT_export)


# ------------------------------------------------------------------ command line

def main(argv):
    import argparse
    parser = argparse.ArgumentParser(prog="blender -b FILE.blend --python relight_export.py --")
    parser.add_argument("outdir", nargs="?", help="folder to write scene.json, geometry.obj and the photo to")
    parser.add_argument("--photo", help="the HDR photo (default: the camera's background image)")
    parser.add_argument("--import-rig", metavar="RIG", help="instead: create the lights of RIG as Blender lights")
    parser.add_argument("--replace", action="store_true", help="with --import-rig: delete the scene's lights first")
    parser.add_argument("--save", metavar="BLEND", help="with --import-rig: save the result as BLEND")
    args = parser.parse_args(argv)
    try:
        if args.import_rig:
            made = import_rig(args.import_rig, replace=args.replace)
            print("relight_export: %d lights imported from %s" % (len(made), args.import_rig))
            if args.save:
                bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(args.save))
        elif args.outdir:
            export_scene(bpy.context.scene, os.path.abspath(args.outdir), args.photo)
        else:
            parser.error("give OUTDIR, or --import-rig RIG")
    except (BridgeError, KeyError, ValueError, OSError) as e:
        print("relight_export: error: %s" % e, file=sys.stderr)
        sys.exit(2)


if __name__ == "__main__":
    main(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])

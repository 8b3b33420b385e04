# A small scene built in Blender for relight's Blender bridge: a floor, a box,
# a ball, a camera with a shifted lens, and one light of each kind.
#   blender -b --factory-startup --python-exit-code 1 --python make_example_scene.py -- OUT.blend PHOTO.exr [--render SAMPLES]
# Without --render the photo is a grey placeholder of the camera's resolution
# (enough to load the exported scene); with it, Cycles renders the photo.
# Paths may be relative to the current folder. Any error exits non-zero, with
# or without --python-exit-code.
import argparse
import math
import os
import sys
import traceback

import bpy
from mathutils import Vector


def look(obj, target):
    obj.rotation_euler = (Vector(target) - obj.location).to_track_quat('-Z', 'Y').to_euler()


def add_light(scene, name, kind, location, energy, target=None, **settings):
    data = bpy.data.lights.new(name, kind)
    data.energy = energy
    for key, value in settings.items():
        setattr(data, key, value)
    obj = bpy.data.objects.new(name, data)
    obj.location = location
    if target is not None:
        look(obj, target)
    scene.collection.objects.link(obj)
    return obj


def build_scene():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = 320, 240, 100
    bpy.ops.mesh.primitive_plane_add(size=8.0, location=(0, 0, 0))
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=(0.6, 0.3, 0.5))
    bpy.context.object.name = "Box"
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.45, location=(-0.8, -0.4, 0.45), segments=32, ring_count=16)
    bpy.ops.object.shade_smooth()
    bpy.context.object.name = "Ball"
    for obj, colour in zip(scene.objects, [(0.6, 0.6, 0.6), (0.7, 0.25, 0.15), (0.2, 0.4, 0.7)]):
        # Lambertian, as relight takes every surface to be.
        material = bpy.data.materials.new(obj.name)
        material.use_nodes = True
        nodes = material.node_tree.nodes
        nodes.remove(nodes["Principled BSDF"])
        diffuse = nodes.new("ShaderNodeBsdfDiffuse")
        diffuse.inputs["Color"].default_value = (*colour, 1.0)
        material.node_tree.links.new(diffuse.outputs["BSDF"], nodes["Material Output"].inputs["Surface"])
        obj.data.materials.append(material)

    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.location = (6.0, -5.0, 3.5)
    look(camera, (0.0, 0.0, 0.6))
    camera.data.lens, camera.data.sensor_width, camera.data.shift_x = 35.0, 36.0, 0.05
    scene.collection.objects.link(camera)
    scene.camera = camera

    add_light(scene, "Lamp", 'POINT', (2.0, -2.0, 3.0), 150.0, color=(1.0, 0.9, 0.8), shadow_soft_size=0.1)
    add_light(scene, "Spot", 'SPOT', (-2.0, -3.0, 3.0), 300.0, target=(0.0, 0.0, 0.0),
              spot_size=math.radians(40.0), spot_blend=0.2, shadow_soft_size=0.0)
    add_light(scene, "Panel", 'AREA', (0.0, 3.0, 2.5), 200.0, target=(0.0, 0.0, 0.5), shape='RECTANGLE',
              size=1.0, size_y=0.5)
    add_light(scene, "Sun", 'SUN', (0.0, 0.0, 5.0), 1.0, target=(-0.4, 0.5, 0.0), angle=math.radians(0.5),
              color=(1.0, 0.95, 0.9))

    world = bpy.data.worlds.new("World")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.05, 0.06, 0.08, 1.0)
    scene.world = world
    return scene


def write_photo(scene, path, samples):
    scene.render.image_settings.file_format = 'OPEN_EXR'
    scene.render.image_settings.color_depth = '32'
    if samples:
        scene.render.engine = 'CYCLES'
        scene.cycles.samples = samples
        scene.cycles.use_denoising = False  # Debian's Blender has no OpenImageDenoise
        scene.view_settings.view_transform = 'Standard'
        scene.render.filepath = path
        bpy.ops.render.render(write_still=True)
    else:
        photo = bpy.data.images.new("photo", 320, 240, float_buffer=True)
        photo.pixels.foreach_set([0.3] * (320 * 240 * 4))
        photo.save_render(path, scene=scene)  # linear floats (Image.save() would colour-manage them)
        bpy.data.images.remove(photo)


def main():
    parser = argparse.ArgumentParser(prog="blender -b --python make_example_scene.py --")
    parser.add_argument("blend")
    parser.add_argument("photo")
    parser.add_argument("--render", type=int, metavar="SAMPLES", default=0)
    args = parser.parse_args(sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else [])
    scene = build_scene()
    write_photo(scene, os.path.abspath(args.photo), args.render)
    bpy.ops.wm.save_as_mainfile(filepath=os.path.abspath(args.blend))


try:
    main()
except Exception:  # Blender without --python-exit-code would carry on and exit 0
    traceback.print_exc()
    sys.exit(1)

# A reference for a rig's new environment: a reference scene rebuilt by its
# generator (the true materials), its world swapped for an HDRI turned about Z,
# rendered by Cycles from the scene's camera; writes the render (half-float
# EXR) and the matching rig.json (the HDRI copied beside it).
#
#   blender -b --factory-startup --python tests/blender/new_sky.py -- \
#       SCENEGEN/make_scenes.py SCENE HDRI.exr ROT_Z_DEG OUT_DIR [--keep-lights] [--res W H] [--spp N]
#
# The generator's functions are used as they are (its main() is not run).
import argparse, json, math, os, shutil, sys

import bpy

argv = sys.argv[sys.argv.index('--') + 1:]
ap = argparse.ArgumentParser(prog='new_sky.py')
ap.add_argument('generator')
ap.add_argument('scene')
ap.add_argument('hdri')
ap.add_argument('rot_z_deg', type=float)
ap.add_argument('out')
ap.add_argument('--keep-lights', action='store_true', help="keep the scene's own lights in the rig")
ap.add_argument('--res', type=int, nargs=2, default=[640, 480])
ap.add_argument('--spp', type=int, default=64)
ap.add_argument('--seed', type=int, default=11)
args = ap.parse_args(argv)

gen = {'__file__': args.generator, '__name__': 'make_scenes'}
source = open(args.generator).read()
exec(compile(source[:source.rindex('\nmain()')], args.generator, 'exec'), gen)

bpy.ops.wm.read_factory_settings(use_empty=True)
gen['setup_render'](argparse.Namespace(spp=args.spp, threshold=0.0, seed=args.seed))
bpy.context.scene.cycles.use_adaptive_sampling = False
S = gen['SCENES'][args.scene]()
lights = S['lights'] if args.keep_lights else []
for light in lights:
    gen['add_light'](light)
gen['set_world'](dict(kind='hdri', path=os.path.abspath(args.hdri), strength=1.0, rot_z_deg=args.rot_z_deg))

im = bpy.context.scene.render.image_settings
im.file_format, im.color_depth, im.exr_codec, im.color_mode = 'OPEN_EXR', '16', 'ZIP', 'RGB'
cam = S['camera']
res = tuple(args.res)
camobj = gen['make_camera']('camera', 'persp', cam['position'],
                            gen['v3'](cam['look_at']) - gen['v3'](cam['position']), cam['up'], res,
                            vfov_deg=cam['vfov_deg'])
os.makedirs(args.out, exist_ok=True)
name = '%s_%s_%g' % (args.scene, os.path.splitext(os.path.basename(args.hdri))[0], args.rot_z_deg)
gen['render'](os.path.join(args.out, name + '.exr'), camobj, res, args.seed, False)

# Blender's default world mapping is the equirect frame forward +X, up +Z; a
# Mapping rotation by t about Z looks the image up at R(t) d, so the image's
# forward is +X turned by -t (docs/formats.md, probes).
shutil.copyfile(args.hdri, os.path.join(args.out, os.path.basename(args.hdri)))
t = -math.radians(args.rot_z_deg)
rig = {'format': 'relight-rig/1',
       'environment': {'image': os.path.basename(args.hdri), 'mapping': 'equirect',
                       'forward': [round(math.cos(t), 7), round(math.sin(t), 7), 0.0], 'up': [0.0, 0.0, 1.0]},
       'environment_scale': 1.0, 'lights': lights}
with open(os.path.join(args.out, name + '.json'), 'w') as fh:
    json.dump(rig, fh, indent=2)
print('NEW SKY', name, flush=True)

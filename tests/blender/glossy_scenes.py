# Glossy test scenes and their matte twins, made by the reference scenes'
# generator with its functions as they are (its main() is run, as in
# bench/own_scenes.py): the public studio and bookcase with a few surfaces
# turned glossy by the generator's make_glossy (a Principled BSDF with the same
# base colour, so albedo_gt.exr is unchanged), and the unchanged public scenes
# under other names, rendered at the same resolution and samples as the twins.
#
#   blender -b --factory-startup --python tests/blender/glossy_scenes.py -- \
#       ../shared/scenegen/make_scenes.py --scene glossy_studio --out tests/data/glossy/glossy_studio \
#       --res 320 240 --spp 256 --probe-res 256 128
#
# After the generator's path, the generator's own arguments; the scenes below
# are added to the ones it knows (tests/data/glossy/README.md has the four runs).
#   glossy_studio    studio; floor (concrete) roughness 0.3, ball (ball_paint) 0.2
#   glossy_bookcase  bookcase; floor (floor_tiles) roughness 0.3, ball_blue (rubber_blue) 0.2
#   matte_studio     the public studio, unchanged
#   matte_bookcase   the public bookcase, unchanged
#   glossy_studio_b  studio; ball (ball_paint) roughness 0.35 specular 0.8, stool (stool_wood) 0.15
#   glossy_outdoor   outdoor; the ten column caps (column_cap) roughness 0.25 specular 0.6
#   glossy_floor_studio, glossy_floor_bookcase  the floor alone, roughness 0.12
# Glossy surfaces: specular 0.5, distribution GGX (single scattering; Blender
# 3.4's default, set explicitly). For the glossy scenes the script then adds
# "materials" {OBJECT: {roughness, specular}} to OUT/scene.json (keys: the
# `o NAME` objects of geometry.obj) and a paragraph to OUT/README.md.
#
# One change to the generator's lights in the glossy scenes: it makes every
# light invisible to glossy rays (right for its all-diffuse scenes and the
# mirror ball), which in Cycles also drops the light's glossy (specular)
# contribution, so a glossy floor would show no highlight of any lamp. Here
# the lights of the glossy scenes stay invisible to the camera but are seen by
# glossy rays, in the photo, the probes and every rig. (For all-diffuse
# materials that setting changes nothing, so the matte twins are the public
# scenes exactly.)
import json, os, sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'bench'))
import scene_generator

gen = scene_generator.load()

import bpy

# scene -> (public scene, {object: (material, roughness, specular)})
GLOSSY = {
    'glossy_studio': ('studio', {'floor': ('concrete', 0.3, 0.5), 'ball': ('ball_paint', 0.2, 0.5)}),
    'glossy_bookcase': ('bookcase', {'floor': ('floor_tiles', 0.3, 0.5), 'ball_blue': ('rubber_blue', 0.2, 0.5)}),
    # Not committed (docs/benchmarks.md, "Materials from the photo", measures on them): other
    # objects, roughnesses and speculars; the outdoor caps share one material.
    'glossy_studio_b': ('studio', {'ball': ('ball_paint', 0.35, 0.8), 'stool': ('stool_wood', 0.15, 0.5)}),
    'glossy_outdoor': ('outdoor', {'cap_%s_%d' % (row, i): ('column_cap', 0.25, 0.6)
                                   for row in 'sn' for i in range(5)}),
    # A glossy floor alone, sharper than the committed scenes' (0.3); every light's mirror point on it is out
    # of the frame, so it mirrors the room (docs/benchmarks.md, "Materials from the photo").
    'glossy_floor_studio': ('studio', {'floor': ('concrete', 0.12, 0.5)}),
    'glossy_floor_bookcase': ('bookcase', {'floor': ('floor_tiles', 0.12, 0.5)}),
}
MATTE = {'matte_studio': 'studio', 'matte_bookcase': 'bookcase'}
# Every material of a public scene glossy at the Principled BSDF's defaults (roughness 0.5, specular 0.5):
# a room a new user models without touching the materials. Not committed (docs/benchmarks.md, "Materials
# from the photo").
EVERY_SURFACE = {'default_studio': 'studio', 'default_bookcase': 'bookcase'}
DEFAULT_ROUGHNESS, DEFAULT_SPECULAR = 0.5, 0.5

_add_light = gen['add_light']


def add_light_glossy_visible(spec):
    o = _add_light(spec)
    o.visible_glossy = True
    return o


def glossy_scene(name):
    public, surfaces = GLOSSY[name]

    def build():
        gen['add_light'] = add_light_glossy_visible   # main() looks add_light up at call time
        S = gen['SCENES'][public]()
        for mat, rough, spec in sorted(set(surfaces.values())):
            m = bpy.data.materials[mat]
            users = [o.name for o in gen['GEOM'] if m.name in [s.material.name for s in o.material_slots if s.material]]
            listed = sorted(o for o, (om, _, _) in surfaces.items() if om == mat)
            assert sorted(users) == listed, 'material %s is on %s, expected only %s' % (mat, users, listed)
            gen['make_glossy'](m, rough, spec)
            p = [n for n in m.node_tree.nodes if n.type == 'BSDF_PRINCIPLED'][0]
            p.distribution = 'GGX'   # single-scattering GGX (already Blender 3.4's default)
        return S
    return build


def every_surface_scene(name):
    def build():
        gen['add_light'] = add_light_glossy_visible
        S = gen['SCENES'][EVERY_SURFACE[name]]()
        for m in sorted({s.material for o in gen['GEOM'] for s in o.material_slots if s.material}, key=lambda m: m.name):
            gen['make_glossy'](m, DEFAULT_ROUGHNESS, DEFAULT_SPECULAR)
            [n for n in m.node_tree.nodes if n.type == 'BSDF_PRINCIPLED'][0].distribution = 'GGX'
        return S
    return build


for _n in GLOSSY:
    gen['SCENES'][_n] = glossy_scene(_n)
for _n in EVERY_SURFACE:
    gen['SCENES'][_n] = every_surface_scene(_n)
for _n, _p in MATTE.items():
    gen['SCENES'][_n] = gen['SCENES'][_p]

gen['main']()

# ---- glossy scenes: say which surfaces are glossy in scene.json and README.md
args = gen['parse_args']()
if args.scene in GLOSSY or args.scene in EVERY_SURFACE:
    out = os.path.abspath(args.out)
    objs = [l.split()[1] for l in open(os.path.join(out, 'geometry.obj')) if l.startswith('o ')]
    surfaces = GLOSSY[args.scene][1] if args.scene in GLOSSY else {
        o: ('every material', DEFAULT_ROUGHNESS, DEFAULT_SPECULAR) for o in objs}
    missing = [o for o in surfaces if o not in objs]
    if missing:
        raise SystemExit('glossy_scenes.py: %s not among the objects of geometry.obj (%s)' % (missing, objs))
    sp = os.path.join(out, 'scene.json')
    scene = json.load(open(sp))
    scene['materials'] = {o: {'roughness': r, 'specular': s} for o, (_, r, s) in surfaces.items()}
    with open(sp, 'w') as fh:
        json.dump(scene, fh, indent=2)
    line = ('**Glossy surfaces** (unlike the sentence above, not every material is a Diffuse BSDF): %s are a '
            'Principled BSDF (Blender %s, Cycles; distribution GGX, single scattering; metallic 0, every other '
            'input at its default; specular 0.5 is a normal-incidence reflectance of 0.08 x 0.5 = 0.04) made by the generator\'s `make_glossy` from the diffuse material, '
            'with the same base colour (so `albedo_gt.exr`, the Diffuse Color pass, is still the base colour). '
            'Its diffuse part is Cycles 3.x\'s Principled diffuse (Disney/Burley, with a roughness-dependent '
            'retro-reflection term), not Lambertian. `scene.json` lists them under `materials`. The lights are '
            'invisible to the camera but seen by glossy rays (the generator hides them from glossy rays, which '
            'would drop their highlights), in the photo, the probes and every rig.' %
            (', '.join('`%s` (material `%s`) roughness %g, specular %g' % (o, m, r, s)
                       for o, (m, r, s) in surfaces.items()), bpy.app.version_string))
    rp = os.path.join(out, 'README.md')
    text = open(rp).read().split('\n')
    at = next(i for i, l in enumerate(text) if l.startswith('Scene `%s`, rendered with Blender' % args.scene))
    text[at + 1:at + 1] = ['', line]
    with open(rp, 'w') as fh:
        fh.write('\n'.join(text))
    print('GLOSSY NOTED', args.scene, json.dumps(scene['materials']), flush=True)

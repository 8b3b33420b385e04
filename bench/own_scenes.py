# Check scenes of the project's own, made by the reference scenes' generator
# with its functions as they are: figures measured on the public scenes are
# checked on these before they are believed (docs/benchmarks.md).
#
#   blender -b --factory-startup --python bench/own_scenes.py -- \
#       ../shared/scenegen/make_scenes.py --scene panelroom --out OUT [--res 320 240 --spp 256 --probe-res 256 128]
#
# After the generator's path, the generator's own arguments; the scenes
# below are added to the ones it knows.
#   panelroom  a closed 4 x 3.4 x 2.6 m room, sage and cream plaster, an oak
#              floor, a table with a vase, a ball and a brick cabinet; lit by
#              a soft ceiling panel (area light, 1 x 0.6 m, facing down) and a
#              warm floor lamp; a black world, so most light has bounced; an
#              equirect probe. Rig `moved`: the panel 0.64 m across the room.
#   lamproom   a closed 5 x 3.6 x 2.5 m room, terracotta and pale blue
#              plaster, a grey tiled floor, a sofa, a side table and a
#              bookshelf; lit by a square ceiling panel and two weak lamps
#              (a warm table lamp, a cool reading lamp), each a few pixels
#              across in a 256 x 128 probe. Rig `dim`: the panel off.
import os, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scene_generator

gen = scene_generator.load()


def closed_room(X, Y, Z, floor, ceiling, back, front, left, right):
    """A box room from (-X, -Y, 0) to (X, Y, Z), its six faces facing in."""
    quad = gen['quad']
    quad('floor', [(-X, -Y, 0), (X, -Y, 0), (X, Y, 0), (-X, Y, 0)], floor)
    quad('ceiling', [(-X, -Y, Z), (-X, Y, Z), (X, Y, Z), (X, -Y, Z)], ceiling)
    quad('wall_back', [(-X, Y, 0), (X, Y, 0), (X, Y, Z), (-X, Y, Z)], back)
    quad('wall_front', [(-X, -Y, 0), (-X, -Y, Z), (X, -Y, Z), (X, -Y, 0)], front)
    quad('wall_left', [(-X, -Y, 0), (-X, Y, 0), (-X, Y, Z), (-X, -Y, Z)], left)
    quad('wall_right', [(X, -Y, 0), (X, -Y, Z), (X, Y, Z), (X, Y, 0)], right)


def scene_panelroom():
    g = gen
    sage = g['mat_noise']('sage_plaster', (0.40, 0.48, 0.36), (0.52, 0.60, 0.46), scale=2.2)
    cream = g['mat_noise']('cream_plaster', (0.78, 0.74, 0.62), (0.88, 0.84, 0.72), scale=3.0)
    oak = g['mat_noise']('oak_floor', (0.45, 0.30, 0.16), (0.62, 0.44, 0.26), scale=6.0, detail=8.0)
    closed_room(2.0, 1.7, 2.6, oak, cream, sage, cream, cream, sage)
    table = g['mat_noise']('table_top', (0.70, 0.66, 0.60), (0.80, 0.76, 0.70), scale=5.0)
    g['box']('table', (1.1, 0.7, 0.75), (-0.2, 0.6, 0.0), table, rot_z=10.0)
    vase = g['mat_noise']('vase', (0.15, 0.25, 0.55), (0.22, 0.34, 0.66), scale=4.0)
    g['cylinder']('vase', 0.09, 0.35, (-0.35, 0.55, 0.75), vase)
    ball = g['mat_noise']('ball', (0.70, 0.55, 0.10), (0.85, 0.70, 0.20), scale=3.0)
    g['sphere']('ball', 0.16, (0.9, 0.2, 0.16), ball)
    cabinet = g['mat_brick']('cabinet', (0.55, 0.20, 0.15), (0.65, 0.28, 0.20), (0.85, 0.82, 0.78), 1.0, 0.3, 0.15)
    g['box']('cabinet', (0.45, 1.0, 1.3), (1.7, 0.9, 0.0), cabinet)
    panel = dict(name='panel', type='area', position=[0.1, 0.2, 2.5], direction=[0.0, 0.0, -1.0],
                 up=[0.0, 1.0, 0.0], size=[1.0, 0.6], color=[1.0, 0.98, 0.95], power=300.0)
    lamp = dict(name='floor_lamp', type='point', position=[-1.3, -0.4, 1.6], color=[1.0, 0.75, 0.5],
                power=45.0, radius=0.06)
    moved = dict(panel, position=[0.5, -0.3, 2.5])
    return dict(
        camera=dict(position=[1.2, -1.5, 1.5], look_at=[-0.2, 0.6, 0.6], up=[0, 0, 1], vfov_deg=55.0),
        lights=[panel, lamp], world=dict(kind='uniform', color=[0.0, 0.0, 0.0]), background=[0.0, 0.0, 0.0],
        probes=[dict(mapping='equirect', image='probe_equirect.exr', position=[0.3, -0.5, 1.4],
                     forward=[0.0, 1.0, 0.0], up=[0.0, 0.0, 1.0])],
        rigs=dict(moved=dict(environment_scale=1.0, lights=[moved, lamp])),
        readme='Own check scene (bench/own_scenes.py): a closed room lit by a soft ceiling panel and a floor lamp.')


def scene_lamproom():
    g = gen
    terracotta = g['mat_noise']('terracotta', (0.62, 0.36, 0.26), (0.72, 0.44, 0.32), scale=2.5)
    blue = g['mat_noise']('pale_blue', (0.55, 0.62, 0.70), (0.64, 0.70, 0.78), scale=3.5)
    tiles = g['mat_brick']('floor_tiles', (0.40, 0.40, 0.42), (0.50, 0.50, 0.52), (0.75, 0.75, 0.72), 2.0, 0.5, 0.5)
    closed_room(2.5, 1.8, 2.5, tiles, blue, terracotta, blue, blue, terracotta)
    fabric = g['mat_noise']('sofa', (0.25, 0.35, 0.30), (0.32, 0.44, 0.38), scale=8.0)
    g['box']('sofa_seat', (2.0, 0.9, 0.45), (0.3, 1.25, 0.0), fabric)
    g['box']('sofa_back', (2.0, 0.2, 0.85), (0.3, 1.6, 0.0), fabric)
    wood = g['mat_noise']('walnut', (0.30, 0.18, 0.10), (0.42, 0.27, 0.15), scale=7.0, detail=8.0)
    g['box']('side_table', (0.5, 0.5, 0.55), (-1.2, 1.3, 0.0), wood)
    g['box']('bookshelf', (0.4, 1.4, 1.9), (2.2, -0.6, 0.0), wood, rot_z=0.0)
    shade = g['mat_noise']('pot', (0.80, 0.78, 0.70), (0.88, 0.86, 0.80), scale=4.0)
    g['cylinder']('pot', 0.14, 0.4, (-0.6, -0.2, 0.0), shade)
    panel = dict(name='panel', type='area', position=[0.4, 0.0, 2.45], direction=[0.0, 0.0, -1.0],
                 up=[0.0, 1.0, 0.0], size=[0.8, 0.8], color=[0.95, 0.97, 1.0], power=250.0)
    table_lamp = dict(name='table_lamp', type='point', position=[-1.2, 1.3, 0.95], color=[1.0, 0.72, 0.45],
                      power=35.0, radius=0.05)
    reading = dict(name='reading_lamp', type='point', position=[1.6, 0.9, 1.45], color=[0.85, 0.9, 1.0],
                   power=30.0, radius=0.07)
    return dict(
        camera=dict(position=[-1.9, -1.4, 1.6], look_at=[0.6, 0.9, 0.8], up=[0, 0, 1], vfov_deg=60.0),
        lights=[panel, table_lamp, reading], world=dict(kind='uniform', color=[0.0, 0.0, 0.0]),
        background=[0.0, 0.0, 0.0],
        probes=[dict(mapping='equirect', image='probe_equirect.exr', position=[0.0, -0.6, 1.3],
                     forward=[0.0, 1.0, 0.0], up=[0.0, 0.0, 1.0])],
        rigs=dict(dim=dict(environment_scale=1.0, lights=[table_lamp, reading])),
        readme='Own check scene (bench/own_scenes.py): a closed room lit by a ceiling panel and two weak lamps.')


gen['SCENES']['panelroom'] = scene_panelroom
gen['SCENES']['lamproom'] = scene_lamproom
gen['main']()

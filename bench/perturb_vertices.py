#!/usr/bin/env python3
"""Writes a copy of a scene whose geometry's every vertex is moved by a random
offset of at most R metres (uniform in the ball; shared vertices move
together), file paths made absolute, as docs/benchmarks.md's "Vertices moved".
  bench/perturb_vertices.py SCENE.json OUT/scene.json R [SEED]"""
import json, os, random, sys

from scene_json import load_absolute
scene, out, radius = sys.argv[1], sys.argv[2], float(sys.argv[3])
random.seed(int(sys.argv[4]) if len(sys.argv) > 4 else 1)
s = load_absolute(scene)
geo = s["geometry"]
out_dir = os.path.dirname(os.path.abspath(out))
os.makedirs(out_dir, exist_ok=True)
moved = os.path.join(out_dir, "moved_" + os.path.basename(geo))
with open(geo) as f, open(moved, "w") as g:
    for line in f:
        if line.startswith("v "):
            p = [float(x) for x in line.split()[1:4]]
            while True:
                d = [random.uniform(-1, 1) for _ in range(3)]
                if sum(x * x for x in d) <= 1: break
            p = [x + radius * y for x, y in zip(p, d)]
            g.write("v %.6f %.6f %.6f\n" % tuple(p))
        else:
            g.write(line)
s["geometry"] = moved
json.dump(s, open(out, "w"), indent=1)

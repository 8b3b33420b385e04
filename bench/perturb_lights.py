#!/usr/bin/env python3
"""Writes a copy of a scene whose lights are where a rough guess would put
them (docs/benchmarks.md, "Lights placed from the photo"): each point, spot
and area light moved M metres sideways (along the camera's right), each sun
turned DEG degrees about the camera's up; with --size F, each light's size
(an area light's rectangle, a lamp's radius) times F instead ("A light's
size given wrong"). File paths become absolute.
  bench/perturb_lights.py SCENE.json OUT.json [--light NAME]... [--move M] [--turn DEG]
  bench/perturb_lights.py SCENE.json OUT.json [--light NAME]... --size F"""
import argparse, json, math

from scene_json import add, camera_axes, load_absolute, rotate, scale

ap = argparse.ArgumentParser()
ap.add_argument("scene"), ap.add_argument("out")
ap.add_argument("--light", action="append", help="only these lights (default: all)")
ap.add_argument("--move", type=float, default=0.2), ap.add_argument("--turn", type=float, default=3.0)
ap.add_argument("--size", type=float, help="scale each light's size by this, and leave it where it is")
a = ap.parse_args()
s = load_absolute(a.scene)
_, right, up = camera_axes(s["camera"])
for light in s["lights"]:
    if a.light and light["name"] not in a.light:
        continue
    if a.size is not None:
        if "size" in light:
            light["size"] = scale(light["size"], a.size)
        if "radius" in light:
            light["radius"] *= a.size
    elif light["type"] == "directional":
        light["direction"] = rotate(light["direction"], up, math.radians(a.turn))
    else:
        light["position"] = add(light["position"], scale(right, a.move))
json.dump(s, open(a.out, "w"), indent=2)

#!/usr/bin/env python3
"""Writes a scene.json whose camera is the given one turned, zoomed and shifted
as tests/registration_test.cpp does: turned about the axis 0.8 up + 0.6 right
of the view, vfov_deg scaled, the principal point moved right by a fraction of
the width. File paths become absolute, so the copy may live anywhere.
  bench/perturb_camera.py SCENE.json OUT.json [--turn DEG] [--fov-scale S] [--shift F]"""
import argparse, json, math, os


def sub(a, b): return [x - y for x, y in zip(a, b)]
def add(a, b): return [x + y for x, y in zip(a, b)]
def scale(a, s): return [x * s for x in a]
def dot(a, b): return sum(x * y for x, y in zip(a, b))
def cross(a, b): return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
def unit(a): return scale(a, 1 / math.sqrt(dot(a, a)))


def rotate(v, axis, angle):  # Rodrigues
    c, s = math.cos(angle), math.sin(angle)
    return add(add(scale(v, c), scale(cross(axis, v), s)), scale(axis, dot(axis, v) * (1 - c)))


ap = argparse.ArgumentParser()
ap.add_argument("scene"), ap.add_argument("out")
ap.add_argument("--turn", type=float, default=0.0), ap.add_argument("--fov-scale", type=float, default=1.0)
ap.add_argument("--shift", type=float, default=0.0)
a = ap.parse_args()
folder = os.path.dirname(os.path.abspath(a.scene))
s = json.load(open(a.scene))
for key in ("photo", "geometry"):
    s[key] = os.path.join(folder, s[key])
for p in s.get("probes", []):
    p["image"] = os.path.join(folder, p["image"])
cam = s["camera"]
f = unit(sub(cam["look_at"], cam["position"]))
right = unit(cross(f, cam["up"]))
up = cross(right, f)
axis = unit(add(scale(up, 0.8), scale(right, 0.6)))
angle = math.radians(a.turn)
cam["look_at"] = add(cam["position"], rotate(sub(cam["look_at"], cam["position"]), axis, angle))
cam["up"] = rotate(cam["up"], axis, angle)
cam["vfov_deg"] *= a.fov_scale
pp = cam.get("principal_point", [0.5, 0.5])
cam["principal_point"] = [pp[0] + a.shift, pp[1]]
json.dump(s, open(a.out, "w"), indent=2)

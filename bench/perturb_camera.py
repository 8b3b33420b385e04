#!/usr/bin/env python3
"""Writes a scene.json whose camera is the given one turned, zoomed and shifted
as tests/registration_test.cpp does: turned about the axis 0.8 up + 0.6 right
of the view, vfov_deg scaled, the principal point moved right by a fraction of
the width. File paths become absolute, so the copy may live anywhere.
  bench/perturb_camera.py SCENE.json OUT.json [--turn DEG] [--fov-scale S] [--shift F]"""
import argparse, json, math

from scene_json import add, camera_axes, load_absolute, rotate, scale, sub, unit

ap = argparse.ArgumentParser()
ap.add_argument("scene"), ap.add_argument("out")
ap.add_argument("--turn", type=float, default=0.0), ap.add_argument("--fov-scale", type=float, default=1.0)
ap.add_argument("--shift", type=float, default=0.0)
a = ap.parse_args()
s = load_absolute(a.scene)
cam = s["camera"]
f, right, up = camera_axes(cam)
axis = unit(add(scale(up, 0.8), scale(right, 0.6)))
angle = math.radians(a.turn)
cam["look_at"] = add(cam["position"], rotate(sub(cam["look_at"], cam["position"]), axis, angle))
cam["up"] = rotate(cam["up"], axis, angle)
cam["vfov_deg"] *= a.fov_scale
pp = cam.get("principal_point", [0.5, 0.5])
cam["principal_point"] = [pp[0] + a.shift, pp[1]]
json.dump(s, open(a.out, "w"), indent=2)

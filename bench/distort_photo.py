#!/usr/bin/env python3
"""Writes a copy of a scene whose photo a lens has bent (docs/benchmarks.md,
"A lens's distortion"): radial distortion x_d = x_u (1 + k1 r^2 + k2 r^4),
x in units of the focal length about the photo's centre (OpenCV's and
Blender's polynomial model). The copy's focal length is the longest whose
whole frame the original photo covers, so a barrel (k1 < 0) photo has no
empty corners; its camera says that field of view and, with --given, the
distortion too (without it, what a user with the lens's focal length alone
would write). The photo, true albedo and mask are resampled (bilinear) and
written beside OUT as OUT's name with .exr, _albedo_gt.exr and _mask.exr;
--k1 0 gives the same resampling without the distortion, to compare with.
File paths become absolute. Needs Python's OpenImageIO and numpy.
  bench/distort_photo.py SCENE.json OUT.json [--k1 K1] [--k2 K2] [--given]"""
import argparse, json, math, os

import numpy as np
import OpenImageIO as oiio

from scene_json import load_absolute

ap = argparse.ArgumentParser()
ap.add_argument("scene"), ap.add_argument("out")
ap.add_argument("--k1", type=float, default=-0.05), ap.add_argument("--k2", type=float, default=0.0)
ap.add_argument("--given", action="store_true")
a = ap.parse_args()
s = load_absolute(a.scene)
folder = os.path.dirname(os.path.abspath(a.scene))
if s["camera"].get("principal_point", [0.5, 0.5]) != [0.5, 0.5] or "distortion" in s["camera"]:
    raise SystemExit(f"{a.scene}: the camera must be a centred pinhole")


def undistort(xd, yd):
    """The undistorted position whose distortion is (xd, yd): fixed-point iteration."""
    xu, yu = xd.copy(), yd.copy()
    for _ in range(30):
        r2 = xu * xu + yu * yu
        g = 1 + a.k1 * r2 + a.k2 * r2 * r2
        xu, yu = xd / g, yd / g
    return xu, yu


def read(path):
    return oiio.ImageBuf(path).get_pixels(oiio.FLOAT)


photo = read(s["photo"])
h, w = photo.shape[:2]
f0 = (h / 2) / math.tan(math.radians(s["camera"]["vfov_deg"]) / 2)
# The border's pixels: the copy's focal length f1 is the one at which the
# farthest of them maps onto the original frame's border (bisection).
border = np.concatenate([np.stack([np.arange(w + 1), np.zeros(w + 1)], 1), np.stack([np.arange(w + 1), np.full(w + 1, h)], 1),
                         np.stack([np.zeros(h + 1), np.arange(h + 1)], 1), np.stack([np.full(h + 1, w), np.arange(h + 1)], 1)])
bx, by = border[:, 0] - w / 2, border[:, 1] - h / 2


def reach(f1):
    xu, yu = undistort(bx / f1, by / f1)
    return max(np.max(np.abs(xu)) * f0 / (w / 2), np.max(np.abs(yu)) * f0 / (h / 2))


lo, hi = 0.5 * f0, 2.0 * f0
for _ in range(60):
    f1 = 0.5 * (lo + hi)
    lo, hi = (f1, hi) if reach(f1) > 1 else (lo, f1)
f1 = hi
y, x = np.mgrid[0:h, 0:w]
xu, yu = undistort((x + 0.5 - w / 2) / f1, (y + 0.5 - h / 2) / f1)
sx, sy = xu * f0 + w / 2 - 0.5, yu * f0 + h / 2 - 0.5  # source pixel index coordinates


def resample(img):
    x0 = np.clip(np.floor(sx).astype(int), 0, w - 2)
    y0 = np.clip(np.floor(sy).astype(int), 0, h - 2)
    tx, ty = np.clip(sx - x0, 0, 1)[..., None], np.clip(sy - y0, 0, 1)[..., None]
    return ((img[y0, x0] * (1 - tx) + img[y0, x0 + 1] * tx) * (1 - ty) +
            (img[y0 + 1, x0] * (1 - tx) + img[y0 + 1, x0 + 1] * tx) * ty).astype(np.float32)


def write(pixels, path, fmt=oiio.HALF):
    out = oiio.ImageOutput.create(path)
    out.open(path, oiio.ImageSpec(w, h, pixels.shape[2], fmt))
    out.write_image(pixels)
    out.close()


stem = os.path.splitext(os.path.abspath(a.out))[0]
write(resample(photo), stem + ".exr")
for name in ("albedo_gt", "mask"):
    source = os.path.join(folder, name + ".exr")
    if os.path.exists(source):
        write(resample(read(source)), f"{stem}_{name}.exr", oiio.FLOAT)
s["photo"] = stem + ".exr"
s["camera"]["vfov_deg"] = math.degrees(2 * math.atan((h / 2) / f1))
if a.given:
    s["camera"]["distortion"] = [a.k1, a.k2]
json.dump(s, open(a.out, "w"), indent=2)
print(f"focal length {f1 / f0:.4f} times the original's: vfov {s['camera']['vfov_deg']:.3f} degrees")

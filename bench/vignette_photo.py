#!/usr/bin/env python3
"""Writes a copy of a scene whose photo a lens has darkened towards its
corners (docs/benchmarks.md, "A lens's vignetting"): each pixel times
1 - S r^2 (r its distance from the centre over the half diagonal), or, with
--cos4 DEG, the cos^4 law of a lens whose half diagonal sees DEG degrees.
The photo is written beside OUT as OUT's name with .exr; file paths become
absolute. Needs Python's OpenImageIO and numpy.
  bench/vignette_photo.py SCENE.json OUT.json [--falloff S] [--cos4 DEG]"""
import argparse, json, os

import numpy as np
import OpenImageIO as oiio

from scene_json import load_absolute

ap = argparse.ArgumentParser()
ap.add_argument("scene"), ap.add_argument("out")
ap.add_argument("--falloff", type=float, default=0.35), ap.add_argument("--cos4", type=float)
a = ap.parse_args()
s = load_absolute(a.scene)
photo = oiio.ImageBuf(s["photo"])
pixels = photo.get_pixels(oiio.FLOAT)
h, w = pixels.shape[:2]
y, x = np.mgrid[0:h, 0:w]
r2 = ((x + 0.5 - w / 2) ** 2 + (y + 0.5 - h / 2) ** 2) / ((w / 2) ** 2 + (h / 2) ** 2)
if a.cos4 is not None:
    falloff = np.cos(np.arctan(np.sqrt(r2) * np.tan(np.radians(a.cos4)))) ** 4
else:
    falloff = 1 - a.falloff * r2
pixels[..., :3] *= falloff[..., None]
out_photo = os.path.splitext(os.path.abspath(a.out))[0] + ".exr"
spec = oiio.ImageSpec(w, h, pixels.shape[2], oiio.HALF)
image = oiio.ImageOutput.create(out_photo)
image.open(out_photo, spec)
image.write_image(pixels.astype(np.float32))
image.close()
s["photo"] = out_photo
json.dump(s, open(a.out, "w"), indent=2)

#!/usr/bin/env python3
"""Writes a copy of a scene whose photo is softer than the render, as a real
camera's is (docs/benchmarks.md, "A photo softer than the render"): blurred
by a Gaussian of standard deviation SIGMA pixels (separable, edges
replicated). The photo is written beside OUT as OUT's name with .exr, and the
scene folder's albedo_gt.exr blurred alike as _albedo_gt.exr (the truth a
division can reach: the texture's own blur is not undone); file paths become
absolute. Needs Python's OpenImageIO and numpy.
  bench/blur_photo.py SCENE.json OUT.json [--sigma SIGMA]"""
import argparse, json, math, os

import numpy as np
import OpenImageIO as oiio

from scene_json import load_absolute

ap = argparse.ArgumentParser()
ap.add_argument("scene"), ap.add_argument("out")
ap.add_argument("--sigma", type=float, default=1.0)
a = ap.parse_args()
s = load_absolute(a.scene)
folder = os.path.dirname(os.path.abspath(a.scene))


def blur(img):
    r = int(math.ceil(3 * a.sigma))
    k = np.exp(-0.5 * (np.arange(-r, r + 1) / a.sigma) ** 2)
    k /= k.sum()
    pad = np.pad(img, ((r, r), (r, r), (0, 0)), mode="edge")
    rows = sum(k[i] * pad[:, i:i + img.shape[1]] for i in range(2 * r + 1))
    return sum(k[i] * rows[i:i + img.shape[0]] for i in range(2 * r + 1)).astype(np.float32)


def write(pixels, path):
    out = oiio.ImageOutput.create(path)
    out.open(path, oiio.ImageSpec(pixels.shape[1], pixels.shape[0], pixels.shape[2], oiio.FLOAT))
    out.write_image(pixels)
    out.close()


stem = os.path.splitext(os.path.abspath(a.out))[0]
write(blur(oiio.ImageBuf(s["photo"]).get_pixels(oiio.FLOAT)), stem + ".exr")
truth = os.path.join(folder, "albedo_gt.exr")
if os.path.exists(truth):
    write(blur(oiio.ImageBuf(truth).get_pixels(oiio.FLOAT)), stem + "_albedo_gt.exr")
s["photo"] = stem + ".exr"
json.dump(s, open(a.out, "w"), indent=2)

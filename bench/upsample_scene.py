#!/usr/bin/env python3
"""Writes a copy of a scene whose photo (and mask, true albedo and true re-lit
photos, where present) N times as wide and tall (N need not be whole), resampled with a
Lanczos filter: a camera-sized stand-in for docs/benchmarks.md's "Photo
size" figures. The geometry, probes and rigs are the original's, copied (the
camera takes its resolution from the photo).
  bench/upsample_scene.py SCENE_DIR OUT_DIR N"""
import json, os, shutil, sys

import OpenImageIO as oiio

from scene_json import load_absolute

scene_dir, out_dir, n = sys.argv[1], sys.argv[2], float(sys.argv[3])
os.makedirs(os.path.join(out_dir, "relit"), exist_ok=True)


def upsample(src, dst):
    image = oiio.ImageBuf(src)
    spec = image.spec()
    roi = oiio.ROI(0, round(spec.width * n), 0, round(spec.height * n), 0, 1, 0, spec.nchannels)
    # Lanczos rings below zero beside bright edges: radiance is clamped at 0.
    bigger = oiio.ImageBufAlgo.max(oiio.ImageBufAlgo.resize(image, "lanczos3", roi=roi), 0.0)
    if not bigger.write(dst, "half"):
        sys.exit("upsample_scene: %s: %s" % (dst, bigger.geterror()))


s = load_absolute(os.path.join(scene_dir, "scene.json"))
upsample(s["photo"], os.path.join(out_dir, "photo.exr"))
s["photo"] = "photo.exr"


def link(path):
    name = os.path.basename(path)
    if not os.path.exists(os.path.join(out_dir, name)):
        shutil.copy(path, os.path.join(out_dir, name))
    return name


s["geometry"] = link(s["geometry"])
for probe in s.get("probes", []):
    probe["image"] = link(probe["image"])
for name in ["mask.exr", "albedo_gt.exr"] + ["relit/" + f for f in sorted(os.listdir(os.path.join(scene_dir, "relit")))
                                               if os.path.isdir(os.path.join(scene_dir, "relit"))]:
    if os.path.exists(os.path.join(scene_dir, name)):
        upsample(os.path.join(scene_dir, name), os.path.join(out_dir, name))
if os.path.isdir(os.path.join(scene_dir, "rigs")) and not os.path.exists(os.path.join(out_dir, "rigs")):
    os.symlink(os.path.abspath(os.path.join(scene_dir, "rigs")), os.path.join(out_dir, "rigs"))
json.dump(s, open(os.path.join(out_dir, "scene.json"), "w"), indent=1)

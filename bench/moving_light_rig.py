"""The animated rig of bench/frame_sequence.sh: a scene's first light (kept
still), a key spot and a fill light (still), and a small warm point light
carried through the room over the frames — from one side of the camera's
view to the other, raised and lowered on the way, dimmed and brightened —
placed from the camera so that it fits any scene (and, for an OBJ geometry,
kept 10 cm inside its bounding box):
    moving_light_rig.py SCENE.json OUT_RIG.json FRAMES"""
import json
import os
import sys

import numpy as np


def main(scene_path, out_path, frames):
    scene = json.load(open(scene_path))
    cam = scene["camera"]
    position, look_at = np.array(cam["position"], float), np.array(cam["look_at"], float)
    up = np.array(cam.get("up", [0, 0, 1]), float)
    forward = look_at - position
    distance = np.linalg.norm(forward)
    forward /= distance
    right = np.cross(forward, up)
    right /= np.linalg.norm(right)
    true_up = np.cross(right, forward)

    low, high = np.full(3, -np.inf), np.full(3, np.inf)
    geometry = os.path.join(os.path.dirname(scene_path), scene["geometry"])
    if geometry.lower().endswith(".obj"):
        vertices = np.array([line.split()[1:4] for line in open(geometry) if line.startswith("v ")], float)
        low, high = vertices.min(axis=0) + 0.1, vertices.max(axis=0) - 0.1

    def at(ahead, across, above):  # a point in front of the camera, in units of the distance to look_at
        p = position + distance * (ahead * forward + across * right + above * true_up)
        return list(map(float, np.clip(p, low, high)))

    key_position = at(0.3, -0.4, 0.3)
    key_direction = np.array(look_at) - np.array(key_position)
    lights = [scene["lights"][0]] if scene.get("lights") else []
    lights += [
        {"name": "key", "type": "spot", "position": key_position,
         "direction": list(map(float, key_direction / np.linalg.norm(key_direction))),
         "power": 300, "color": [0.85, 0.92, 1.0], "spot_angle_deg": 35, "blend": 0.2},
        {"name": "fill", "type": "point", "position": at(0.5, 0.5, 0.4), "power": 25,
         "color": [0.9, 0.8, 1.0], "radius": 0.1},
        {"name": "runner", "type": "point", "position": at(0.8, -0.5, 0.0), "power": 40,
         "color": [1.0, 0.7, 0.4], "radius": 0.05,
         "keys": [{"frame": 1, "position": at(0.8, -0.5, 0.0), "power": 40},
                  {"frame": (frames + 1) // 2, "position": at(0.9, 0.0, 0.15), "power": 80},
                  {"frame": frames, "position": at(0.8, 0.5, -0.1), "power": 40}]},
    ]
    json.dump({"format": "relight-rig/1", "environment_scale": 1.0, "lights": lights}, open(out_path, "w"), indent=1)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]))

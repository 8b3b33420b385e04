#!/usr/bin/env bash
# Writes the seed corpora of fuzz/corpus/ from small files made here and
# small copies of the example scene and the reference scenes' JSON (never
# their big images). Needs oiiotool and python3; run from anywhere. The
# corpus is committed: CI does not run this.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$here/.."
shared="$root/../shared/scenes"
c="$here/corpus"
rm -rf "$c"
mkdir -p "$c"/{scene_json,rig_json,probe,mesh,image}

# scene.json: scenes pointing at the files the target provides (photo.exr,
# geometry.obj, probe.exr equirect, ball.exr mirror ball).
python3 - "$c/scene_json" "$root" "$shared" <<'PY'
import json, sys, pathlib, glob
out, root, shared = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2]), sys.argv[3]
def save(name, scene): (out / name).write_text(json.dumps(scene, indent=1))
sources = [root / "examples/room/scene.json"] + [pathlib.Path(p) for p in sorted(glob.glob(shared + "/*/scene.json"))]
for src in sources:
    s = json.loads(src.read_text())
    s["photo"], s["geometry"] = "photo.exr", "geometry.obj"
    for p in s.get("probes", []):
        p["image"] = "ball.exr" if p["mapping"] == "mirrorball" else "probe.exr"
    save(src.parent.name + ".json", s)
save("all_lights.json", {
  "format": "relight-scene/1", "photo": "photo.exr", "geometry": "geometry.obj",
  "camera": {"position": [0, -5, 1], "look_at": [0, 0, 0], "up": [0, 0, 1], "vfov_deg": 35},
  "lights": [
    {"type": "point", "position": [1, 2, 3], "power": 100},
    {"type": "spot", "name": "key", "color": "#ff8000", "enabled": False, "position": [0, 0, 4],
     "direction": [0, 0, -2], "power": 800, "spot_angle_deg": 40, "blend": 0.2, "radius": 0.1},
    {"type": "area", "position": [0, 0, 3], "direction": [0, 0, -1], "up": [0, 1, 0], "size": [2, 0.5],
     "power": 50, "color": [0.5, 0.25, 1.0]},
    {"type": "directional", "direction": [-0.4, 0.3, -0.87], "irradiance": 4, "angle_deg": 0.5}],
  "background": [0.35, 0.45, 0.6],
  "probes": [{"image": "probe.exr", "mapping": "equirect", "position": [0, 0, 1], "forward": [0, 1, 0], "up": [0, 0, 1]},
             {"image": "ball.exr", "mapping": "mirrorball", "position": [1, 0, 1], "forward": [1, 0, 0], "up": [0, 0, 1]}]})
PY
cp "$root"/examples/room/rigs/*.json "$c/rig_json/"
for f in "$shared"/*/rigs/*.json; do
  [ -f "$f" ] && cp "$f" "$c/rig_json/$(basename "$(dirname "$(dirname "$f")")")_$(basename "$f")"
done
cp "$c/scene_json/all_lights.json" "$c/rig_json/scene_lights.json"

# probe: the fuzz bytes read as mapping, size, frame, pixels, queries.
python3 - "$c/probe" <<'PY'
import random, sys, pathlib
out = pathlib.Path(sys.argv[1]); rng = random.Random(7)
for i, n in enumerate([32, 96, 256, 1024]):
    (out / f"random_{i}").write_bytes(bytes([i % 2, 3 + i]) + bytes(rng.randrange(256) for _ in range(n)))
PY

# mesh: the first byte picks the extension (obj ply stl off gltf glb).
python3 - "$c/mesh" "$root/examples/room/geometry.obj" <<'PY'
import base64, json, struct, sys, pathlib
out = pathlib.Path(sys.argv[1])
def save(name, ext_index, data):
    (out / name).write_bytes(bytes([ext_index]) + (data.encode() if isinstance(data, str) else data))
save("quad.obj", 0, "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 1//1 3//1 4//1\n")
save("room.obj", 0, pathlib.Path(sys.argv[2]).read_bytes())
save("quad_ascii.ply", 1, "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
     "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
     "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n")
verts = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]
save("tri_binary.ply", 1, b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
     b"property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
     + b"".join(struct.pack("<3f", *v) for v in verts) + struct.pack("<B3i", 3, 0, 1, 2))
save("tri.stl", 2, "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
     "endloop\nendfacet\nendsolid t\n")
save("quad.off", 3, "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n")
binary = struct.pack("<3H", 0, 1, 2) + b"\0\0" + b"".join(struct.pack("<3f", *v) for v in verts)
def gltf(uri):
    g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
         "nodes": [{"mesh": 0, "translation": [0, 0, 1]}],
         "meshes": [{"primitives": [{"attributes": {"POSITION": 1}, "indices": 0}]}],
         "buffers": [{"byteLength": len(binary)} | ({"uri": uri} if uri else {})],
         "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 6, "target": 34963},
                         {"buffer": 0, "byteOffset": 8, "byteLength": 36, "target": 34962}],
         "accessors": [{"bufferView": 0, "componentType": 5123, "count": 3, "type": "SCALAR", "max": [2], "min": [0]},
                       {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3",
                        "max": [1, 1, 0], "min": [0, 0, 0]}]}
    return json.dumps(g)
save("tri.gltf", 4, gltf("data:application/octet-stream;base64," + base64.b64encode(binary).decode()))
j = gltf(None).encode(); j += b" " * (-len(j) % 4)
glb = struct.pack("<I4s", len(j), b"JSON") + j + struct.pack("<I4s", len(binary), b"BIN\0") + binary
save("tri.glb", 5, struct.pack("<4sII", b"glTF", 2, 12 + len(glb)) + glb)
PY

# image: the first byte picks the extension (exr hdr pfm png jpg tif ppm bmp).
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
image() {  # NAME INDEX EXT OIIOTOOL_ARGS...
  local name="$1" index="$2" ext="$3"; shift 3
  oiiotool "$@" -o "$tmp/$name.$ext"
  { printf "\\x$(printf %02x "$index")"; cat "$tmp/$name.$ext"; } > "$c/image/$name.$ext"
}
room="$root/examples/room/photo.exr"
image room_float 0 exr "$room" --resize 16x12
image room_half_piz 0 exr "$room" --resize 12x9 -d half --compression piz
image ramp_rle 0 exr --pattern fill:top=0,0,0:bottom=4,2,1 8x6 3 -d half --compression rle
image mask_y 0 exr --pattern checker:width=2:height=2 8x6 1 --chnames Y
image room 1 hdr "$room" --resize 16x12
# OpenImageIO reads PFM but does not write it: 4 x 3 RGB floats, little-endian, bottom row first.
python3 -c "import struct,sys; sys.stdout.buffer.write(bytes([2]) + b'PF\\n4 3\\n-1.0\\n' + b''.join(struct.pack('<3f', 0.1*x, 0.2*y, 0.5) for y in range(3) for x in range(4)))" > "$c/image/ramp.pfm"
image room 3 png "$room" --resize 8x6 -d uint8
image ramp16 3 png --pattern fill:left=0,0,0:right=1,1,1 8x4 3 -d uint16
image room 4 jpg "$room" --resize 8x6 -d uint8
image room 5 tif "$room" --resize 8x6 -d float
image room_sideways 5 tif "$room" --resize 6x8 -d float --orientation 6  # read upright: turned by its Orientation
image room_sideways 4 jpg "$room" --resize 6x8 -d uint8 --orientation 8
image room 6 ppm "$room" --resize 8x6 -d uint8
image room 7 bmp "$room" --resize 8x6 -d uint8
chmod -R u+w "$c"
du -sh "$c"

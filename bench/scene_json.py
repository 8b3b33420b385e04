"""What the bench's perturb_*.py scripts share: a scene.json read with its
file paths made absolute (so the perturbed copy may live anywhere), and the
few vector operations they need."""
import json, math, os


def load_absolute(scene):
    folder = os.path.dirname(os.path.abspath(scene))
    s = json.load(open(scene))
    for key in ("photo", "geometry"):
        s[key] = os.path.join(folder, s[key])
    for p in s.get("probes", []):
        p["image"] = os.path.join(folder, p["image"])
    return s


def sub(a, b): return [x - y for x, y in zip(a, b)]
def add(a, b): return [x + y for x, y in zip(a, b)]
def scale(a, s): return [x * s for x in a]
def dot(a, b): return sum(x * y for x, y in zip(a, b))
def cross(a, b): return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
def unit(a): return scale(a, 1 / math.sqrt(dot(a, a)))


def rotate(v, axis, angle):  # Rodrigues
    c, s = math.cos(angle), math.sin(angle)
    return add(add(scale(v, c), scale(cross(axis, v), s)), scale(axis, dot(axis, v) * (1 - c)))


def camera_axes(cam):
    """The camera's forward, right and up unit vectors."""
    f = unit(sub(cam["look_at"], cam["position"]))
    right = unit(cross(f, cam["up"]))
    return f, right, cross(right, f)

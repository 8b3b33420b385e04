#include "scene/animation.h"

#include <algorithm>
#include <cmath>

namespace relight {

namespace {

template <class T>
struct Keyed {
  float frame;
  T value;
  Interpolation interpolation;
};

float component(float v, int) { return v; }
float component(const Vec3& v, int i) { return v[i]; }
constexpr int components(float) { return 1; }
constexpr int components(const Vec3&) { return 3; }

// A smooth track's slope at key i (value per frame): its neighbours' chord,
// flat at the ends and, component by component, where the value turns.
template <class T>
T slope(const std::vector<Keyed<T>>& keys, size_t i) {
  T m = keys[i].value - keys[i].value;  // zero of T
  if (i == 0 || i + 1 == keys.size()) return m;
  const T chord = (keys[i + 1].value - keys[i - 1].value) / (keys[i + 1].frame - keys[i - 1].frame);
  for (int c = 0; c < components(m); ++c) {
    const float before = component(keys[i].value, c) - component(keys[i - 1].value, c);
    const float after = component(keys[i + 1].value, c) - component(keys[i].value, c);
    const bool turns = before * after <= 0.0f;
    if constexpr (std::is_same_v<T, float>)
      m = turns ? 0.0f : chord;
    else
      m[c] = turns ? 0.0f : chord[c];
  }
  return m;
}

// The track's value at `frame`.
template <class T>
T evaluate(const std::vector<Keyed<T>>& keys, float frame) {
  if (frame <= keys.front().frame) return keys.front().value;
  if (frame >= keys.back().frame) return keys.back().value;
  size_t k = 0;
  while (keys[k + 1].frame <= frame) ++k;
  const Keyed<T>&a = keys[k], &b = keys[k + 1];
  const float span = b.frame - a.frame, t = (frame - a.frame) / span;
  switch (a.interpolation) {
    case Interpolation::constant:
      return a.value;
    case Interpolation::linear:
      return T(a.value + (b.value - a.value) * t);
    case Interpolation::smooth:
      break;
  }
  // Cubic Hermite.
  const float t2 = t * t, t3 = t2 * t;
  const float h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + t, h01 = -2 * t3 + 3 * t2, h11 = t3 - t2;
  return T(a.value * h00 + slope(keys, k) * (h10 * span) + b.value * h01 + slope(keys, k + 1) * (h11 * span));
}

// The value of the last key at or before `frame`.
template <class T>
T held(std::vector<Keyed<T>> keys, float frame) {
  for (auto& key : keys) key.interpolation = Interpolation::constant;
  return evaluate(keys, frame);
}

// The keys of `keys` that set the value `member` picks out.
template <class T, class Member>
std::vector<Keyed<T>> track(const std::vector<LightKey>& keys, Member member) {
  std::vector<Keyed<T>> out;
  for (const LightKey& key : keys)
    if (const auto& value = key.*member) out.push_back({float(key.frame), T(*value), key.interpolation});
  return out;
}

}  // namespace

bool keys_in_order(const std::vector<LightKey>& keys) {
  return std::adjacent_find(keys.begin(), keys.end(),
                            [](const LightKey& a, const LightKey& b) { return a.frame >= b.frame; }) == keys.end();
}

bool moves(const Light& light) {
  std::optional<Vec3> position, direction;
  for (const LightKey& key : light.keys) {
    if (key.position && position && *key.position != *position) return true;
    if (key.direction && direction && *key.direction != *direction) return true;
    if (key.position) position = key.position;
    if (key.direction) direction = key.direction;
  }
  return false;
}

std::optional<FrameRange> keyed_frames(const Rig& rig) {
  std::optional<FrameRange> range;
  for (const Light& light : rig.lights) {
    if (light.keys.empty()) continue;
    const int first = light.keys.front().frame, last = light.keys.back().frame;
    range = range ? FrameRange{std::min(range->first, first), std::max(range->last, last)} : FrameRange{first, last};
  }
  return range;
}

Light light_at_frame(const Light& light, int frame) {
  Light out = light;
  out.keys.clear();
  const std::vector<LightKey>& keys = light.keys;
  const float f = float(frame);
  if (const auto t = track<Vec3>(keys, &LightKey::position); !t.empty()) out.position = evaluate(t, f);
  if (const auto t = track<Vec3>(keys, &LightKey::direction); !t.empty()) {
    const Vec3 d = evaluate(t, f);
    // Opposite directions halfway between two keys have no mean: the earlier key's.
    if (d.norm() > 1e-6f)
      out.direction = d.normalized();
    else
      out.direction = held(t, f).normalized();
  }
  // A smooth curve can dip below zero between keys; light cannot.
  if (const auto t = track<Vec3>(keys, &LightKey::color); !t.empty()) out.color = evaluate(t, f).cwiseMax(0.0f);
  if (const auto t = track<float>(keys, &LightKey::power); !t.empty()) {
    const float power = std::max(0.0f, evaluate(t, f));
    (out.type == LightType::directional ? out.irradiance : out.power) = power;
  }
  if (const auto t = track<float>(keys, &LightKey::enabled); !t.empty()) out.enabled = held(t, f) > 0.5f;
  return out;
}

Rig rig_at_frame(const Rig& rig, int frame) {
  Rig out = rig;
  for (Light& light : out.lights) light = light_at_frame(light, frame);
  return out;
}

}  // namespace relight

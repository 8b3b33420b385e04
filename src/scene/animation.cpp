#include "scene/animation.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace relight {

namespace {

// One key of one value; a scalar (power, on/off) as a Vec3 of three alike.
struct Keyed {
  float frame;
  Vec3 value;
  Interpolation interpolation;
};
using Track = std::vector<Keyed>;

// A smooth track's slope at key i (value per frame): its neighbours' chord,
// flat at the ends and, component by component, where the value turns.
Vec3 slope(const Track& keys, size_t i) {
  if (i == 0 || i + 1 == keys.size()) return Vec3::Zero();
  const Vec3 chord = (keys[i + 1].value - keys[i - 1].value) / (keys[i + 1].frame - keys[i - 1].frame);
  const Vec3 before = keys[i].value - keys[i - 1].value, after = keys[i + 1].value - keys[i].value;
  return (before.cwiseProduct(after).array() > 0.0f).select(chord, Vec3::Zero());
}

// The track's value at `frame`; `hold`: the last key's at or before it,
// whatever the keys' interpolation.
Vec3 evaluate(const Track& keys, float frame, bool hold = false) {
  if (frame <= keys.front().frame) return keys.front().value;
  if (frame >= keys.back().frame) return keys.back().value;
  size_t k = 0;
  while (keys[k + 1].frame <= frame) ++k;
  const Keyed &a = keys[k], &b = keys[k + 1];
  const float span = b.frame - a.frame, t = (frame - a.frame) / span;
  if (hold || a.interpolation == Interpolation::constant) return a.value;
  if (a.interpolation == Interpolation::linear) return a.value + (b.value - a.value) * t;
  // Cubic Hermite.
  const float t2 = t * t, t3 = t2 * t;
  const float h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + t, h01 = -2 * t3 + 3 * t2, h11 = t3 - t2;
  return a.value * h00 + slope(keys, k) * (h10 * span) + b.value * h01 + slope(keys, k + 1) * (h11 * span);
}

// The keys of `keys` that set the value `member` picks out.
template <class Member>
Track track(const std::vector<LightKey>& keys, Member member) {
  Track out;
  for (const LightKey& key : keys)
    if (const auto& value = key.*member) {
      Vec3 v;
      if constexpr (std::is_same_v<std::decay_t<decltype(*value)>, Vec3>)
        v = *value;
      else
        v = Vec3::Constant(float(*value));
      out.push_back({float(key.frame), v, key.interpolation});
    }
  return out;
}

}  // namespace

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
  if (const Track t = track(keys, &LightKey::position); !t.empty()) out.position = evaluate(t, f);
  if (const Track t = track(keys, &LightKey::direction); !t.empty()) {
    const Vec3 d = evaluate(t, f);
    // Opposite directions halfway between two keys have no mean: the earlier key's.
    out.direction = (d.norm() > 1e-6f ? d : evaluate(t, f, true)).normalized();
  }
  // A smooth curve can dip below zero between keys; light cannot.
  if (const Track t = track(keys, &LightKey::color); !t.empty()) out.color = evaluate(t, f).cwiseMax(0.0f);
  if (const Track t = track(keys, &LightKey::power); !t.empty())
    (out.type == LightType::directional ? out.irradiance : out.power) = std::max(0.0f, evaluate(t, f).x());
  if (const Track t = track(keys, &LightKey::enabled); !t.empty()) out.enabled = evaluate(t, f, true).x() > 0.5f;
  return out;
}

Rig rig_at_frame(const Rig& rig, int frame) {
  Rig out = rig;
  for (Light& light : out.lights) light = light_at_frame(light, frame);
  return out;
}

}  // namespace relight

// Animated rigs: a light's position, direction, colour, power and on/off
// keyed over frames (Light::keys; docs/formats.md "Animated rigs"), and the
// still rig a frame shows. Each value is interpolated between the keys that
// set it, on its own: constant (held), linear, or smooth (a cubic through
// the keys, its slopes those of the neighbouring keys, flat at the first and
// last key and where the value turns, as Blender's auto-clamped curves are).
// Before its first key a value is the first key's, after its last the last
// key's. On/off always holds from key to key.
#pragma once

#include <optional>

#include "scene/scene.h"

namespace relight {

struct FrameRange {
  int first = 0, last = 0;
};

// The frames from the rig's first key to its last; none for a still rig.
std::optional<FrameRange> keyed_frames(const Rig& rig);

// The light as frame `frame` shows it: keys applied, keys dropped.
Light light_at_frame(const Light& light, int frame);
// The rig as frame `frame` shows it: a still rig.
Rig rig_at_frame(const Rig& rig, int frame);

// Whether the light's keys move or turn it: its place or direction keyed to
// two different values.
bool moves(const Light& light);

}  // namespace relight

// Probe: a light probe of FORMAT.md — an HDR image of the light arriving at
// one point — and its two mappings between world directions and image
// positions.
#pragma once

#include <optional>
#include <string>

#include "core/image.h"

namespace relight {

enum class ProbeMapping { equirect, mirrorball };

struct Probe {
  std::string path;  // for messages
  Image image;
  ProbeMapping mapping = ProbeMapping::equirect;
  Vec3 position = Vec3::Zero();
  Vec3 forward = Vec3(0, 1, 0);
  Vec3 up = Vec3(0, 0, 1);
  // scene.json's optional `scale`: the image as read times this is `image`,
  // in the photo's units (relight fit finds it, probe_exposure.h).
  Vec3 scale = Vec3::Ones();
};

// The probe's orthonormal frame: right = forward x up (up re-orthogonalised).
struct ProbeFrame {
  Vec3 right, up, forward;
  ProbeFrame(const Vec3& forward, const Vec3& up);
};

// Image position (u, v) in [0,1]^2 (u right, v down) showing the light that
// arrives from world direction d (unit, pointing away from the probe).
Vec2 probe_direction_to_uv(ProbeMapping mapping, const ProbeFrame& frame, const Vec3& d);
// The world direction shown at image position (u, v); nothing for a
// mirror-ball position outside the ball's disc.
std::optional<Vec3> probe_uv_to_direction(ProbeMapping mapping, const ProbeFrame& frame, const Vec2& uv);
// Solid angle (sr) covered by a pixel at image position (u, v) of a w x h probe.
float probe_pixel_solid_angle(ProbeMapping mapping, const Vec2& uv, int width, int height);

}  // namespace relight

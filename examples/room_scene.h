// The example scene, built by the program's own tools: a small room (floor,
// three walls) with a block and a ball, one lamp, a grey-blue background, and
// a procedural albedo, so its true albedo is known exactly. `make_example`
// renders it into examples/room/; the round-trip test renders it in memory.
#pragma once

#include <vector>

#include "render/gbuffer.h"
#include "render/integrator.h"
#include "scene/scene.h"

namespace relight::example {

// The room's geometry (its objects named floor, back_wall, left_wall,
// right_wall, block and ball), camera (for a width x height photo), lamp and
// background.
// The photo is left empty: render it with room_photo.
Scene room_scene(int width, int height);

// The room's true albedo: a checker floor, plaster walls with a soft band,
// a blue block and a red ball.
class RoomAlbedo final : public SurfaceAlbedo {
 public:
  explicit RoomAlbedo(std::vector<int> object_of_triangle) : object_(std::move(object_of_triangle)) {}
  Vec3 at(const SurfacePoint& p) const override;

 private:
  std::vector<int> object_;
};
RoomAlbedo room_albedo();
// The true albedo each pixel of `gbuffer` shows, weighted by its coverage
// (0 on the background), as a renderer's diffuse-colour pass: albedo_gt.exr.
Image room_albedo_image(const GBuffer& gbuffer);

// The room lit by `lights` and its background times environment_scale.
Lighting room_lighting(const Scene& room, const std::vector<Light>& lights, float environment_scale = 1.0f);

// The room's photo through `camera` (the room's own, or another): path
// traced with its lamp, its background and its true albedo, `paths` a
// pixel over 4 sub-pixel samples.
Image room_photo(const Scene& room, const Camera& camera, const RayScene& rays, int paths, uint64_t seed);

// A re-lighting of the room: the lamp moved and warmer, a cool spot on the
// ball, the background dimmed.
Rig evening_rig();

}  // namespace relight::example

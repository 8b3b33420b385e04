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

// How the room's walls are painted: plaster (near grey) with a terracotta
// band, or each wall a colour of its own (ochre at the back, blue at the
// left, green at the right).
enum class RoomPaint { plaster, coloured };

// The room's true albedo: a checker floor, the walls as painted, a blue
// block and a red ball.
class RoomAlbedo final : public SurfaceAlbedo {
 public:
  RoomAlbedo(std::vector<int> object_of_triangle, RoomPaint paint)
      : object_(std::move(object_of_triangle)), paint_(paint) {}
  Vec3 at(const SurfacePoint& p) const override;

 private:
  std::vector<int> object_;
  RoomPaint paint_;
};
RoomAlbedo room_albedo(RoomPaint paint = RoomPaint::plaster);
// The true albedo each pixel of `gbuffer` shows, weighted by its coverage
// (0 on the background), as a renderer's diffuse-colour pass: albedo_gt.exr.
Image room_albedo_image(const GBuffer& gbuffer, RoomPaint paint = RoomPaint::plaster);

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

// Where the OpenGL backend's shadow maps look from and how they project:
// the fixed samples a light is drawn with, each with the view and
// projection of its map (a cube for a point light, a perspective map for a
// spot or an area sample, orthographic cascades for the sun). Geometry
// only, no OpenGL call (column vectors, OpenGL clip space).
#pragma once

#include <Eigen/Geometry>
#include <limits>
#include <vector>

#include "realtime/shadow_maps.h"

namespace relight {

using Mat4 = Eigen::Matrix4f;

Mat4 look_at(const Vec3& eye, const Vec3& forward, const Vec3& up_hint);
Mat4 perspective(float fovy, float near, float far);
Mat4 orthographic(float left, float right, float bottom, float top, float near, float far);
// The view from `eye` of OpenGL's cube face `face` (0..5: +x, -x, +y, -y, +z, -z).
Mat4 cube_face_view(const Vec3& eye, int face);

// One fixed sample of a light and the shadow map that goes with it.
struct LightSamplePoint {
  enum class Map { cube, perspective, orthographic } map = Map::cube;
  Vec3 eye = Vec3::Zero();       // where the map looks from
  Vec3 forward = Vec3::UnitZ();  // perspective: its axis
  Mat4 view_projection = Mat4::Identity();
  float near = 0.01f, far = 1.0f;
  float texel_per_depth = 0.0f, texel_world = 0.0f;
  Vec2 disc_offset = Vec2::Zero();  // point/spot
  Vec3 area_point = Vec3::Zero();   // area
  Vec3 sun_direction = Vec3::UnitZ();
  int side = 0;                                                              // of the map (of each cube face), texels
  float weight = 1.0f;                                                       // its share of the light
  Vec2 distance_range = Vec2(0.0f, std::numeric_limits<float>::infinity());  // the pixels it serves
};

// A slice of the view by distance from the camera, for the sun's cascaded
// maps: each gets the detail its part of the image needs.
struct Cascade {
  float near = 0.0f, far = std::numeric_limits<float>::infinity();
  Eigen::AlignedBox3f box;  // what the view sees in it
};

// n cascades holding equal shares of the pixels that see a surface: as much
// detail for the far part of the view as it takes in the image.
std::vector<Cascade> view_cascades(const PixelSurfaces& surfaces, int n);

// The light samples of a scene and a view.
class LightViews {
 public:
  // options: sizes already within what the driver allows.
  LightViews(const ShadowMapOptions& options, const Eigen::AlignedBox3f& mesh_box, const PixelSurfaces& surfaces);

  // The fixed samples `light` is drawn with.
  std::vector<LightSamplePoint> samples_of(const Light& light) const;
  int cube_size() const { return std::max(16, options_.size / 2); }
  const Eigen::AlignedBox3f& view_box() const { return view_box_; }
  const std::vector<Cascade>& cascades() const { return cascades_; }

 private:
  float scene_size() const { return std::max(1e-3f, (mesh_box_.max() - mesh_box_.min()).norm()); }
  LightSamplePoint cube_sample(const Vec3& eye) const;
  LightSamplePoint perspective_sample(const Vec3& eye, const Vec3& forward, float fovy) const;
  LightSamplePoint orthographic_sample(const Vec3& towards_light, const Cascade& cascade) const;

  ShadowMapOptions options_;
  Eigen::AlignedBox3f mesh_box_, view_box_;  // the view's: what its pixels see (the mesh's if nothing)
  std::vector<Cascade> cascades_;
};

}  // namespace relight

// RayScene: the one place that talks to Embree. Builds a BVH over the scene
// mesh and answers closest-hit and any-hit (shadow) queries.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <span>

#include "scene/triangle_mesh.h"

namespace relight {

// A point on the scene surface, with normals turned towards the side the
// query came from (surfaces are two-sided).
struct SurfacePoint {
  Vec3 position;
  Vec3 normal;            // shading normal (interpolated where the mesh has normals)
  Vec3 geometric_normal;  // the triangle's normal
  uint32_t prim = 0;      // triangle index in the mesh
  float distance = 0.0f;  // from the query origin
};

// A segment for an occlusion query: origin + t dir, t in (0, tmax). A ray
// with tmax <= 0 is no query at all (reported unblocked).
struct ShadowRay {
  Vec3 origin;
  Vec3 dir;
  float tmax = 0.0f;
};

class RayScene {
 public:
  explicit RayScene(const TriangleMesh& mesh);
  ~RayScene();
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  // Closest surface along the ray (dir unit) in (0, tmax); false if none.
  bool intersect(const Vec3& origin, const Vec3& dir, SurfacePoint& hit,
                 float tmax = std::numeric_limits<float>::infinity()) const;
  // True if anything blocks the segment origin + t dir, t in (0, tmax).
  bool occluded(const Vec3& origin, const Vec3& dir, float tmax) const;
  // The same for many rays at once: blocked[i] = 1 if something blocks
  // rays[i], else 0. Rays that are neighbours in the span should be coherent
  // (shadow rays of neighbouring pixels towards one light): they are traced
  // as packets, several times faster than one by one.
  void occluded(std::span<const ShadowRay> rays, std::span<uint8_t> blocked) const;

  // A ray origin just off the surface on the side of `towards`, so that the
  // ray does not hit the surface it starts on.
  Vec3 offset_origin(const SurfacePoint& p, const Vec3& towards) const;
  // The shadow ray from p towards a point `distance` away along the unit
  // `dir` (infinite distance: a direction), starting just off the surface and
  // stopping just short of the point.
  ShadowRay shadow_ray(const SurfacePoint& p, const Vec3& dir, float distance) const;
  // Offset distance used for origins and shadow-ray ends (scales with the scene).
  float epsilon() const { return epsilon_; }

  const TriangleMesh& mesh() const { return mesh_; }

 private:
  struct Embree;
  const TriangleMesh& mesh_;
  std::unique_ptr<Embree> embree_;
  float epsilon_;
};

}  // namespace relight

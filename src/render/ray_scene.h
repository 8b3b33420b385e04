// RayScene: the one place that talks to Embree. Builds a BVH over the scene
// mesh and answers closest-hit and any-hit (shadow) queries.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>

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
  // How far above the facet (along geometric_normal) the smooth surface its
  // vertices' normals describe lies here; 0 where it lies below or the mesh
  // has no normals. Shadow rays start there (RayScene::shadow_ray).
  float lift = 0.0f;
};

// A segment for an occlusion query: origin + t dir, t in (0, tmax). A ray
// with tmax <= 0 is no query at all (reported unblocked). `from`: the
// triangle of a smooth surface the ray leaves on the side its normals face,
// which does not shadow itself there (RayScene::shadow_ray); kNoTriangle
// for any other ray.
struct ShadowRay {
  static constexpr uint32_t kNoTriangle = ~0u;
  Vec3 origin;
  Vec3 dir;
  float tmax = 0.0f;
  uint32_t from = kNoTriangle;
};

class RayScene;

// Up to 16 shadow rays traced together, as one Embree packet: coherent rays
// (shadow rays of neighbouring pixels towards one light) share the
// traversal of the BVH nodes they all cross, several times faster than one
// by one. Kept field by field, as Embree's packets are, so that filling one
// costs a few stores a ray.
class ShadowPacket {
 public:
  static constexpr int kCapacity = 16;
  int size() const { return size_; }
  bool full() const { return size_ == kCapacity; }
  // Adds a ray and returns its slot.
  int add(const ShadowRay& ray) {
    const int j = size_++;
    for (int c = 0; c < 3; ++c) {
      origin_[c][j] = ray.origin[c];
      dir_[c][j] = ray.dir[c];
    }
    tfar_[j] = ray.tmax;
    from_[j] = ray.from;
    return j;
  }
  // After RayScene::occluded(packet): whether something blocks ray j.
  bool blocked(int j) const { return tfar_[j] < 0.0f; }
  void clear() { size_ = 0; }

 private:
  friend class RayScene;
  alignas(64) float origin_[3][kCapacity] = {};
  alignas(64) float dir_[3][kCapacity] = {};
  alignas(64) float tfar_[kCapacity] = {};
  alignas(64) uint32_t from_[kCapacity] = {};
  int size_ = 0;
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
  // The same for a ray leaving a surface as shadow_ray() sends it (dir
  // unit): the smooth surface it leaves is passed over, as occluded(ray)
  // does. A path's bounce off a ball whose facets stand a little off its
  // normals then sees the room, not the ball's own neighbouring facets.
  bool intersect(const ShadowRay& ray, SurfacePoint& hit) const;
  // Where the ray meets the plane of triangle `prim`, as intersect would
  // report a hit on it (the G-buffer recomputes its samples so rather than
  // keep them); false where the ray runs along the plane.
  bool intersect_triangle(uint32_t prim, const Vec3& origin, const Vec3& dir, SurfacePoint& hit) const;
  // True if anything blocks the segment origin + t dir, t in (0, tmax).
  bool occluded(const Vec3& origin, const Vec3& dir, float tmax) const;
  // True if anything but the smooth surface it leaves blocks the ray.
  bool occluded(const ShadowRay& ray) const;
  // The same for a packet of rays at once; then packet.blocked(j) answers.
  void occluded(ShadowPacket& packet) const;

  // A ray origin just off the surface on the side of `towards`, so that the
  // ray does not hit the surface it starts on.
  Vec3 offset_origin(const SurfacePoint& p, const Vec3& towards) const {
    const float scale = offset_scale(p);
    const Vec3& ng = p.geometric_normal;
    return p.position + (ng.dot(towards) >= 0.0f ? scale : -scale) * ng;
  }
  // The shadow ray from p towards a point `distance` away along the unit
  // `dir` (infinite distance: a direction; or `distance` 1 along a `dir` of
  // any length, as shadow_ray_to), starting just off the surface and
  // stopping just short of the point. Towards the side the shading normal
  // faces it starts on the smooth surface the vertices' normals describe
  // (`lift` above the facet; Hanika, "Hacking the shadow terminator", 2021):
  // a coarse or slightly misplaced facet, tilted against its normals, then
  // neither shadows itself nor cuts off the light that grazes it, and light
  // below the facet but above the smooth surface reaches the point where the
  // facet does not block it. Nor does the rest of that smooth surface
  // (SmoothSurfaces): facets a little off, as a scanned or hand-modelled
  // mesh's are, would speckle it with their own shadows.
  ShadowRay shadow_ray(const SurfacePoint& p, const Vec3& dir, float distance) const {
    const float tmax = std::isfinite(distance) ? distance * (1.0f - 1e-4f) : distance;
    if (dir.dot(p.normal) > 0.0f)
      return {p.position + (offset_scale(p) + p.lift) * p.geometric_normal, dir, tmax,
              mesh_.has_normals() ? p.prim : ShadowRay::kNoTriangle};
    return {offset_origin(p, dir), dir, tmax};
  }
  // The shadow ray from p to the point `target`, its direction not made
  // unit (the target is at t = 1): a square root and a division the less.
  ShadowRay shadow_ray_to(const SurfacePoint& p, const Vec3& target) const {
    return shadow_ray(p, target - p.position, 1.0f);
  }
  // Offset distance used for origins and shadow-ray ends (scales with the scene).
  float epsilon() const { return epsilon_; }
  float offset_scale(const SurfacePoint& p) const { return epsilon_ + 1e-5f * p.position.cwiseAbs().maxCoeff(); }

  const TriangleMesh& mesh() const { return mesh_; }

 private:
  // A hit on triangle `prim` at distance t along the ray, at barycentric
  // (u, v) (the weights of its second and third vertex), ng its normal.
  void describe_hit(uint32_t prim, const Vec3& origin, const Vec3& dir, float t, float u, float v, Vec3 ng,
                    SurfacePoint& hit) const;
  struct Embree;
  const TriangleMesh& mesh_;
  std::unique_ptr<Embree> embree_;
  float epsilon_;
};

}  // namespace relight

// Every Embree call of the program lives in this file.
#include "render/ray_scene.h"

#include <embree3/rtcore.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <unordered_map>
#include <vector>

namespace relight {

namespace {

// Which triangles make one smooth surface, for shadow rays that leave it on
// the side its normals face: a triangle of the same part (joined to the
// ray's own through edges whose facets turn by less than kJoinTurn, or
// where both triangles are gently curved and their normals lean on the mean
// within kSmoothLean) within
// kReach of its size of where the ray leaves, whose vertices' normals lean on
// the mean within kSmoothLean of those of the ray's triangle, does not block
// the ray. So little of a surface bending so little does not shadow itself
// where its normals face the light; a hit there is the facets standing off
// the surface their normals describe: a coarse tessellation at the
// terminator, or vertices a centimetre off (a scanned or hand-modelled
// mesh), which would speckle it with their own shadows. A box's faces (even
// with their normals averaged at the edges), a bowl's far side, a table top
// over a floor (not joined to it) still shadow.
struct SmoothSurfaces {
  static constexpr float kSmoothLean = 0.866f;  // cos 30 degrees
  static constexpr float kJoinTurn = 0.5f;      // cos 60 degrees
  static constexpr float kGentleLean = 0.966f;  // cos 15 degrees
  static constexpr float kReach = 4.0f;         // times the longest edge of the ray's triangle
  std::vector<Vec3> mean_normal;                // per triangle; empty: the mesh has no normals
  std::vector<uint32_t> part;                   // per triangle, its part's first triangle
  std::vector<float> reach;                     // per triangle

  explicit SmoothSurfaces(const TriangleMesh& mesh) {
    if (!mesh.has_normals()) return;
    const size_t n = mesh.triangles.size();
    mean_normal.reserve(n);
    reach.reserve(n);
    std::vector<Vec3> facet(n);
    std::vector<char> gently_curved(n);  // its vertices' normals within kGentleLean of their mean
    for (size_t t = 0; t < n; ++t) {
      const auto& v = mesh.triangles[t];
      const Vec3 sum = mesh.normals[v[0]] + mesh.normals[v[1]] + mesh.normals[v[2]];
      mean_normal.push_back(sum.squaredNorm() > 0.0f ? Vec3(sum.normalized()) : Vec3::Zero());
      gently_curved[t] = std::all_of(v.begin(), v.end(),
                                     [&](uint32_t i) { return mesh.normals[i].dot(mean_normal.back()) > kGentleLean; });
      const Vec3 &p0 = mesh.positions[v[0]], &p1 = mesh.positions[v[1]], &p2 = mesh.positions[v[2]];
      facet[t] = (p1 - p0).cross(p2 - p0).normalized();
      reach.push_back(kReach *
                      std::sqrt(std::max({(p1 - p0).squaredNorm(), (p2 - p1).squaredNorm(), (p0 - p2).squaredNorm()})));
    }
    // Union-find over the triangles, halving the paths; an edge joins the
    // two triangles that share it where their facets turn little, or where
    // both are small on a gently curved surface and their normals say they
    // are one: a ball's facets moved by a centimetre turn by 46 degrees from
    // their neighbours on the median, a third of them by over 60, while its
    // normals turn by 4. (A box shaded smooth has triangles whose normals
    // differ by 45 degrees or more: its faces stay apart.)
    part.resize(n);
    for (uint32_t t = 0; t < n; ++t) part[t] = t;
    const auto root = [&](uint32_t t) {
      while (part[t] != t) t = part[t] = part[part[t]];
      return t;
    };
    std::unordered_map<uint64_t, uint32_t> first_with_edge;
    first_with_edge.reserve(3 * n);
    for (uint32_t t = 0; t < n; ++t)
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
        const uint64_t edge = uint64_t(std::min(a, b)) << 32 | std::max(a, b);
        const auto [it, added] = first_with_edge.try_emplace(edge, t);
        const uint32_t u = it->second;
        if (!added && (std::abs(facet[t].dot(facet[u])) > kJoinTurn ||
                       (gently_curved[t] && gently_curved[u] && mean_normal[t].dot(mean_normal[u]) > kSmoothLean)))
          part[root(t)] = root(it->second);
      }
    for (uint32_t t = 0; t < n; ++t) part[t] = root(t);
  }
  // Whether triangle `hit`, `distance` along a ray leaving triangle `from`,
  // is of the surface the ray leaves.
  bool own_surface(uint32_t from, uint32_t hit, float distance) const {
    return part[from] == part[hit] && distance < reach[from] && mean_normal[from].dot(mean_normal[hit]) > kSmoothLean;
  }
};

// Embree's occlusion and intersection filter: a hit on the smooth surface
// the ray leaves (its id, ShadowRay::from) is passed over.
void pass_over_own_surface(const RTCFilterFunctionNArguments* args) {
  const auto& smooth = *static_cast<const SmoothSurfaces*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const uint32_t from = RTCRayN_id(args->ray, args->N, i);
    if (from != ShadowRay::kNoTriangle &&
        smooth.own_surface(from, RTCHitN_primID(args->hit, args->N, i), RTCRayN_tfar(args->ray, args->N, i)))
      args->valid[i] = 0;
  }
}
}  // namespace

struct RayScene::Embree {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::unique_ptr<SmoothSurfaces> smooth;
  ~Embree() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

namespace {
void embree_error(void*, RTCError code, const char* message) {
  spdlog::error("Embree error {}: {}", int(code), message ? message : "");
}

// How far above the facet, along its normal `ng`, the smooth surface through
// triangle t's vertices with their normals lies at the point p of
// barycentrics b: p projected onto each vertex's tangent plane, the three
// projections interpolated (Hanika 2021). 0 where it lies below. A vertex
// whose normal leans more than kMostLean from the facet's is on a hard edge
// whose normals were averaged (a box's corner, a column's rim), not on a
// curved surface: its tangent plane would lift the ray's start through the
// geometry beside it (a column's capital stopped shadowing its top), so it
// keeps the facet's plane.
float smooth_surface_lift(const TriangleMesh& mesh, const Vec3& p, const Vec3& ng, const std::array<uint32_t, 3>& t,
                          const Vec3& b) {
  constexpr float kMostLean = 0.866f;  // cos 30 degrees
  Vec3 smooth = Vec3::Zero();
  for (int i = 0; i < 3; ++i) {
    const Vec3& vertex = mesh.positions[t[i]];
    const Vec3& n = mesh.normals[t[i]];
    smooth += b[i] * (std::abs(n.dot(ng)) < kMostLean ? p : Vec3(p - (p - vertex).dot(n) * n));
  }
  return std::max(0.0f, (smooth - p).dot(ng));
}
}  // namespace

RayScene::RayScene(const TriangleMesh& mesh) : mesh_(mesh), embree_(std::make_unique<Embree>()) {
  embree_->device = rtcNewDevice(nullptr);
  if (!embree_->device) throw std::runtime_error("Embree: cannot create a device");
  rtcSetDeviceErrorFunction(embree_->device, embree_error, nullptr);

  embree_->scene = rtcNewScene(embree_->device);
  rtcSetSceneBuildQuality(embree_->scene, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geom = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  // Embree reads vertices as float3 but may load 16 bytes: the buffer it
  // allocates itself is padded for that.
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), mesh.positions.size()));
  for (size_t i = 0; i < mesh.positions.size(); ++i)
    for (int c = 0; c < 3; ++c) vertices[3 * i + c] = mesh.positions[i][c];
  auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(uint32_t), mesh.triangles.size()));
  for (size_t i = 0; i < mesh.triangles.size(); ++i)
    for (int c = 0; c < 3; ++c) indices[3 * i + c] = mesh.triangles[i][c];
  embree_->smooth = std::make_unique<SmoothSurfaces>(mesh);
  if (!embree_->smooth->mean_normal.empty()) {
    rtcSetGeometryUserData(geom, embree_->smooth.get());
    rtcSetGeometryOccludedFilterFunction(geom, pass_over_own_surface);
    rtcSetGeometryIntersectFilterFunction(geom, pass_over_own_surface);
  }
  rtcCommitGeometry(geom);
  rtcAttachGeometry(embree_->scene, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(embree_->scene);

  const auto box = mesh.bounds();
  epsilon_ = std::max(1e-5f, 1e-5f * (box.max() - box.min()).maxCoeff());
}

RayScene::~RayScene() = default;

bool RayScene::intersect(const Vec3& origin, const Vec3& dir, SurfacePoint& hit, float tmax) const {
  return intersect(ShadowRay{origin, dir, tmax}, hit);
}

bool RayScene::intersect(const ShadowRay& ray, SurfacePoint& hit) const {
  const Vec3 &origin = ray.origin, &dir = ray.dir;
  const float tmax = ray.tmax;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh{};
  rh.ray.org_x = origin.x(), rh.ray.org_y = origin.y(), rh.ray.org_z = origin.z();
  rh.ray.dir_x = dir.x(), rh.ray.dir_y = dir.y(), rh.ray.dir_z = dir.z();
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = tmax;
  rh.ray.mask = ~0u;
  rh.ray.id = ray.from;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(embree_->scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;

  describe_hit(rh.hit.primID, origin, dir, rh.ray.tfar, rh.hit.u, rh.hit.v, Vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z),
               hit);
  return true;
}

bool RayScene::intersect_triangle(uint32_t prim, const Vec3& origin, const Vec3& dir, SurfacePoint& hit) const {
  // Moller-Trumbore, without the bounds: the ray is known to hit it.
  const auto& tri = mesh_.triangles[prim];
  const Vec3 &p0 = mesh_.positions[tri[0]], &p1 = mesh_.positions[tri[1]], &p2 = mesh_.positions[tri[2]];
  const Vec3 e1 = p1 - p0, e2 = p2 - p0;
  const Vec3 q = dir.cross(e2);
  const float det = e1.dot(q);
  if (std::abs(det) < 1e-20f) return false;
  const Vec3 s = origin - p0, r = s.cross(e1);
  const float u = s.dot(q) / det, v = dir.dot(r) / det, t = e2.dot(r) / det;
  describe_hit(prim, origin, dir, t, u, v, e1.cross(e2), hit);
  return true;
}

void RayScene::describe_hit(uint32_t prim, const Vec3& origin, const Vec3& dir, float t, float u, float v, Vec3 ng,
                            SurfacePoint& hit) const {
  hit.prim = prim;
  hit.distance = t;
  hit.position = origin + dir * t;
  ng.normalize();
  if (ng.dot(dir) > 0.0f) ng = -ng;  // face the ray's origin
  hit.geometric_normal = ng;
  hit.normal = ng;
  hit.lift = 0.0f;
  if (mesh_.has_normals()) {
    const auto& tri = mesh_.triangles[prim];
    Vec3 ns = (1.0f - u - v) * mesh_.normals[tri[0]] + u * mesh_.normals[tri[1]] + v * mesh_.normals[tri[2]];
    if (ns.squaredNorm() > 0.0f) {
      ns.normalize();
      hit.normal = ns.dot(ng) < 0.0f ? Vec3(-ns) : ns;
    }
    hit.lift = smooth_surface_lift(mesh_, hit.position, ng, tri, Vec3(1.0f - u - v, u, v));
  }
}

bool RayScene::occluded(const Vec3& origin, const Vec3& dir, float tmax) const {
  return occluded(ShadowRay{origin, dir, tmax});
}

bool RayScene::occluded(const ShadowRay& shadow) const {
  const Vec3 &origin = shadow.origin, &dir = shadow.dir;
  const float tmax = shadow.tmax;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray{};
  ray.id = shadow.from;
  ray.org_x = origin.x(), ray.org_y = origin.y(), ray.org_z = origin.z();
  ray.dir_x = dir.x(), ray.dir_y = dir.y(), ray.dir_z = dir.z();
  ray.tnear = 0.0f;
  ray.tfar = tmax;
  ray.mask = ~0u;
  rtcOccluded1(embree_->scene, &context, &ray);
  return ray.tfar < 0.0f;
}

void RayScene::occluded(ShadowPacket& packet) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(64) RTCRay16 rays;
  alignas(64) int valid[16];
  static_assert(ShadowPacket::kCapacity == 16);
  std::copy_n(packet.origin_[0], 16, rays.org_x);
  std::copy_n(packet.origin_[1], 16, rays.org_y);
  std::copy_n(packet.origin_[2], 16, rays.org_z);
  std::copy_n(packet.dir_[0], 16, rays.dir_x);
  std::copy_n(packet.dir_[1], 16, rays.dir_y);
  std::copy_n(packet.dir_[2], 16, rays.dir_z);
  std::copy_n(packet.tfar_, 16, rays.tfar);
  for (int j = 0; j < 16; ++j) {
    valid[j] = j < packet.size_ && packet.tfar_[j] > 0.0f ? -1 : 0;
    rays.tnear[j] = 0.0f;
    rays.mask[j] = ~0u;
    rays.time[j] = 0.0f;
    rays.id[j] = packet.from_[j];
    rays.flags[j] = 0;
  }
  rtcOccluded16(valid, embree_->scene, &context, &rays);
  // Embree sets a blocked ray's tfar to -inf; the others keep theirs.
  for (int j = 0; j < packet.size_; ++j) packet.tfar_[j] = valid[j] ? rays.tfar[j] : 0.0f;
}

}  // namespace relight

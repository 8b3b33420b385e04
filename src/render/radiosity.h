// Gathering radiosity (thesis 3.2, 2.3.1): the irradiance at the vertices of
// a mesh, interpolated linearly across its triangles (the Gouraud assumption
// of thesis appendix A).
//
// Each node — a vertex, one per side of the surface and per face normal
// where the vertex lies on a crease — gathers, by ray casting:
//   - the light straight from the lights and the environment (the path
//     tracer's estimator with no bounce: soft shadows, importance sampling);
//   - the light from the other surfaces: a fixed set of cosine-distributed
//     rays, each the form factor to what it hits times that point's
//     radiosity (albedo x irradiance / pi, interpolated from its nodes).
// The rays are cast once; iterating (Jacobi: one bounce of light per pass)
// only looks up the current solution where they hit, so a solve with another
// albedo (the analysis's interreflection passes) costs no ray.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <vector>

#include "core/image.h"
#include "core/progress.h"
#include "core/sampling.h"
#include "render/gbuffer.h"
#include "render/integrator.h"
#include "render/ray_scene.h"

namespace relight {

struct RadiosityOptions {
  int light_samples = 64;                            // per node: the lights and the environment
  int gather_rays = 256;                             // per node: the light from the other surfaces
  int max_bounces = IntegratorOptions::kMaxBounces;  // as the path tracer's: diffuse bounces after the first surface
  float tolerance = 1e-3f;                           // stop bouncing when no node changes by more than this (relative)
  uint64_t seed = 1;
};

// A triangle mesh with radiosity nodes at its vertices. Its triangles are
// pieces of the scene mesh's (`sources`); where the scene mesh has shading
// normals the nodes take them.
class NodeMesh {
 public:
  // Both sides of every surface (the scene, where light may reach either),
  // or only the side facing `viewpoint` (what the camera sees).
  enum class Sides { both, facing_viewpoint };

  NodeMesh(TriangleMesh mesh, std::vector<uint32_t> sources, const TriangleMesh& scene_mesh, Sides sides,
           const Vec3& viewpoint = Vec3::Zero());

  const TriangleMesh& mesh() const { return mesh_; }
  uint32_t source(uint32_t triangle) const { return sources_[triangle]; }
  size_t nodes() const { return nodes_.size(); }

  // The value at barycentric coordinates `bary` of a triangle, on its back
  // (against its winding's normal) or front, from per-node values.
  Vec3 interpolate(std::span<const Vec3> values, uint32_t triangle, const Vec3& bary, bool back) const;
  // The barycentric coordinates of a point on a triangle.
  Vec3 barycentric(uint32_t triangle, const Vec3& point) const;
  // The triangle's unit normal by its winding.
  Vec3 face_normal(uint32_t triangle) const;
  // The surface point at barycentric coordinates `bary` of a triangle, seen
  // from its back or front: the nodes' normals interpolated; prim is the
  // scene triangle.
  SurfacePoint point_at(uint32_t triangle, const Vec3& bary, bool back) const;

  // A surface point of node n's triangles drawn with density proportional
  // to its hat function (1 at the vertex, 0 at the triangles' far sides),
  // facing the node's side; prim is the scene triangle. The mean over such
  // points is the node's share of the light in the least-squares sense,
  // which is what linear interpolation between nodes needs where the light
  // bends (under an overhang, at the foot of a wall).
  SurfacePoint sample_point(size_t n, Rng& rng) const;

 private:
  struct Node {
    uint32_t vertex;
    Vec3 normal;
    std::vector<uint32_t> triangles;  // those it is a corner of, on its side
    std::vector<float> area_up_to;    // their areas (doubled), summed up to and including each
  };
  void add_corner(uint32_t triangle, int corner, int side, const Vec3& normal);

  TriangleMesh mesh_;
  std::vector<uint32_t> sources_;
  Sides sides_;
  std::vector<Node> nodes_;
  std::vector<std::vector<uint32_t>> vertex_nodes_;    // the nodes of each vertex
  std::vector<std::array<uint32_t, 6>> corner_nodes_;  // per triangle: front corners, then back
};

// The rays each node of one mesh casts into the scene (a NodeMesh over the
// whole scene, traced through its own RayScene), and the light each node
// gets straight from the lights and the environment.
class RadiosityGather {
 public:
  // With `viewpoint`, a node's samples are taken only where the viewpoint
  // sees them (where it sees any): a vertex hidden under an object standing
  // on its surface would otherwise darken what is seen around it.
  // With `lights_at_hits`, the light each hit point gets straight from
  // those lights is traced there (a shadow ray per light) rather than
  // interpolated from the scene's nodes: the view's final gather then sees
  // the shadows on the surfaces around it as sharp as they are, however
  // coarse the scene mesh (the shadow of a column on the ground that lights
  // the column). `lighting` is what reaches the nodes themselves.
  RadiosityGather(const NodeMesh& nodes, const NodeMesh& scene, const RayScene& scene_rays, const RayScene& rays,
                  const Lighting& lighting, const RadiosityOptions& options, Progress& progress,
                  const std::string& label, const std::optional<Vec3>& viewpoint = std::nullopt,
                  const Lighting* lights_at_hits = nullptr);

  // The albedo where each ray hit: call before gather() with another albedo.
  void set_albedo(const SurfaceAlbedo& albedo);
  // The radiance known where rays hit (the photo's, where it shows the hit:
  // inverse global illumination), which those hits then bring whatever the
  // albedo and the nodes' irradiance; nullptr: none known.
  void set_known(const KnownRadiance* known);
  // Each node's irradiance: its direct light plus the light of the rays' hit
  // points, from the scene nodes' irradiance `scene_irradiance`, of which
  // `scene_lights` is straight from the lights (needed with lights_at_hits).
  std::vector<Vec3> gather(std::span<const Vec3> scene_irradiance, std::span<const Vec3> scene_lights = {}) const;
  // Each node's irradiance from the lights and the environment, and the
  // lights' part of it.
  const std::vector<Vec3>& direct() const { return direct_; }
  const std::vector<Vec3>& lights() const { return lights_; }

 private:
  struct Hit {
    uint32_t triangle;  // of the scene NodeMesh
    float b1, b2;       // barycentric coordinates of corners 1 and 2
    bool back;
  };
  const NodeMesh& scene_;
  int rays_per_node_;
  std::vector<Vec3> direct_;     // irradiance from the lights and the environment
  std::vector<Vec3> lights_;     // the lights' part of it
  std::vector<uint32_t> first_;  // node n's hits: [first_[n], first_[n + 1])
  std::vector<Hit> hits_;
  std::vector<Vec3> hit_albedo_;
  std::vector<std::optional<Vec3>> hit_known_;  // pi x the known radiance at each hit, where known
  std::vector<Vec3> hit_lights_;                // with lights_at_hits: irradiance from the lights at each hit
};

// The scene's irradiance at its nodes with the albedo `albedo` on every
// surface: bounces light until it settles or max_bounces - 1 bounces (the
// view's final gather adds the last). Returns the bounces done.
int solve_radiosity(const RadiosityGather& scene_gather, const RadiosityOptions& options,
                    std::vector<Vec3>& irradiance);

// The illumination of each pixel (irradiance / pi, as the path tracer's
// renders) interpolated from the view mesh's nodes: the mean over the
// pixel's G-buffer samples that see the view mesh (0 where none does).
Image illumination_from_nodes(const GBuffer& gbuffer, const Camera& camera, const NodeMesh& view,
                              const RayScene& view_rays, std::span<const Vec3> irradiance);

}  // namespace relight

#include "render/radiosity.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace relight {

namespace {

// Corners whose normals are within about 20 degrees share a node: a smooth
// or flat surface has one node per vertex and side, a crease one per face.
constexpr float kSameNodeCos = 0.94f;
constexpr uint32_t kNoNode = UINT32_MAX;
// Sample points drawn before a node is taken for hidden from the viewpoint.
constexpr int kViewpointTries = 2;

// The barycentric coordinates of a point on triangle t of a mesh (the
// centre's for a degenerate triangle).
Vec3 barycentric_on(const TriangleMesh& mesh, uint32_t t, const Vec3& point) {
  const auto& c = mesh.triangles[t];
  const Vec3 a = mesh.positions[c[0]], b = mesh.positions[c[1]], d = mesh.positions[c[2]];
  const Vec3 n = (b - a).cross(d - a);
  const float area2 = n.squaredNorm();
  if (!(area2 > 0.0f)) return Vec3::Constant(1.0f / 3.0f);
  const float w1 = n.dot((point - a).cross(d - a)) / area2, w2 = n.dot((b - a).cross(point - a)) / area2;
  return Vec3(1.0f - w1 - w2, w1, w2);
}

// The shading normal of scene triangle t at a point (the face normal where
// the scene mesh has none).
Vec3 scene_normal(const TriangleMesh& scene, uint32_t t, const Vec3& point, const Vec3& face_normal) {
  if (!scene.has_normals()) return face_normal;
  const auto& c = scene.triangles[t];
  const Vec3 w = barycentric_on(scene, t, point);
  const Vec3 shading = w.x() * scene.normals[c[0]] + w.y() * scene.normals[c[1]] + w.z() * scene.normals[c[2]];
  const float len = shading.norm();
  if (!(len > 0.0f)) return face_normal;
  // Shading normals point to the winding's side or against it; keep the winding's.
  return shading.dot(face_normal) >= 0.0f ? Vec3(shading / len) : Vec3(-shading / len);
}

}  // namespace

NodeMesh::NodeMesh(TriangleMesh mesh, std::vector<uint32_t> sources, const TriangleMesh& scene_mesh, Sides sides,
                   const Vec3& viewpoint)
    : mesh_(std::move(mesh)), sources_(std::move(sources)), sides_(sides) {
  vertex_nodes_.resize(mesh_.positions.size());
  corner_nodes_.assign(mesh_.triangles.size(), {kNoNode, kNoNode, kNoNode, kNoNode, kNoNode, kNoNode});
  for (uint32_t t = 0; t < mesh_.triangles.size(); ++t) {
    const Vec3 face = face_normal(t);
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = mesh_.positions[mesh_.triangles[t][k]];
      const Vec3 n = scene_normal(scene_mesh, sources_[t], p, face);
      if (sides_ == Sides::both) {
        add_corner(t, k, 0, n);
        add_corner(t, k, 1, -n);
      } else {
        // The side the viewpoint sees is the face's: a shading normal can
        // turn away from the viewer near a silhouette while the face does not.
        add_corner(t, k, 0, face.dot(viewpoint - p) >= 0.0f ? n : Vec3(-n));
      }
    }
  }
  for (Node& node : nodes_) {
    node.normal.normalize();
    float sum = 0.0f;
    for (uint32_t t : node.triangles) {
      const auto& c = mesh_.triangles[t];
      sum += (mesh_.positions[c[1]] - mesh_.positions[c[0]]).cross(mesh_.positions[c[2]] - mesh_.positions[c[0]]).norm();
      node.area_up_to.push_back(sum);
    }
  }
}

void NodeMesh::add_corner(uint32_t t, int corner, int side, const Vec3& normal) {
  const uint32_t v = mesh_.triangles[t][corner];
  uint32_t chosen = kNoNode;
  for (uint32_t n : vertex_nodes_[v])
    if (nodes_[n].normal.normalized().dot(normal) > kSameNodeCos) {
      chosen = n;
      break;
    }
  if (chosen == kNoNode) {
    chosen = uint32_t(nodes_.size());
    nodes_.push_back({v, Vec3::Zero(), {}, {}});
    vertex_nodes_[v].push_back(chosen);
  }
  nodes_[chosen].normal += normal;  // normalised once all corners are in
  nodes_[chosen].triangles.push_back(t);
  corner_nodes_[t][size_t(side * 3 + corner)] = chosen;
}

Vec3 NodeMesh::face_normal(uint32_t t) const {
  const auto& c = mesh_.triangles[t];
  const Vec3 n = (mesh_.positions[c[1]] - mesh_.positions[c[0]]).cross(mesh_.positions[c[2]] - mesh_.positions[c[0]]);
  const float len = n.norm();
  return len > 0.0f ? Vec3(n / len) : Vec3(0.0f, 0.0f, 1.0f);
}

Vec3 NodeMesh::barycentric(uint32_t t, const Vec3& point) const { return barycentric_on(mesh_, t, point); }

SurfacePoint NodeMesh::point_at(uint32_t t, const Vec3& bary, bool back) const {
  const auto& c = mesh_.triangles[t];
  SurfacePoint p;
  p.position = bary.x() * mesh_.positions[c[0]] + bary.y() * mesh_.positions[c[1]] + bary.z() * mesh_.positions[c[2]];
  const int side = sides_ == Sides::both && back ? 3 : 0;
  const auto& nodes = corner_nodes_[t];
  const Vec3 n = bary.x() * nodes_[nodes[side]].normal + bary.y() * nodes_[nodes[side + 1]].normal +
                 bary.z() * nodes_[nodes[side + 2]].normal;
  const Vec3 face = back ? Vec3(-face_normal(t)) : face_normal(t);
  p.geometric_normal = face;
  p.normal = n.squaredNorm() > 0.0f ? Vec3(n.normalized()) : face;
  p.prim = sources_[t];
  return p;
}

Vec3 NodeMesh::interpolate(std::span<const Vec3> values, uint32_t t, const Vec3& bary, bool back) const {
  const int side = sides_ == Sides::both && back ? 3 : 0;
  const auto& nodes = corner_nodes_[t];
  return bary.x() * values[nodes[side]] + bary.y() * values[nodes[side + 1]] + bary.z() * values[nodes[side + 2]];
}

SurfacePoint NodeMesh::sample_point(size_t n, Rng& rng) const {
  const Node& node = nodes_[n];
  // A triangle by its area, then the vertex's barycentric coordinate by
  // its density there, w(1 - w) (the hat times the uniform's), which is the
  // middle of three uniform numbers; the rest of the point uniform.
  const float pick = rng.uniform() * node.area_up_to.back();
  const size_t chosen = size_t(std::upper_bound(node.area_up_to.begin(), node.area_up_to.end(), pick) -
                               node.area_up_to.begin());
  const uint32_t t = node.triangles[std::min(chosen, node.triangles.size() - 1)];
  const float u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
  const float w = std::max(std::min(u1, u2), std::min(std::max(u1, u2), u3));
  const float s = rng.uniform();
  const auto& c = mesh_.triangles[t];
  int k = 0;
  while (c[k] != node.vertex) ++k;
  const Vec3 v = mesh_.positions[node.vertex];
  const Vec3 a = mesh_.positions[c[(k + 1) % 3]], b = mesh_.positions[c[(k + 2) % 3]];
  SurfacePoint p;
  p.position = w * v + (1.0f - w) * (s * a + (1.0f - s) * b);
  p.normal = node.normal;
  const Vec3 face = face_normal(t);
  p.geometric_normal = face.dot(node.normal) >= 0.0f ? face : Vec3(-face);
  p.prim = sources_[t];
  return p;
}

RadiosityGather::RadiosityGather(const NodeMesh& nodes, const NodeMesh& scene, const RayScene& scene_rays,
                                 const RayScene& rays, const Lighting& lighting, const RadiosityOptions& options,
                                 Progress& progress, const std::string& label, const std::optional<Vec3>& viewpoint,
                                 const Lighting* lights_at_hits)
    : scene_(scene), rays_per_node_(std::max(1, options.gather_rays)) {
  IntegratorOptions direct_only;
  direct_only.max_bounces = 0;  // lights and environment, no light from other surfaces
  const WhiteAlbedo white;
  const Integrator integrator(rays, lighting, &white, direct_only);
  // At the hits only the lights are wanted: no environment sample there.
  const Lighting hit_lighting = lights_at_hits ? lights_at_hits->lights_only() : Lighting{};
  std::optional<Integrator> hit_integrator;
  if (lights_at_hits) hit_integrator.emplace(rays, hit_lighting, &white, direct_only);

  const size_t n_nodes = nodes.nodes();
  direct_.assign(n_nodes, Vec3::Zero());
  lights_.assign(n_nodes, Vec3::Zero());
  std::vector<std::vector<Hit>> node_hits(n_nodes);
  std::vector<std::vector<Vec3>> node_hit_lights(n_nodes);
  progress.begin(label, int64_t(n_nodes));
  const auto seen = [&](const SurfacePoint& p) {
    const Vec3 to_eye = *viewpoint - p.position;
    const float distance = to_eye.norm();
    const ShadowRay ray = rays.shadow_ray(p, to_eye / distance, distance);
    return !rays.occluded(ray);
  };
  tbb::parallel_for(size_t(0), n_nodes, [&](size_t n) {
    Rng rng(options.seed, n, 0x7ad105);
    // The node's sample points, drawn anew for each use; with a viewpoint,
    // a few tries for one it sees.
    bool any_seen = viewpoint.has_value();
    const auto sample_point = [&](int i) {
      SurfacePoint p = nodes.sample_point(n, rng);
      for (int tries = 0; any_seen && !seen(p); ++tries) {
        if (tries == kViewpointTries) {
          any_seen = i > 0;  // the first sample found none: the node is hidden, take any
          break;
        }
        p = nodes.sample_point(n, rng);
      }
      return p;
    };
    Vec3 light_sum = Vec3::Zero(), environment_sum = Vec3::Zero();
    const int samples = std::max(1, options.light_samples);
    for (int i = 0; i < samples; ++i) {
      Vec3 from_lights, from_environment;
      integrator.illumination(sample_point(i), rng, from_lights, from_environment);
      light_sum += from_lights;
      environment_sum += from_environment;
    }
    lights_[n] = light_sum * (kPi / float(samples));
    direct_[n] = lights_[n] + environment_sum * (kPi / float(samples));

    std::vector<Hit>& hits = node_hits[n];
    // Directions well spread over the hemisphere: far less noise than independent ones.
    const Vec2 shift = rng.uniform2();
    for (int i = 0; i < rays_per_node_; ++i) {
      const SurfacePoint p = sample_point(i);
      const Vec3 d = to_world(sample_cosine_hemisphere(shifted(hammersley(i, rays_per_node_), shift)), p.normal);
      if (d.dot(p.geometric_normal) <= 0.0f) continue;  // below the actual surface: no light
      SurfacePoint hit;
      if (!scene_rays.intersect(scene_rays.offset_origin(p, d), d, hit)) continue;  // the environment: in direct_
      const Vec3 b = scene.barycentric(hit.prim, hit.position);
      const bool back = d.dot(scene.face_normal(hit.prim)) > 0.0f;
      hits.push_back({hit.prim, b.y(), b.z(), back});
      if (lights_at_hits) {
        Vec3 from_lights, from_environment;
        hit_integrator->illumination(scene.point_at(hit.prim, b, back), rng, from_lights, from_environment);
        node_hit_lights[n].push_back(from_lights * kPi);
      }
    }
    progress.advance();
  });
  progress.end();

  first_.assign(n_nodes + 1, 0);
  for (size_t n = 0; n < n_nodes; ++n) first_[n + 1] = first_[n] + uint32_t(node_hits[n].size());
  hits_.reserve(first_.back());
  for (auto& h : node_hits) hits_.insert(hits_.end(), h.begin(), h.end());
  hit_albedo_.assign(hits_.size(), Vec3::Ones());
  hit_known_.assign(hits_.size(), std::nullopt);
  if (lights_at_hits) {
    hit_lights_.reserve(hits_.size());
    for (auto& l : node_hit_lights) hit_lights_.insert(hit_lights_.end(), l.begin(), l.end());
  }
}

void RadiosityGather::set_albedo(const SurfaceAlbedo& albedo) {
  tbb::parallel_for(size_t(0), hits_.size(), [&](size_t i) {
    const Hit& h = hits_[i];
    hit_albedo_[i] = albedo.at(scene_.point_at(h.triangle, Vec3(1.0f - h.b1 - h.b2, h.b1, h.b2), h.back));
  });
}

void RadiosityGather::set_known(const KnownRadiance* known) {
  tbb::parallel_for(size_t(0), hits_.size(), [&](size_t i) {
    const Hit& h = hits_[i];
    std::optional<Vec3> radiance;
    if (known) radiance = known->at(scene_.point_at(h.triangle, Vec3(1.0f - h.b1 - h.b2, h.b1, h.b2), h.back));
    hit_known_[i] = radiance ? std::optional<Vec3>(*radiance * kPi) : std::nullopt;
  });
}

std::vector<Vec3> RadiosityGather::gather(std::span<const Vec3> scene_irradiance,
                                          std::span<const Vec3> scene_lights) const {
  std::vector<Vec3> out(direct_.size());
  // With the lights traced at the hits, the scene's nodes give only the rest.
  std::vector<Vec3> rest;
  if (!hit_lights_.empty()) {
    rest.resize(scene_irradiance.size());
    for (size_t n = 0; n < rest.size(); ++n) rest[n] = scene_irradiance[n] - scene_lights[n];
    scene_irradiance = rest;
  }
  // Cosine-distributed rays: the irradiance is pi x the mean radiance they
  // bring, and a diffuse surface's radiance is albedo x irradiance / pi.
  const float per_ray = 1.0f / float(rays_per_node_);
  tbb::parallel_for(size_t(0), direct_.size(), [&](size_t n) {
    Vec3 sum = Vec3::Zero();
    for (uint32_t i = first_[n]; i < first_[n + 1]; ++i) {
      if (hit_known_[i]) {
        sum += *hit_known_[i];
        continue;
      }
      const Hit& h = hits_[i];
      Vec3 e = scene_.interpolate(scene_irradiance, h.triangle, Vec3(1.0f - h.b1 - h.b2, h.b1, h.b2), h.back);
      if (!hit_lights_.empty()) e += hit_lights_[i];
      sum += hit_albedo_[i].cwiseProduct(e);
    }
    out[n] = direct_[n] + sum * per_ray;
  });
  return out;
}

int solve_radiosity(const RadiosityGather& scene_gather, const RadiosityOptions& options,
                    std::vector<Vec3>& irradiance) {
  irradiance = scene_gather.direct();
  double mean = 0.0;
  for (const Vec3& e : irradiance) mean += luminance(e);
  mean /= std::max<size_t>(1, irradiance.size());
  int bounces = 0;
  while (bounces + 1 < options.max_bounces) {
    std::vector<Vec3> next = scene_gather.gather(irradiance);
    ++bounces;
    // Relative to the node's value, or to a thousandth of the mean for
    // nodes in the dark (where any change is negligible).
    float largest = 0.0f;
    for (size_t n = 0; n < next.size(); ++n) {
      const float scale = std::max(luminance(next[n]), float(1e-3 * mean));
      if (scale > 0.0f) largest = std::max(largest, luminance(next[n] - irradiance[n]) / scale);
    }
    irradiance = std::move(next);
    if (largest < options.tolerance) break;
  }
  return bounces;
}

Image illumination_from_nodes(const GBuffer& gbuffer, const Camera& camera, const NodeMesh& view,
                              const RayScene& view_rays, std::span<const Vec3> irradiance) {
  const int w = gbuffer.width(), h = gbuffer.height(), spp = gbuffer.samples_per_pixel();
  Image out(w, h);
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      Vec3 sum = Vec3::Zero();
      int n = 0;
      for (int k = 0; k < spp; ++k) {
        if (!gbuffer.sample(x, y, k).hit) continue;
        const Vec2 pos = gbuffer.sample_position(x, y, k);
        SurfacePoint hit;
        if (!view_rays.intersect(camera.position(), camera.ray_direction(pos.x(), pos.y()), hit)) continue;
        sum += view.interpolate(irradiance, hit.prim, view.barycentric(hit.prim, hit.position), false);
        ++n;
      }
      if (n) out.at(x, y) = sum * (kInvPi / float(n));
    }
  });
  return out;
}

}  // namespace relight

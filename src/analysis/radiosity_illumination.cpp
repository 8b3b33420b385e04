#include "analysis/radiosity_illumination.h"

#include <spdlog/spdlog.h>

#include "mesh/refine.h"

namespace relight {

namespace {

// The scene mesh's edges are split to this length per metre from the
// camera (about 6 degrees of view), up to kMaxSceneTriangles.
constexpr float kSceneEdgePerDistance = 0.1f;
constexpr size_t kMaxSceneTriangles = 40000;
// The view mesh's edges before the photo-driven subdivision, in pixels.
constexpr float kViewEdgePx = 12.0f;

NodeMesh view_node_mesh(const Scene& scene, const GBuffer& gbuffer) {
  RefineReport refine;
  RefineOptions options;
  options.max_edge_px = kViewEdgePx;
  const PhotoSamples photo = photo_samples(scene.photo, gbuffer);
  ConnectivityMesh refined = refine_mesh_for_photo(scene.mesh, scene.camera, photo, options, refine);
  // Pieces of triangles no pixel shows (the far sides of things) need no node.
  std::vector<uint8_t> seen(scene.mesh.triangles.size(), 0);
  for (uint32_t t : photo.triangle)
    if (t != PhotoSamples::kNoTriangle) seen[t] = 1;
  refined.keep_triangles([&](const MeshTriangle& t) { return seen[t.source] != 0; });
  std::vector<uint32_t> sources;
  TriangleMesh mesh = refined.to_triangle_mesh(&sources);
  return NodeMesh(std::move(mesh), std::move(sources), scene.mesh, NodeMesh::Sides::facing_viewpoint,
                  scene.camera.position());
}

NodeMesh scene_node_mesh(const Scene& scene) {
  ConnectivityMesh mesh(scene.mesh);
  const Vec3 eye = scene.camera.position();
  split_long_edges(
      mesh,
      [&](const Vec3& a, const Vec3& b) {
        return (b - a).norm() / (kSceneEdgePerDistance * (0.5f * (a + b) - eye).norm());
      },
      kMaxSceneTriangles);
  std::vector<uint32_t> sources;
  TriangleMesh split = mesh.to_triangle_mesh(&sources);
  return NodeMesh(std::move(split), std::move(sources), scene.mesh, NodeMesh::Sides::both);
}

}  // namespace

RadiosityIllumination::RadiosityIllumination(const Scene& scene, const RayScene& rays, const GBuffer& gbuffer,
                                             const Lighting& lighting, const RadiosityOptions& options,
                                             bool direct_per_pixel, const IlluminationOptions& pixel_options,
                                             Progress& progress)
    : gbuffer_(gbuffer), camera_(scene.camera), options_(options) {
  view_ = std::make_unique<NodeMesh>(view_node_mesh(scene, gbuffer));
  scene_ = std::make_unique<NodeMesh>(scene_node_mesh(scene));
  view_rays_ = std::make_unique<RayScene>(view_->mesh());
  scene_rays_ = std::make_unique<RayScene>(scene_->mesh());
  spdlog::info("radiosity: view mesh {} triangles, {} nodes; scene mesh {} triangles, {} nodes",
               view_->mesh().triangles.size(), view_->nodes(), scene_->mesh().triangles.size(), scene_->nodes());
  scene_gather_ = std::make_unique<RadiosityGather>(*scene_, *scene_, *scene_rays_, rays, lighting, options, progress,
                                                    "radiosity: scene nodes");
  Lighting view_lighting = lighting;  // what reaches the view's nodes
  if (direct_per_pixel) {
    const Lighting lights_only = lighting.lights_only();
    IntegratorOptions no_bounce;
    no_bounce.max_bounces = 0;
    const Integrator integrator(rays, lights_only, nullptr, no_bounce);
    direct_ = render_direct_part(gbuffer, integrator, pixel_options, progress, "direct light");
    view_lighting.lights.clear();  // traced per pixel instead
  }
  view_gather_ = std::make_unique<RadiosityGather>(*view_, *scene_, *scene_rays_, rays, view_lighting, options,
                                                   progress, "radiosity: view nodes", scene.camera.position(),
                                                   &lighting);
  const Integrator environment(rays, lighting, nullptr);
  background_ = render_background(gbuffer, scene.camera, environment);
}

IlluminationImages RadiosityIllumination::render(const SurfaceAlbedo& albedo, const KnownRadiance* known) {
  scene_gather_->set_albedo(albedo);
  view_gather_->set_albedo(albedo);
  if (known != known_) {
    scene_gather_->set_known(known);
    view_gather_->set_known(known);
    known_ = known;
  }
  std::vector<Vec3> scene_irradiance;
  const int bounces = solve_radiosity(*scene_gather_, options_, scene_irradiance);
  spdlog::debug("radiosity: {} bounces between scene nodes", bounces);
  // The view's final gather is the last bounce; with none, the nodes' direct light alone.
  const std::vector<Vec3> view_irradiance = options_.max_bounces > 0
                                          ? view_gather_->gather(scene_irradiance, scene_gather_->lights())
                                          : view_gather_->direct();
  IlluminationImages out{illumination_from_nodes(gbuffer_, camera_, *view_, *view_rays_, view_irradiance),
                         background_};
  if (!direct_.empty()) add_into(out.surface, direct_);
  return out;
}

}  // namespace relight

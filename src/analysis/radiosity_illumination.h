// The initial illumination by radiosity (thesis 3.2) on the mesh refined
// along the photo's shadow edges (thesis chapter 4): `relight analyze
// --method radiosity`, the alternative to the path tracer.
//
// Two node meshes: the view mesh (the scene mesh clipped to the view and
// refined for the photo: the pixels' illumination is interpolated from its
// nodes) and the scene mesh (all of it, both sides of every surface, split
// evenly to about 2 degrees as the camera sees it: what light bounces off,
// in view or not). The scene's radiosity is solved by gathering; the view's
// nodes then gather from it once (a final gather).
//
// The light straight from the lights is either interpolated from the view's
// nodes too (the thesis's Gouraud assumption: shadows as sharp as the mesh
// follows them), or traced per pixel, as the path tracer does, so that the
// nodes carry only the smooth part (environment and interreflection).
#pragma once

#include <memory>
#include <string>

#include "core/progress.h"
#include "render/radiosity.h"
#include "render/render_illumination.h"
#include "scene/scene.h"

namespace relight {

class RadiosityIllumination {
 public:
  // Refines and splits the meshes and casts every ray: the costly part.
  // `lighting` is read only here.
  // direct_per_pixel: trace the lights' direct light per pixel with the
  // path tracer's `pixel_options`, else interpolate it from the nodes.
  RadiosityIllumination(const Scene& scene, const RayScene& rays, const GBuffer& gbuffer, const Lighting& lighting,
                        const RadiosityOptions& options, bool direct_per_pixel,
                        const IlluminationOptions& pixel_options, Progress& progress);
  RadiosityIllumination(const RadiosityIllumination&) = delete;
  RadiosityIllumination& operator=(const RadiosityIllumination&) = delete;

  // The illumination with `albedo` on the surfaces light bounces off, and
  // with the radiance `known` gives where it gives one (the photo's).
  IlluminationImages render(const SurfaceAlbedo& albedo, const KnownRadiance* known = nullptr);

 private:
  const GBuffer& gbuffer_;
  const Camera& camera_;
  RadiosityOptions options_;
  std::unique_ptr<NodeMesh> view_, scene_;
  std::unique_ptr<RayScene> view_rays_, scene_rays_;
  std::unique_ptr<RadiosityGather> view_gather_, scene_gather_;
  Image background_;
  const KnownRadiance* known_ = nullptr;  // what the gathers' hits were last given
  Image direct_;                          // per pixel, from the lights (empty when the nodes carry it)
};

}  // namespace relight

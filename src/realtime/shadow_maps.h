// The OpenGL backend of the interactive engine, as in the thesis's chapter 5:
// the surface each pixel sees (position and normal, from the G-buffer) as
// float textures, a shadow map per light —
// a cube map for a point light, a perspective map for a spot, an
// orthographic map for the sun, several maps with percentage-closer
// filtering for lights with an extent (light_views.h) — rendered into a
// float framebuffer (by a compute shader on a GPU, ShadowMapOptions::shading) and read
// back; the session multiplies by the albedo.
// Headless through EGL (a GPU driver, or Mesa's llvmpipe). The shaders are
// in glsl/, embedded at build time.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "render/direct_light.h"
#include "scene/triangle_mesh.h"

namespace relight {

struct ShadowMapOptions {
  int size = 1024;              // side of a spot's or an area sample's map; a point's six cube faces are half
  int sun_size = 2048;          // side of each of the sun's maps
  float normal_offset = 0.25f;  // biases against self-shadowing ("acne"), in texels at the surface: the lookup
  float depth_offset = 1.0f;    //   point moves off its surface, and its depth towards the light
  int pcf_radius = 1;           // lights with an extent: percentage-closer filtering over (2r+1)^2 bilinear taps
  int soft_samples = 8;         // shadow maps per light with an extent (a disc, a rectangle, the sun's disc)
  int sun_cascades = 3;         // the sun's maps, each for a slice of the view by distance (equal shares of pixels)
  // Shading by compute or fragment shader. automatic: by compute shader on a
  // GPU whose driver has them (OpenGL 4.3; a data-centre GPU runs fragment
  // shaders on its few graphics units only), by fragment shader on a
  // software rasteriser (llvmpipe's fragment path is the faster there).
  enum class Shading { automatic, fragment, compute } shading = Shading::automatic;
};

class GlRelighter final : public DirectLightBackend {
 public:
  // Opens a headless OpenGL 3.3 core context and uploads the scene and the
  // view: nullptr, with the reason in `why`, where that is not possible (no
  // EGL display, no OpenGL 3.3).
  static std::unique_ptr<GlRelighter> open(const TriangleMesh& mesh, const PixelSurfaces& surfaces,
                                           const ShadowMapOptions& options, std::string& why);
  ~GlRelighter() override;

  const char* name() const override { return "gl"; }
  // The OpenGL renderer's name (GL_RENDERER), e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  const std::string& renderer() const;
  // Whether it shades by compute shader (ShadowMapOptions::shading).
  bool shades_by_compute() const;

  // The direct light of `light` (its emission as given) at each pixel's
  // surface, irradiance / pi, like render_direct_light.
  void render(const Light& light, Image& out) override;

 private:
  struct State;
  explicit GlRelighter(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace relight

#include "relight/view.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace relight {

namespace {

// Bilinear lookup at a continuous image position (pixel centres at +0.5);
// nothing outside the image.
std::optional<Vec3> bilinear(const Image& image, const Vec2& pos) {
  if (pos.x() < 0.0f || pos.y() < 0.0f || pos.x() > float(image.width) || pos.y() > float(image.height))
    return std::nullopt;
  const float fx = std::clamp(pos.x() - 0.5f, 0.0f, float(image.width - 1));
  const float fy = std::clamp(pos.y() - 0.5f, 0.0f, float(image.height - 1));
  const int x0 = int(fx), y0 = int(fy);
  const int x1 = std::min(x0 + 1, image.width - 1), y1 = std::min(y0 + 1, image.height - 1);
  const float tx = fx - float(x0), ty = fy - float(y0);
  return (1 - ty) * ((1 - tx) * image.at(x0, y0) + tx * image.at(x1, y0)) +
         ty * ((1 - tx) * image.at(x0, y1) + tx * image.at(x1, y1));
}

// The analysis's layers for a view of another size than the photo: each
// surface sample's albedo from the photo (as bounce light sees it:
// AnalysedScene::bounce_albedo); behind partly covered pixels the
// environment, behind empty ones the photo where the view overlaps it.
RelitLayers resampled_layers(const Scene& scene, const PhotoAlbedo& albedo, const Environment& environment,
                             const Camera& camera, const GBuffer& gbuffer) {
  const int w = gbuffer.width(), h = gbuffer.height(), spp = gbuffer.samples_per_pixel();
  const ProbeEnvironment* probe = environment.probe_for(camera.position());
  RelitLayers layers{Image(w, h), Image(w, h)};
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      Vec3 albedo_sum = Vec3::Zero(), environment_sum = Vec3::Zero();
      int hits = 0;
      for (int k = 0; k < spp; ++k) {
        const GBufferSample s = gbuffer.sample(x, y, k);
        if (s.hit) {
          albedo_sum += albedo.at(s.surface);
          ++hits;
        } else {
          const Vec2 pos = gbuffer.sample_position(x, y, k);
          environment_sum += environment.radiance(probe, camera.ray_direction(pos.x(), pos.y()));
        }
      }
      layers.albedo_coverage.at(x, y) = albedo_sum / float(spp);
      const float c = float(hits) / float(spp);
      if (hits == spp) continue;
      const Vec3 environment_mean = environment_sum / float(spp - hits);
      if (hits > 0) {
        layers.background.at(x, y) = (1.0f - c) * environment_mean;
      } else {
        const auto photo_pos = scene.camera.project(camera.position() + camera.ray_direction(x + 0.5f, y + 0.5f));
        const auto photo = photo_pos ? bilinear(scene.photo, *photo_pos) : std::nullopt;
        layers.background.at(x, y) = photo ? *photo : environment_mean;
      }
    }
  });
  return layers;
}

}  // namespace

RelightView::RelightView(const AnalysedScene& analysed, int width, int height, int samples_per_pixel)
    : camera_(analysed.scene().camera), gbuffer_(&analysed.gbuffer()) {
  const Scene& scene = analysed.scene();
  const Analysis& analysis = analysed.analysis();
  const GBuffer& photo_gbuffer = analysed.gbuffer();
  if ((width == 0) != (height == 0) || width < 0 || height < 0)
    throw std::invalid_argument("RelightView: give both width and height, or neither");
  const bool photo_size = width == 0 || (width == scene.photo.width && height == scene.photo.height);
  if (photo_size) {
    layers_ = photo_layers(scene, analysis);
    coverage_ = &analysis.coverage;
  } else {
    camera_ = Camera(scene.camera.spec(), width, height);
    owned_gbuffer_ = std::make_unique<GBuffer>(camera_, analysed.rays(),
                                               samples_per_pixel > 0 ? samples_per_pixel : photo_gbuffer.samples_per_pixel(),
                                               analysis.options.seed, scene.path.string());
    gbuffer_ = owned_gbuffer_.get();
    layers_ = resampled_layers(scene, analysed.bounce_albedo(), analysed.environment(), camera_, *gbuffer_);
    coverage_ = &gbuffer_->coverage();
  }
  surfaces_ = PixelSurfaces::central_samples(*gbuffer_);
}

Image upsample_illumination(const Image& coarse, const std::vector<float>& coarse_coverage, int width, int height) {
  Image out(width, height);
  const float sx = float(coarse.width) / float(width), sy = float(coarse.height) / float(height);
  tbb::parallel_for(0, height, [&](int y) {
    const float fy = std::clamp((y + 0.5f) * sy - 0.5f, 0.0f, float(coarse.height - 1));
    const int y0 = int(fy), y1 = std::min(y0 + 1, coarse.height - 1);
    const float ty = fy - float(y0);
    for (int x = 0; x < width; ++x) {
      const float fx = std::clamp((x + 0.5f) * sx - 0.5f, 0.0f, float(coarse.width - 1));
      const int x0 = int(fx), x1 = std::min(x0 + 1, coarse.width - 1);
      const float tx = fx - float(x0);
      Vec3 sum = Vec3::Zero();
      float weight = 0.0f;
      const auto add = [&](int cx, int cy, float w) {
        const size_t i = size_t(cy) * coarse.width + cx;
        w *= coarse_coverage[i];
        sum += w * coarse.pixels[i];
        weight += w;
      };
      add(x0, y0, (1 - tx) * (1 - ty));
      add(x1, y0, tx * (1 - ty));
      add(x0, y1, (1 - tx) * ty);
      add(x1, y1, tx * ty);
      if (weight > 0.0f) out.at(x, y) = sum / weight;
    }
  });
  return out;
}

}  // namespace relight

#include "render/render_illumination.h"

#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "render/pixel_estimate.h"

namespace relight {

namespace {

// The environment and interreflection at a pixel: its paths' first bounces
// a randomly shifted Hammersley set, spread over the hemisphere evenly;
// path(surface, rng, first_bounce) follows one.
template <class Path>
PixelEstimate estimate_paths(const GBuffer& g, int x, int y, int paths, uint64_t seed, const Path& path) {
  Rng rng(seed, size_t(y) * g.width() + x, kIndirectStream);
  const Vec2 shift = rng.uniform2();
  return estimate_pixel(g, x, y, paths, rng, [&](const SurfacePoint& p, int i, int n, Rng& r) {
    const Vec2 first_bounce = shifted(hammersley(i, n), shift);
    return path(p, r, first_bounce);
  });
}

PixelEstimate estimate_indirect(const GBuffer& g, int x, int y, const Integrator& integrator, int paths,
                                uint64_t seed) {
  return estimate_paths(g, x, y, paths, seed, [&](const SurfacePoint& p, Rng& r, const Vec2& first_bounce) {
    return integrator.indirect_light(p, r, &first_bounce);
  });
}

bool all_zero(const Image& image) {
  for (const Vec3& p : image.pixels)
    if (!p.isZero()) return false;
  return true;
}

// The pixels a sparse render traces: the middle pixel of each stride x
// stride block (the last row and column clamped to the image), and the
// surface each sees (its centre sample's, else the first that hits).
struct SparseGrid {
  int stride, width, height;
  std::vector<int> xs, ys;  // the traced pixels' columns and rows
  PixelSurfaces surfaces;

  SparseGrid(const GBuffer& g, int stride) : stride(stride) {
    const auto positions = [&](int size) {
      std::vector<int> at;
      for (int p = stride / 2; at.empty() || at.back() < size - 1 - stride / 2; p += stride)
        at.push_back(std::min(p, size - 1));
      return at;
    };
    xs = positions(g.width());
    ys = positions(g.height());
    width = int(xs.size());
    height = int(ys.size());
    surfaces.width = width;
    surfaces.height = height;
    surfaces.surface.resize(size_t(width) * height);
    surfaces.hit.assign(surfaces.surface.size(), 0);
    for (int j = 0; j < height; ++j)
      for (int i = 0; i < width; ++i) {
        const size_t k = size_t(j) * width + i;
        for (int s = -1; s < g.samples_per_pixel() && !surfaces.hit[k]; ++s) {
          const GBufferSample sample = s < 0 ? g.central(xs[i], ys[j]) : g.sample(xs[i], ys[j], s);
          surfaces.surface[k] = sample.surface;
          surfaces.hit[k] = sample.hit;
        }
      }
  }
};

// How well traced surface q stands in for p, 0..1: normals alike (a
// crease's other side gets ~0) and q on p's plane (another surface behind
// or in front gets ~0), as the denoiser weighs its taps.
float stands_in_for(const SurfacePoint& p, const SurfacePoint& q) {
  static const DenoiseOptions denoiser;  // its default weights
  const float n_dot = p.normal.dot(q.normal);
  if (n_dot <= 0.0f) return 0.0f;
  const float plane = std::abs(p.geometric_normal.dot(q.position - p.position));
  return std::exp(denoiser.normal_power * std::log(n_dot) - plane / (denoiser.plane_sigma * p.distance));
}

// Below this, a traced pixel does not count as on the surface it is asked for.
constexpr float kLeastStandIn = 0.05f;

// The traced light at p, seen at image position (px, py): the traced pixels
// around it on p's surface, weighted by a tent over `reach` pixels; false
// where none lies on p's surface.
bool interpolate(const SparseGrid& grid, const Image& traced, const SurfacePoint& p, float px, float py, int reach,
                 Vec3& out) {
  const int s = grid.stride;
  const int i0 = std::max(0, int(std::floor((px - reach) / s))), i1 = std::min(grid.width - 1, int((px + reach) / s));
  const int j0 = std::max(0, int(std::floor((py - reach) / s))), j1 = std::min(grid.height - 1, int((py + reach) / s));
  Vec3 sum = Vec3::Zero();
  float weight = 0.0f;
  for (int j = j0; j <= j1; ++j) {
    const float wy = 1.0f - std::abs(float(grid.ys[j]) + 0.5f - py) / float(reach);
    if (wy <= 0.0f) continue;
    for (int i = i0; i <= i1; ++i) {
      const float wx = 1.0f - std::abs(float(grid.xs[i]) + 0.5f - px) / float(reach);
      const size_t k = size_t(j) * grid.width + i;
      if (wx <= 0.0f || !grid.surfaces.hit[k]) continue;
      const float stand_in = stands_in_for(p, grid.surfaces.surface[k]);
      if (stand_in < kLeastStandIn) continue;
      sum += wx * wy * stand_in * traced.pixels[k];
      weight += wx * wy * stand_in;
    }
  }
  if (weight <= 0.0f) return false;
  out = sum / weight;
  return true;
}

// Pixel (x, y)'s share of the traced light: from the traced pixels on its
// surface (each sub-sample's where it holds an edge), the nearest first,
// then those twice as far; false where none lies on it.
bool interpolate_pixel(const GBuffer& g, const SparseGrid& grid, const Image& traced, int x, int y, Vec3& out) {
  const auto at = [&](const SurfacePoint& p, float px, float py, Vec3& v) {
    return interpolate(grid, traced, p, px, py, grid.stride, v) ||
           interpolate(grid, traced, p, px, py, 2 * grid.stride, v);
  };
  if (g.one_surface(x, y)) return at(g.central(x, y).surface, x + 0.5f, y + 0.5f, out);
  Vec3 sum = Vec3::Zero();
  int n = 0;
  for (int k = 0; k < g.samples_per_pixel(); ++k) {
    const GBufferSample s = g.sample(x, y, k);
    if (!s.hit) continue;
    const Vec2 pos = g.sample_position(x, y, k);
    Vec3 v;
    if (!at(s.surface, pos.x(), pos.y(), v)) return false;
    sum += v;
    ++n;
  }
  if (n) out = sum / float(n);
  return n > 0;
}

}  // namespace

int sparse_indirect_stride(int width, int height) {
  const double pixels = double(width) * double(height);
  return std::max(1, int(std::lround(std::sqrt(pixels / double(kSparseIndirectPixels)))));
}

int indirect_stride(const IlluminationOptions& options, int width, int height) {
  return options.indirect_stride > 0 ? options.indirect_stride : sparse_indirect_stride(width, height);
}

int direct_samples_per_pixel(int paths_per_pixel, const GBuffer& g) {
  const double pixels = double(g.width()) * double(g.height());
  const int budget = int(std::min(double(paths_per_pixel), paths_per_pixel * double(kDirectSampledPixels) / pixels));
  return std::max(budget, g.samples_per_pixel());
}

Image render_direct_part(const GBuffer& g, const Integrator& integrator, const IlluminationOptions& options,
                         Progress& progress, const std::string& label) {
  const int w = g.width(), h = g.height();
  Image image(w, h);
  std::vector<float> variance(image.size(), 0.0f);
  const int samples = direct_samples_per_pixel(options.paths_per_pixel, g);
  progress.begin(label, h);
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      if (g.coverage(x, y) <= 0.0f) continue;
      Rng rng(options.seed, i, kDirectStream);
      const PixelEstimate e = estimate_pixel(g, x, y, samples, rng, [&](const SurfacePoint& p, int, int, Rng& r) {
        return integrator.direct_light(p, r);
      });
      image.pixels[i] = e.mean;
      variance[i] = e.variance;
    }
    progress.advance();
  });
  progress.end();
  // Direct light has sharp shadow edges: filter it only where its noise is
  // far above the local differences (soft shadows of area lights). A render
  // without direct light (the interactive engine renders it apart) has
  // nothing to filter.
  if (!options.denoise || all_zero(image)) return image;
  DenoiseOptions direct_options;
  direct_options.luminance_sigma = 1.0f;
  direct_options.progress = &progress;
  return denoise_illumination(image, variance, g, direct_options);
}

KeptPaths::KeptPaths(const GBuffer& g, const Integrator& paths, const IlluminationOptions& options, Progress& progress,
                     size_t budget_bytes)
    : stride_(indirect_stride(options, g.width(), g.height())), seed_(options.seed) {
  const SparseGrid grid(g, stride_);
  width_ = grid.width;
  rows_.resize(size_t(grid.height));
  std::atomic<size_t> kept_bytes{0};
  progress.begin("tracing the paths kept for the moving lights", grid.height);
  tbb::parallel_for(0, grid.height, [&](int j) {
    if (kept_bytes > budget_bytes) return;  // over: the rest need not be traced
    Row& row = rows_[size_t(j)];
    for (int i = 0; i < grid.width; ++i) {
      const int x = grid.xs[i], y = grid.ys[j];
      if (g.coverage(x, y) > 0.0f)
        estimate_paths(g, x, y, options.paths_per_pixel, options.seed,
                       [&](const SurfacePoint& p, Rng& r, const Vec2& first_bounce) {
                         paths.bounce_vertices(p, r, &first_bounce, row.vertices);
                         row.path_end.push_back(uint32_t(row.vertices.size()));
                         return Vec3::Zero();
                       });
      row.pixel_end.push_back(uint32_t(row.path_end.size()));
    }
    row.vertices.shrink_to_fit();  // a vector grows by up to twice what it holds
    row.path_end.shrink_to_fit();
    kept_bytes += row.bytes();
    progress.advance();
  });
  progress.end();
  if (kept_bytes > budget_bytes) {
    within_budget_ = false;
    rows_.clear();
  }
}

size_t KeptPaths::Row::bytes() const {
  return vertices.size() * sizeof(Integrator::PathVertex) + (path_end.size() + pixel_end.size()) * sizeof(uint32_t);
}

size_t KeptPaths::bytes() const {
  size_t bytes = 0;
  for (const Row& row : rows_) bytes += row.bytes();
  return bytes;
}

Vec3 KeptPaths::light(size_t pixel, const Integrator& lights, float& variance) const {
  const Row& row = rows_[pixel / size_t(width_)];
  const size_t i = pixel % size_t(width_);
  const uint32_t first_path = i ? row.pixel_end[i - 1] : 0, paths = row.pixel_end[i] - first_path;
  Rng rng(seed_, pixel, kKeptPathStream);
  EstimateSum sum;
  for (uint32_t k = first_path; k < first_path + paths; ++k) {
    Vec3 v = Vec3::Zero();
    for (uint32_t n = k ? row.path_end[k - 1] : 0; n < row.path_end[k]; ++n)
      v += lights.light_at_vertex(row.vertices[n], rng);
    sum.add(v);
  }
  const PixelEstimate e = sum.estimate();
  variance = e.variance;
  return e.mean;
}

Image render_indirect_part(const GBuffer& g, const Integrator& integrator, const IlluminationOptions& options,
                           Progress& progress, const std::string& label, const KeptPaths* kept) {
  const int w = g.width(), h = g.height();
  const int stride = indirect_stride(options, w, h);
  if (kept && (!kept->within_budget() || kept->stride() != stride || kept->seed() != options.seed))
    throw std::logic_error("render_indirect_part: the kept paths are of another render's pixels, or incomplete");
  const SparseGrid grid(g, stride);
  Image traced(grid.width, grid.height);
  std::vector<float> variance(traced.size(), 0.0f);
  progress.begin(label, grid.height);
  tbb::parallel_for(0, grid.height, [&](int j) {
    for (int i = 0; i < grid.width; ++i) {
      const int x = grid.xs[i], y = grid.ys[j];
      const size_t k = size_t(j) * grid.width + i;
      if (g.coverage(x, y) <= 0.0f) continue;
      if (kept) {
        traced.pixels[k] = kept->light(k, integrator, variance[k]);
        continue;
      }
      const PixelEstimate e = estimate_indirect(g, x, y, integrator, options.paths_per_pixel, options.seed);
      traced.pixels[k] = e.mean;
      variance[k] = e.variance;
    }
    progress.advance();
  });
  progress.end();
  if (options.denoise) {
    DenoiseOptions indirect_options;
    indirect_options.progress = &progress;
    // The filter's footprint over the image stays what it is at stride 1.
    for (int s = stride; s > 1 && indirect_options.passes > 1; s /= 2) --indirect_options.passes;
    traced = denoise_illumination(traced, std::move(variance), grid.surfaces, indirect_options);
  }
  if (stride == 1) return traced;

  Image image(w, h);
  std::vector<uint8_t> own(image.size(), 0);  // pixels no traced pixel stands in for
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x)
      if (g.coverage(x, y) > 0.0f) own[size_t(y) * w + x] = !interpolate_pixel(g, grid, traced, x, y, image.at(x, y));
  });
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x)
      if (own[size_t(y) * w + x])
        image.at(x, y) = estimate_indirect(g, x, y, integrator, options.paths_per_pixel, options.seed).mean;
  });
  return image;
}

double mean_path_vertices(const GBuffer& g, const Integrator& integrator, int paths, uint64_t seed) {
  const int step = std::max(1, int(std::sqrt(double(g.width()) * g.height() / std::max(paths, 1))));
  std::vector<Integrator::PathVertex> vertices;
  size_t traced = 0, met = 0;
  for (int y = step / 2; y < g.height(); y += step)
    for (int x = step / 2; x < g.width(); x += step) {
      const GBufferSample s = g.central(x, y);
      if (!s.hit) continue;
      Rng rng(seed, size_t(y) * g.width() + x, kSurveyStream);
      vertices.clear();
      integrator.bounce_vertices(s.surface, rng, nullptr, vertices);
      met += vertices.size();
      ++traced;
    }
  return traced ? double(met) / double(traced) : 0.0;
}

Image render_background(const GBuffer& gbuffer, const Camera& camera, const Integrator& integrator) {
  const int w = gbuffer.width(), h = gbuffer.height();
  Image out(w, h);
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      if (gbuffer.coverage(x, y) >= 1.0f) continue;  // no sample sees the background
      Vec3 sum = Vec3::Zero();
      int n = 0;
      for (int k = 0; k < gbuffer.samples_per_pixel(); ++k) {
        if (gbuffer.sample(x, y, k).hit) continue;
        const Vec2 pos = gbuffer.sample_position(x, y, k);
        sum += integrator.environment(camera.position(), camera.ray_direction(pos.x(), pos.y()));
        ++n;
      }
      if (n) out.at(x, y) = sum / float(n);
    }
  });
  return out;
}

Image IlluminationParts::total() const {
  Image sum = direct;
  add_into(sum, indirect);
  return sum;
}

IlluminationParts render_illumination_parts(const GBuffer& gbuffer, const Integrator& integrator,
                                            const IlluminationOptions& options, Progress& progress,
                                            const std::string& label) {
  Image direct = render_direct_part(gbuffer, integrator, options, progress, label + ": direct light");
  return {std::move(direct), render_indirect_part(gbuffer, integrator, options, progress, label)};
}

IlluminationImages render_illumination(const GBuffer& gbuffer, const Camera& camera, const Integrator& integrator,
                                       const IlluminationOptions& options, Progress& progress, const std::string& label,
                                       const Image* direct, const KeptPaths* kept) {
  // Nothing to light with (a rig of lights switched off, no environment):
  // no path needs tracing.
  if (integrator.is_dark()) return {Image(gbuffer.width(), gbuffer.height()), Image(gbuffer.width(), gbuffer.height())};
  // The direct light is added into the indirect part's image: a render holds
  // no copy of a direct light given, nor a third image for their sum.
  std::optional<Image> own_direct;
  if (!direct) own_direct = render_direct_part(gbuffer, integrator, options, progress, label + ": direct light");
  Image surface = render_indirect_part(gbuffer, integrator, options, progress, label, kept);
  add_into(surface, direct ? *direct : *own_direct);
  own_direct.reset();
  return {std::move(surface), render_background(gbuffer, camera, integrator)};
}

Image synthesize_photo(const GBuffer& gbuffer, const Camera& camera, const Integrator& integrator,
                       const SurfaceAlbedo& albedo, int paths_per_pixel, uint64_t seed, Progress& progress) {
  const int w = gbuffer.width(), h = gbuffer.height();
  const Image background = render_background(gbuffer, camera, integrator);
  Image photo(w, h);
  progress.begin("photo", h);
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      Rng rng(seed, i, kPhotoStream);
      const Vec2 shift = rng.uniform2();
      const PixelEstimate e =
          estimate_pixel(gbuffer, x, y, paths_per_pixel, rng, [&](const SurfacePoint& p, int k, int n, Rng& r) {
            const Vec2 first_bounce = shifted(hammersley(k, n), shift);
            Vec3 d, ind;
            integrator.illumination(p, r, d, ind, &first_bounce);
            return Vec3((d + ind).cwiseProduct(albedo.at(p)));
          });
      const float c = gbuffer.coverage()[i];
      photo.pixels[i] = c * e.mean + (1.0f - c) * background.pixels[i];
    }
    progress.advance();
  });
  progress.end();
  return photo;
}

}  // namespace relight

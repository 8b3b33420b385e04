#include "mesh/mesh_picture.h"

#include <algorithm>
#include <cmath>

namespace relight {

std::vector<uint8_t> visible_edge_pixels(const ConnectivityMesh& mesh, const Camera& camera,
                                         const PhotoSamples& photo) {
  std::vector<uint8_t> marked(size_t(photo.width) * photo.height, 0);
  std::vector<uint32_t> visible;
  for (uint32_t e = 0; e < mesh.edges().size(); ++e) {
    const auto a = camera.project(mesh.vertices()[mesh.edges()[e].vertices[0]].position);
    const auto b = camera.project(mesh.vertices()[mesh.edges()[e].vertices[1]].position);
    if (!a || !b) continue;
    mesh.edge_sources(e, visible);
    walk_visible_pixels(photo, *a, *b, visible, [&](int x, int y) { marked[size_t(y) * photo.width + x] = 1; });
  }
  return marked;
}

Image draw_edges_over_photo(const Image& photo, const std::vector<uint8_t>& edges) {
  Image picture(photo.width, photo.height);
  for (size_t i = 0; i < photo.size(); ++i)
    picture.pixels[i] =
        edges[i] ? Vec3(0.0f, 1.0f, 0.0f) : Vec3(photo.pixels[i].array() / (1.0f + photo.pixels[i].array().max(0.0f)));
  return picture;
}

std::vector<uint8_t> shadow_edge_pixels(const Image& photo, const Image& albedo, const std::vector<float>& mask,
                                        const GBuffer& gbuffer, float jump) {
  const int w = photo.width, h = photo.height;
  std::vector<float> light(photo.size(), 0.0f);
  for (size_t i = 0; i < photo.size(); ++i) {
    const float a = luminance(albedo.pixels[i]);
    if (mask[i] >= 0.999f && a > 1e-3f) light[i] = luminance(photo.pixels[i]) / a;
  }
  std::vector<uint8_t> marked(photo.size(), 0);
  const float log_jump = std::log(jump);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (const auto& [nx, ny] : {std::pair{x + 1, y}, std::pair{x, y + 1}}) {
        if (nx >= w || ny >= h) continue;
        const size_t i = size_t(y) * w + x, n = size_t(ny) * w + nx;
        if (!(light[i] > 0 && light[n] > 0) || !gbuffer.same_surface(x, y, nx, ny)) continue;
        if (std::abs(std::log(light[i] / light[n])) > log_jump) marked[i] = marked[n] = 1;
      }
  return marked;
}

double share_within_1_5_px(const std::vector<uint8_t>& targets, const std::vector<uint8_t>& edges, int width,
                           int height) {
  size_t total = 0, near = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      if (!targets[size_t(y) * width + x]) continue;
      ++total;
      bool found = false;
      for (int dy = -1; dy <= 1 && !found; ++dy)
        for (int dx = -1; dx <= 1 && !found; ++dx) {
          const int nx = x + dx, ny = y + dy;
          found = nx >= 0 && ny >= 0 && nx < width && ny < height && edges[size_t(ny) * width + nx];
        }
      near += found;
    }
  return total ? double(near) / double(total) : 0.0;
}

}  // namespace relight

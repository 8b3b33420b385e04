// Looking at a refined mesh: which pixels its edges cover where they are
// visible, the picture of the edges over the photo (like thesis Fig.
// 4.2-4.4), and how closely the edges follow the photo's shadow edges.
#pragma once

#include <cstdint>
#include <vector>

#include "mesh/connectivity_mesh.h"
#include "mesh/photo_samples.h"
#include "render/gbuffer.h"
#include "scene/camera.h"

namespace relight {

// 1 where a mesh edge passes through a pixel that shows one of its triangles.
std::vector<uint8_t> visible_edge_pixels(const ConnectivityMesh& mesh, const Camera& camera, const PhotoSamples& photo);

// The photo tone-mapped (x / (1 + x)) with the marked pixels in green.
Image draw_edges_over_photo(const Image& photo, const std::vector<uint8_t>& edges);

// The shadow edges of a photo whose albedo is known: pixels where the light
// (photo / albedo luminance) differs from a 4-neighbour's by more than the
// factor `jump`, both on the same surface (not a crease or silhouette) and
// fully covered (mask >= 0.999).
std::vector<uint8_t> shadow_edge_pixels(const Image& photo, const Image& albedo, const std::vector<float>& mask,
                                        const GBuffer& gbuffer, float jump = 1.5f);

// The share of the marked `targets` that have a marked `edges` pixel within
// 1.5 px (their 3 x 3 neighbourhood); 0 when there are no targets.
double share_within_1_5_px(const std::vector<uint8_t>& targets, const std::vector<uint8_t>& edges, int width,
                           int height);

}  // namespace relight

// Image-based adaptive subdivision (thesis 4.2): each edge is projected to
// the photo and the pixels under it read with a Bresenham walk (only where
// the edge itself is visible); an edge whose intensities do not follow a
// straight line (the Gouraud interpolation a triangle can show, appendix A)
// is split at the pixel of largest error, its triangles with it, and the new
// edges are examined in turn. The new vertex lies on the 3D edge (4.2.4).
#pragma once

#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "mesh/connectivity_mesh.h"
#include "mesh/photo_samples.h"
#include "scene/camera.h"

namespace relight {

// How an edge is judged to cross a shadow boundary (thesis 4.2.1, 4.2.3).
enum class SplitCriterion {
  line_fit,            // least-squares line through intensity vs distance; split at the largest error
  compare_end_points,  // the intensities at the two ends differ; split in the middle
  standard_deviation,  // the intensities vary (eq. 4.1); split in the middle
};

struct SubdivisionOptions {
  SplitCriterion criterion = SplitCriterion::line_fit;
  // The error (line fit: largest residual; end points: their difference;
  // standard deviation: sigma) relative to the edge's mean intensity above
  // which the edge is split. Relative, because a shadow scales the light.
  float threshold = 0.15f;
  // No split closer than this (in pixels, at least 2) to an end of the edge,
  // so edges shorter than twice this are never split, and none that would
  // leave a triangle under half this squared in image area; this bounds the work.
  float min_edge_px = 4.0f;
  size_t max_triangles = 4'000'000;
};

// A pixel read under an edge: its distance along the edge from the edge's
// first end (pixels) and its intensity.
struct LineSample {
  float distance;
  float intensity;
};

// The least-squares line intensity = a + b * distance (eqs. 4.2-4.4).
struct LineFit {
  double a = 0, b = 0;
};
LineFit fit_line(std::span<const LineSample> samples);

// Where an edge `length_px` long whose pixels read `samples` is to be split
// (its distance from the first end), or nothing if it is not to be split.
std::optional<float> find_split(std::span<const LineSample> samples, float length_px,
                                const SubdivisionOptions& options);

// The pixels under the image segment from `from` to `to` (Bresenham) that
// show one of the `visible` triangles, appended to `out` (cleared first).
void read_line(const PhotoSamples& photo, const Vec2& from, const Vec2& to, std::span<const uint32_t> visible,
               std::vector<LineSample>& out);

// The point of the 3D segment a-b that the camera sees at the fraction s of
// the segment's image from a's image to b's (perspective-correct).
Vec3 point_at_image_fraction(const Camera& camera, const Vec3& a, const Vec3& b, float s);

struct SubdivisionStats {
  size_t edges_tested = 0;
  size_t edges_split = 0;
};

// Subdivides the mesh (clipped to the view: every vertex in front of the
// camera) along the changes in the photo. `photo` is the camera's size.
SubdivisionStats subdivide_along_shadows(ConnectivityMesh& mesh, const Camera& camera, const PhotoSamples& photo,
                                         const SubdivisionOptions& options);

// How far an edge from a to b is over the length wanted there: its length
// over that length (over 1: too long).
using EdgeExcess = std::function<float(const Vec3& a, const Vec3& b)>;

// Splits the edges too long by `excess` in the middle, the worst first, and
// the pieces in turn, until none is or the mesh has max_triangles; returns
// the splits. The even subdivision a radiosity solution needs (its nodes are
// the vertices), as against the photo-driven one above.
size_t split_long_edges(ConnectivityMesh& mesh, const EdgeExcess& excess, size_t max_triangles);

}  // namespace relight

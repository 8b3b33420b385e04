// Registering the camera to the photo: a camera matched by hand, from fSpy
// or from a focal length is a few pixels off, and the albedo then shows the
// modelled objects' edges as bright and dark lines. The geometry's edges
// (silhouettes, depth steps and creases, where neighbouring G-buffer pixels
// see different surfaces) are points on the surfaces; the photo's edges
// (Canny on log luminance) a distance field. The camera (orientation,
// position, vertical field of view, principal point, the lens's radial
// distortion k1) is moved so that the
// projected edge points fall on the photo's edges: robust least squares
// (Huber, capped: the photo's shadow and texture edges the geometry lacks
// and the geometry's edges the photo does not show cost a constant),
// Levenberg-Marquardt with a numeric Jacobian, coarse to fine over an image
// pyramid. A camera that would have to move further than the options allow
// is refused: a wrong match is reported, not "fixed".
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/progress.h"
#include "render/ray_scene.h"
#include "scene/scene.h"

namespace relight {

struct RegistrationOptions {
  // The refusal range: how far the registered camera may be from the given one.
  float max_turn_deg = 3.0f;
  float max_fov_change = 0.10f;             // fraction of vfov_deg
  float max_principal_point_shift = 0.05f;  // fraction of the photo's width
  float max_move_m = 0.20f;
  // The prior on the camera's position: a few centimetres. Near-planar or far
  // geometry cannot tell a small move from a small turn; the turn is taken.
  float position_sigma_m = 0.02f;
  // The prior on the principal point, a fraction of the width. A turn of the
  // camera and a shift of the principal point move the photo's edges alike
  // but for the perspective across the frame, less than the edges' noise
  // over a few pixels: the given principal point (most photos are uncropped)
  // decides between them.
  float principal_point_sigma = 0.005f;
  // The lens's radial distortion k1 is fitted too (a wide lens bends the
  // corners' edges by several pixels). Its prior only keeps it within
  // reason (most lenses lie within +-0.1): a tighter one held a 5 % barrel
  // at 1 % (docs/benchmarks.md, "A lens's distortion"); a pinhole photo is
  // kept a pinhole by the choice between the two fits instead.
  float distortion_sigma = 1.0f;
  float max_distortion_change = 0.25f;
  bool refine_position = true;
  bool refine_distortion = true;
};

struct RegistrationResult {
  CameraSpec before, after;
  double mismatch_before_px = 0.0, mismatch_after_px = 0.0;  // mean capped edge distance, full-resolution pixels
  size_t edge_points = 0;                                    // the geometry's edge points matched at the end
  float turned_deg() const;
  float fov_change() const;  // fraction of the given vfov_deg, signed
  Vec2 principal_point_shift_px(int width, int height) const;
  float moved_m() const;
  // "turned 0.25 degrees, moved 0.3 cm, vfov 58 -> 58.1 degrees (+0.17 %),
  // principal point shifted +0.00 +0.00 px"
  std::string what_moved(int width, int height) const;
};

// What `relight register` prints: the camera unchanged and why, or what
// moved and how much the edge mismatch fell (one line each).
std::vector<std::string> describe_registration(const RegistrationResult& r, int width, int height);

// The largest distance (pixels), over a 9 x 9 grid on a photo of width x
// height, between where the two cameras show the same direction: how far
// apart what their pixels see is.
float view_difference_px(const CameraSpec& a, const CameraSpec& b, int width, int height);

// The photo or the geometry shows too few edges to register the camera by.
class TooFewEdges : public InputError {
 public:
  using InputError::InputError;
};

// The mean capped distance (full-resolution pixels) of the geometry's edges
// seen through `camera` to the photo's edges: what registration minimises.
double edge_mismatch(const Scene& scene, const RayScene& rays, const Camera& camera);

// Registers scene.camera to scene.photo and sets it; where no camera
// matches better than the given one, it stays (after == before). Throws
// TooFewEdges when the photo or the geometry shows too few edges to register
// by, InputError (scene file, "/camera") when the best match lies outside the
// options' range; the camera is then left as it was.
RegistrationResult register_camera(Scene& scene, const RayScene& rays, const RegistrationOptions& options,
                                   Progress& progress);

// relight analyze's look at the camera: registered as above, and kept when
// it shows the photo more than kVisiblyOffPx from where the given camera
// does (registration itself comes within 0.1-1.1 px of the true camera on the
// reference scenes, docs/benchmarks.md: less is within its noise), with
// a warning that says what moved. The scene's camera is then the registered
// one, and that is returned. Where the photo or the geometry has too few
// edges, or registration would move further than its range (a wrong match,
// or a camera off by more than registration reaches), the camera stays as
// given, with a warning for the latter.
constexpr float kVisiblyOffPx = 1.5f;
// And only where the registered camera's edges meet the photo's visibly
// better: the edge mismatch falls by this share of its value at least. A
// camera truly a few pixels off falls by half or more (docs/benchmarks.md);
// one moved by the edge fit's noise gains a few percent (a 320 x 240
// photo's exact camera: its view moved 2 px, its mismatch 0.90 -> 0.88 px).
constexpr float kVisiblyBetterShare = 0.1f;
// What that look found, without a word logged (relight studio's Match the
// Scene to the Photo reports it itself).
struct CameraCheck {
  std::optional<RegistrationResult> registered;  // taken: the scene's camera is its `after`
  float moved_px = 0.0f;                         // how far the registered camera shows the photo from the given one
  std::string kept_because;                      // where not taken, why
  bool refused = false;                          // not taken because the match went beyond the refusal range
};
CameraCheck check_camera(Scene& scene, const RayScene& rays, Progress& progress);
// check_camera, logged (the refusal and the registration as warnings).
std::optional<CameraSpec> register_when_off(Scene& scene, const RayScene& rays, Progress& progress);

}  // namespace relight

// Camera: FORMAT.md's pinhole camera, bound to the photo's size. Maps pixel
// positions to rays and world points back to pixels.
#pragma once

#include <optional>

#include "core/vec.h"

namespace relight {

struct CameraSpec {
  Vec3 position = Vec3::Zero();
  Vec3 look_at = Vec3(0, 1, 0);
  Vec3 up = Vec3(0, 0, 1);
  float vfov_deg = 40.0f;
  // Where the optical axis meets the photo, as fractions of its width (from
  // the left) and height (from the top); off centre in a cropped or
  // shifted photo. vfov_deg is the field of view the photo's height would
  // span with the principal point at its centre (it fixes the focal length).
  Vec2 principal_point = Vec2(0.5f, 0.5f);
  // Width / height of the image the camera was matched on (fSpy's image, a
  // glTF camera's aspectRatio, scene.json's optional camera.aspect); 0 where
  // nothing says. A photo of another shape was cropped or resized since.
  float aspect = 0.0f;
  // The lens's radial distortion (k1, k2): a ray at position u on the image
  // plane one focal length from the lens, about the principal point, shows
  // at u (1 + k1 |u|^2 + k2 |u|^4); OpenCV's and Blender's polynomial model
  // without its tangential terms. Barrel distortion (most wide lenses) has
  // k1 < 0. Zero: a pinhole.
  Vec2 distortion = Vec2::Zero();
};

class Camera {
 public:
  Camera() = default;
  Camera(const CameraSpec& spec, int width, int height);

  const CameraSpec& spec() const { return spec_; }
  int width() const { return width_; }
  int height() const { return height_; }
  const Vec3& position() const { return spec_.position; }
  const Vec3& forward() const { return forward_; }

  // Unit ray direction through the continuous image position (x, y) in pixels,
  // (0,0) the top-left corner; the centre of pixel (c, r) is (c+0.5, r+0.5).
  Vec3 ray_direction(float x, float y) const;
  // The continuous image position of a world point, or nothing if it is
  // behind the camera.
  std::optional<Vec2> project(const Vec3& p) const;
  // Whether the distortion bends back on itself within the photo (a
  // wrong sign or unit): rays would then reach two pixels at once.
  bool distortion_folds() const;

 private:
  CameraSpec spec_;
  int width_ = 0, height_ = 0;
  Vec3 forward_, right_, up_;
  float tan_half_ = 0.0f, aspect_ = 1.0f;
  Vec2 shift_ = Vec2::Zero();  // the principal point in normalised device coordinates
  bool distorted_ = false;

  // The lens's distortion of a position on the image plane at unit focal
  // length, and its inverse.
  Vec2 distort(const Vec2& u) const;
  Vec2 undistort(const Vec2& d) const;
};

}  // namespace relight

#include "realtime/light_views.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/sampling.h"

namespace relight {

namespace {

std::array<Vec3, 8> corners(const Eigen::AlignedBox3f& box) {
  std::array<Vec3, 8> c;
  for (int i = 0; i < 8; ++i) c[i] = box.corner(Eigen::AlignedBox3f::CornerType(i));
  return c;
}

}  // namespace

Mat4 look_at(const Vec3& eye, const Vec3& forward, const Vec3& up_hint) {
  const Vec3 f = forward.normalized();
  Vec3 up = up_hint;
  if (std::abs(f.dot(up.normalized())) > 0.99f) up = std::abs(f.z()) < 0.9f ? Vec3(0, 0, 1) : Vec3(1, 0, 0);
  const Vec3 s = f.cross(up).normalized();
  const Vec3 u = s.cross(f);
  Mat4 m = Mat4::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(eye);
  m(1, 3) = -u.dot(eye);
  m(2, 3) = f.dot(eye);
  return m;
}

Mat4 perspective(float fovy, float near, float far) {
  const float t = 1.0f / std::tan(fovy * 0.5f);
  Mat4 m = Mat4::Zero();
  m(0, 0) = t;
  m(1, 1) = t;
  m(2, 2) = -(far + near) / (far - near);
  m(2, 3) = -2.0f * far * near / (far - near);
  m(3, 2) = -1.0f;
  return m;
}

Mat4 orthographic(float left, float right, float bottom, float top, float near, float far) {
  Mat4 m = Mat4::Identity();
  m(0, 0) = 2.0f / (right - left);
  m(1, 1) = 2.0f / (top - bottom);
  m(2, 2) = -2.0f / (far - near);
  m(0, 3) = -(right + left) / (right - left);
  m(1, 3) = -(top + bottom) / (top - bottom);
  m(2, 3) = -(far + near) / (far - near);
  return m;
}

Mat4 cube_face_view(const Vec3& eye, int face) {
  static const Vec3 forward[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  static const Vec3 up[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
  return look_at(eye, forward[face], up[face]);
}

std::vector<Cascade> view_cascades(const PixelSurfaces& surfaces, int n) {
  std::vector<float> distances;
  for (size_t i = 0; i < surfaces.surface.size(); ++i)
    if (surfaces.hit[i]) distances.push_back(surfaces.surface[i].distance);
  std::sort(distances.begin(), distances.end());
  std::vector<Cascade> cascades(distances.empty() ? 1 : size_t(n));
  for (int c = 1; c < int(cascades.size()); ++c)
    cascades[c].near = cascades[c - 1].far = distances[distances.size() * size_t(c) / size_t(n)];
  for (size_t i = 0; i < surfaces.surface.size(); ++i) {
    if (!surfaces.hit[i]) continue;
    const SurfacePoint& s = surfaces.surface[i];
    for (Cascade& c : cascades)
      if (s.distance >= c.near && s.distance < c.far) c.box.extend(s.position);
  }
  for (Cascade& c : cascades)
    if (c.box.isEmpty()) c.box.extend(Vec3::Zero());
  return cascades;
}

LightViews::LightViews(const ShadowMapOptions& options, const Eigen::AlignedBox3f& mesh_box,
                       const PixelSurfaces& surfaces)
    : options_(options), mesh_box_(mesh_box), cascades_(view_cascades(surfaces, std::max(1, options.sun_cascades))) {
  for (size_t i = 0; i < surfaces.surface.size(); ++i)
    if (surfaces.hit[i]) view_box_.extend(surfaces.surface[i].position);
  if (view_box_.isEmpty()) view_box_ = mesh_box_;
}

LightSamplePoint LightViews::cube_sample(const Vec3& eye) const {
  LightSamplePoint s;
  s.map = LightSamplePoint::Map::cube;
  s.eye = eye;
  float far = 0.0f;
  for (const Vec3& c : corners(mesh_box_)) far = std::max(far, (c - eye).cwiseAbs().maxCoeff());
  s.far = std::max(far * 1.01f, 1e-3f);
  s.near = std::max(1e-4f, 1e-4f * scene_size());
  s.side = cube_size();
  s.texel_per_depth = 2.0f / float(s.side);
  return s;
}

LightSamplePoint LightViews::perspective_sample(const Vec3& eye, const Vec3& forward, float fovy) const {
  LightSamplePoint s;
  s.map = LightSamplePoint::Map::perspective;
  s.eye = eye;
  s.forward = forward.normalized();
  float far = 0.0f;
  for (const Vec3& c : corners(mesh_box_)) far = std::max(far, (c - eye).norm());
  s.far = std::max(far * 1.01f, 1e-3f);
  s.near = std::max(1e-4f, 1e-4f * scene_size());
  s.view_projection = perspective(fovy, s.near, s.far) * look_at(eye, s.forward, Vec3(0, 0, 1));
  s.side = options_.size;
  s.texel_per_depth = 2.0f * std::tan(fovy * 0.5f) / float(s.side);
  return s;
}

// The sun's map: along its direction, over what the view sees, deep enough
// to hold every occluder of the scene.
LightSamplePoint LightViews::orthographic_sample(const Vec3& towards_light, const Cascade& cascade) const {
  LightSamplePoint s;
  s.map = LightSamplePoint::Map::orthographic;
  s.sun_direction = towards_light.normalized();
  s.distance_range = Vec2(cascade.near, cascade.far);
  const Vec3 center = cascade.box.center();
  const Mat4 view = look_at(center, -s.sun_direction, Vec3(0, 0, 1));
  Eigen::AlignedBox3f seen, all;
  for (const Vec3& c : corners(cascade.box)) seen.extend((view * c.homogeneous()).head<3>());
  for (const Vec3& c : corners(mesh_box_)) all.extend((view * c.homogeneous()).head<3>());
  const float margin = 1e-3f * scene_size();
  const float side = std::max(seen.max().x() - seen.min().x(), seen.max().y() - seen.min().y()) + 2 * margin;
  const Vec2 mid = 0.5f * (seen.min() + seen.max()).head<2>();
  // Looking down -z: depth runs from -max z (nearest the sun) to -min z.
  s.near = -all.max().z() - margin;
  s.far = -all.min().z() + margin;
  s.view_projection =
      orthographic(mid.x() - side / 2, mid.x() + side / 2, mid.y() - side / 2, mid.y() + side / 2, s.near, s.far) *
      view;
  s.side = options_.sun_size;
  s.texel_world = side / float(s.side);
  return s;
}

// The fixed samples a light is drawn with: one for a light without extent,
// options_.soft_samples spread over its disc, rectangle or cone otherwise —
// but a sun of at most 1 degree is drawn from its centre: its penumbra, under
// 2 cm per metre between occluder and receiver, is narrower than the blur of
// the filtering. The sun's maps come in cascades.
std::vector<LightSamplePoint> LightViews::samples_of(const Light& light) const {
  const bool extended =
      LightSampler(light).needs_random() && !(light.type == LightType::directional && light.angle_deg <= 1.0f);
  const int n = extended ? std::max(1, options_.soft_samples) : 1;
  std::vector<LightSamplePoint> samples;
  for (int i = 0; i < n; ++i) {
    const Vec2 u = extended ? hammersley(i, n) : Vec2(0.5f, 0.5f);
    switch (light.type) {
      case LightType::point:
      case LightType::spot: {
        // The disc faces each lit point; the maps look from points of a disc
        // facing the middle of the view.
        const Vec2 offset = light.radius > 0.0f ? Vec2(sample_concentric_disc(u) * light.radius) : Vec2::Zero();
        Vec3 t, b;
        orthonormal_basis((view_box_.center() - light.position).normalized(), t, b);
        const Vec3 eye = light.position + offset.x() * t + offset.y() * b;
        const float fovy = radians(light.spot_angle_deg) * 1.05f + 0.02f;
        LightSamplePoint s = (light.type == LightType::spot && fovy < radians(160.0f))
                                 ? perspective_sample(eye, light.direction, fovy)
                                 : cube_sample(eye);
        s.disc_offset = offset;
        samples.push_back(s);
        break;
      }
      case LightType::area: {
        const Vec3 normal = light.direction.normalized();
        const Vec3 side_w = normal.cross(light.up).normalized(), side_h = side_w.cross(normal);
        const Vec3 q =
            light.position + (u.x() - 0.5f) * light.size.x() * side_w + (u.y() - 0.5f) * light.size.y() * side_h;
        // A perspective map along the light's normal, wide enough for what the view sees.
        float half = radians(5.0f);
        for (const Vec3& c : corners(view_box_)) {
          const Vec3 d = c - q;
          if (d.dot(normal) > 0.0f)
            half = std::max(half, std::acos(std::clamp(d.normalized().dot(normal), -1.0f, 1.0f)));
        }
        LightSamplePoint s = perspective_sample(q, normal, std::min(2.0f * half + 0.05f, radians(160.0f)));
        s.area_point = q;
        samples.push_back(s);
        break;
      }
      case LightType::directional: {
        const Vec3 to_sun = -light.direction.normalized();
        const Vec3 d = light.angle_deg > 0.0f
                           ? to_world(sample_uniform_cone(u, std::cos(radians(light.angle_deg) * 0.5f)), to_sun)
                           : to_sun;
        for (const Cascade& cascade : cascades_) samples.push_back(orthographic_sample(d, cascade));
        break;
      }
    }
  }
  // Cascades split the pixels between them; samples share the light.
  for (LightSamplePoint& s : samples) s.weight = 1.0f / float(n);
  return samples;
}

}  // namespace relight

#include "room_scene.h"

#include <cmath>

#include "render/render_illumination.h"

namespace relight::example {

namespace {

enum Object { kFloor, kBackWall, kLeftWall, kRightWall, kBlock, kBall };

void add_quad(TriangleMesh& m, std::vector<int>& objects, int object, const Vec3& a, const Vec3& b, const Vec3& c,
              const Vec3& d) {
  const Vec3 n = (b - a).cross(c - a).normalized();
  const uint32_t base = uint32_t(m.positions.size());
  for (const Vec3& p : {a, b, c, d}) {
    m.positions.push_back(p);
    m.normals.push_back(n);
  }
  m.triangles.push_back({base, base + 1, base + 2});
  m.triangles.push_back({base, base + 2, base + 3});
  objects.insert(objects.end(), 2, object);
}

void add_box(TriangleMesh& m, std::vector<int>& objects, int object, const Vec3& lo, const Vec3& hi) {
  const auto p = [&](int x, int y, int z) { return Vec3(x ? hi.x() : lo.x(), y ? hi.y() : lo.y(), z ? hi.z() : lo.z()); };
  add_quad(m, objects, object, p(0, 0, 1), p(1, 0, 1), p(1, 1, 1), p(0, 1, 1));  // top
  add_quad(m, objects, object, p(0, 0, 0), p(1, 0, 0), p(1, 0, 1), p(0, 0, 1));  // -y
  add_quad(m, objects, object, p(1, 1, 0), p(0, 1, 0), p(0, 1, 1), p(1, 1, 1));  // +y
  add_quad(m, objects, object, p(0, 1, 0), p(0, 0, 0), p(0, 0, 1), p(0, 1, 1));  // -x
  add_quad(m, objects, object, p(1, 0, 0), p(1, 1, 0), p(1, 1, 1), p(1, 0, 1));  // +x
}

void add_sphere(TriangleMesh& m, std::vector<int>& objects, int object, const Vec3& centre, float radius) {
  constexpr int kRings = 16, kSegments = 32;
  const uint32_t base = uint32_t(m.positions.size());
  for (int r = 0; r <= kRings; ++r)
    for (int s = 0; s <= kSegments; ++s) {
      const float theta = kPi * r / kRings, phi = 2.0f * kPi * s / kSegments;
      const Vec3 n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      m.positions.push_back(centre + radius * n);
      m.normals.push_back(n);
    }
  const auto idx = [&](int r, int s) { return base + uint32_t(r * (kSegments + 1) + s); };
  for (int r = 0; r < kRings; ++r)
    for (int s = 0; s < kSegments; ++s) {
      if (r > 0) m.triangles.push_back({idx(r, s), idx(r + 1, s), idx(r, s + 1)}), objects.push_back(object);
      if (r < kRings - 1)
        m.triangles.push_back({idx(r, s + 1), idx(r + 1, s), idx(r + 1, s + 1)}), objects.push_back(object);
    }
}

std::vector<int> build_room(TriangleMesh& m) {
  std::vector<int> objects;
  const float half = 2.0f, height = 2.5f;
  add_quad(m, objects, kFloor, {-half, -half, 0}, {half, -half, 0}, {half, half, 0}, {-half, half, 0});
  add_quad(m, objects, kBackWall, {-half, half, 0}, {half, half, 0}, {half, half, height}, {-half, half, height});
  add_quad(m, objects, kLeftWall, {-half, -half, 0}, {-half, half, 0}, {-half, half, height}, {-half, -half, height});
  add_quad(m, objects, kRightWall, {half, half, 0}, {half, -half, 0}, {half, -half, height}, {half, half, height});
  add_box(m, objects, kBlock, {-0.9f, 0.2f, 0.0f}, {-0.2f, 0.9f, 0.7f});
  add_sphere(m, objects, kBall, {0.6f, -0.1f, 0.35f}, 0.35f);
  return objects;
}

}  // namespace

Scene room_scene(int width, int height) {
  Scene s;
  const std::vector<int> objects = build_room(s.mesh);
  s.mesh.objects = {"floor", "back_wall", "left_wall", "right_wall", "block", "ball"};  // in Object's order
  s.mesh.triangle_objects.assign(objects.begin(), objects.end());
  CameraSpec camera;
  camera.position = Vec3(0.3f, -3.6f, 1.5f);
  camera.look_at = Vec3(0.0f, 0.3f, 0.6f);
  camera.up = Vec3(0, 0, 1);
  camera.vfov_deg = 50.0f;
  s.camera = Camera(camera, width, height);
  Light lamp;
  lamp.type = LightType::point;
  lamp.name = "lamp";
  lamp.position = Vec3(-1.0f, -1.2f, 2.0f);
  lamp.color = Vec3(1.0f, 0.9f, 0.75f);
  lamp.power = 250.0f;
  lamp.radius = 0.05f;
  s.lights.push_back(lamp);
  s.background = Vec3(0.25f, 0.28f, 0.33f);
  return s;
}

RoomAlbedo room_albedo(RoomPaint paint) {
  TriangleMesh m;
  return RoomAlbedo(build_room(m), paint);
}

Lighting room_lighting(const Scene& room, const std::vector<Light>& lights, float environment_scale) {
  Lighting lighting;
  lighting.lights = lights;
  lighting.environment = Environment::constant(room.background);
  lighting.environment.set_scale(environment_scale);
  return lighting;
}

Image room_photo(const Scene& room, const Camera& camera, const RayScene& rays, int paths, uint64_t seed) {
  const Lighting lighting = room_lighting(room, room.lights);
  const RoomAlbedo albedo = room_albedo();
  const Integrator integrator(rays, lighting, &albedo);
  const GBuffer samples(camera, rays, 4, 5, "room");
  return synthesize_photo(samples, camera, integrator, albedo, paths, seed, Progress::silent());
}

Image room_albedo_image(const GBuffer& gbuffer, RoomPaint paint) {
  const RoomAlbedo albedo = room_albedo(paint);
  Image image(gbuffer.width(), gbuffer.height());
  for (int y = 0; y < gbuffer.height(); ++y)
    for (int x = 0; x < gbuffer.width(); ++x)
      for (int k = 0; k < gbuffer.samples_per_pixel(); ++k)
        if (const GBufferSample& s = gbuffer.sample(x, y, k); s.hit)
          image.at(x, y) += albedo.at(s.surface) / float(gbuffer.samples_per_pixel());
  return image;
}

Vec3 RoomAlbedo::at(const SurfacePoint& p) const {
  const Vec3& x = p.position;
  switch (object_[p.prim]) {
    case kFloor: {  // 0.5 m checker of light and dark tiles
      const bool odd = (int(std::floor(x.x() / 0.5f)) + int(std::floor(x.y() / 0.5f))) & 1;
      return odd ? Vec3(0.75f, 0.72f, 0.65f) : Vec3(0.25f, 0.22f, 0.2f);
    }
    case kBackWall:
      if (paint_ == RoomPaint::coloured) return Vec3(0.75f, 0.55f, 0.2f);
      // plaster with a terracotta band
      return (x.z() > 0.9f && x.z() < 1.2f) ? Vec3(0.65f, 0.3f, 0.2f) : Vec3(0.8f, 0.78f, 0.72f);
    case kLeftWall:
      return paint_ == RoomPaint::coloured ? Vec3(0.25f, 0.4f, 0.7f) : Vec3(0.55f, 0.65f, 0.55f);
    case kRightWall:
      return paint_ == RoomPaint::coloured ? Vec3(0.3f, 0.6f, 0.3f) : Vec3(0.55f, 0.65f, 0.55f);
    case kBlock: return Vec3(0.15f, 0.3f, 0.7f);
    case kBall: return Vec3(0.8f, 0.12f, 0.1f);
  }
  return Vec3::Constant(0.5f);
}

Rig evening_rig() {
  Rig rig;
  rig.environment_scale = 0.3f;
  Light lamp;
  lamp.type = LightType::point;
  lamp.name = "lamp";
  lamp.position = Vec3(1.2f, -1.0f, 1.6f);
  lamp.color = Vec3(1.0f, 0.7f, 0.4f);
  lamp.power = 200.0f;
  lamp.radius = 0.05f;
  Light spot;
  spot.type = LightType::spot;
  spot.name = "cool spot";
  spot.position = Vec3(-1.5f, -1.5f, 2.3f);
  spot.direction = (Vec3(0.6f, -0.1f, 0.35f) - spot.position).normalized();
  spot.color = Vec3(0.5f, 0.7f, 1.0f);
  spot.power = 300.0f;
  spot.spot_angle_deg = 30.0f;
  spot.blend = 0.3f;
  rig.lights = {lamp, spot};
  return rig;
}

}  // namespace relight::example

// Analytic tests of the radiometry of every light type (FORMAT.md "Lights"),
// through the whole direct-lighting path: sample_light, the shadow ray in
// Embree and the integrator's division by pi. A large white diffuse plane
// z = 0 (normal +z) is lit; the illumination at a point of it (the radiance a
// white Lambertian surface reflects = irradiance / pi) averaged over many
// samples must match the closed form within 1 %.
#include "scene/light.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include "core/sampling.h"
#include "render/direct_light.h"
#include "render/gbuffer.h"
#include "render/integrator.h"
#include "render/ray_scene.h"
#include "scene/environment.h"
#include "scene/probe.h"
#include "scene/triangle_mesh.h"

namespace relight {
namespace {

constexpr double kPiD = std::numbers::pi;

// Appends an axis-aligned rectangle (two triangles) of half-sizes `half_x`
// and `half_y` centred on `centre`, lying in the plane z = centre.z().
void add_rectangle(TriangleMesh& mesh, const Vec3& centre, float half_x, float half_y) {
  const uint32_t base = uint32_t(mesh.positions.size());
  mesh.positions.push_back(centre + Vec3(-half_x, -half_y, 0));
  mesh.positions.push_back(centre + Vec3(half_x, -half_y, 0));
  mesh.positions.push_back(centre + Vec3(half_x, half_y, 0));
  mesh.positions.push_back(centre + Vec3(-half_x, half_y, 0));
  mesh.triangles.push_back({base + 0, base + 1, base + 2});
  mesh.triangles.push_back({base + 0, base + 2, base + 3});
}

void add_square(TriangleMesh& mesh, const Vec3& centre, float half) { add_rectangle(mesh, centre, half, half); }

TriangleMesh plane_mesh() {
  TriangleMesh mesh;
  add_square(mesh, Vec3::Zero(), 50.0f);
  return mesh;
}

// A scene, its lighting and an integrator with direct light only.
class LitPlane {
 public:
  LitPlane(TriangleMesh mesh, std::vector<Light> lights, Environment env = Environment::constant(Vec3::Zero()),
           int max_exhaustive_lights = IntegratorOptions{}.max_exhaustive_lights)
      : mesh_(std::move(mesh)), scene_(mesh_) {
    lighting_.lights = std::move(lights);
    lighting_.environment = std::move(env);
    IntegratorOptions options;
    options.max_bounces = 0;
    options.max_exhaustive_lights = max_exhaustive_lights;
    integrator_ = std::make_unique<Integrator>(scene_, lighting_, nullptr, options);
  }

  // The surface point of the plane at (x, y, 0), found by a ray from above
  // so the normal is the one the renderer would see.
  SurfacePoint point(float x, float y) const {
    SurfacePoint hit;
    EXPECT_TRUE(scene_.intersect(Vec3(x, y, 0.25f), Vec3(0, 0, -1), hit));
    EXPECT_NEAR(hit.position.z(), 0.0f, 1e-5f);
    EXPECT_NEAR(hit.normal.z(), 1.0f, 1e-6f);
    return hit;
  }

  // Mean illumination at (x, y, 0) over n samples (deterministic seed).
  Vec3 mean_illumination(float x, float y, int n, uint64_t seed = 7) const {
    const SurfacePoint p = point(x, y);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Rng rng(seed, 0);
    for (int i = 0; i < n; ++i) sum += integrator_->illumination(p, rng).cast<double>();
    return (sum / n).cast<float>();
  }

 private:
  TriangleMesh mesh_;
  RayScene scene_;
  Lighting lighting_;
  std::unique_ptr<Integrator> integrator_;
};

// |value - expected| <= 1 % of expected, on every channel.
void expect_within_1_percent(const Vec3& value, const Vec3& expected) {
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(value[c], expected[c], 0.01 * std::abs(expected[c])) << "channel " << c;
}

Light point_light(const Vec3& position, float power) {
  Light l;
  l.type = LightType::point;
  l.position = position;
  l.power = power;
  return l;
}

// A spot straight above the origin at height h whose axis is tilted by
// `tilt_deg` from straight down, so the origin sees it at theta = tilt.
Light spot_light(float h, float tilt_deg, float power, float angle_deg, float blend) {
  Light l;
  l.type = LightType::spot;
  l.position = Vec3(0, 0, h);
  const float t = radians(tilt_deg);
  l.direction = Vec3(std::sin(t), 0.0f, -std::cos(t));
  l.power = power;
  l.spot_angle_deg = angle_deg;
  l.blend = blend;
  return l;
}

Light sun(const Vec3& direction, float irradiance, float angle_deg = 0.0f) {
  Light l;
  l.type = LightType::directional;
  l.direction = direction.normalized();
  l.irradiance = irradiance;
  l.angle_deg = angle_deg;
  return l;
}

// A string of 200 bulbs 0.5 m above the plane, every third one bright and
// warm, the rest dim and blue: far more than get a shadow ray each.
std::vector<Light> string_of_bulbs() {
  std::vector<Light> bulbs;
  for (int i = 0; i < 200; ++i) {
    Light l = point_light(Vec3(-5.0f + 0.05f * float(i), 0.3f * std::sin(0.2f * float(i)), 0.5f), i % 3 ? 2.0f : 20.0f);
    l.color = i % 3 ? Vec3(0.6f, 0.7f, 1.0f) : Vec3(1.0f, 0.8f, 0.5f);
    bulbs.push_back(l);
  }
  return bulbs;
}

// ---------------------------------------------------------------- many lights

// Resampling the bulbs (four shadow rays a sample) is unbiased: the mean
// illumination is the closed form sum P cos / (4 pi^2 d^2) within 1 %; a
// sun beside them keeps its own ray and adds E cos / pi.
TEST(ManyLights, ResampledBulbsGiveTheClosedForm) {
  const std::vector<Light> bulbs = string_of_bulbs();
  std::vector<Light> lights = bulbs;
  const Vec3 towards_sun = Vec3(0.3f, 0.0f, 1.0f).normalized();
  lights.push_back(sun(-towards_sun, 0.5f));
  const LitPlane scene(plane_mesh(), lights);
  for (const Vec3& at : {Vec3(0, 0, 0), Vec3(-4.2f, 0.5f, 0), Vec3(3, -1, 0)}) {
    Eigen::Vector3d expected = Eigen::Vector3d::Constant(0.5 * towards_sun.z() / kPiD);
    for (const Light& l : bulbs) {
      const Vec3 d = l.position - at;
      const double cos = d.z() / d.norm();
      expected += (l.emission().cast<double>() * cos / (4.0 * kPiD * kPiD * d.squaredNorm()));
    }
    expect_within_1_percent(scene.mean_illumination(at.x(), at.y(), 40000), expected.cast<float>());
  }
}

// With shadows (a board 0.25 m up, under half the string) the resampled mean
// is the exhaustive one (every bulb its own shadow ray) within 1 %.
TEST(ManyLights, ResampledShadowsMatchEveryBulbsOwnRay) {
  TriangleMesh mesh = plane_mesh();
  add_square(mesh, Vec3(-2.5f, 0.0f, 0.25f), 1.0f);
  const LitPlane resampled(mesh, string_of_bulbs());
  const LitPlane exhaustive(mesh, string_of_bulbs(), Environment::constant(Vec3::Zero()), 1000);
  for (const Vec2& at : {Vec2(-2.5f, 0.0f), Vec2(-1.2f, 0.4f), Vec2(0.5f, 0.0f)})
    expect_within_1_percent(resampled.mean_illumination(at.x(), at.y(), 400000),
                            exhaustive.mean_illumination(at.x(), at.y(), 400));
}

// ---------------------------------------------------------------- point

TEST(PointLight, FacingAtDistanceGivesPowerOver4PiSquaredDSquared) {
  const float d = 2.0f, power = 100.0f;
  LitPlane scene(plane_mesh(), {point_light(Vec3(0, 0, d), power)});
  const double expected = power / (4.0 * kPiD * kPiD * d * d);  // FORMAT.md: P/(4 pi^2 d^2)
  expect_within_1_percent(scene.mean_illumination(0, 0, 64), Vec3::Constant(float(expected)));
}

TEST(PointLight, OffAxisFollowsCosineOverDistanceSquared) {
  // Light at height 1, point 1 m to the side: d^2 = 2, cos = 1/sqrt(2).
  const float power = 50.0f;
  LitPlane scene(plane_mesh(), {point_light(Vec3(1, 0, 1), power)});
  const double expected = power / (4.0 * kPiD) / 2.0 * (1.0 / std::sqrt(2.0)) / kPiD;
  expect_within_1_percent(scene.mean_illumination(0, 0, 64), Vec3::Constant(float(expected)));
}

TEST(PointLight, ColourScalesEachChannel) {
  Light l = point_light(Vec3(0, 0, 1.5f), 80.0f);
  l.color = Vec3(1.0f, 0.5f, 0.25f);
  LitPlane scene(plane_mesh(), {l});
  const double white = 80.0 / (4.0 * kPiD * kPiD * 1.5 * 1.5);
  expect_within_1_percent(scene.mean_illumination(0, 0, 64), Vec3(float(white), float(white * 0.5), float(white * 0.25)));
}

TEST(PointLight, DisabledLightGivesNothing) {
  Light l = point_light(Vec3(0, 0, 1), 100.0f);
  l.enabled = false;
  LitPlane scene(plane_mesh(), {l});
  EXPECT_EQ(scene.mean_illumination(0, 0, 16), Vec3::Zero());
}

TEST(PointLight, WithRadiusGivesPowerOver4PiSquaredTimesDSquaredPlusRSquared) {
  const float d = 2.0f, r = 0.5f, power = 100.0f;
  Light l = point_light(Vec3(0, 0, d), power);
  l.radius = r;
  LitPlane scene(plane_mesh(), {l});
  // FORMAT.md: P/(4 pi^2 (d^2 + r^2)) -- a facing disc of radiance
  // P/(4 pi^2 r^2) delivers E = pi L r^2/(d^2 + r^2).
  const double expected = power / (4.0 * kPiD * kPiD * (d * d + r * r));
  const Vec3 value = scene.mean_illumination(0, 0, 200000);
  expect_within_1_percent(value, Vec3::Constant(float(expected)));
  // And it really differs from the point-source value (by 6 %), so the
  // radius is not ignored.
  EXPECT_LT(value.x(), 0.97 * power / (4.0 * kPiD * kPiD * d * d));
}

TEST(PointLight, BehindTheSurfaceGivesNothing) {
  LitPlane scene(plane_mesh(), {point_light(Vec3(0, 0, -1), 100.0f)});
  EXPECT_EQ(scene.mean_illumination(0, 0, 16), Vec3::Zero());
}

// ----------------------------------------------------------------- spot

// FORMAT.md: I(theta) = P/(4 pi) c s; s the smoothstep of the blend.
double spot_expected(double power, double h, double theta_deg, double angle_deg, double blend) {
  const double c = std::cos(theta_deg * kPiD / 180.0);
  const double c0 = std::cos(angle_deg * 0.5 * kPiD / 180.0);
  double s = 0.0;
  if (c > c0) {
    if (blend <= 0.0) {
      s = 1.0;
    } else {
      const double t = std::clamp((c - c0) / ((1.0 - c0) * blend), 0.0, 1.0);
      s = t * t * (3.0 - 2.0 * t);
    }
  }
  const double intensity = power / (4.0 * kPiD) * c * s;
  return intensity / (h * h) / kPiD;  // facing surface at distance h, then / pi
}

TEST(SpotLight, InsideConeWithoutBlendHasCosineFactor) {
  const float h = 2.0f, power = 200.0f;
  LitPlane scene(plane_mesh(), {spot_light(h, 20.0f, power, 60.0f, 0.0f)});
  const double expected = spot_expected(power, h, 20.0, 60.0, 0.0);
  // The factor c (cos 20 deg = 0.94) is Cycles' own: check it is applied.
  EXPECT_NEAR(expected, power / (4.0 * kPiD * kPiD * h * h) * std::cos(20.0 * kPiD / 180.0), 1e-9);
  expect_within_1_percent(scene.mean_illumination(0, 0, 64), Vec3::Constant(float(expected)));
}

TEST(SpotLight, OnAxisEqualsPointLight) {
  const float h = 1.5f, power = 120.0f;
  LitPlane scene(plane_mesh(), {spot_light(h, 0.0f, power, 30.0f, 0.0f)});
  expect_within_1_percent(scene.mean_illumination(0, 0, 64),
                          Vec3::Constant(float(power / (4.0 * kPiD * kPiD * h * h))));
}

TEST(SpotLight, OutsideConeGivesNothing) {
  LitPlane scene(plane_mesh(), {spot_light(2.0f, 40.0f, 200.0f, 60.0f, 0.0f)});
  EXPECT_EQ(scene.mean_illumination(0, 0, 64), Vec3::Zero());
}

TEST(SpotLight, OutsideConeWithBlendAndRadiusGivesNothing) {
  Light l = spot_light(2.0f, 40.0f, 200.0f, 60.0f, 1.0f);
  l.radius = 0.1f;
  LitPlane scene(plane_mesh(), {l});
  EXPECT_EQ(scene.mean_illumination(0, 0, 64), Vec3::Zero());
}

TEST(SpotLight, BlendGivesSmoothstepValue) {
  // Cone 60 deg, blend 0.5, seen at 25 deg: t = 0.60, s = 0.648.
  const float h = 2.0f, power = 200.0f;
  LitPlane scene(plane_mesh(), {spot_light(h, 25.0f, power, 60.0f, 0.5f)});
  const double expected = spot_expected(power, h, 25.0, 60.0, 0.5);
  const double unblended = spot_expected(power, h, 25.0, 60.0, 0.0);
  ASSERT_GT(expected, 0.5 * unblended);  // t strictly inside (0, 1)
  ASSERT_LT(expected, 0.8 * unblended);
  expect_within_1_percent(scene.mean_illumination(0, 0, 64), Vec3::Constant(float(expected)));
}

TEST(SpotLight, SpotFactorMatchesFormat) {
  Light l = spot_light(1.0f, 0.0f, 1.0f, 90.0f, 0.3f);
  const double c0 = std::cos(45.0 * kPiD / 180.0);
  for (double c : {0.5, 0.70, 0.72, 0.75, 0.8, 0.9, 0.99, 1.0}) {
    double s = 0.0;
    if (c > c0) {
      const double t = std::clamp((c - c0) / ((1.0 - c0) * 0.3), 0.0, 1.0);
      s = t * t * (3.0 - 2.0 * t);
    }
    EXPECT_NEAR(spot_factor(l, float(c)), c * s, 1e-5) << "c = " << c;
  }
}

// ----------------------------------------------------------------- area

// Configuration factor from a differential area to a parallel rectangle of
// sides a x b at distance c, the rectangle's corner on the element's normal
// (Howell's catalogue of radiation configuration factors, case B-3):
//   F = 1/(2 pi) [ A/sqrt(1+A^2) atan(B/sqrt(1+A^2)) + B/sqrt(1+B^2) atan(A/sqrt(1+B^2)) ],
// A = a/c, B = b/c. (Limit a, b -> infinity: 1/4, a quarter of the plane.)
double corner_factor(double a, double b, double c) {
  const double A = a / c, B = b / c;
  const double sa = std::sqrt(1 + A * A), sb = std::sqrt(1 + B * B);
  return (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2.0 * kPiD);
}

// The configuration factor of the rectangle x in [x1, x2], y in [y1, y2] at
// height c above a point: the signed sum of four corner rectangles
// (corner_factor is odd in a and in b).
double rectangle_factor(double x1, double x2, double y1, double y2, double c) {
  return corner_factor(x2, y2, c) - corner_factor(x1, y2, c) - corner_factor(x2, y1, c) + corner_factor(x1, y1, c);
}

// A w x h area light centred at height d above the origin, emitting down,
// up = +y: its w side runs along x.
Light downward_area_light(float w, float h, float d, float power) {
  Light l;
  l.type = LightType::area;
  l.position = Vec3(0, 0, d);
  l.direction = Vec3(0, 0, -1);
  l.up = Vec3(0, 1, 0);
  l.size = Vec2(w, h);
  l.power = power;
  return l;
}

TEST(AreaLight, CornerFactorFormulaIsRight) {
  // Sanity of the closed form against a brute-force midpoint quadrature of
  // F = (1/pi) \int cos^2 / r^2 dA = (1/pi) \int c^2 / (x^2+y^2+c^2)^2 dA.
  const double a = 0.7, b = 1.3, c = 0.9;
  const int n = 800;
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = (i + 0.5) * a / n, y = (j + 0.5) * b / n;
      const double r2 = x * x + y * y + c * c;
      sum += c * c / (r2 * r2);
    }
  sum *= (a / n) * (b / n) / kPiD;
  EXPECT_NEAR(corner_factor(a, b, c), sum, 1e-6);
  EXPECT_NEAR(corner_factor(1e6, 1e6, 1.0), 0.25, 1e-5);
}

// The solid angle of a rectangle seen from a point: on axis, a square of
// side a at distance d covers 4 asin(a^2 / (a^2 + 4 d^2)); off axis and
// tilted, against a midpoint quadrature of cos / r^2 over its area. Far
// away it tends to w h cos / d^2.
TEST(AreaLight, SolidAngleIsExactNearAndTendsToTheSmallLightLimitFar) {
  Light l;
  l.type = LightType::area;
  l.position = Vec3(0, 0, 1);
  l.direction = Vec3(0, 0, -1);
  l.up = Vec3(0, 1, 0);
  l.size = Vec2(2, 2);
  EXPECT_NEAR(area_light_solid_angle(l, Vec3::Zero()), 4.0 * std::asin(4.0 / 8.0), 1e-5);

  l.size = Vec2(0.8f, 0.6f);
  l.position = Vec3(0.3f, -0.2f, 1.1f);
  l.direction = Vec3(0.3f, 0.2f, -1.0f).normalized();
  const Vec3 from(0.1f, 0.2f, 0.0f);
  const AreaLightSides sides = area_light_sides(l);
  const int n = 400;
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const Vec3 q = l.position + ((i + 0.5f) / n - 0.5f) * l.size.x() * sides.w +
                     ((j + 0.5f) / n - 0.5f) * l.size.y() * sides.h;
      const Vec3 to = q - from;
      sum += std::abs(to.normalized().dot(l.direction)) / to.squaredNorm();
    }
  sum *= double(l.size.x()) * l.size.y() / (double(n) * n);
  EXPECT_NEAR(area_light_solid_angle(l, from), sum, 1e-4 * sum);

  const Vec3 far(0.3f, -0.2f, -99.0f);  // 100 m below
  const Vec3 to_far = far - l.position;
  const double limit = l.size.x() * l.size.y() * std::abs(to_far.normalized().dot(l.direction)) / to_far.squaredNorm();
  EXPECT_NEAR(area_light_solid_angle(l, far), limit, 1e-3 * limit);
}

TEST(AreaLight, FacingOnAxisMatchesRectangleClosedForm) {
  // A w x h rectangle at height d, centred above the point, emitting down.
  // Uniform Lambertian radiance L = P/(4 w h) (FORMAT.md). The irradiance is
  // E = pi L F with F the configuration factor of the whole rectangle: four
  // corner rectangles of (w/2) x (h/2). Illumination = E/pi = L F.
  const float w = 1.0f, h = 0.6f, d = 0.8f, power = 100.0f;
  Light l = downward_area_light(w, h, d, power);
  LitPlane scene(plane_mesh(), {l});
  const double radiance = power / (4.0 * w * h);
  const double expected = radiance * 4.0 * corner_factor(w / 2.0, h / 2.0, d);
  expect_within_1_percent(scene.mean_illumination(0, 0, 400000), Vec3::Constant(float(expected)));
}

TEST(AreaLight, UpOrientsTheHSideOffAxis) {
  // A 2 m (w) x 0.5 m (h) light at height d with up = +y: the w side runs
  // along x = direction x up. Seen from (0.8, 0, 0) the rectangle spans
  // x in [-1.8, 0.2], y in [-0.25, 0.25] relative to the point; the
  // configuration factor of an offset rectangle is rectangle_factor.
  const float w = 2.0f, h = 0.5f, d = 0.7f, power = 100.0f;
  Light l = downward_area_light(w, h, d, power);
  LitPlane scene(plane_mesh(), {l});
  const double radiance = power / (4.0 * w * h);
  const double expected = radiance * rectangle_factor(-1.8, 0.2, -0.25, 0.25, d);
  const double swapped = radiance * rectangle_factor(-1.05, -0.55, -1.0, 1.0, d);  // w and h exchanged
  ASSERT_GT(std::abs(expected - swapped), 0.2 * expected);           // the test can tell them apart
  expect_within_1_percent(scene.mean_illumination(0.8f, 0, 400000), Vec3::Constant(float(expected)));
}

// The exact irradiance of a rectangle: on axis and offset against the
// closed form; tilted, and cut by the receiving surface's horizon, against a
// midpoint quadrature of the light's own samples.
TEST(AreaLight, ExactIrradianceMatchesTheClosedFormAndTheSamples) {
  const float w = 2.0f, h = 0.5f, d = 0.7f, power = 100.0f;
  Light l = downward_area_light(w, h, d, power);
  l.color = Vec3(1.0f, 0.5f, 0.25f);
  const double radiance = power / (4.0 * w * h);
  const Vec3 up = Vec3::UnitZ();
  EXPECT_NEAR(LightSampler(l).unshadowed_irradiance(Vec3::Zero(), up).x(),
              kPiD * radiance * 4.0 * corner_factor(1.0, 0.25, d), 1e-4 * radiance);
  const Vec3 offset = LightSampler(l).unshadowed_irradiance(Vec3(0.8f, 0, 0), up);
  EXPECT_NEAR(offset.x(), kPiD * radiance * rectangle_factor(-1.8, 0.2, -0.25, 0.25, d), 1e-4 * radiance);
  EXPECT_NEAR(offset.y(), 0.5f * offset.x(), 1e-6 * offset.x());  // the light's colour

  const auto quadrature = [&](const Light& light, const Vec3& p, const Vec3& n) {
    const LightSampler sampler(light);
    const int k = 600;
    double sum = 0.0;
    for (int i = 0; i < k; ++i)
      for (int j = 0; j < k; ++j) sum += sampler.sample(p, n, Vec2((i + 0.5f) / k, (j + 0.5f) / k)).irradiance.x();
    return sum / (double(k) * k);
  };
  l.color = Vec3::Ones();
  l.direction = Vec3(0.3f, 0.2f, -1.0f).normalized();
  const Vec3 tilted_n = Vec3(0.2f, -0.3f, 1.0f).normalized();
  const double tilted = quadrature(l, Vec3(0.1f, 0.2f, 0), tilted_n);
  EXPECT_NEAR(LightSampler(l).unshadowed_irradiance(Vec3(0.1f, 0.2f, 0), tilted_n).x(), tilted, 2e-3 * tilted);

  // A point on a wall (normal +x) at the light's height: half the rectangle
  // lies behind the wall's plane.
  l.direction = Vec3(0, 0, -1);
  l.position = Vec3(0.2f, 0, 0.3f);
  const Vec3 wall(0, 0.1f, 0), wall_n = Vec3::UnitX();
  const double cut = quadrature(l, wall, wall_n);
  ASSERT_GT(cut, 0.0);
  EXPECT_NEAR(LightSampler(l).unshadowed_irradiance(wall, wall_n).x(), cut, 2e-3 * cut);
  EXPECT_EQ(LightSampler(l).unshadowed_irradiance(Vec3(0, 0, 1), up), Vec3::Zero());  // above the emitting side
}

TEST(AreaLight, SmallAndFarApproachesLambertianPointLimit) {
  // A small w x h light at distance d >> w, h: E = L w h / d^2 with
  // L = P/(4 w h), so illumination = P/(4 pi d^2).
  const float d = 5.0f, power = 100.0f;
  Light l;
  l.type = LightType::area;
  l.position = Vec3(0, 0, d);
  l.direction = Vec3(0, 0, -1);
  l.up = Vec3(1, 0, 0);
  l.size = Vec2(0.05f, 0.1f);
  l.power = power;
  LitPlane scene(plane_mesh(), {l});
  expect_within_1_percent(scene.mean_illumination(0, 0, 20000),
                          Vec3::Constant(float(power / (4.0 * kPiD * d * d))));
}

TEST(AreaLight, EmittingAwayGivesNothing) {
  Light l;
  l.type = LightType::area;
  l.position = Vec3(0, 0, 1);
  l.direction = Vec3(0, 0, 1);  // emits upwards, away from the plane
  l.up = Vec3(0, 1, 0);
  l.size = Vec2(1, 1);
  l.power = 100.0f;
  LitPlane scene(plane_mesh(), {l});
  EXPECT_EQ(scene.mean_illumination(0, 0, 1000), Vec3::Zero());
}

// ---------------------------------------------------------- directional

TEST(DirectionalLight, FacingGivesIrradianceOverPi) {
  LitPlane scene(plane_mesh(), {sun(Vec3(0, 0, -1), 4.0f)});
  expect_within_1_percent(scene.mean_illumination(0, 0, 16), Vec3::Constant(float(4.0 / kPiD)));
}

TEST(DirectionalLight, SixtyDegreesGivesHalf) {
  const float t = radians(60.0f);
  LitPlane scene(plane_mesh(), {sun(Vec3(std::sin(t), 0, -std::cos(t)), 4.0f)});
  expect_within_1_percent(scene.mean_illumination(3, -2, 16), Vec3::Constant(float(4.0 * 0.5 / kPiD)));
}

TEST(DirectionalLight, HalfDegreeDiscFacingGivesIrradianceOverPi) {
  LitPlane scene(plane_mesh(), {sun(Vec3(0, 0, -1), 4.0f, 0.5f)});
  expect_within_1_percent(scene.mean_illumination(0, 0, 2000), Vec3::Constant(float(4.0 / kPiD)));
}

TEST(DirectionalLight, HalfDegreeDiscAtSixtyDegreesGivesHalf) {
  const float t = radians(60.0f);
  LitPlane scene(plane_mesh(), {sun(Vec3(0, std::sin(t), -std::cos(t)), 3.0f, 0.5f)});
  expect_within_1_percent(scene.mean_illumination(0, 0, 20000), Vec3::Constant(float(3.0 * 0.5 / kPiD)));
}

TEST(DirectionalLight, FromBelowGivesNothing) {
  LitPlane scene(plane_mesh(), {sun(Vec3(0.2f, 0, 1), 4.0f, 0.5f)});
  EXPECT_EQ(scene.mean_illumination(0, 0, 100), Vec3::Zero());
}

// ------------------------------------------------- shadows and sums

TEST(Shadow, BlockerBetweenPointLightAndPlaneGivesZero) {
  TriangleMesh mesh = plane_mesh();
  add_square(mesh, Vec3(0, 0, 1), 0.25f);  // 0.5 m square at z = 1
  LitPlane scene(std::move(mesh), {point_light(Vec3(0, 0, 2), 100.0f)});
  EXPECT_EQ(scene.mean_illumination(0, 0, 64), Vec3::Zero());
  // Outside the shadow (which reaches |x| = 0.5) the light arrives in full:
  // distance^2 = 4 + 4 = 8, cos = 2/sqrt(8).
  const double lit = 100.0 / (4.0 * kPiD) / 8.0 * (2.0 / std::sqrt(8.0)) / kPiD;
  expect_within_1_percent(scene.mean_illumination(2, 0, 64), Vec3::Constant(float(lit)));
}

TEST(Shadow, BlockerShadowsEveryLightType) {
  TriangleMesh mesh = plane_mesh();
  add_square(mesh, Vec3(0, 0, 1), 2.0f);  // 4 m square at z = 1 over the origin
  Light area;
  area.type = LightType::area;
  area.position = Vec3(0, 0, 2);
  area.direction = Vec3(0, 0, -1);
  area.up = Vec3(0, 1, 0);
  area.size = Vec2(1, 1);
  area.power = 100.0f;
  Light soft_point = point_light(Vec3(0, 0, 2), 100.0f);
  soft_point.radius = 0.3f;
  LitPlane scene(std::move(mesh),
                 {soft_point, spot_light(2.0f, 0.0f, 100.0f, 60.0f, 0.2f), area, sun(Vec3(0, 0, -1), 5.0f, 0.5f)});
  EXPECT_EQ(scene.mean_illumination(0, 0, 2000), Vec3::Zero());
}

// An area light's direct light as the exact unshadowed irradiance times the
// unblocked share of its samples: exact where the whole light is seen, black
// where none of it is, and in the penumbra the plain estimator's value on
// average.
TEST(Shadow, ExactUnshadowedAreaLightIsExactInTheOpenAndDarkInTheUmbra) {
  TriangleMesh mesh = plane_mesh();
  add_square(mesh, Vec3(0, 0, 0.5f), 0.5f);  // x, y in [-0.5, 0.5]: the penumbra is x in [0.8, 1.2]
  const Light area = downward_area_light(0.4f, 0.4f, 1.0f, 50.0f);
  const RayScene rays(mesh);
  PixelSurfaces surfaces;
  surfaces.width = 3, surfaces.height = 1;
  for (const float x : {3.0f, 0.0f, 1.0f}) {  // open, umbra, penumbra
    SurfacePoint hit;
    ASSERT_TRUE(rays.intersect(Vec3(x, 0, 0.25f), Vec3(0, 0, -1), hit));
    surfaces.surface.push_back(hit);
    surfaces.hit.push_back(1);
  }
  DirectLightSettings exact;
  exact.exact_unshadowed = true;
  // A ratio of sums, biased where the sums spread: 4 samples at random were
  // 20 % low here, 4 stratified are within 1 %.
  exact.light_samples = 4;
  Image one, mean(3, 1);
  const int passes = 400;
  for (int pass = 0; pass < passes; ++pass) {
    exact.pass = uint64_t(pass);
    render_direct_light(surfaces, rays, area, exact, one);
    EXPECT_NEAR(one.at(0, 0).x(),
                LightSampler(area).unshadowed_irradiance(surfaces.surface[0].position, Vec3::UnitZ()).x() / kPiD, 1e-6);
    EXPECT_EQ(one.at(1, 0), Vec3::Zero());
    for (size_t i = 0; i < mean.size(); ++i) mean.pixels[i] += one.pixels[i] / float(passes);
  }
  DirectLightSettings plain;
  plain.light_samples = 20000;
  Image reference;
  render_direct_light(surfaces, rays, area, plain, reference);
  const double unshadowed =
      LightSampler(area).unshadowed_irradiance(surfaces.surface[2].position, Vec3::UnitZ()).x() / kPiD;
  ASSERT_GT(reference.at(2, 0).x(), 0.2 * unshadowed);  // a penumbra, about half lit
  ASSERT_LT(reference.at(2, 0).x(), 0.8 * unshadowed);
  EXPECT_NEAR(mean.at(2, 0).x(), reference.at(2, 0).x(), 0.02 * reference.at(2, 0).x());
  EXPECT_NEAR(mean.at(0, 0).x(), reference.at(0, 0).x(), 0.01 * reference.at(0, 0).x());
}

// A unit sphere of `around` segments and `rings` rings with its vertices'
// normals radial, as a smooth-shaded model exports it; its vertices
// alternately `bumps` (a fraction of the radius) out and in, as a model a
// little off is.
TriangleMesh uv_sphere(int around, int rings, float bumps) {
  TriangleMesh mesh;
  for (int r = 0; r <= rings; ++r)
    for (int a = 0; a < around; ++a) {
      const float polar = float(kPiD) * float(r) / rings, azimuth = 2.0f * float(kPiD) * float(a) / around;
      const Vec3 n(std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth), std::cos(polar));
      mesh.positions.push_back((1.0f + bumps * float((r + a) % 2 ? 1 : -1)) * n);
      mesh.normals.push_back(n);
    }
  const auto at = [around](int r, int a) { return uint32_t(r * around + (a % around)); };
  for (int r = 0; r < rings; ++r)
    for (int a = 0; a < around; ++a) {
      if (r > 0) mesh.triangles.push_back({at(r, a), at(r + 1, a), at(r, a + 1)});
      if (r < rings - 1) mesh.triangles.push_back({at(r, a + 1), at(r + 1, a), at(r + 1, a + 1)});
    }
  return mesh;
}

// A coarse sphere: 12 segments around, 6 rings.
TriangleMesh coarse_sphere(float bumps) { return uv_sphere(12, 6, bumps); }

// Over points of the coarse sphere where the sun grazes its smooth surface
// (cosine 0.05-0.4 to the shading normal): the mean direct light over the
// smooth sphere's (E cos / pi), and the share of the points the sun lights
// from below their facet's plane. With `lift`, shadow rays start on the
// smooth surface (RayScene::shadow_ray), without, on the facet.
struct GrazingSunlight {
  double of_smooth = 0.0, below_facet = 0.0;
};
GrazingSunlight grazing_sunlight(float bumps, bool lift) {
  const TriangleMesh mesh = coarse_sphere(bumps);
  const RayScene rays(mesh);
  Lighting lighting;
  // From 15 degrees beside the +x axis: the smooth surface's terminator then
  // crosses the facets between the vertices' meridians, 30 degrees apart.
  const Vec3 towards_sun(std::cos(radians(15.0f)), -std::sin(radians(15.0f)), 0.0f);
  lighting.lights = {sun(-towards_sun, 3.0f)};
  lighting.environment = Environment::constant(Vec3::Zero());
  IntegratorOptions options;
  options.max_bounces = 0;
  const Integrator integrator(rays, lighting, nullptr, options);
  GrazingSunlight g;
  int points = 0;
  for (float x = 0.0f; x < 0.5f; x += 0.01f)
    for (float z = -0.6f; z <= 0.6f; z += 0.05f) {
      SurfacePoint p;
      if (!rays.intersect(Vec3(x, 3, z), Vec3(0, -1, 0), p)) continue;
      const float cosine = p.normal.dot(towards_sun);
      if (cosine < 0.05f || cosine > 0.4f) continue;
      if (!lift) p.lift = 0.0f;
      Rng rng(1, uint64_t(points));
      g.of_smooth += double(integrator.illumination(p, rng).x()) / (3.0 * cosine / kPiD);
      g.below_facet += p.geometric_normal.dot(towards_sun) < 0.0f;
      ++points;
    }
  EXPECT_GT(points, 100);
  g.of_smooth /= points, g.below_facet /= points;
  return g;
}

// The shadow terminator: where the light grazes a coarse smooth-shaded
// sphere it comes from below some facets' planes (a test of the facet's
// normal turned those black), and where the facets are a little uneven their
// neighbours shadow them. Started on the smooth surface, the shadow rays give
// the smooth sphere's light; and started on the facets too, since a smooth
// surface's own facets do not block the rays that leave it (RayScene's
// SmoothSurfaces; the lift is for the shadow maps, which cannot tell).
TEST(Shadow, ACoarseSmoothSphereIsLitAsTheSmoothSphereWhereTheLightGrazesIt) {
  const GrazingSunlight even = grazing_sunlight(0.0f, true);
  EXPECT_GT(even.below_facet, 0.1);
  EXPECT_GT(even.of_smooth, 0.98);
  const GrazingSunlight uneven = grazing_sunlight(0.02f, true), uneven_on_facets = grazing_sunlight(0.02f, false);
  std::printf(
      "grazing sun on a coarse sphere: %.3f of the smooth sphere's (%.0f %% of the points lit from below "
      "their facet); vertices 2 %% uneven: %.3f, from the facets %.3f\n",
      even.of_smooth, 100 * even.below_facet, uneven.of_smooth, uneven_on_facets.of_smooth);
  EXPECT_GT(uneven.of_smooth, 0.95);
  EXPECT_GT(uneven_on_facets.of_smooth, 0.95);
}

// A finer sphere whose vertices stand alternately out and in by half its
// edge (a smooth-shaded ball modelled a centimetre off, its triangles a
// centimetre across): neighbouring facets turn by up to 80 degrees, yet
// under a white sky it is lit as the smooth sphere is, by all of the sky
// (radiance 1): neither the sky's shadow rays nor the paths' bounce rays
// stop on its own facets (a bounce that did saw the ball itself, and
// speckled it).
TEST(Shadow, ASmoothSphereWhoseVerticesAreOffByHalfAnEdgeSeesAllOfTheSky) {
  const TriangleMesh mesh = uv_sphere(48, 24, 0.06f);
  const RayScene rays(mesh);
  Lighting lighting;
  lighting.environment = Environment::constant(Vec3::Ones());
  IntegratorOptions options;
  options.max_bounces = 0;
  const Integrator integrator(rays, lighting, nullptr, options);
  double sum = 0.0;
  int samples = 0;
  for (float x = -0.8f; x <= 0.8f; x += 0.05f)
    for (float z = -0.8f; z <= 0.8f; z += 0.05f) {
      SurfacePoint p;
      if (!rays.intersect(Vec3(x, 3, z), Vec3(0, -1, 0), p)) continue;
      Rng rng(1, uint64_t(samples));
      for (int k = 0; k < 16; ++k, ++samples) sum += integrator.illumination(p, rng).x();
    }
  ASSERT_GT(samples, 1000);
  std::printf("a sphere 6 %% uneven under a white sky: %.3f of the sky's light\n", sum / samples);
  EXPECT_GT(sum / samples, 0.99);  // 0.975 when a path's bounce stopped on the ball's own facets
}

// What a smooth surface passes over is only itself: a plate of the same
// object 1 m over a floor, their normals alike but not joined, shadows it;
// so does a wall joined to the floor's edge, its corners' normals averaged
// (a box shaded smooth): their facets turn by 90 degrees.
TEST(Shadow, ASmoothSurfaceIsShadowedByWhatIsNotItself) {
  TriangleMesh mesh;
  add_square(mesh, Vec3::Zero(), 5.0f);
  add_square(mesh, Vec3(0, 0, 1), 0.5f);
  mesh.normals.assign(mesh.positions.size(), Vec3::UnitZ());
  // A wall standing on the floor's edge at x = 5, joined to its corners.
  const uint32_t a = 1, b = 2;  // the floor's corners at x = +5 (add_rectangle's order)
  ASSERT_FLOAT_EQ(mesh.positions[a].x(), 5.0f);
  ASSERT_FLOAT_EQ(mesh.positions[b].x(), 5.0f);
  mesh.normals[a] = mesh.normals[b] = Vec3(-1, 0, 1).normalized();
  const uint32_t top = uint32_t(mesh.positions.size());
  mesh.positions.push_back(mesh.positions[a] + Vec3(0, 0, 3));
  mesh.positions.push_back(mesh.positions[b] + Vec3(0, 0, 3));
  mesh.normals.push_back(-Vec3::UnitX());
  mesh.normals.push_back(-Vec3::UnitX());
  mesh.triangles.push_back({a, b, top + 1});
  mesh.triangles.push_back({a, top + 1, top});
  const RayScene rays(mesh);
  SurfacePoint under_plate, by_wall;
  ASSERT_TRUE(rays.intersect(Vec3(0, 0, 0.5f), Vec3(0, 0, -1), under_plate));
  EXPECT_TRUE(rays.occluded(rays.shadow_ray(under_plate, Vec3::UnitZ(), 10.0f)));
  ASSERT_TRUE(rays.intersect(Vec3(4.5f, 0, 0.5f), Vec3(0, 0, -1), by_wall));
  EXPECT_TRUE(rays.occluded(rays.shadow_ray(by_wall, Vec3(1, 0, 1).normalized(), 10.0f)));
  EXPECT_FALSE(rays.occluded(rays.shadow_ray(by_wall, Vec3(-1, 0, 1).normalized(), 10.0f)));
}

TEST(Lights, ContributionsOfSeveralLightsAdd) {
  const Light a = point_light(Vec3(0, 0, 2), 100.0f);
  const Light b = sun(Vec3(0, 0, -1), 2.0f);
  LitPlane scene(plane_mesh(), {a, b});
  const double expected = 100.0 / (4.0 * kPiD * kPiD * 4.0) + 2.0 / kPiD;
  expect_within_1_percent(scene.mean_illumination(0, 0, 64), Vec3::Constant(float(expected)));
}

// ---------------------------------------------------------- environment

TEST(Environment, ConstantEnvironmentOverOpenPlaneGivesItsRadiance) {
  // White furnace for a plane: a white Lambertian surface under a constant
  // sky of radiance B reflects B (irradiance pi B, divided by pi).
  const Vec3 b(0.3f, 0.6f, 1.2f);
  LitPlane scene(plane_mesh(), {}, Environment::constant(b));
  expect_within_1_percent(scene.mean_illumination(0, 0, 200000), b);
}

TEST(Environment, ScaleMultipliesTheEnvironment) {
  Environment env = Environment::constant(Vec3::Ones());
  env.set_scale(0.25f);
  LitPlane scene(plane_mesh(), {}, env);
  expect_within_1_percent(scene.mean_illumination(0, 0, 200000), Vec3::Constant(0.25f));
}

// A probe whose frame is forward = +y, up = +z (world up is the probe's up).
Probe equirect_probe(int w, int h) {
  Probe p;
  p.path = "synthetic";
  p.mapping = ProbeMapping::equirect;
  p.forward = Vec3(0, 1, 0);
  p.up = Vec3(0, 0, 1);
  p.image = Image(w, h, Vec3(0.2f, 0.3f, 0.4f));
  return p;
}

TEST(Environment, UniformEquirectProbeOverOpenPlaneGivesItsRadiance) {
  LitPlane scene(plane_mesh(), {}, Environment::from_probes({equirect_probe(32, 16)}));
  expect_within_1_percent(scene.mean_illumination(0, 0, 200000), Vec3(0.2f, 0.3f, 0.4f));
}

TEST(Environment, UniformMirrorballProbeOverOpenPlaneGivesItsRadiance) {
  // The ball looks straight up: the singular direction "behind the ball"
  // (+forward) is the zenith, and the rim pixels the probe sampler cannot
  // reach are around it; MIS with the cosine lobe must still cover them.
  Probe p;
  p.path = "synthetic";
  p.mapping = ProbeMapping::mirrorball;
  p.forward = Vec3(0, 0, 1);
  p.up = Vec3(0, 1, 0);
  p.image = Image(24, 24, Vec3(0.5f, 0.25f, 1.0f));
  LitPlane scene(plane_mesh(), {}, Environment::from_probes({p}));
  expect_within_1_percent(scene.mean_illumination(0, 0, 200000), Vec3(0.5f, 0.25f, 1.0f));
}

TEST(Environment, EquirectProbeWithBrightPatchMatchesExactIrradiance) {
  // Probe up = world +z, so rows 0..H/2-1 are the sky above the plane. A
  // pixel of row r spans polar angles [r pi/H, (r+1) pi/H] and azimuth
  // 2 pi/W; its cosine-weighted solid angle is exactly
  //   (2 pi/W) (sin^2 theta1 - sin^2 theta0)/2,
  // so illumination = (1/pi) sum over sky pixels of L x that.
  const int w = 32, h = 16;
  Probe p = equirect_probe(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) p.image.at(x, y) = Vec3(0.05f, 0.1f, 0.2f) * float(1 + (x + 2 * y) % 3);
  for (int y = 2; y < 5; ++y)
    for (int x = 20; x < 23; ++x) p.image.at(x, y) = Vec3(60.0f, 40.0f, 20.0f);  // a sun-like patch
  for (int x = 0; x < w; ++x) p.image.at(x, 12) = Vec3(50.0f, 50.0f, 50.0f);  // below the plane: unseen
  Eigen::Vector3d expected = Eigen::Vector3d::Zero();
  for (int y = 0; y < h / 2; ++y) {
    const double t0 = y * kPiD / h, t1 = (y + 1) * kPiD / h;
    const double weight = (2 * kPiD / w) * (std::pow(std::sin(t1), 2) - std::pow(std::sin(t0), 2)) / 2;
    for (int x = 0; x < w; ++x) expected += p.image.at(x, y).cast<double>() * weight;
  }
  expected /= kPiD;
  LitPlane scene(plane_mesh(), {}, Environment::from_probes({p}));
  expect_within_1_percent(scene.mean_illumination(0, 0, 1000000), expected.cast<float>());
}

TEST(Environment, ZeroScaleGivesNothing) {
  Environment env = Environment::constant(Vec3::Ones());
  env.set_scale(0.0f);
  LitPlane scene(plane_mesh(), {}, env);
  EXPECT_EQ(scene.mean_illumination(0, 0, 1000), Vec3::Zero());
}


// The session renders a light's next interactive image into the storage of
// the last one, handed on by move: an image moved from is 0 x 0, so the
// render makes a new one rather than writing where the pixels were (it kept
// its size and crashed relight studio's test now and then).
TEST(DirectLight, RendersIntoAnImageMovedFrom) {
  const Light lamp = point_light(Vec3(0, 0, 1), 100.0f);
  const TriangleMesh mesh = plane_mesh();
  const RayScene rays(mesh);
  PixelSurfaces surfaces;
  surfaces.width = 2, surfaces.height = 1;
  for (const float x : {0.0f, 0.5f}) {
    SurfacePoint hit;
    ASSERT_TRUE(rays.intersect(Vec3(x, 0, 0.25f), Vec3(0, 0, -1), hit));
    surfaces.surface.push_back(hit);
    surfaces.hit.push_back(1);
  }
  Image last(2, 1);
  const Image kept = std::move(last);
  EXPECT_EQ(last.width, 0);
  EXPECT_EQ(last.height, 0);
  EXPECT_TRUE(last.empty());
  Image assigned(2, 1);
  assigned = std::move(last);  // from an empty one
  EXPECT_EQ(assigned.width, 0);
  render_direct_light(surfaces, rays, lamp, DirectLightSettings{}, last);
  ASSERT_EQ(last.size(), 2u);
  EXPECT_GT(last.at(0, 0).x(), last.at(1, 0).x());  // under the lamp, brighter
  EXPECT_EQ(kept.size(), 2u);
}

// The moving light's checkerboard (CpuDirectLight) seen from above: a floor,
// a square 0.5 m over it and a strip 1 cm wide 0.6 m over it, whose shadow
// is about a pixel wide.
class CheckerboardView : public testing::Test {
 protected:
  CheckerboardView() : mesh_(shadowed_floor()), rays_(mesh_) {
    CameraSpec spec;
    spec.position = Vec3(0, 0, 3);
    spec.look_at = Vec3::Zero();
    spec.up = Vec3(0, 1, 0);
    spec.vfov_deg = 60.0f;
    const GBuffer gbuffer(Camera(spec, 160, 120), rays_, 1, 1, "checkerboard view");
    surfaces_ = PixelSurfaces::central_samples(gbuffer);
  }
  static TriangleMesh shadowed_floor() {
    TriangleMesh mesh = plane_mesh();
    add_square(mesh, Vec3(-0.6f, -0.3f, 0.5f), 0.25f);
    add_rectangle(mesh, Vec3(0.7f, 0.0f, 0.6f), 0.005f, 0.8f);
    return mesh;
  }
  // A sphere light over the floor, off the view's middle.
  static Light sphere_light() {
    Light soft = point_light(Vec3(0.2f, 0.1f, 2.0f), 100.0f);
    soft.radius = 0.15f;
    return soft;
  }
  // The light's direct light in the view by the checkerboard, and by 256
  // light samples a pixel, every pixel its own rays.
  std::pair<Image, Image> checkerboard_and_dense(const Light& light) const {
    Image checkerboard, dense;
    CpuDirectLight(surfaces_, rays_).render(light, checkerboard);
    DirectLightSettings settings;
    settings.light_samples = 256;
    render_direct_light(surfaces_, rays_, light, settings, dense);
    return {std::move(checkerboard), std::move(dense)};
  }
  // The share of the pixels the two images light differently, and the
  // largest relative difference where both light a pixel.
  static std::pair<double, double> differences(const Image& a, const Image& b) {
    size_t unlike = 0;
    double largest = 0.0;
    for (size_t i = 0; i < a.size(); ++i) {
      const float x = a.pixels[i].x(), y = b.pixels[i].x();
      if ((x > 0.0f) != (y > 0.0f))
        ++unlike;
      else if (y > 0.0f)
        largest = std::max(largest, double(std::abs(x - y) / y));
    }
    return {double(unlike) / double(a.size()), largest};
  }

  TriangleMesh mesh_;
  RayScene rays_;
  PixelSurfaces surfaces_;
};

// A point light: half the rays, and the image every pixel's own ray gives,
// the strip's shadow a pixel wide included.
TEST_F(CheckerboardView, GivesWhatEveryPixelsOwnRayGivesWithHalfTheRays) {
  const Light lamp = point_light(Vec3(0.2f, 0.1f, 2.0f), 100.0f);
  Image checkerboard, every_ray;
  CpuDirectLight backend(surfaces_, rays_);
  const size_t rays = backend.render_counting_rays(lamp, checkerboard);
  render_direct_light(surfaces_, rays_, lamp, DirectLightSettings{}, every_ray);
  size_t strip_shadow = 0;  // the strip's shadow, on the floor beside the square's
  for (int y = 0; y < 120; ++y)
    for (int x = 100; x < 160; ++x) strip_shadow += every_ray.at(x, y).x() == 0.0f;
  ASSERT_GT(strip_shadow, 60u);   // a line down the view
  ASSERT_LT(strip_shadow, 240u);  // at most two pixels wide
  const auto [unlike, largest] = differences(checkerboard, every_ray);
  std::printf(
      "[ figures  ] checkerboard: %.3f rays a pixel, %.4f %% of pixels lit otherwise, largest difference %.2e\n",
      double(rays) / double(checkerboard.size()), 100.0 * unlike, largest);
  EXPECT_LT(double(rays), 0.6 * double(checkerboard.size()));
  EXPECT_EQ(unlike, 0.0);
  EXPECT_LT(largest, 1e-3);
}

// Lights with an extent: their soft shadows and (an area light) their
// light are sampled once a pixel; over the view they give the light of
// many samples a pixel.
TEST_F(CheckerboardView, GivesASoftLightsMeanLight) {
  const Light area = downward_area_light(0.4f, 0.3f, 2.0f, 100.0f);
  for (const Light& light : {sphere_light(), area, sun(Vec3(0.3f, 0.2f, -1.0f), 5.0f, 3.0f)}) {
    const auto [checkerboard, many] = checkerboard_and_dense(light);
    double sum = 0.0, reference = 0.0;
    for (size_t i = 0; i < many.size(); ++i) {
      sum += checkerboard.pixels[i].x();
      reference += many.pixels[i].x();
    }
    std::printf("[ figures  ] checkerboard, %s light: mean %.5f against %.5f\n", to_string(light.type),
                sum / double(many.size()), reference / double(many.size()));
    EXPECT_NEAR(sum, reference, 0.01 * reference) << to_string(light.type);
  }
}

// A sphere light's penumbra across the square's shadow edge, row by row
// (averaged over 14 rows), has the width and profile of the light of 256
// samples a pixel: each pixel's one shadow ray aims at a point of the disc
// that faces it (3-sphere points, docs/algorithms.md section 8).
TEST_F(CheckerboardView, KeepsASphereLightsPenumbra) {
  const auto [checkerboard, many] = checkerboard_and_dense(sphere_light());
  double largest = 0.0, penumbra = 0.0;
  for (int x = 30; x < 45; ++x) {
    double a = 0.0, b = 0.0;
    for (int y = 68; y < 82; ++y) a += checkerboard.at(x, y).x() / 14.0, b += many.at(x, y).x() / 14.0;
    largest = std::max(largest, std::abs(a - b));
    if (b > 0.05 && b < 0.25) ++penumbra;  // neither lit (0.3) nor dark
  }
  ASSERT_GE(penumbra, 2);  // the penumbra is a few pixels wide
  EXPECT_LT(largest, 0.05);
}

}  // namespace
}  // namespace relight

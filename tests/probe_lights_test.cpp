// Finding the principal lights in light probes: a synthetic probe with a known
// lamp, and the lamp and sun of the reference scenes (skipped where absent).
#include "analysis/probe_lights.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <limits>

#include "analysis/probe_cleanup.h"
#include "io/scene_io.h"
#include "reference_scenes.h"
#include "render/ray_scene.h"

namespace fs = std::filesystem;
using namespace relight;

namespace {

// A 512x256 equirect probe of a uniform environment with a point lamp of
// radius r and power P at `lamp` seen from the origin: the lamp's disc has
// radiance P/(4 pi^2 r^2).
Probe probe_with_lamp(const Vec3& lamp, float radius, float power, const Vec3& environment) {
  Probe p;
  p.image = Image(512, 256, environment);
  const ProbeFrame frame(p.forward, p.up);
  const float dist = lamp.norm(), cos_disc = std::cos(std::asin(radius / dist));
  const float radiance = power / (4.0f * kPi * kPi * radius * radius);
  // Supersample each pixel so its value is the mean over its area, like a camera's.
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 512; ++x) {
      int inside = 0;
      for (int s = 0; s < 16; ++s) {
        const Vec2 uv((x + (s % 4 + 0.5f) / 4) / 512, (y + (s / 4 + 0.5f) / 4) / 256);
        inside += probe_uv_to_direction(ProbeMapping::equirect, frame, uv)->dot(lamp / dist) >= cos_disc;
      }
      p.image.at(x, y) += Vec3::Constant(radiance * inside / 16.0f);
    }
  return p;
}

TEST(ProbeLights, MeasuresAKnownLampsPowerAndDirection) {
  const Vec3 lamp(1.0f, 1.5f, 0.8f);
  const Probe probe = probe_with_lamp(lamp, 0.05f, 100.0f, Vec3::Constant(0.3f));
  Light guess;
  guess.position = lamp + Vec3(0.1f, -0.1f, 0.05f);  // the user's estimate is a little off
  guess.radius = 0.05f;
  guess.power = 30.0f;
  const auto seen = locate_light_in_probe(probe, guess);
  ASSERT_TRUE(seen);
  EXPECT_LT(std::acos(std::min(1.0f, seen->direction.dot(lamp.normalized()))), radians(0.5f));
  Light at_truth = guess;
  at_truth.position = lamp;
  const auto emission = emission_from_probe(probe, at_truth, *seen);
  ASSERT_TRUE(emission);
  EXPECT_NEAR(emission->x(), 100.0f, 5.0f);
  EXPECT_NEAR(seen->surround.x(), 0.3f, 1e-4f);
}

// Where the probe resolves a lamp's disc, the size given gives its distance;
// a lamp a few pixels across is not resolved.
TEST(ProbeLights, ALampsSizeSeenGivesItsDistance) {
  const Vec3 lamp(1.0f, 1.5f, 0.8f);                  // 1.97 m away
  for (const float radius : {0.12f, 0.06f, 0.03f}) {  // 10, 5 and 2.5 pixels across
    const Probe probe = probe_with_lamp(lamp, radius, 100.0f, Vec3::Constant(0.3f));
    Light guess;
    guess.position = lamp + Vec3(0.1f, -0.1f, 0.05f);
    guess.radius = radius;
    const auto seen = locate_light_in_probe(probe, guess);
    ASSERT_TRUE(seen);
    const auto distance = distance_from_apparent_size(probe, guess, *seen, seen->direction);
    if (radius < 0.04f) {
      EXPECT_FALSE(distance) << *distance;
      continue;
    }
    ASSERT_TRUE(distance);
    std::printf("[ figures  ] a lamp of radius %.2f m 1.97 m away: its size seen puts it %.3f m away\n", radius,
                *distance);
    EXPECT_NEAR(*distance, lamp.norm(), 0.01f * lamp.norm());
  }
}

// A 512x256 equirect probe at the origin of a uniform environment with an
// area light's rectangle (radiance P / (4 w h), one-sided) where `panel` has
// it; one pixel of the rectangle, near a corner, a little brighter than the
// rest, as a rendered or photographed panel's noise makes some pixel.
Probe probe_with_panel(const Light& panel, const Vec3& environment) {
  Probe p;
  p.image = Image(512, 256, environment);
  const ProbeFrame frame(p.forward, p.up);
  const AreaLightSides sides = area_light_sides(panel);
  const Vec3 n = panel.direction.normalized();
  const float radiance = panel.power / (4.0f * panel.size.x() * panel.size.y());
  Vec2 corner(0, 0);
  float nearest = std::numeric_limits<float>::max();
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 512; ++x) {
      int inside = 0;
      for (int s = 0; s < 16; ++s) {
        const Vec2 uv((x + (s % 4 + 0.5f) / 4) / 512, (y + (s / 4 + 0.5f) / 4) / 256);
        const Vec3 d = *probe_uv_to_direction(ProbeMapping::equirect, frame, uv);
        if (d.dot(n) >= 0.0f) continue;  // the light's back, or parallel
        const Vec3 hit = d * (panel.position.dot(n) / d.dot(n)) - panel.position;
        const float a = hit.dot(sides.w), b = hit.dot(sides.h);
        if (std::abs(a) > 0.5f * panel.size.x() || std::abs(b) > 0.5f * panel.size.y()) continue;
        ++inside;
        const float to_corner = Vec2(0.5f * panel.size.x() - a, 0.5f * panel.size.y() - b).norm();
        if (to_corner < nearest) nearest = to_corner, corner = Vec2(float(x), float(y));
      }
      p.image.at(x, y) += Vec3::Constant(radiance * inside / 16.0f);
    }
  p.image.at(int(corner.x()), int(corner.y())) *= 1.01f;
  return p;
}

// A 1 x 0.6 m panel of 300 W at `position`, facing down, as a ceiling panel.
Light ceiling_panel(const Vec3& position) {
  Light panel;
  panel.type = LightType::area;
  panel.position = position;
  panel.direction = Vec3(0, 0, -1);
  panel.up = Vec3(0, 1, 0);
  panel.size = Vec2(1.0f, 0.6f);
  panel.power = 300.0f;
  return panel;
}

// The 300 W panel's power as the probe measures it, located as `guess`
// (0 where it is not found).
float measured_panel_power(const Probe& probe, const Light& guess, const Light& panel) {
  const auto seen = locate_light_in_probe(probe, guess);
  if (!seen) return 0.0f;
  const auto emission = emission_from_probe(probe, panel, *seen);
  return emission ? emission->x() : 0.0f;
}

TEST(ProbeLights, MeasuresAnEvenlyBrightPanelWhole) {
  const Light panel = ceiling_panel(Vec3(0.2f, 0.3f, 1.1f));  // overhead
  const Probe probe = probe_with_panel(panel, Vec3::Constant(0.3f));
  Light guess = panel;
  guess.position += Vec3(0.1f, 0.05f, 0.0f);  // the user's estimate is a little off
  EXPECT_NEAR(measured_panel_power(probe, guess, panel), 300.0f, 9.0f);  // 3 %
}

TEST(ProbeLights, APanelsSizeSeenGivesItsDistance) {
  const Light panel = ceiling_panel(Vec3(0.6f, 0.3f, 1.1f));
  const Probe probe = probe_with_panel(panel, Vec3::Constant(0.3f));
  Light guess = panel;
  guess.position += Vec3(0.1f, 0.05f, 0.0f);
  const auto seen = locate_light_in_probe(probe, guess);
  ASSERT_TRUE(seen);
  const Vec3 to_centre = panel.position - probe.position;
  const auto distance = distance_from_apparent_size(probe, guess, *seen, to_centre.normalized());
  ASSERT_TRUE(distance);
  EXPECT_NEAR(*distance, to_centre.norm(), 0.01f * to_centre.norm());
}

// A panel seen at a slant fills more of the view with its near half: the
// probe measures the middle of what it fills (seen_middle), which `relight
// fit` turns back into a line through its centre.
TEST(ProbeLights, SeesASlantedPanelsMiddleNotItsCentre) {
  const Light panel = ceiling_panel(Vec3(0.9f, 0.3f, 0.8f));
  const Probe probe = probe_with_panel(panel, Vec3::Constant(0.3f));
  const auto seen = locate_light_in_probe(probe, panel);
  ASSERT_TRUE(seen);
  const auto degrees_to = [&](const Vec3& d) { return angle_degrees(seen->direction, d); };
  const float to_middle = degrees_to(seen_middle(panel, probe.position));
  const float to_centre = degrees_to((panel.position - probe.position).normalized());
  std::printf(
      "[ figures  ] the measured direction is %.2f degrees from the panel's seen middle, %.2f from its "
      "centre\n",
      to_middle, to_centre);
  EXPECT_LT(to_middle, 0.5f);
  EXPECT_GT(to_centre, 1.0f);
}

TEST(ProbeLights, TwoLampsSideBySideAreMeasuredApart) {
  // 10 degrees apart: each within the other's search cone, but not its region.
  const Vec3 a = 2.0f * Vec3(std::sin(radians(-5.0f)), std::cos(radians(-5.0f)), 0.0f);
  const Vec3 b = 2.0f * Vec3(std::sin(radians(5.0f)), std::cos(radians(5.0f)), 0.0f);
  Probe probe = probe_with_lamp(a, 0.05f, 100.0f, Vec3::Constant(0.3f));
  const Probe other = probe_with_lamp(b, 0.05f, 100.0f, Vec3::Zero());
  for (size_t i = 0; i < probe.image.size(); ++i) probe.image.pixels[i] += other.image.pixels[i];
  for (const Vec3& lamp : {a, b}) {
    Light light;
    light.position = lamp;
    light.radius = 0.05f;
    light.power = 30.0f;
    const auto seen = locate_light_in_probe(probe, light);
    ASSERT_TRUE(seen);
    EXPECT_LT(std::acos(std::min(1.0f, seen->direction.dot(lamp.normalized()))), radians(0.5f));
    const auto emission = emission_from_probe(probe, light, *seen);
    ASSERT_TRUE(emission);
    EXPECT_NEAR(emission->x(), 100.0f, 5.0f);
  }
}

TEST(ProbeLights, RemovalLeavesOnlyTheEnvironment) {
  const Vec3 lamp(-1.0f, 0.5f, 1.2f);
  const Probe probe = probe_with_lamp(lamp, 0.05f, 100.0f, Vec3::Constant(0.3f));
  Light light;
  light.position = lamp;
  light.radius = 0.05f;
  light.power = 100.0f;
  const Probe clean = remove_lights_from_probe(probe, {light});
  for (const auto& p : clean.image.pixels) ASSERT_NEAR(p.x(), 0.3f, 1e-4f);
}

// A light given a quarter of its size: its region is what the probe shows
// of it, not what was given. Its rim would otherwise stay in the probe, and
// the photo's radiance bounce it as the wall's behind it.
TEST(ProbeLights, ALightGivenTooSmallIsFoundWhole) {
  const Light panel = ceiling_panel(Vec3(0.2f, 0.3f, 1.1f));
  const Vec3 lamp(-1.0f, 0.5f, 1.2f);
  Light small_panel = panel, small_lamp;
  small_panel.size *= 0.25f;
  small_lamp.position = lamp;
  small_lamp.radius = 0.03f;  // of 0.12
  small_lamp.power = 100.0f;
  const Probe with_panel = probe_with_panel(panel, Vec3::Constant(0.3f));
  const Probe with_lamp = probe_with_lamp(lamp, 0.12f, 100.0f, Vec3::Constant(0.3f));
  for (const auto& [probe, light] : {std::pair(with_panel, small_panel), std::pair(with_lamp, small_lamp)}) {
    const Probe clean = remove_lights_from_probe(probe, {light});
    float left = 0.0f;
    for (const auto& p : clean.image.pixels) left = std::max(left, std::abs(p.x() - 0.3f));
    EXPECT_LT(left, 1e-4f) << (light.type == LightType::area ? "panel" : "lamp");
  }
  EXPECT_NEAR(measured_panel_power(with_panel, small_panel, panel), 300.0f, 9.0f);  // 3 %
}

// A sky that brightens smoothly towards its sun, 50 degrees from where a
// lamp was put that the probe (an HDRI of the sky alone) does not show:
// nothing is found there. Joined up the sky's slope, the sun would have
// been taken for the lamp and taken out of the sky.
TEST(ProbeLights, ASkysSunIsNotTakenForALampFarFromIt) {
  const Vec3 sun = Vec3(std::sin(radians(50.0f)), std::cos(radians(50.0f)), 0.0f);
  Probe probe = probe_with_lamp(20.0f * sun, 0.1f, 1e6f, Vec3::Zero());
  const ProbeFrame frame(probe.forward, probe.up);
  for (int y = 0; y < probe.image.height; ++y)
    for (int x = 0; x < probe.image.width; ++x) {
      const Vec2 uv((x + 0.5f) / probe.image.width, (y + 0.5f) / probe.image.height);
      const float towards = std::max(0.0f, probe_uv_to_direction(ProbeMapping::equirect, frame, uv)->dot(sun));
      probe.image.at(x, y) += Vec3::Constant(0.3f + 3.0f * std::pow(towards, 4.0f));
    }
  Light lamp;
  lamp.position = Vec3(0.0f, 2.0f, 0.0f);  // straight ahead, 50 degrees from the sun
  lamp.radius = 0.05f;
  lamp.power = 100.0f;
  EXPECT_FALSE(locate_light_in_probe(probe, lamp));
}

TEST(ProbeLights, NoLightWhereThereIsNone) {
  Probe probe;
  probe.image = Image(64, 32, Vec3::Constant(0.5f));
  Light light;
  light.position = Vec3(0, 2, 1);
  light.power = 10.0f;
  EXPECT_FALSE(locate_light_in_probe(probe, light));
}

TEST(ProbeLights, TwoProbesTriangulateALamp) {
  const Vec3 lamp(0.4f, 2.0f, 1.7f), a(0, 0, 1), b(1.5f, 0.2f, 0.9f);
  const auto p = triangulate(a, (lamp - a).normalized(), b, (lamp - b).normalized());
  ASSERT_TRUE(p);
  EXPECT_LT((*p - lamp).norm(), 1e-4f);
  EXPECT_FALSE(triangulate(a, Vec3(1, 0, 0), b, Vec3(1, 0, 0)));
}

// A 64x32 equirect probe at the origin of a sky of radiance 1 over a 6 x 6 m
// floor 1 m below, which it shows at radiance 5; each pixel the mean over
// its square (8 x 8 samples), so pixels on the floor's edge mix the two.
// `coverage`: each pixel's share of floor.
Probe probe_over_a_floor(const RayScene& floor, std::vector<float>& coverage) {
  Probe p;
  p.image = Image(64, 32);
  coverage.assign(p.image.size(), 0.0f);
  const ProbeFrame frame(p.forward, p.up);
  SurfacePoint hit;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) {
      int on_floor = 0;
      for (int s = 0; s < 64; ++s) {
        const Vec2 uv((x + (s % 8 + 0.5f) / 8) / 64, (y + (s / 8 + 0.5f) / 8) / 32);
        on_floor += floor.intersect(Vec3::Zero(), *probe_uv_to_direction(ProbeMapping::equirect, frame, uv), hit);
      }
      coverage[size_t(y) * 64 + x] = float(on_floor) / 64.0f;
      p.image.at(x, y) = Vec3::Constant(1.0f + 4.0f * coverage[size_t(y) * 64 + x]);
    }
  return p;
}

TriangleMesh floor_below_origin() {
  TriangleMesh m;
  m.positions = {{-3, -3, -1}, {3, -3, -1}, {3, 3, -1}, {-3, 3, -1}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

TEST(ProbeCleanup, PixelsThatShowAnyGeometryTakeTheFillAndTheRestStay) {
  const TriangleMesh mesh = floor_below_origin();
  const RayScene floor(mesh);
  std::vector<float> coverage;
  const Probe raw = probe_over_a_floor(floor, coverage);
  const Vec3 fill(0.3f, 0.4f, 0.5f);
  const Probe cleaned = remove_local_geometry_from_probe(raw, floor, fill).value();
  int mixed = 0;
  for (size_t i = 0; i < coverage.size(); ++i) {
    if (coverage[i] == 0.0f) {
      EXPECT_EQ(cleaned.image.pixels[i], Vec3::Ones()) << "pixel " << i;
    }
    if (coverage[i] >= 0.1f) {
      EXPECT_EQ(cleaned.image.pixels[i], fill) << "pixel " << i << ", " << coverage[i] << " floor";
    }
    mixed += coverage[i] > 0.0f && coverage[i] < 1.0f;
  }
  EXPECT_GT(mixed, 16);  // the floor's edge crosses pixels: the case that matters
}

TEST(ProbeCleanup, WithoutAFillTheSkyFillsWhatTheFloorHid) {
  // The floor's edge pixels must not bleed its radiance into the fill.
  const TriangleMesh mesh = floor_below_origin();
  const RayScene floor(mesh);
  std::vector<float> coverage;
  const Probe cleaned = remove_local_geometry_from_probe(probe_over_a_floor(floor, coverage), floor).value();
  for (size_t i = 0; i < coverage.size(); ++i)
    EXPECT_NEAR(cleaned.image.pixels[i].maxCoeff(), 1.0f, 1e-5f) << "pixel " << i << ", " << coverage[i] << " floor";
}

// The reference probes see the real lamp and sun: the power and colour they
// imply match the scene's within 10 %.
class ReferenceProbe : public testing::TestWithParam<std::string> {};

TEST_P(ReferenceProbe, ImpliesTheLightsTruePower) {
  const fs::path file = relight::test::reference_scenes_folder() / GetParam() / "scene.json";
  if (!fs::exists(file)) GTEST_SKIP() << file << " not found (set RELIGHT_SCENES)";
  const Scene scene = load_scene(file);
  const RayScene rays(scene.mesh);
  for (const Light& light : scene.lights)  // the studio's lamp and softbox too
    for (const Probe& raw : scene.probes) {
      // As `fit` does: a probe that shows only the geometry (a closed room) still shows the lights.
      const Probe probe = remove_local_geometry_from_probe(raw, rays).value_or(raw);
      const auto seen = locate_light_in_probe(probe, light);
      ASSERT_TRUE(seen) << raw.path;
      const auto emission = emission_from_probe(probe, light, *seen);
      ASSERT_TRUE(emission);
      const Vec3 truth = light.emission();
      std::printf("[ figures  ] %s: %s implies emission %.3f %.3f %.3f (true %.3f %.3f %.3f)\n", GetParam().c_str(),
                  fs::path(raw.path).filename().c_str(), emission->x(), emission->y(), emission->z(), truth.x(),
                  truth.y(), truth.z());
      for (int c = 0; c < 3; ++c) EXPECT_NEAR((*emission)[c] / truth[c], 1.0f, 0.05f) << raw.path << " channel " << c;
    }
}

// Where the probe resolves a light (the studio's lamp and softbox, the
// bookcase's lamp), its true size fills what the probe sees at its true
// distance, to 2 cm.
TEST_P(ReferenceProbe, ResolvedLightsSizeGivesItsDistance) {
  const fs::path file = relight::test::reference_scenes_folder() / GetParam() / "scene.json";
  if (!fs::exists(file)) GTEST_SKIP() << file << " not found (set RELIGHT_SCENES)";
  const Scene scene = load_scene(file);
  const RayScene rays(scene.mesh);
  for (const Light& light : scene.lights)
    for (const Probe& raw : scene.probes) {
      const Probe probe = remove_local_geometry_from_probe(raw, rays).value_or(raw);
      const auto seen = locate_light_in_probe(probe, light);
      ASSERT_TRUE(seen) << raw.path;
      const Vec3 to_light = light.position - probe.position;
      const auto distance = distance_from_apparent_size(probe, light, *seen, to_light.normalized());
      EXPECT_EQ(distance.has_value(), light.type != LightType::directional) << light.name;
      if (!distance) continue;
      std::printf("[ figures  ] %s: %s's size puts it %.3f m from the probe (true %.3f)\n", GetParam().c_str(),
                  light.name.c_str(), *distance, to_light.norm());
      EXPECT_NEAR(*distance, to_light.norm(), 0.02f) << light.name;
    }
}

INSTANTIATE_TEST_SUITE_P(Scenes, ReferenceProbe, testing::Values("outdoor", "bookcase", "studio"));

}  // namespace

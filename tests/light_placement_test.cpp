// Light placement from the shadows (analysis/light_placement.h) on the
// example room, its photo made by the path tracer with the known albedo and
// every bounce: a lamp moved 20 cm, a sun turned 3 degrees and a spot moved
// 15 cm and turned 3 degrees go back towards where they were, alone and
// together; a light already in place stays. The bounds hold for photos of
// three seeds (3, 7, 11) with a margin; each test says what they measured.
#include "analysis/light_placement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "render/render_illumination.h"
#include "room_scene.h"

using namespace relight;

namespace {

struct Placed {
  float before_m, after_m;      // position error
  float before_deg, after_deg;  // direction error
};

// The room lit by `truths` photographed, then `givens` placed from their
// shadows; how far each was from its truth before and after.
std::vector<Placed> place(const std::vector<Light>& truths, const std::vector<Light>& givens,
                          const SightLineOf& sight_line_of = no_sight_line) {
  Scene scene = example::room_scene(320, 240);
  const RayScene rays(scene.mesh);
  const GBuffer gbuffer(scene.camera, rays, 4, 5, "room");
  const example::RoomAlbedo albedo = example::room_albedo();
  Lighting lighting = example::room_lighting(scene, truths);
  scene.photo =
      synthesize_photo(gbuffer, scene.camera, Integrator(rays, lighting, &albedo), albedo, 64, 3, Progress::silent());

  // The illumination of the lighting as given less its lights' direct light
  // (white surfaces, the bounce light of the known albedo, as the fit
  // recovers it).
  lighting.lights = givens;
  IlluminationOptions options;
  options.paths_per_pixel = 16;
  const Image indirect =
      render_illumination_parts(gbuffer, Integrator(rays, lighting, &albedo), options, Progress::silent()).indirect;
  scene.lights = givens;
  const std::vector<PlacedLight> placed = refine_light_placement(
      scene, scene.photo, rays, gbuffer, indirect, own_emission, sight_line_of, PlacementOptions{}, Progress::silent());
  EXPECT_EQ(placed.size(), truths.size());

  std::vector<Placed> result;
  for (size_t i = 0; i < truths.size(); ++i) {
    const Light& truth = truths[i];
    const auto metres = [&](const Light& l) { return (l.position - truth.position).norm(); };
    const auto degrees = [&](const Light& l) { return angle_degrees(l.direction, truth.direction); };
    const Placed p{metres(givens[i]), metres(scene.lights[i]), degrees(givens[i]), degrees(scene.lights[i])};
    std::printf("[ figures  ] %s: %.3g m and %.3g degrees off before, %.3g m and %.3g degrees after\n",
                truth.name.c_str(), p.before_m, p.before_deg, p.after_m, p.after_deg);
    result.push_back(p);
  }
  return result;
}

Placed place(const Light& truth, const Light& given, const SightLineOf& sight_line_of = no_sight_line) {
  return place(std::vector{truth}, std::vector{given}, sight_line_of).front();
}

// The line a probe 1.5 m from the light sees it along, as fit measures it.
SightLineOf seen_by_a_probe(const Light& truth) {
  const Vec3 towards = Vec3(0.6f, 0.6f, 0.53f).normalized();
  return [=](size_t) {
    return std::optional<SightLine>(SightLine{truth.position - 1.5f * towards, towards, std::nullopt, std::nullopt});
  };
}

// `d` turned by `degrees` about an axis across it.
Vec3 turned(const Vec3& d, float degrees) {
  const Vec3 across = Vec3(0.6f, -0.8f, 0.0f).cross(d).normalized();
  return (d + std::tan(radians(degrees)) * across).normalized();
}

Light room_lamp() { return example::room_scene(8, 6).lights.front(); }

Light sun() {
  Light s;
  s.type = LightType::directional;
  s.name = "sun";
  s.direction = Vec3(0.45f, 0.35f, -0.82f).normalized();
  s.irradiance = 3.0f;
  s.angle_deg = 0.5f;
  return s;
}

TEST(LightPlacement, MovesALampBackToItsShadows) {
  const Light truth = room_lamp();
  Light given = truth;
  given.position += Vec3(0.12f, -0.1f, 0.12f);  // 0.2 m
  const Placed p = place(truth, given);
  EXPECT_NEAR(p.before_m, 0.2f, 0.01f);
  EXPECT_LE(p.after_m, 0.06f);  // 0.012, 0.033, 0.043 m
}

TEST(LightPlacement, TurnsASunBackToItsShadows) {
  const Light truth = sun();
  Light given = truth;
  given.direction = turned(truth.direction, 3.0f);
  const Placed p = place(truth, given);
  EXPECT_NEAR(p.before_deg, 3.0f, 0.05f);
  EXPECT_LE(p.after_deg, 0.3f);
}

// The cone comes back; the position hardly does: in this room, lit mostly by
// its walls, the spot's soft shadows fix it to no better than its 15 cm.
TEST(LightPlacement, TurnsASpotBackToItsConeAndKeepsItNearItsShadows) {
  const Light truth = example::evening_rig().lights.at(1);
  ASSERT_EQ(truth.type, LightType::spot);
  Light given = truth;
  given.position += Vec3(-0.1f, 0.1f, 0.05f);  // 0.15 m
  given.direction = turned(truth.direction, 3.0f);
  const Placed p = place(truth, given);
  EXPECT_LE(p.after_deg, 1.6f);  // 0.70, 1.41, 1.31 degrees
  EXPECT_LE(p.after_m, 0.16f);   // 0.069, 0.127, 0.126 m
}

// A spot a probe sees comes back along the line it is seen along, its place
// then fixed by the photo to the one free distance along it.
TEST(LightPlacement, BringsASpotAProbeSeesBackAlongItsSightLine) {
  const Light truth = example::evening_rig().lights.at(1);
  Light given = truth;
  given.position += Vec3(-0.1f, 0.1f, 0.05f);  // 0.15 m
  given.direction = turned(truth.direction, 3.0f);
  const Placed p = place(truth, given, seen_by_a_probe(truth));
  EXPECT_LE(p.after_deg, 1.6f);
  EXPECT_LE(p.after_m, 0.05f);
}

// Two probes see the lamp: it starts where their lines cross, 20 cm from
// where it was given, and stays there.
TEST(LightPlacement, PlacesALampTwoProbesSeeWhereTheirLinesCross) {
  const Light truth = room_lamp();
  Light given = truth;
  given.position += Vec3(0.12f, -0.1f, 0.12f);  // 0.2 m
  const SightLineOf two_probes = [&](size_t) {
    SightLine line = *seen_by_a_probe(truth)(0);
    line.crossing = truth.position;
    return std::optional<SightLine>(line);
  };
  EXPECT_LE(place(truth, given, two_probes).after_m, 0.01f);
}

// A lamp whose size a probe sees is put where that size fills the probe's
// view: given 20 cm off along the line (the distance the photo tells
// least), it is put there, whatever the photo's search would find.
TEST(LightPlacement, PutsALampWhereItsSizeSeenByAProbePutsIt) {
  const Light truth = room_lamp();
  const SightLine line = *seen_by_a_probe(truth)(0);
  const SightLineOf sized = [&](size_t) {
    SightLine with_distance = line;
    with_distance.distance = 1.5f;
    return std::optional<SightLine>(with_distance);
  };
  Light given = truth;
  given.position -= 0.2f * line.direction;
  EXPECT_LE(place(truth, given, sized).after_m, 0.005f);
}

// Both at once: the lamp's shadows and falloff dominate the photo and it
// comes back; the spot's own shadows change the mismatch by less than the
// photo's noise does, so only its cone, the turn, comes back part of the way.
TEST(LightPlacement, PlacesTwoLightsTogether) {
  const std::vector<Light> truths = {room_lamp(), example::evening_rig().lights.at(1)};
  std::vector<Light> given = truths;
  given[0].position += Vec3(0.12f, -0.1f, 0.12f);
  given[1].position += Vec3(-0.1f, 0.1f, 0.05f);
  given[1].direction = turned(truths[1].direction, 3.0f);
  const std::vector<Placed> p = place(truths, given);
  EXPECT_LE(p[0].after_m, 0.07f);   // 0.023, 0.023, 0.055 m
  EXPECT_LE(p[1].after_deg, 2.2f);  // 1.96, 0.71, 0.43 degrees
}

TEST(LightPlacement, LeavesALightInPlaceWhereItIs) {
  const Light truth = room_lamp();
  EXPECT_LE(place(truth, truth).after_m, 0.02f);
}

}  // namespace

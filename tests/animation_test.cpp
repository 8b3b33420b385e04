// Animated rigs: each keyed value interpolated on its own between the keys
// that set it, held before the first and after the last; smooth curves pass
// through their keys without overshooting them; on/off holds; the file
// names of a frame sequence.
#include "scene/animation.h"

#include <gtest/gtest.h>

#include "io/frame_files.h"

using namespace relight;

namespace {

LightKey key_at(int frame, Interpolation interpolation = Interpolation::smooth) {
  LightKey key;
  key.frame = frame;
  key.interpolation = interpolation;
  return key;
}

Light power_keyed(std::vector<std::pair<int, float>> powers, Interpolation interpolation) {
  Light light;
  light.power = 1.0f;
  for (const auto& [frame, power] : powers) {
    LightKey key = key_at(frame, interpolation);
    key.power = power;
    light.keys.push_back(key);
  }
  return light;
}

}  // namespace

TEST(Animation, LinearKeysAreInterpolatedAndHeldOutside) {
  const Light light = power_keyed({{10, 100.0f}, {20, 200.0f}}, Interpolation::linear);
  EXPECT_FLOAT_EQ(light_at_frame(light, 1).power, 100.0f);
  EXPECT_FLOAT_EQ(light_at_frame(light, 10).power, 100.0f);
  EXPECT_FLOAT_EQ(light_at_frame(light, 15).power, 150.0f);
  EXPECT_FLOAT_EQ(light_at_frame(light, 18).power, 180.0f);
  EXPECT_FLOAT_EQ(light_at_frame(light, 20).power, 200.0f);
  EXPECT_FLOAT_EQ(light_at_frame(light, 99).power, 200.0f);
  EXPECT_TRUE(light_at_frame(light, 15).keys.empty());
}

TEST(Animation, ConstantKeysHold) {
  const Light light = power_keyed({{1, 5.0f}, {10, 50.0f}}, Interpolation::constant);
  EXPECT_FLOAT_EQ(light_at_frame(light, 9).power, 5.0f);
  EXPECT_FLOAT_EQ(light_at_frame(light, 10).power, 50.0f);
}

// Two keys: an ease in and out, symmetric about the middle, flat at both ends.
TEST(Animation, SmoothKeysEaseInAndOut) {
  const Light light = power_keyed({{0, 0.0f}, {100, 100.0f}}, Interpolation::smooth);
  EXPECT_NEAR(light_at_frame(light, 50).power, 50.0f, 1e-4f);
  EXPECT_NEAR(light_at_frame(light, 10).power + light_at_frame(light, 90).power, 100.0f, 1e-3f);
  EXPECT_LT(light_at_frame(light, 1).power, 0.1f);   // flat start: 0.0298
  EXPECT_GT(light_at_frame(light, 10).power, 2.0f);  // 2.8, and rising
  EXPECT_LT(light_at_frame(light, 10).power, 4.0f);
}

// Through every key; flat where the value turns (frame 20), so it never
// rises above that key's 100 nor falls below 0 around frame 40.
TEST(Animation, SmoothKeysPassThroughTheirKeysWithoutOvershoot) {
  const Light light =
      power_keyed({{0, 0.0f}, {20, 100.0f}, {40, 0.0f}, {60, 30.0f}, {80, 60.0f}}, Interpolation::smooth);
  for (const int f : {0, 20, 40, 60, 80})
    EXPECT_NEAR(light_at_frame(light, f).power, light.keys[size_t(f / 20)].power.value(), 1e-3f);
  float previous = 0.0f;
  for (int f = 0; f <= 80; ++f) {
    const float p = light_at_frame(light, f).power;
    EXPECT_GE(p, 0.0f) << "frame " << f;
    EXPECT_LE(p, 100.0f) << "frame " << f;
    if (f > 40) {
      EXPECT_GE(p, previous) << "frame " << f << ": the rise from 40 to 80 is monotone";
    }
    previous = p;
  }
  // Frames 60 -> 80 continue the rise at 1.5 a frame: the slope at 60 is the
  // chord of its neighbours, not flat.
  EXPECT_NEAR(light_at_frame(light, 61).power - light_at_frame(light, 60).power, 1.5f, 0.1f);
}

// Each value follows only the keys that set it.
TEST(Animation, EachValueFollowsItsOwnKeys) {
  Light light;
  light.type = LightType::spot;
  light.position = Vec3(9, 9, 9);
  light.direction = Vec3(0, 0, -1);
  light.power = 7.0f;
  LightKey a = key_at(0, Interpolation::linear), b = key_at(10, Interpolation::linear),
           c = key_at(20, Interpolation::linear);
  a.position = Vec3(0, 0, 0);
  c.position = Vec3(2, 0, 0);
  a.direction = Vec3(1, 0, 0);
  b.direction = Vec3(0, 1, 0);
  b.color = Vec3(1, 0, 0);
  a.enabled = true;
  c.enabled = false;
  light.keys = {a, b, c};
  const Light at5 = light_at_frame(light, 5);
  EXPECT_TRUE(at5.position.isApprox(Vec3(0.5f, 0, 0)));
  EXPECT_TRUE(at5.direction.isApprox(Vec3(1, 1, 0).normalized())) << at5.direction.transpose();
  EXPECT_EQ(at5.color, Vec3(1, 0, 0));  // keyed once: held everywhere
  EXPECT_EQ(at5.power, 7.0f);           // never keyed: the light's own
  EXPECT_TRUE(at5.enabled);
  EXPECT_TRUE(light_at_frame(light, 19).enabled);  // on/off holds, never fades
  EXPECT_FALSE(light_at_frame(light, 20).enabled);
  EXPECT_TRUE(light_at_frame(light, 15).position.isApprox(Vec3(1.5f, 0, 0)));
}

// A sun's keyed "power" is its irradiance; light cannot go negative.
TEST(Animation, SunIrradianceAndNoNegativeLight) {
  Light sun;
  sun.type = LightType::directional;
  sun.irradiance = 3.0f;
  LightKey a = key_at(0), b = key_at(10), c = key_at(20);
  a.power = 0.0f, b.power = 0.0f, c.power = 10.0f;
  a.color = Vec3(1, 1, 1), b.color = Vec3(0, 0, 0), c.color = Vec3(1, 1, 1);
  sun.keys = {a, b, c};
  for (int f = 0; f <= 20; ++f) {
    const Light l = light_at_frame(sun, f);
    EXPECT_GE(l.irradiance, 0.0f);
    EXPECT_GE(l.color.minCoeff(), 0.0f);
    EXPECT_EQ(l.power, sun.power);
  }
  EXPECT_FLOAT_EQ(light_at_frame(sun, 20).irradiance, 10.0f);
}

TEST(Animation, KeyedFramesSpanEveryLight) {
  Rig rig;
  rig.lights.resize(3);
  EXPECT_FALSE(keyed_frames(rig).has_value());
  rig.lights[0].keys = {key_at(5), key_at(30)};
  rig.lights[2].keys = {key_at(-2), key_at(12)};
  const std::optional<FrameRange> range = keyed_frames(rig);
  ASSERT_TRUE(range.has_value());
  EXPECT_EQ(range->first, -2);
  EXPECT_EQ(range->last, 30);
}

TEST(FrameFiles, HashesBecomeTheZeroPaddedFrame) {
  EXPECT_EQ(frame_file("out/relit.####.exr", 7), std::filesystem::path("out/relit.0007.exr"));
  EXPECT_EQ(frame_file("relit_#.exr", 120), std::filesystem::path("relit_120.exr"));
  EXPECT_EQ(frame_file("a#b/c.##.exr", 3), std::filesystem::path("a#b/c.03.exr"));  // the name's, not the folder's
  EXPECT_TRUE(has_frame_digits("relit.####.exr"));
  EXPECT_FALSE(has_frame_digits("a#b/relit.exr"));
}

TEST(FrameFiles, FrameRanges) {
  EXPECT_EQ(parse_frame_range("12")->first, 12);
  EXPECT_EQ(parse_frame_range("12")->last, 12);
  EXPECT_EQ(parse_frame_range("1-120")->last, 120);
  for (const char* bad : {"", "x", "5-1", "1-", "-3", "1-2-3", "1.5"})
    EXPECT_FALSE(parse_frame_range(bad).has_value()) << bad;
}

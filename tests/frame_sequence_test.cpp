// An animated rig's frames: each is the still render of the rig at that
// frame (render_rig's image, up to the path tracer's noise); only the lights
// that moved since the frame before are rendered again (recolouring,
// dimming or switching one off and on costs none), and a frame is the same
// image whatever was rendered before it (a farm's chunks join seamlessly).
#include "relight/frame_sequence.h"

#include <gtest/gtest.h>

#include <cmath>

#include "analysed_room.h"
#include "scene/animation.h"

using namespace relight;

namespace {

const AnalysedScene& room() { return test::analysed_room(); }

RenderOptions options() { return RenderOptions{16, 4}; }

// The evening rig, its lamp moving 20 cm a frame from frame 1 to 3 and its
// spot dimmed, recoloured, switched off at frame 3 and on again at frame 4.
Rig animated_rig() {
  Rig rig = example::evening_rig();
  LightKey from, to;
  from.frame = 1;
  from.position = rig.lights[0].position;
  to.frame = 3;
  to.position = rig.lights[0].position + Vec3(0.4f, 0.0f, 0.0f);
  from.interpolation = to.interpolation = Interpolation::linear;
  rig.lights[0].keys = {from, to};
  LightKey bright, dim, off, on;
  bright.frame = 1, bright.power = 300.0f, bright.color = Vec3(0.5f, 0.7f, 1.0f), bright.enabled = true;
  dim.frame = 2, dim.power = 100.0f, dim.color = Vec3(1.0f, 0.5f, 0.2f);
  off.frame = 3, off.enabled = false;
  on.frame = 4, on.enabled = true;
  rig.lights[1].keys = {bright, dim, off, on};
  return rig;
}

// The relative difference of two images' mean luminance, and their
// rms pixel difference relative to the mean.
struct Difference {
  double mean, rms;
};
Difference difference(const Image& a, const Image& b) {
  double sa = 0, sb = 0, sq = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    const double la = luminance(a.pixels[i]), lb = luminance(b.pixels[i]);
    sa += la, sb += lb, sq += (la - lb) * (la - lb);
  }
  const double mean = sb / double(b.size());
  return {std::abs(sa - sb) / sb, std::sqrt(sq / double(a.size())) / mean};
}

}  // namespace

// Each light rendered apart and summed is the still render of the frame:
// the same mean light, and pixels apart only by the two renders' noise
// (render_rig against itself with another seed differs as much).
TEST(FrameSequence, AFrameIsTheStillRenderOfTheRigAtThatFrame) {
  const Rig rig = animated_rig();
  FrameSequence sequence(room(), rig, options());
  for (const int frame : {1, 2}) {
    const Image image = sequence.render(frame, Progress::silent());
    const Image still = render_rig(room(), rig_at_frame(rig, frame), options(), Progress::silent());
    const Difference d = difference(image, still);
    EXPECT_LT(d.mean, 0.01) << "frame " << frame;
    EXPECT_LT(d.rms, 0.05) << "frame " << frame;
  }
  // Against the still render of another frame (the lamp 20 cm away, the
  // spot dimmed): not the same.
  EXPECT_GT(difference(sequence.render(2, Progress::silent()),
                       render_rig(room(), rig_at_frame(rig, 1), options(), Progress::silent()))
                .rms,
            0.1);
}

TEST(FrameSequence, OnlyTheLightsThatMovedAreRenderedAgain) {
  Rig rig = animated_rig();
  Light still = rig.lights[0];  // a third light, without keys: in the still part
  still.keys.clear();
  rig.lights.push_back(still);
  FrameSequence sequence(room(), rig, options());
  sequence.render(1, Progress::silent());
  EXPECT_EQ(sequence.stats().still_renders, 1);
  EXPECT_EQ(sequence.stats().light_renders, 2);
  sequence.render(2, Progress::silent());  // the lamp moved; the spot dimmed and recoloured
  EXPECT_EQ(sequence.stats().light_renders, 3);
  EXPECT_EQ(sequence.stats().light_reuses, 1);
  sequence.render(3, Progress::silent());  // the lamp moved; the spot off
  EXPECT_EQ(sequence.stats().light_renders, 4);
  sequence.render(4, Progress::silent());  // the lamp still; the spot on again
  sequence.render(5, Progress::silent());
  EXPECT_EQ(sequence.stats().light_renders, 4);
  EXPECT_EQ(sequence.stats().light_reuses, 1 + 2 + 2);
  EXPECT_EQ(sequence.stats().still_renders, 1);
}

// Without keys a frame is one render: the still render itself, to the bit.
TEST(FrameSequence, ARigWithoutKeysIsTheStillRender) {
  const Rig rig = example::evening_rig();
  FrameSequence sequence(room(), rig, options());
  EXPECT_EQ(sequence.render(7, Progress::silent()).pixels,
            render_rig(room(), rig, options(), Progress::silent()).pixels);
  EXPECT_EQ(sequence.stats().still_renders, 1);
  EXPECT_EQ(sequence.stats().light_renders, 0);
}

// The farm's property: frame 3 alone, in a sequence of its own, is frame 3
// after frames 1 and 2, to the bit.
TEST(FrameSequence, AFrameIsTheSameWhateverWasRenderedBefore) {
  const Rig rig = animated_rig();
  FrameSequence all(room(), rig, options());
  all.render(1, Progress::silent());
  all.render(2, Progress::silent());
  const Image after = all.render(3, Progress::silent());
  FrameSequence alone(room(), rig, options());
  const Image by_itself = alone.render(3, Progress::silent());
  ASSERT_EQ(after.size(), by_itself.size());
  for (size_t i = 0; i < after.size(); ++i) ASSERT_EQ(after.pixels[i], by_itself.pixels[i]) << "pixel " << i;
}

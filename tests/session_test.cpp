// The interactive relighting session on the example room: it converges to
// exactly render_rig's image, an edit re-renders only the light it changes
// (a colour or power change none at all), stale work never reaches the
// screen, other view sizes and the OpenGL backend give the same picture; a
// new sky is previewed at once with the lights kept, turns as a rig's
// forward does, and converges to the offline render too.
#include "relight/session.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <thread>

#include "analysed_room.h"
#include "io/image_io.h"
#include "relight/render_rig.h"
#include "render/render_illumination.h"

using namespace relight;

namespace {

const AnalysedScene& room() { return test::analysed_room(); }

// Cheap refinement, so that the tests converge in a second or two.
SessionOptions quick_options() {
  SessionOptions o;
  o.soft_light_samples = 4;
  o.bounce_paths = 2;
  o.final_render.paths_per_pixel = 4;
  o.final_render.max_bounces = 1;
  o.settle = std::chrono::milliseconds(20);
  return o;
}

Image offline_render(const Rig& rig, const SessionOptions& options) {
  const AnalysedScene& r = room();
  return render_rig(r, rig, options.final_render, Progress::silent());
}

// Where to write images for a look (RELIGHT_TEST_IMAGES=folder), if anywhere.
void keep_image(const std::string& name, const Image& image) {
  if (const char* folder = std::getenv("RELIGHT_TEST_IMAGES")) {
    std::filesystem::create_directories(folder);
    write_png(std::filesystem::path(folder) / (name + ".png"), image);
  }
}

float max_difference(const Image& a, const Image& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  float d = 0.0f;
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i)
    d = std::max(d, (a.pixels[i] - b.pixels[i]).cwiseAbs().maxCoeff());
  return d;
}

Light moved(Light light, const Vec3& by) {
  light.position += by;
  return light;
}

Light sun_light() {
  Light sun;
  sun.name = "sun";
  sun.type = LightType::directional;
  sun.direction = Vec3(0.3f, 0.5f, -0.8f).normalized();
  sun.irradiance = 2.0f;
  return sun;
}

// A new sky for the open-topped room: an equirect image, blue above the
// horizon, dark ground below and a sun 40 degrees up, 60 degrees right of
// forward (+y). Turned by `turn_deg` about up (+z): forward turned so.
RigEnvironment sky(float turn_deg = 0.0f) {
  static const std::shared_ptr<const Probe> image = [] {
    auto probe = std::make_shared<Probe>();
    probe->path = "sky";
    probe->image = Image(128, 64);
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 128; ++x) {
        const float elevation = 90.0f - (y + 0.5f) * 180.0f / 64.0f, azimuth = (x + 0.5f) * 360.0f / 128.0f - 180.0f;
        Vec3 radiance = elevation > 0.0f ? Vec3(0.3f, 0.45f, 0.8f) : Vec3(0.08f, 0.07f, 0.05f);
        if (std::abs(elevation - 40.0f) < 4.0f && std::abs(azimuth - 60.0f) < 4.0f) radiance = Vec3(90, 80, 60);
        probe->image.at(x, y) = radiance;
      }
    return probe;
  }();
  if (turn_deg == 0.0f) return RigEnvironment{Vec3::Zero(), image};
  auto turned = std::make_shared<Probe>(*image);
  const float t = turn_deg * kPi / 180.0f;
  turned->forward = Vec3(-std::sin(t), std::cos(t), 0.0f);
  return RigEnvironment{Vec3::Zero(), turned};
}

Rig evening_under(const RigEnvironment& environment) {
  Rig rig = example::evening_rig();
  rig.environment = environment;
  rig.environment_scale = 1.0f;
  return rig;
}

double tonemapped_psnr(const Image& a, const Image& b) {
  return psnr(tonemap_reinhard_srgb(a), tonemap_reinhard_srgb(b));
}

TEST(Session, ConvergesToExactlyTheOfflineRender) {
  const AnalysedScene& r = room();
  const SessionOptions options = quick_options();
  Rig rig = example::evening_rig();
  RelightSession session(r, rig, options);
  const Frame first = session.wait_until_converged();
  EXPECT_EQ(first.quality, FrameQuality::converged);
  EXPECT_EQ(max_difference(*first.image, offline_render(rig, options)), 0.0f);

  rig.lights[0] = moved(rig.lights[0], Vec3(-0.5f, 0.2f, 0.1f));
  session.set_light(0, rig.lights[0]);
  const Frame second = session.wait_until_converged();
  EXPECT_EQ(max_difference(*second.image, offline_render(rig, options)), 0.0f);
  EXPECT_GT(max_difference(*first.image, *second.image), 0.01f);  // the lamp did move
}

TEST(Session, StaleRendersNeverReachTheFinalImage) {
  const AnalysedScene& r = room();
  const SessionOptions options = quick_options();
  Rig rig = example::evening_rig();
  RelightSession session(r, rig, options);
  // A drag: moves in quick succession, while earlier ones are still rendering.
  for (int i = 1; i <= 8; ++i) {
    rig.lights[1] = moved(rig.lights[1], Vec3(0.05f, 0.0f, 0.0f));
    session.set_light(1, rig.lights[1]);
  }
  const uint64_t last = session.set_environment_scale(0.5f);
  rig.environment_scale = 0.5f;
  const Frame frame = session.wait_until_converged();
  EXPECT_EQ(frame.edit, last);
  EXPECT_EQ(max_difference(*frame.image, offline_render(rig, options)), 0.0f);
}

// Light is linear: a frame is the albedo times the sum of each light's
// cached image times its emission. Refinement is held back (settle) so the
// caches stay as they are.
TEST(Session, RecolouringAndRepoweringCastNoRay) {
  const AnalysedScene& r = room();
  SessionOptions options = quick_options();
  options.settle = std::chrono::hours(1);
  Rig rig = example::evening_rig();
  RelightSession session(r, rig, options);
  const Frame start = session.wait_for_edit(1);
  const SessionStats stats = session.stats();
  EXPECT_EQ(stats.interactive_renders, 2u);

  Light lamp = rig.lights[0];
  lamp.enabled = false;
  const Frame off = session.wait_for_edit(session.set_light(0, lamp));
  lamp.enabled = true;
  lamp.power *= 3.0f;
  lamp.color = rig.lights[0].color.cwiseProduct(Vec3(0.2f, 0.4f, 1.0f));
  const Frame recoloured = session.wait_for_edit(session.set_light(0, lamp));
  const Frame back = session.wait_for_edit(session.set_light(0, rig.lights[0]));
  EXPECT_EQ(session.stats().interactive_renders, stats.interactive_renders);
  EXPECT_EQ(session.stats().refinements, 0u);

  // recoloured - off = 3 x (0.2, 0.4, 1) x (start - off), channel by channel.
  const Vec3 factor = 3.0f * Vec3(0.2f, 0.4f, 1.0f);
  double worst = 0.0, largest = 0.0;
  for (size_t i = 0; i < start.image->size(); ++i) {
    const Vec3 lamp_light = start.image->pixels[i] - off.image->pixels[i];
    const Vec3 expected = lamp_light.cwiseProduct(factor);
    const Vec3 got = recoloured.image->pixels[i] - off.image->pixels[i];
    worst = std::max(worst, double((got - expected).cwiseAbs().maxCoeff()));
    largest = std::max(largest, double(expected.cwiseAbs().maxCoeff()));
  }
  EXPECT_GT(largest, 0.05);
  EXPECT_LT(worst, 1e-5 * largest + 1e-6);
  EXPECT_EQ(max_difference(*back.image, *start.image), 0.0f);
}

TEST(Session, MovingOneLightRendersOnlyThatLight) {
  const AnalysedScene& r = room();
  Rig rig = example::evening_rig();
  RelightSession session(r, rig, quick_options());
  session.wait_until_converged();
  const SessionStats stats = session.stats();
  const Frame frame = session.wait_for_edit(session.set_light(1, moved(rig.lights[1], Vec3(0.3f, 0.0f, 0.0f))));
  EXPECT_EQ(session.stats().interactive_renders, stats.interactive_renders + 1);
  EXPECT_TRUE(frame.image);
}

// A window is told of each new frame as it is published, and may ask the
// session for it from the listener (it is called outside the session's lock).
TEST(Session, TellsItsListenerOfEveryNewFrame) {
  const AnalysedScene& r = room();
  Rig rig = example::evening_rig();
  std::mutex heard_mutex;
  std::condition_variable heard_changed;
  uint64_t heard_edit = 0;
  int calls = 0;
  RelightSession session(r, rig, quick_options());
  session.set_frame_listener([&] {
    const uint64_t edit = session.frame().edit;
    std::lock_guard lock(heard_mutex);
    heard_edit = std::max(heard_edit, edit);
    ++calls;
    heard_changed.notify_all();
  });
  const uint64_t edit = session.set_light(1, moved(rig.lights[1], Vec3(0.3f, 0.0f, 0.0f)));
  std::unique_lock lock(heard_mutex);
  EXPECT_TRUE(heard_changed.wait_for(lock, std::chrono::minutes(2), [&] { return heard_edit >= edit; }));
  const int calls_then = calls;
  lock.unlock();
  session.wait_until_converged();
  lock.lock();
  EXPECT_TRUE(heard_changed.wait_for(lock, std::chrono::minutes(2),
                                     [&] { return calls > calls_then && heard_edit == session.last_edit(); }));
}

TEST(Session, AddsAndRemovesLights) {
  const AnalysedScene& r = room();
  const SessionOptions options = quick_options();
  Rig rig = example::evening_rig();
  RelightSession session(r, rig, options);
  const Light sun = sun_light();
  session.add_light(sun);
  session.remove_light(0);
  rig.lights = {rig.lights[1], sun};
  EXPECT_EQ(session.rig().lights.size(), 2u);
  EXPECT_EQ(max_difference(*session.wait_until_converged().image, offline_render(rig, options)), 0.0f);
}

// Undo of a delete puts a light back in the middle: that light is rendered,
// the others keep their images.
TEST(Session, InsertingALightRendersOnlyThatLight) {
  const AnalysedScene& r = room();
  const SessionOptions options = quick_options();
  Rig rig = example::evening_rig();
  RelightSession session(r, rig, options);
  session.wait_until_converged();
  const SessionStats before = session.stats();
  session.insert_light(1, sun_light());
  rig.lights.insert(rig.lights.begin() + 1, sun_light());
  const Frame frame = session.wait_until_converged();
  EXPECT_EQ(session.stats().interactive_renders, before.interactive_renders + 1);
  ASSERT_EQ(session.rig().lights.size(), 3u);
  EXPECT_EQ(session.rig().lights[1].name, "sun");
  EXPECT_EQ(max_difference(*frame.image, offline_render(rig, options)), 0.0f);
  EXPECT_THROW(session.insert_light(4, sun_light()), std::out_of_range);
}

// Opening a rig: a light that did not move keeps its images (a new colour
// or power costs no ray); a moved or new one is rendered.
TEST(Session, ANewRigRendersOnlyTheLightsThatMovedOrAreNew) {
  const AnalysedScene& r = room();
  const SessionOptions options = quick_options();
  const Rig evening = example::evening_rig();
  RelightSession session(r, evening, options);
  session.wait_until_converged();
  const SessionStats before = session.stats();

  Rig rig = evening;
  rig.lights[0].color = Vec3(1.0f, 0.5f, 0.25f);
  rig.lights[0].power *= 2.0f;
  rig.lights[1] = moved(rig.lights[1], Vec3(0.2f, 0.0f, 0.0f));
  rig.lights.push_back(sun_light());
  rig.environment_scale = 0.5f;
  session.set_rig(rig);
  const Frame frame = session.wait_until_converged();
  EXPECT_EQ(session.stats().interactive_renders, before.interactive_renders + 2);
  EXPECT_EQ(max_difference(*frame.image, offline_render(rig, options)), 0.0f);
  EXPECT_EQ(session.rig().environment_scale, 0.5f);

  // The same rig again: nothing but the final render is done again.
  const SessionStats converged = session.stats();
  session.set_rig(rig);
  EXPECT_EQ(max_difference(*session.wait_until_converged().image, *frame.image), 0.0f);
  EXPECT_EQ(session.stats().interactive_renders, converged.interactive_renders);
  EXPECT_EQ(session.stats().refinements, converged.refinements + 1);
}

// The drop at the end of a drag sets the light the last move left: no edit,
// so the refinement of that position goes on.
TEST(Session, SettingALightAsItIsMakesNoEdit) {
  const AnalysedScene& r = room();
  Rig rig = example::evening_rig();
  RelightSession session(r, rig, quick_options());
  const uint64_t move = session.set_light(1, moved(rig.lights[1], Vec3(0.3f, 0.0f, 0.0f)));
  session.wait_for_edit(move);
  const uint64_t cancelled = session.stats().cancelled;  // whatever the move itself cancelled
  Light renamed = moved(rig.lights[1], Vec3(0.3f, 0.0f, 0.0f));
  renamed.name = "renamed";
  EXPECT_EQ(session.set_light(1, renamed), move);
  EXPECT_EQ(session.last_edit(), move);
  EXPECT_EQ(session.rig().lights[1].name, "renamed");
  const Frame frame = session.wait_until_converged();
  EXPECT_EQ(frame.edit, move);
  EXPECT_EQ(session.stats().cancelled, cancelled);
}

// A view twice the photo's size shows the same picture: averaged down 2x2
// it matches the photo-size render.
TEST(Session, AViewOfAnotherSizeShowsTheSamePicture) {
  const AnalysedScene& r = room();
  SessionOptions options = quick_options();
  options.width = 2 * r.scene().photo.width;
  options.height = 2 * r.scene().photo.height;
  const Rig rig = example::evening_rig();
  RelightSession session(r, rig, options);
  const Image& big = *session.wait_until_converged().image;
  ASSERT_EQ(big.width, options.width);
  Image small(r.scene().photo.width, r.scene().photo.height);
  for (int y = 0; y < small.height; ++y)
    for (int x = 0; x < small.width; ++x)
      small.at(x, y) = 0.25f * (big.at(2 * x, 2 * y) + big.at(2 * x + 1, 2 * y) + big.at(2 * x, 2 * y + 1) +
                                big.at(2 * x + 1, 2 * y + 1));
  const double db = psnr(tonemap_reinhard_srgb(small), tonemap_reinhard_srgb(offline_render(rig, options)));
  std::printf("[ figures  ] room view at 2x the photo's size vs the photo-size render: PSNR %.2f dB\n", db);
  EXPECT_GE(db, 30.0);
}

// A new sky costs one preview of the environment's layer and no light's
// render; the preview looks like the offline render, and the view converges
// to exactly that render.
TEST(Session, ANewSkyIsPreviewedAtOnceWithTheLightsKept) {
  const AnalysedScene& r = room();
  SessionOptions options = quick_options();
  options.settle = std::chrono::hours(1);  // the preview alone
  Rig rig = example::evening_rig();
  rig.environment_scale = 1.0f;
  RelightSession session(r, rig, options);
  const Frame old_sky = session.wait_for_edit(1);
  const SessionStats before = session.stats();
  const Frame preview = session.wait_for_edit(session.set_environment(sky()));
  EXPECT_EQ(preview.quality, FrameQuality::interactive);
  EXPECT_EQ(session.stats().interactive_renders, before.interactive_renders);
  EXPECT_EQ(session.stats().environment_previews, before.environment_previews + 1);
  EXPECT_EQ(session.stats().refinements, 0u);
  ASSERT_TRUE(session.rig().environment);
  EXPECT_EQ(session.rig().environment->image, sky().image);
  const Image offline = offline_render(evening_under(sky()), options);
  keep_image("room_new_sky_preview", *preview.image);
  keep_image("room_new_sky_offline", offline);
  const double preview_db = tonemapped_psnr(*preview.image, offline);
  const double old_db = tonemapped_psnr(*old_sky.image, offline);
  std::printf("[ figures  ] room under a new sky, preview vs offline render: PSNR %.2f dB (the old sky: %.2f dB)\n",
              preview_db, old_db);
  EXPECT_GE(preview_db, 28.0);
  EXPECT_GE(preview_db, old_db + 5.0);
  // The same sky again is no edit.
  EXPECT_EQ(session.set_environment(sky()), session.last_edit());
  EXPECT_EQ(session.stats().environment_previews, before.environment_previews + 1);

  SessionOptions converging_options = quick_options();
  RelightSession converging(r, rig, converging_options);
  converging.set_environment(sky());
  EXPECT_EQ(max_difference(*converging.wait_until_converged().image, offline), 0.0f);
  // Its strength costs no preview and no light's render: the layer is scaled.
  const SessionStats converged = converging.stats();
  converging.set_environment_scale(0.5f);
  Rig weaker = evening_under(sky());
  weaker.environment_scale = 0.5f;
  EXPECT_EQ(max_difference(*converging.wait_until_converged().image, offline_render(weaker, converging_options)),
            0.0f);
  EXPECT_EQ(converging.stats().environment_previews, converged.environment_previews);
  EXPECT_EQ(converging.stats().interactive_renders, converged.interactive_renders);
}

// Turning the sky 90 degrees in the session shows what a rig with its
// forward turned shows: the same preview, bit for bit, and the same
// converged image, the offline render of that rig.
TEST(Session, TurningTheSkyEqualsARigWithItsForwardTurned) {
  const AnalysedScene& r = room();
  SessionOptions options = quick_options();
  options.settle = std::chrono::hours(1);
  const Rig turned = evening_under(sky(90.0f));
  RelightSession session(r, evening_under(sky()), options);
  const Frame unturned = session.wait_for_edit(1);
  const Frame turned_here = session.wait_for_edit(session.set_environment(turned.environment));
  RelightSession started_turned(r, turned, options);
  EXPECT_EQ(max_difference(*turned_here.image, *started_turned.wait_for_edit(1).image), 0.0f);
  const double db = tonemapped_psnr(*turned_here.image, *unturned.image);
  std::printf("[ figures  ] room: the sky turned 90 degrees vs not turned, PSNR %.2f dB\n", db);
  EXPECT_LT(db, 35.0);  // the turn shows

  SessionOptions converging_options = quick_options();
  RelightSession converging(r, evening_under(sky()), converging_options);
  converging.wait_for_edit(1);
  converging.set_environment(turned.environment);
  EXPECT_EQ(max_difference(*converging.wait_until_converged().image, offline_render(turned, converging_options)),
            0.0f);
  // Back to the scene's own sky (a rig without `environment`).
  Rig own = turned;
  own.environment.reset();
  converging.set_rig(own);
  EXPECT_FALSE(converging.rig().environment);
  EXPECT_EQ(max_difference(*converging.wait_until_converged().image, offline_render(own, converging_options)), 0.0f);
}

// At twice the photo's size the new sky shows past the geometry and lights
// it as at the photo's: averaged down 2x2, the converged view matches the
// offline render.
TEST(Session, AViewOfAnotherSizeShowsTheNewSkyToo) {
  const AnalysedScene& r = room();
  SessionOptions options = quick_options();
  options.width = 2 * r.scene().photo.width;
  options.height = 2 * r.scene().photo.height;
  const Rig rig = evening_under(sky(30.0f));
  RelightSession session(r, rig, options);
  const Image& big = *session.wait_until_converged().image;
  Image small(r.scene().photo.width, r.scene().photo.height);
  for (int y = 0; y < small.height; ++y)
    for (int x = 0; x < small.width; ++x)
      small.at(x, y) = 0.25f * (big.at(2 * x, 2 * y) + big.at(2 * x + 1, 2 * y) + big.at(2 * x, 2 * y + 1) +
                                big.at(2 * x + 1, 2 * y + 1));
  const double db = tonemapped_psnr(small, offline_render(rig, options));
  std::printf("[ figures  ] room under a new sky, view at 2x the photo's size vs the offline render: PSNR %.2f dB\n",
              db);
  EXPECT_GE(db, 30.0);
}

TEST(Session, FallsBackToTheCpuWithoutOpenGL) {
  const AnalysedScene& r = room();
  SessionOptions options = quick_options();
  options.backend = Backend::gl;
  setenv("RELIGHT_GL", "off", 1);
  RelightSession session(r, example::evening_rig(), options);
  unsetenv("RELIGHT_GL");
  EXPECT_EQ(session.backend(), Backend::cpu);
  EXPECT_NE(session.backend_note().find("OpenGL unavailable"), std::string::npos);
  EXPECT_TRUE(session.wait_for_edit(1).image);
}

// The OpenGL backend's frames while a light moves look like the CPU
// backend's, and the session still converges to the offline render.
TEST(Session, OpenGLBackendShowsTheSameAndConvergesTheSame) {
  const AnalysedScene& r = room();
  SessionOptions options = quick_options();
  options.settle = std::chrono::hours(1);  // no refinement: compare the interactive frames
  options.backend = Backend::gl;
  const Rig rig = example::evening_rig();
  RelightSession gl(r, rig, options);
  if (gl.backend() != Backend::gl) GTEST_SKIP() << gl.backend_note();
  options.backend = Backend::cpu;
  RelightSession cpu(r, rig, options);
  const Frame on_gl = gl.wait_for_edit(1), on_cpu = cpu.wait_for_edit(1);
  EXPECT_EQ(on_gl.quality, FrameQuality::interactive);
  keep_image("room_interactive_gl", *on_gl.image);
  keep_image("room_interactive_cpu", *on_cpu.image);
  const double db = psnr(tonemap_reinhard_srgb(*on_gl.image), tonemap_reinhard_srgb(*on_cpu.image));
  std::printf("[ figures  ] room interactive frame, OpenGL vs CPU backend: PSNR %.2f dB\n", db);
  EXPECT_GE(db, 30.0);

  options.backend = Backend::gl;
  options.settle = std::chrono::milliseconds(20);
  RelightSession converging(r, rig, options);
  EXPECT_EQ(max_difference(*converging.wait_until_converged().image, offline_render(rig, options)), 0.0f);
}

}  // namespace

namespace {

// The room with a glossy floor and ball, analysed.
const AnalysedScene& glossy_room() {
  static const std::unique_ptr<AnalysedScene> r =
      test::analyse_room({{"floor", Gloss{0.3f, 0.5f}}, {"ball", Gloss{0.2f, 0.5f}}});
  return *r;
}

// The projection of `change` on `highlights` times the coverage: 1 where
// the change is those highlights, 0 where it holds none of them.
double share_of_highlights(const Image& change, const Image& highlights, const std::vector<float>& coverage) {
  double along = 0.0, norm = 0.0;
  for (size_t i = 0; i < highlights.size(); ++i) {
    const Vec3 h = coverage[i] * highlights.pixels[i];
    along += change.pixels[i].dot(h);
    norm += h.dot(h);
  }
  return along / norm;
}

Image difference(const Image& a, const Image& b) {
  Image d(a.width, a.height);
  for (size_t i = 0; i < d.size(); ++i) d.pixels[i] = a.pixels[i] - b.pixels[i];
  return d;
}

TEST(Session, GlossySurfacesShowTheHighlightsWhileALightMovesAndConvergeToTheOfflineRender) {
  const AnalysedScene& r = glossy_room();
  SessionOptions options = quick_options();
  options.bounce_paths = 64;
  options.final_render.paths_per_pixel = 64;
  // Refinement waits long enough for the interactive frame to be caught.
  options.settle = std::chrono::milliseconds(1000);
  Rig rig = example::evening_rig();
  rig.lights.resize(1);  // the lamp
  RelightSession session(r, rig, options);
  const Frame at_first_place = session.wait_until_converged();

  // The lamp dragged 60 cm along the wall: the frame that first shows it
  // there, against the frame it converges to.
  const NewIllumination renderer(r);
  const auto lit_by = [](const Rig& lit) {
    Lighting lighting;
    lighting.lights = lit.lights;
    return lighting;
  };
  const Image own_highlights_before =
      renderer.highlight_parts(r.gbuffer(), r.scene().camera, lit_by(rig), options.final_render, Progress::silent())
          .lights;
  rig.lights[0].position += Vec3(-0.6f, 0.0f, 0.0f);
  const Frame moved = session.wait_for_edit(session.set_light(0, rig.lights[0]));
  ASSERT_EQ(moved.quality, FrameQuality::interactive);
  const Frame converged = session.wait_until_converged();
  const Image highlights_after =
      renderer.highlights(r.gbuffer(), r.scene().camera, lit_by(rig), options.final_render, Progress::silent());
  ASSERT_FALSE(highlights_after.empty());
  const Image left = difference(*converged.image, *moved.image);
  const std::vector<float>& coverage = r.analysis().coverage;
  // What the converged frame adds to the moving one: little of the lamp's
  // highlights where it now is (its own move with it; the surfaces the
  // floor mirrors are lit as they were, as its bounce light is), and next
  // to none of its own where it was (-1: left behind there).
  const double of_new = share_of_highlights(left, highlights_after, coverage);
  const double of_old = share_of_highlights(left, own_highlights_before, coverage);
  std::printf(
      "[ figures  ] the lamp moved: the converged frame adds %.3f of its highlights there, %.3f of its own "
      "where it was\n",
      of_new, of_old);
  EXPECT_LT(std::abs(of_new), 0.25);
  EXPECT_GT(of_old, -0.3);
  keep_image("glossy_moved", *moved.image);
  keep_image("glossy_converged", *converged.image);
  keep_image("glossy_first_place", *at_first_place.image);
  EXPECT_EQ(max_difference(*converged.image, render_rig(r, rig, options.final_render, Progress::silent())), 0.0f);
}

}  // namespace

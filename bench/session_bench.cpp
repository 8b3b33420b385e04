// The interactive engine: frame time while dragging one light of eight (one
// of each type in turn), for each backend at 640x480, 1280x720 and 1920x1080, and the
// time the view takes to
// converge (to the render of `relight render`) once the light is let go;
// and one light's render by each backend alone. The CPU column is the
// process's CPU time (all threads) per frame: on a busy machine, half of it
// is about what a frame takes on two idle cores.
// On the reference scene `bookcase` where ../shared/scenes holds it
// (RELIGHT_SCENES overrides), else on the example room. And a new sky
// turning on the outdoor scene: from the turn to the frame that shows it.
// Results and the machine they ran on: docs/benchmarks.md, "Interactive
// relighting". And a dragged lamp's highlights on a glossy view alone.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/statistics.h"
#include "io/scene_io.h"
#include "relight/session.h"
#include "render/specular.h"
#include "room_scene.h"

using namespace relight;
namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

fs::path reference_scene(const std::string& name) {
  if (const char* env = std::getenv("RELIGHT_SCENES")) return fs::path(env) / name;
  return fs::path(RELIGHT_SOURCE_DIR) / ".." / "shared" / "scenes" / name;
}

// A quick analysis: the engine's speed does not depend on how good the albedo is.
std::unique_ptr<AnalysedScene> quick_analysis(Scene scene) {
  std::fprintf(stderr, "session_bench: scene %s (%zu triangles)\n", scene.path.string().c_str(),
               scene.mesh.triangles.size());
  AnalysisOptions options;
  options.strategy = Strategy::lights;
  options.paths_per_pixel = 4;
  options.interreflection = false;
  return AnalysedScene::analyse(std::move(scene), options, Progress::silent());
}

// The scene, with a quick analysis.
struct Fixture {
  std::unique_ptr<AnalysedScene> analysed;
  Rig rig;

  Fixture() {
    Scene scene;
    const fs::path folder = reference_scene("bookcase");
    if (fs::exists(folder / "scene.json")) {
      scene = load_scene(folder / "scene.json");
    } else {
      scene = example::room_scene(640, 480);
      scene.path = "room";
      scene.photo = Image(640, 480, Vec3::Constant(0.2f));
    }
    analysed = quick_analysis(std::move(scene));
    rig = eight_lights();
  }
  const Scene& scene() const { return analysed->scene(); }

  // One light of each type (the ones dragged: a point, a spot, an area
  // light, a soft point and a sun), and three more to compose with, placed
  // around what the camera looks at.
  Rig eight_lights() const {
    const CameraSpec& camera = scene().camera.spec();
    const Vec3 target = camera.look_at, to_camera = camera.position - target;
    const float d = to_camera.norm();
    const Vec3 up = camera.up.normalized(), side = to_camera.cross(up).normalized();
    const Vec3 front = target + 0.5f * to_camera;
    Rig r;
    r.environment_scale = 0.5f;
    Light point;
    point.type = LightType::point;
    point.name = "point";
    point.position = front + 0.3f * d * side + 0.3f * d * up;
    point.power = 40.0f * d * d;
    Light spot = point;
    spot.type = LightType::spot;
    spot.name = "spot";
    spot.position = front - 0.3f * d * side + 0.4f * d * up;
    spot.direction = (target - spot.position).normalized();
    spot.spot_angle_deg = 40.0f;
    spot.blend = 0.2f;
    spot.color = Vec3(0.6f, 0.8f, 1.0f);
    Light area;
    area.type = LightType::area;
    area.name = "area";
    area.position = front + 0.5f * d * up;
    area.direction = (target - area.position).normalized();
    area.up = up;
    area.size = Vec2(0.15f * d, 0.15f * d);
    area.power = 20.0f * d * d;
    Light soft = point;
    soft.name = "soft point";
    soft.position = front - 0.4f * d * side + 0.1f * d * up;
    soft.radius = 0.03f * d;
    soft.color = Vec3(1.0f, 0.7f, 0.4f);
    Light sun;
    sun.type = LightType::directional;
    sun.name = "sun";
    sun.position = target + d * (side + up);  // where the drag circles; a sun's light comes from its direction
    sun.direction = (target - sun.position).normalized();
    sun.irradiance = 10.0f;
    sun.angle_deg = 0.5f;
    Light fill = point, rim = spot, top = area;
    fill.name = "fill";
    fill.position = front - 0.2f * d * side;
    fill.power *= 0.3f;
    rim.name = "rim";
    rim.position = target - 0.3f * to_camera + 0.5f * d * up;
    rim.direction = (target - rim.position).normalized();
    top.name = "top";
    top.position = target + 0.8f * d * up;
    top.direction = -up;
    r.lights = {point, spot, area, soft, sun, fill, rim, top};
    return r;
  }
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

const int kSizes[3][2] = {{640, 480}, {1280, 720}, {1920, 1080}};

// The one open session: one at a time, so that no other session's
// refinement runs beside what is measured. Made after the fixture, so
// destroyed before it at exit (the session refers to the fixture's scene).
std::unique_ptr<RelightSession>& open_session() {
  fixture();
  static std::unique_ptr<RelightSession> s;
  return s;
}

// The session for a backend and size.
RelightSession& session(Backend backend, int size) {
  std::unique_ptr<RelightSession>& s = open_session();
  static std::pair<Backend, int> made_for;
  if (!s || made_for != std::pair{backend, size}) {
    s.reset();
    made_for = {backend, size};
    Fixture& f = fixture();
    SessionOptions options;
    options.backend = backend;
    options.width = kSizes[size][0];
    options.height = kSizes[size][1];
    s = std::make_unique<RelightSession>(*f.analysed, f.rig, options);
    s->wait_for_edit(1);
  }
  return *s;
}

// Light `index` one step further around a circle about where it started (a
// sun turned with it: its direction follows the circle's point).
Light dragged(int index, int step) {
  const Fixture& f = fixture();
  Light light = f.rig.lights[size_t(index)];
  const float radius = 0.1f * (f.scene().camera.spec().position - f.scene().camera.spec().look_at).norm();
  const float angle = 0.1f * float(step);
  Vec3 a, b;
  orthonormal_basis(f.scene().camera.spec().up.normalized(), a, b);
  light.position += radius * (std::cos(angle) * a + std::sin(angle) * b);
  if (light.type == LightType::directional)
    light.direction = (f.scene().camera.spec().look_at - light.position).normalized();
  return light;
}

// Arguments: backend (0 cpu, 1 gl), size (0: 640x480, 1: 1280x720, 2:
// 1920x1080), the
// light dragged (0 point, 1 spot, 2 area, 3 soft point, 4 sun).
void BM_DragOneLightOfEight(benchmark::State& state) {
  const Backend backend = state.range(0) ? Backend::gl : Backend::cpu;
  const int size = int(state.range(1)), index = int(state.range(2));
  RelightSession& s = session(backend, size);
  if (s.backend() != backend) {
    state.SkipWithError(("OpenGL unavailable: " + s.backend_note()).c_str());
    return;
  }
  std::vector<double> ms;
  int step = 0;
  for (auto _ : state) {
    const auto start = Clock::now();
    s.wait_for_edit(s.set_light(size_t(index), dragged(index, ++step)));
    const double secs = std::chrono::duration<double>(Clock::now() - start).count();
    state.SetIterationTime(secs);
    ms.push_back(1e3 * secs);
  }
  s.set_light(size_t(index), fixture().rig.lights[size_t(index)]);
  state.counters["median_ms"] = percentile(ms, 0.5);
  state.counters["p95_ms"] = percentile(ms, 0.95);
  state.SetLabel(std::string(to_string(backend)) + " " + std::to_string(kSizes[size][0]) + "x" +
                 std::to_string(kSizes[size][1]) + " dragging the " + fixture().rig.lights[size_t(index)].name);
}
BENCHMARK(BM_DragOneLightOfEight)
    ->ArgsProduct({{0, 1}, {0, 1, 2}, {0, 1, 2, 3, 4}})
    ->Iterations(60)
    ->MeasureProcessCPUTime()
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

// One light's interactive render by a backend alone, outside a session: how
// much of a frame is the backend's (the rest is composing the frame and
// handing it over). Real time and the process's CPU time (both cores).
// Arguments as BM_DragOneLightOfEight's, but backend 2: OpenGL shading by
// fragment shader where it would by compute shader (on a GPU).
void BM_BackendRender(benchmark::State& state) {
  const int size = int(state.range(1)), index = int(state.range(2));
  Fixture& f = fixture();
  open_session().reset();  // its refinement would run beside the backend
  const AnalysedScene& a = *f.analysed;
  const RelightView view(a, kSizes[size][0], kSizes[size][1]);
  std::unique_ptr<DirectLightBackend> backend;
  CpuDirectLight* cpu = nullptr;
  if (state.range(0)) {
    std::string why;
    ShadowMapOptions options;
    if (state.range(0) == 2) options.shading = ShadowMapOptions::Shading::fragment;
    backend = GlRelighter::open(a.scene().mesh, view.surfaces(), options, why);
    if (!backend) {
      state.SkipWithError(("OpenGL unavailable: " + why).c_str());
      return;
    }
  } else {
    backend = std::make_unique<CpuDirectLight>(view.surfaces(), a.rays());
    cpu = static_cast<CpuDirectLight*>(backend.get());
  }
  Image out;
  int step = 0;
  size_t rays = 0;
  for (auto _ : state) {
    const Light light = unit_light(dragged(index, ++step));
    if (cpu)
      rays += cpu->render_counting_rays(light, out);
    else
      backend->render(light, out);
  }
  if (cpu) state.counters["rays_per_pixel"] = double(rays) / double(state.iterations() * out.pixels.size());
  const std::string device = cpu ? ""
                                 : " (" + static_cast<GlRelighter*>(backend.get())->renderer() +
                                       (state.range(0) == 2 ? ", fragment shader)" : ")");
  state.SetLabel(std::string(backend->name()) + device + " " + std::to_string(view.width()) + "x" +
                 std::to_string(view.height()) + " " + f.rig.lights[size_t(index)].name);
}
BENCHMARK(BM_BackendRender)
    ->ArgsProduct({{0, 1, 2}, {0, 1, 2}, {0, 1, 2, 3, 4}})
    ->Iterations(30)
    ->MeasureProcessCPUTime()
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// From letting go of the dragged point light to the converged frame (the
// final render at relight render's defaults: 64 paths per pixel, 4 bounces),
// starting from a converged view.
void BM_ConvergeAfterRelease(benchmark::State& state) {
  const Backend backend = state.range(0) ? Backend::gl : Backend::cpu;
  RelightSession& s = session(backend, int(state.range(1)));
  if (s.backend() != backend) {
    state.SkipWithError(("OpenGL unavailable: " + s.backend_note()).c_str());
    return;
  }
  s.wait_until_converged();
  int step = 0;
  for (auto _ : state) {
    s.wait_for_edit(s.set_light(0, dragged(0, ++step)));
    const auto start = Clock::now();
    s.wait_until_converged();
    state.SetIterationTime(std::chrono::duration<double>(Clock::now() - start).count());
  }
}
BENCHMARK(BM_ConvergeAfterRelease)
    ->ArgsProduct({{0, 1}, {0, 1}})
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

// A new sky on the outdoor scene (640x480, CPU backend): the rig of
// tests/data/new_sky/outdoor_sunset_90.json (the sunset HDRI alone), turned
// 10 degrees further about up per iteration. Each iteration times the turn
// (a new probe: the image copied, its sampling table built) to the frame
// that shows it, at preview quality, as in a drag (no refinement between);
// and, once let go, the time to the converged frame (converged_s). Skipped
// without the outdoor scene.
void BM_TurnTheSky(benchmark::State& state) {
  const fs::path folder = reference_scene("outdoor");
  if (!fs::exists(folder / "scene.json")) {
    state.SkipWithError(("no scene at " + folder.string()).c_str());
    return;
  }
  open_session().reset();  // no other session refining beside this one
  const auto analysed = quick_analysis(load_scene(folder / "scene.json"));
  const Rig rig = load_rig(fs::path(RELIGHT_SOURCE_DIR) / "tests" / "data" / "new_sky" / "outdoor_sunset_90.json");
  RelightSession session(*analysed, rig);
  session.wait_for_edit(1);
  std::vector<double> ms;
  int step = 0;
  for (auto _ : state) {
    const auto start = Clock::now();
    const Frame frame =
        session.wait_for_edit(session.set_environment(turned_environment(*rig.environment, 10.0f * float(++step))));
    const double secs = std::chrono::duration<double>(Clock::now() - start).count();
    state.SetIterationTime(secs);
    ms.push_back(1e3 * secs);
    if (frame.quality != FrameQuality::interactive) state.SkipWithError("the turn's frame was not the preview");
  }
  state.counters["median_ms"] = percentile(ms, 0.5);
  state.counters["p95_ms"] = percentile(ms, 0.95);
  state.counters["previews"] = double(session.stats().environment_previews);
  // Let go: the refinement and the final render (relight render's, 64
  // paths per pixel) after the last turn.
  const auto released = Clock::now();
  session.wait_until_converged();
  state.counters["converged_s"] = std::chrono::duration<double>(Clock::now() - released).count();
  state.SetLabel("cpu " + std::to_string(session.view().width()) + "x" + std::to_string(session.view().height()) +
                 " turning the sunset sky of outdoor");
}
BENCHMARK(BM_TurnTheSky)->Iterations(30)->MeasureProcessCPUTime()->UseManualTime()->Unit(benchmark::kMillisecond);

// A dragged lamp's highlights on the glossy bookcase of tests/data/glossy
// (its floor and blue ball glossy) at 1280x960, outside a session: the CPU
// backend's render of its direct light, and MovingHighlights from it (what
// a frame adds on a glossy view). Real time, both cores.
void BM_MovingHighlights(benchmark::State& state) {
  open_session().reset();
  const fs::path folder = fs::path(RELIGHT_SOURCE_DIR) / "tests" / "data" / "glossy" / "glossy_bookcase";
  const Scene scene = load_scene(folder / "scene.json");
  const Camera camera(scene.camera.spec(), 1280, 960);
  const RayScene rays(scene.mesh);
  const GBuffer gbuffer(camera, rays, 1, 1, "moving highlights");
  const PixelSurfaces surfaces = PixelSurfaces::central_samples(gbuffer);
  const Light lamp = unit_light(load_rig(folder / "rigs" / "move_lamp.json").lights[0]);
  CpuDirectLight backend(surfaces, rays);
  const MovingHighlights highlights(surfaces, scene.gloss, camera.position());
  Image direct, out(camera.width(), camera.height());
  backend.render(lamp, direct);
  const bool only_highlights = state.range(0) == 1;
  for (auto _ : state) {
    if (only_highlights)
      highlights.render(lamp, direct, out);
    else
      backend.render(lamp, direct);
  }
  state.counters["glossy_pixels"] = double(highlights.pixels().size());
  state.SetLabel(only_highlights ? "moving highlights" : "cpu backend's direct light");
}
BENCHMARK(BM_MovingHighlights)->Arg(0)->Arg(1)->Iterations(50)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

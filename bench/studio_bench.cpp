// relight studio's own cost on top of the relighting session: turning a
// session frame into the picture on screen (exposure, sRGB, 8 bits), and
// redrawing the geometry view while it orbits (the mesh, back to front with
// QPainter). On the reference scene `bookcase` where ../shared/scenes holds
// it (RELIGHT_SCENES overrides), else on the example room. And a new sky
// turned through the document, as the sky strip's drag does, on the outdoor
// scene. And a light dragged while a full analysis runs behind the
// picture, and one dragged in the window itself. Offscreen: no display needed. Results: docs/benchmarks.md,
// "relight studio".
#include <benchmark/benchmark.h>

#include <QApplication>
#include <QElapsedTimer>
#include <QEventLoop>
#include <QImage>
#include <QTimer>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <thread>

#include "analysis/analysis_folder.h"
#include "analysis/strategy.h"
#include "core/background_work.h"
#include "core/error.h"
#include "core/statistics.h"
#include "gui/geometry_overlay.h"
#include "gui/geometry_view.h"
#include "gui/main_window.h"
#include "gui/photo_view.h"
#include "gui/sky_strip.h"
#include "gui/tone_map.h"
#include "io/image_io.h"
#include "io/scene_io.h"
#include "room_scene.h"

using namespace relight;
using namespace relight::gui;
namespace fs = std::filesystem;

namespace {

fs::path reference_scene(const std::string& name) {
  if (const char* env = std::getenv("RELIGHT_SCENES")) return fs::path(env) / name;
  return fs::path(RELIGHT_SOURCE_DIR) / ".." / "shared" / "scenes" / name;
}

std::shared_ptr<StudioScene> bench_scene(const std::string& name = "bookcase") {
  const fs::path folder = reference_scene(name);
  Scene scene;
  if (fs::exists(folder / "scene.json")) {
    scene = load_scene(folder / "scene.json");
  } else {
    scene = example::room_scene(640, 480);
    scene.photo = Image(640, 480, Vec3::Constant(0.2f));
  }
  std::fprintf(stderr, "studio_bench: %zu triangles\n", scene.mesh.triangles.size());
  // A quick analysis: the view's speed does not depend on the albedo.
  AnalysisOptions options;
  options.strategy = Strategy::lights;
  options.paths_per_pixel = 2;
  options.interreflection = false;
  auto s = std::make_shared<StudioScene>();
  s->analysed = AnalysedScene::analyse(std::move(scene), options, Progress::silent());
  return s;
}

void BM_DisplayFrame(benchmark::State& state) {
  const Image frame(int(state.range(0)), int(state.range(1)), Vec3(0.3f, 0.2f, 0.1f));
  for (auto _ : state) benchmark::DoNotOptimize(to_qimage(frame, 0.5f));
  state.SetItemsProcessed(state.iterations() * frame.width * frame.height);
}
BENCHMARK(BM_DisplayFrame)->Args({640, 480})->Args({1280, 720})->Unit(benchmark::kMillisecond);

// The geometry's edges drawn over the photo (Ctrl+G), made once per opened
// analysis: the example room at the photo's size, the analysis's G-buffer.
void BM_GeometryEdges(benchmark::State& state) {
  const Scene scene = example::room_scene(int(state.range(0)), int(state.range(1)));
  const RayScene rays(scene.mesh);
  const GBuffer gbuffer(scene.camera, rays, AnalysisOptions().gbuffer_samples, 1, "room");
  for (auto _ : state) benchmark::DoNotOptimize(geometry_edges_image(gbuffer));
  state.SetItemsProcessed(state.iterations() * gbuffer.width() * gbuffer.height());
}
BENCHMARK(BM_GeometryEdges)->Args({640, 480})->Args({3264, 2448})->Unit(benchmark::kMillisecond);

void BM_GeometryViewOrbit(benchmark::State& state) {
  static const std::shared_ptr<StudioScene> scene = bench_scene();
  SessionOptions options;
  options.settle = std::chrono::hours(1);  // no refinement running beside the measurement
  LightingDocument document(scene, rig_from_scene(scene->analysed->scene()), options);
  document.session().wait_for_edit(1);
  GeometryView view;
  view.resize(int(state.range(0)), int(state.range(1)));
  view.set_document(&document);
  QImage target(view.size(), QImage::Format_RGB32);
  const float distance = 1.3f * scene->analysed->scene().mesh.bounds().diagonal().norm();
  float yaw = 0.0f;
  for (auto _ : state) {
    view.set_orbit(yaw += 1.0f, 35.0f, distance);  // every frame redraws the mesh
    view.render(&target);
  }
  state.counters["triangles"] = double(scene->analysed->scene().mesh.triangles.size());
}
BENCHMARK(BM_GeometryViewOrbit)->Args({420, 320})->Args({800, 600})->Unit(benchmark::kMillisecond);

// The outdoor scene (640x480, CPU backend) under tests/data/new_sky's sunset
// HDRI, turned 10 degrees further per iteration through the document (the
// strip's drag): from the turn to its frame at preview quality made the
// picture on screen. Skipped without the outdoor scene.
void BM_TurnTheSkyInTheStudio(benchmark::State& state) {
  if (!fs::exists(reference_scene("outdoor") / "scene.json")) {
    state.SkipWithError("no outdoor scene");
    return;
  }
  static const std::shared_ptr<StudioScene> scene = bench_scene("outdoor");
  const Rig rig = load_rig(fs::path(RELIGHT_SOURCE_DIR) / "tests" / "data" / "new_sky" / "outdoor_sunset_90.json");
  LightingDocument document(scene, rig, SessionOptions{});
  document.session().wait_for_edit(1);
  std::vector<double> ms;
  SkyEdit sky = document.sky();
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    sky.turn_deg = wrapped_turn(sky.turn_deg + 10.0f);
    document.set_sky(sky);
    const Frame frame = document.session().wait_for_edit(document.session().last_edit());
    benchmark::DoNotOptimize(to_qimage(*frame.image, 0.0f));
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    state.SetIterationTime(secs);
    ms.push_back(1e3 * secs);
  }
  state.counters["median_ms"] = percentile(ms, 0.5);
  state.counters["p95_ms"] = percentile(ms, 0.95);
}
BENCHMARK(BM_TurnTheSkyInTheStudio)->Iterations(30)->MeasureProcessCPUTime()->UseManualTime()->Unit(benchmark::kMillisecond);

// Dragging the scene's first light at 1280x720 (CPU backend, the window's
// frame as the document gives it) alone (0), and while a full analysis of
// the same scene runs behind the picture, as the full analysis after a
// large photo's preview does: on a thread like any other (1), and given
// way as BackgroundTask runs it (2). Counters: the drag's median and 95th
// percentile frame time, and how many analyses were done meanwhile.
void BM_DragWhileAnalysing(benchmark::State& state) {
  static const std::shared_ptr<StudioScene> scene = bench_scene();
  const Scene& photo_scene = scene->analysed->scene();
  SessionOptions options;
  options.backend = Backend::cpu;
  options.width = 1280;
  options.height = 720;
  const Rig rig = rig_from_scene(photo_scene);
  LightingDocument document(scene, rig, options);
  document.session().wait_for_edit(1);

  Progress analysis_progress(false);
  std::atomic<int> analyses{0};
  const auto analyse = [&] {
    try {
      while (true) {
        AnalysedScene::analyse(Scene(photo_scene), AnalysisOptions{}, analysis_progress);
        ++analyses;
      }
    } catch (const Cancelled&) {
    }
  };
  const int mode = int(state.range(0));
  std::thread behind;
  if (mode == 1) behind = std::thread(analyse);
  if (mode == 2) behind = std::thread([&] { run_giving_way(analyse); });
  if (mode) std::this_thread::sleep_for(std::chrono::seconds(2));  // into its renders

  std::vector<double> ms;
  int step = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    Light light = rig.lights.front();
    light.position += 0.3f * Vec3(std::cos(0.1f * float(step)), std::sin(0.1f * float(step)), 0.0f);
    ++step;
    document.set_light(0, light);
    const Frame frame = document.session().wait_for_edit(document.session().last_edit());
    benchmark::DoNotOptimize(to_qimage(*frame.image, 0.0f));
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    state.SetIterationTime(secs);
    ms.push_back(1e3 * secs);
  }
  const double analysed = analyses + analysis_progress.job_fraction();
  analysis_progress.cancel();
  if (behind.joinable()) behind.join();
  state.counters["median_ms"] = percentile(ms, 0.5);
  state.counters["p95_ms"] = percentile(ms, 0.95);
  state.counters["analyses_done"] = analysed;
  state.SetLabel(mode == 0 ? "no analysis behind" : mode == 1 ? "analysis on a plain thread" : "analysis giving way");
}
BENCHMARK(BM_DragWhileAnalysing)
    ->DenseRange(0, 2)
    ->Iterations(120)
    ->MeasureProcessCPUTime()
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

// The example room with its photo enlarged to w x h (each pixel the
// nearest of the original's), in a folder of its own.
fs::path enlarged_room(int w, int h) {
  const fs::path room = fs::path(RELIGHT_SOURCE_DIR) / "examples" / "room";
  const fs::path folder = fs::temp_directory_path() / ("relight_studio_bench_room_" + std::to_string(w));
  fs::remove_all(folder);
  fs::create_directories(folder);
  for (const char* f : {"scene.json", "geometry.obj"}) fs::copy_file(room / f, folder / f);
  const Image small = read_image(room / "photo.exr");
  Image photo(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) photo.at(x, y) = small.at(x * small.width / w, y * small.height / h);
  write_exr(folder / "photo.exr", photo);
  return folder;
}

// The enlarged room analysed quickly into SCENE/analysis: what relight
// studio opens in BM_OpenLargePhoto.
fs::path large_room(int w, int h) {
  const fs::path folder = enlarged_room(w, h);
  Scene scene = load_scene(folder / "scene.json");
  AnalysisOptions options;
  options.strategy = default_strategy(scene);
  options.paths_per_pixel = 1;
  options.interreflection = false;
  const auto analysed = AnalysedScene::analyse(std::move(scene), options, Progress::silent());
  save_analysis(folder / "analysis", analysed->analysis(), analysed->scene());
  return folder;
}

// A timer asking the window's event loop every 5 ms: the longest it went
// without turning is how long the window froze.
class StallWatch {
 public:
  StallWatch() {
    QObject::connect(&ticks_, &QTimer::timeout, [this] { longest_ = std::max(longest_, since_tick_.restart()); });
    since_tick_.start();
    ticks_.start(5);
  }
  qint64 longest_ms() const { return longest_; }

 private:
  QTimer ticks_;
  QElapsedTimer since_tick_;
  qint64 longest_ = 0;
};

// relight studio as the benches run it: the CPU backend, nothing
// remembered, a window of `size` shown.
std::unique_ptr<MainWindow> shown_window(QSize size) {
  StudioOptions options;
  options.session.backend = Backend::cpu;
  options.remember_recent = false;
  auto window = std::make_unique<MainWindow>(options);
  window->resize(size);
  window->show();
  return window;
}

// Opens the scene in `folder` in `window` (with its analysis folder
// SCENE/analysis where `analysed`), the event loop turning until it is
// shown and, where a preview came first, until the full analysis took its
// place; then 500 ms more (its first frames). Returns the seconds until it
// was first shown.
double open_in(MainWindow& window, const fs::path& folder, bool analysed) {
  QElapsedTimer clock;
  double shown_s = 0.0;
  QEventLoop loop;
  QObject::connect(&window, &MainWindow::sceneOpened, &loop, [&] {
    shown_s = double(clock.elapsed()) / 1e3;
    if (!window.document()->studio_scene().preview) loop.quit();
  });
  QObject::connect(&window, &MainWindow::fullAnalysisDone, &loop, &QEventLoop::quit);
  QObject::connect(&window, &MainWindow::openFailed, &loop, &QEventLoop::quit);
  clock.start();
  window.open_scene(QString::fromStdString((folder / "scene.json").string()), {},
                    analysed ? QString::fromStdString((folder / "analysis").string()) : QString());
  loop.exec();
  QTimer::singleShot(500, &loop, &QEventLoop::quit);
  loop.exec();
  return shown_s;
}

// One iteration of the benches below: a window opens the scene in `folder`
// (open_in), the iteration's time is how long that took, and the counter
// longest_stall_ms how long the window froze meanwhile. Returns the seconds
// until the scene was first shown.
double time_opening(benchmark::State& state, const fs::path& folder, bool analysed) {
  const auto window = shown_window({1200, 800});
  QElapsedTimer clock;
  clock.start();
  const StallWatch stalls;
  const double shown_s = open_in(*window, folder, analysed);
  state.SetIterationTime(double(clock.elapsed()) / 1e3);
  state.counters["longest_stall_ms"] = double(stalls.longest_ms());
  return shown_s;
}

// relight studio opening an analysed photo of w x h: the time until the
// scene is shown, and the longest the window's event loop went without
// turning meanwhile (a timer asks every 5 ms): how long the window froze.
void BM_OpenLargePhoto(benchmark::State& state) {
  const fs::path folder = large_room(int(state.range(0)), int(state.range(1)));
  for (auto _ : state) time_opening(state, folder, true);
  fs::remove_all(folder);
}
BENCHMARK(BM_OpenLargePhoto)
    ->Args({640, 480})
    ->Args({3264, 2448})
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

// relight studio opening a photo of w x h it has no analysis of, at the
// defaults: a preview analysis shown first, the full one run behind it and
// put in its place. Counters: seconds until the preview is shown and until
// the full analysis is, and the longest the window froze over all of it.
void BM_AnalyseLargePhoto(benchmark::State& state) {
  const fs::path folder = enlarged_room(int(state.range(0)), int(state.range(1)));
  for (auto _ : state) state.counters["preview_s"] = time_opening(state, folder, false);
  fs::remove_all(folder);
}
BENCHMARK(BM_AnalyseLargePhoto)
    ->Args({5658, 4243})  // 24 Mpixel
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

// A light dragged in relight studio itself, 1280x960 (the example room's
// photo enlarged, CPU backend): from the edit to the window painting its
// frame — the session's render, the window being told of it, the display
// encoding, the picture painted. Counters: the median and 95th percentile.
void BM_DragOnScreen(benchmark::State& state) {
  const fs::path folder = large_room(1280, 960);
  const auto shown = shown_window({1600, 1000});
  MainWindow& window = *shown;
  open_in(window, folder, true);
  RelightSession& session = window.document()->session();
  session.wait_until_converged();
  const Light start = window.document()->light(0);
  std::vector<double> ms;
  int step = 0;
  for (auto _ : state) {
    const auto begin = std::chrono::steady_clock::now();
    Light light = start;
    light.position += 0.3f * Vec3(std::cos(0.1f * float(step)), 0.0f, std::sin(0.1f * float(step)));
    ++step;
    window.change_light(0, light);
    const uint64_t edit = session.last_edit();
    while (!(window.photo_view().relit() && session.frame().image == window.photo_view().relit() &&
             session.frame().edit >= edit))
      QCoreApplication::processEvents(QEventLoop::WaitForMoreEvents);
    window.photo_view().repaint();  // the frame painted, as the next screen update would
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    state.SetIterationTime(secs);
    ms.push_back(1e3 * secs);
  }
  state.counters["median_ms"] = percentile(ms, 0.5);
  state.counters["p95_ms"] = percentile(ms, 0.95);
  fs::remove_all(folder);
}
BENCHMARK(BM_DragOnScreen)->Iterations(120)->UseManualTime()->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  qputenv("QT_QPA_PLATFORM", "offscreen");
  QApplication app(argc, argv);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

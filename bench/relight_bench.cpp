// Micro-benchmarks of the stages of an analysis on the example room; the
// end-to-end figures on the reference scenes come from bench/end_to_end.sh.
// Results and the machine they ran on: docs/benchmarks.md.
#include <benchmark/benchmark.h>

#include "analysis/analyze.h"
#include "render/denoise.h"
#include "room_scene.h"

using namespace relight;

namespace {

struct Room {
  Scene scene = example::room_scene(640, 480);
  RayScene rays{scene.mesh};
  GBuffer gbuffer{scene.camera, rays, 9, 1, "room"};
  Lighting lighting = [this] {
    Lighting l;
    l.lights = scene.lights;
    l.environment = Environment::constant(scene.background);
    return l;
  }();
};

Room& room() {
  static Room r;
  return r;
}

void BM_GBuffer640x480(benchmark::State& state) {
  Room& r = room();
  for (auto _ : state) benchmark::DoNotOptimize(GBuffer(r.scene.camera, r.rays, 9, 1, "room"));
}
BENCHMARK(BM_GBuffer640x480)->Unit(benchmark::kMillisecond);

// One illumination render: paths per pixel from the argument, 4 bounces.
void BM_Illumination640x480(benchmark::State& state) {
  Room& r = room();
  const Integrator integrator(r.rays, r.lighting, nullptr);
  IlluminationOptions options;
  options.paths_per_pixel = int(state.range(0));
  for (auto _ : state)
    benchmark::DoNotOptimize(render_illumination(r.gbuffer, r.scene.camera, integrator, options, Progress::silent()));
  state.counters["paths/s"] =
      benchmark::Counter(double(state.iterations()) * 640 * 480 * state.range(0), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Illumination640x480)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond);

void BM_Denoise640x480(benchmark::State& state) {
  Room& r = room();
  Rng rng(1, 2);
  Image noisy(640, 480);
  for (auto& p : noisy.pixels) p = Vec3::Constant(rng.uniform());
  const std::vector<float> variance(noisy.size(), 0.01f);
  for (auto _ : state) benchmark::DoNotOptimize(denoise_illumination(noisy, variance, r.gbuffer));
}
BENCHMARK(BM_Denoise640x480)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

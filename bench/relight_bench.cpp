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
  Lighting lighting = example::room_lighting(scene, scene.lights);
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

// A string of `count` bulbs of 2 W (every third 20 W, warm) zigzagging
// under the example room's ceiling, 250 W in all whatever the count.
std::vector<Light> string_of_bulbs(int count) {
  std::vector<Light> bulbs;
  for (int i = 0; i < count; ++i) {
    const float t = (float(i) + 0.5f) / float(count);
    Light l;
    l.position = Vec3(-1.6f + 3.2f * t, 1.2f * std::sin(18.0f * t), 2.1f + 0.2f * std::cos(40.0f * t));
    l.power = (i % 3 ? 2.0f : 20.0f) * 250.0f / (8.0f * float(count));
    l.color = i % 3 ? Vec3(0.6f, 0.7f, 1.0f) : Vec3(1.0f, 0.8f, 0.5f);
    bulbs.push_back(l);
  }
  return bulbs;
}

struct Room320 {
  Scene scene = example::room_scene(320, 240);
  RayScene rays{scene.mesh};
  GBuffer gbuffer{scene.camera, rays, 9, 1, "room"};
};

Room320& room320() {
  static Room320 r;
  return r;
}

Image render_bulbs(int count, int paths, int max_bounces, int max_exhaustive_lights) {
  Room320& r = room320();
  Lighting lighting;
  lighting.lights = string_of_bulbs(count);
  IntegratorOptions integrator_options;
  integrator_options.max_bounces = max_bounces;
  integrator_options.max_exhaustive_lights = max_exhaustive_lights;
  const Integrator integrator(r.rays, lighting, nullptr, integrator_options);
  IlluminationOptions options;
  options.paths_per_pixel = paths;
  options.denoise = false;
  return render_illumination(r.gbuffer, r.scene.camera, integrator, options, Progress::silent()).surface;
}

// The example room at 320x240 lit by a string of bulbs, 16 paths per pixel
// with bounces: the cost against the number of bulbs (above 16 they are
// resampled, one shadow ray a sample for all of them).
void BM_Bulbs320x240(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(render_bulbs(int(state.range(0)), 16, 4, 16));
}
BENCHMARK(BM_Bulbs320x240)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);

// The same with a shadow ray for every bulb at every point, as below the pool.
void BM_BulbsEveryRay320x240(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(render_bulbs(int(state.range(0)), 16, 4, 100000));
}
BENCHMARK(BM_BulbsEveryRay320x240)->Arg(100)->Unit(benchmark::kMillisecond);

// The noise of resampling: 100 bulbs, direct light only, 16 paths per
// pixel, resampled and with a shadow ray for every bulb, each against the
// exhaustive render at 256 paths (PSNR through the tone curve).
void BM_BulbsNoise(benchmark::State& state) {
  const Image reference = render_bulbs(100, 256, 0, 1000);
  for (auto _ : state) {
    const Image resampled = render_bulbs(100, 16, 0, 16), exhaustive = render_bulbs(100, 16, 0, 1000);
    state.counters["resampled_dB"] =
        psnr(tonemap_reinhard_srgb(resampled), tonemap_reinhard_srgb(reference));
    state.counters["exhaustive_dB"] =
        psnr(tonemap_reinhard_srgb(exhaustive), tonemap_reinhard_srgb(reference));
  }
}
BENCHMARK(BM_BulbsNoise)->Iterations(1)->Unit(benchmark::kMillisecond);

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

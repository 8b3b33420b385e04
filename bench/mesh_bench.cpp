// Image-based mesh refinement (thesis chapter 4) of a 1-megapixel photo:
// the example room rendered at 1155 x 866 (16 paths per pixel: its shadows
// and textures are what the subdivision follows). Setup (the photo, the
// G-buffer) is outside the timed loop. Figures: docs/benchmarks.md.
#include <benchmark/benchmark.h>

#include "mesh/refine.h"
#include "render/render_illumination.h"
#include "room_scene.h"

using namespace relight;

namespace {

struct MegapixelRoom {
  Scene scene = example::room_scene(1155, 866);
  RayScene rays{scene.mesh};
  GBuffer gbuffer{scene.camera, rays, 1, 1, "room"};
  PhotoSamples photo = [this] {
    const Lighting lighting = example::room_lighting(scene, scene.lights);
    const example::RoomAlbedo albedo = example::room_albedo();
    const Integrator integrator(rays, lighting, &albedo);
    return photo_samples(synthesize_photo(gbuffer, scene.camera, integrator, albedo, 16, 1, Progress::silent()),
                         gbuffer);
  }();
  ConnectivityMesh clipped = [this] {
    ConnectivityMesh mesh(scene.mesh);
    clip_to_view(mesh, scene.camera);
    return mesh;
  }();
};

MegapixelRoom& room() {
  static MegapixelRoom r;
  return r;
}

// Subdivision alone, from the clipped mesh (copied outside the timing).
void BM_Subdivide1Megapixel(benchmark::State& state) {
  MegapixelRoom& r = room();
  SubdivisionStats stats;
  for (auto _ : state) {
    state.PauseTiming();
    ConnectivityMesh mesh = r.clipped;
    state.ResumeTiming();
    stats = subdivide_along_shadows(mesh, r.scene.camera, r.photo, SubdivisionOptions{});
    benchmark::DoNotOptimize(mesh);
  }
  state.counters["edges_tested"] = double(stats.edges_tested);
  state.counters["edges_split"] = double(stats.edges_split);
}
BENCHMARK(BM_Subdivide1Megapixel)->Unit(benchmark::kMillisecond);

// The whole refinement: connectivity, clip, subdivide, relax.
void BM_Refine1Megapixel(benchmark::State& state) {
  MegapixelRoom& r = room();
  RefineReport report;
  for (auto _ : state)
    benchmark::DoNotOptimize(refine_mesh_for_photo(r.scene.mesh, r.scene.camera, r.photo, RefineOptions{}, report));
  state.counters["triangles_in_view"] = double(report.triangles_clipped);
  state.counters["vertices_moved"] = double(report.relax.vertices_moved);
}
BENCHMARK(BM_Refine1Megapixel)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

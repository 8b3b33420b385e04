// Analysis: works out the light the photo was taken under and removes it.
// Renders the initial illumination (white diffuse surfaces, thesis chapter 3)
// under a strategy, divides the photo by it, and — with interreflection on —
// re-renders with the recovered albedo on the surfaces light bounces off until
// the albedo settles (thesis 3.7's "iterative approach").
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "analysis/albedo.h"
#include "analysis/strategy.h"
#include "core/progress.h"
#include "render/gbuffer.h"
#include "scene/scene.h"

namespace relight {

struct AnalysisOptions {
  Strategy strategy = Strategy::combined;
  int paths_per_pixel = 64;
  int gbuffer_samples = 9;   // sub-pixel samples per pixel (anti-aliasing)
  uint64_t seed = 1;
  int max_bounces = 4;
  bool interreflection = true;
  bool denoise = true;         // filter the environment + interreflection part of each render
  int max_iterations = 4;      // interreflection re-renders at most
  float tolerance = 0.005f;    // stop when the mean albedo change is below this
};

// The render settings of an analysis, shared by every later render of it.
IlluminationOptions illumination_options(const AnalysisOptions& options);

struct Analysis {
  AnalysisOptions options;
  IlluminationImages illumination;  // of the last iteration
  AlbedoImages albedo;
  std::vector<float> coverage;      // the mask
  int iterations = 0;               // renders done
};

// Renders what the scene's camera sees (the G-buffer) with the options' seed
// and sub-pixel samples: the same for the analysis and every later render.
GBuffer scene_gbuffer(const Scene& scene, const RayScene& rays, const AnalysisOptions& options);

// Called with the albedo each render recovers (render 1: white surfaces,
// then one per interreflection pass), to follow the iteration.
using AlbedoObserver = std::function<void(int render, const AlbedoImages& albedo)>;

Analysis analyze(const Scene& scene, const RayScene& rays, const GBuffer& gbuffer, const AnalysisOptions& options,
                 Progress& progress, const AlbedoObserver& on_albedo = {});

// The analysis folder: illumination.exr, albedo.exr (coverage-weighted, like
// albedo_gt.exr), albedo.png, mask.exr, and analysis.json with the options,
// the hash of the scene's inputs (analysis_input_hash) and of the images, and
// the per-surface albedo (albedo_surface.exr) that later renders need.
void save_analysis(const std::filesystem::path& folder, const Analysis& analysis, const Scene& scene);
// Loads a folder written by save_analysis for this scene; throws InputError
// if it is missing, incomplete, made for a photo of another size, stale
// (made from a scene.json, photo, geometry or probe that has changed since),
// or holds images other than those its analysis.json describes.
Analysis load_analysis(const std::filesystem::path& folder, const Scene& scene);

// A hash of everything an analysis depends on: the scene.json file, the
// photo, geometry and probe files (their bytes), and the options that
// analysis.json records.
std::string analysis_input_hash(const Scene& scene, const AnalysisOptions& options);

}  // namespace relight

// The analysis folder (docs/formats.md, "The analysis folder"): the images
// later renders read, and analysis.json with the options, the hashes that
// tie the folder to the scene's inputs and to its own images, and the
// albedo of what the photo does not show.
#pragma once

#include <filesystem>
#include <string>

#include "analysis/analyze.h"

namespace relight {

// illumination.exr, albedo.exr (coverage-weighted, like albedo_gt.exr),
// albedo.png, mask.exr, background.exr, the per-surface albedo
// (albedo_surface.exr) that later renders need, and analysis.json, written
// together (an interrupted save leaves the folder as it was).
void save_analysis(const std::filesystem::path& folder, const Analysis& analysis, const Scene& scene);
// Loads a folder written by save_analysis for this scene; throws InputError
// if it is missing, incomplete, made for a photo of another size, stale
// (made from a scene.json, photo, geometry or probe that has changed since),
// or holds images other than those its analysis.json describes.
Analysis load_analysis(const std::filesystem::path& folder, const Scene& scene);
// Replaces the albedo of the analysis folder `analysis` was loaded from
// (load_analysis; a shot's frame: its albedo fused over the frames), the
// folder's other images and records kept; like save_analysis, all of it at
// once or nothing.
void replace_albedo(const std::filesystem::path& folder, const Analysis& analysis, const Image& albedo);
// Whether the folder's analysis.json marks a preview (made of the photo
// reduced: reduce_for_preview); false where it cannot be read (load_analysis
// then says why).
bool is_preview_analysis(const std::filesystem::path& folder);

// A tracked shot's analysis: one analysis folder per frame inside it,
// frame.0001 ... (frame 1's).
std::filesystem::path shot_frame_folder(const std::filesystem::path& analysis, int frame);

// A hash of everything an analysis depends on: the scene.json file, the
// photo, geometry and probe files (their bytes), and the options that
// analysis.json records.
std::string analysis_input_hash(const Scene& scene, const AnalysisOptions& options);

}  // namespace relight

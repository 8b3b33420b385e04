// The example room, small, its photo made by the path tracer with the known
// albedo and analysed with the scene's own lights: a quick scene for the
// relighting engines' tests (session_test, frame_sequence_test).
#pragma once

#include <map>
#include <memory>
#include <string>

#include "analysis/analysed_scene.h"
#include "room_scene.h"

namespace relight::test {

// The room with `materials` (none: every surface matte), analysed.
inline std::unique_ptr<AnalysedScene> analyse_room(std::map<std::string, Gloss> materials = {}) {
  Scene scene = example::room_scene(120, 90);
  scene.path = "room";
  set_materials(scene, std::move(materials));
  scene.photo = example::room_photo(scene, scene.camera, RayScene(scene.mesh), 4, 3);
  AnalysisOptions options;
  options.strategy = Strategy::lights;
  options.paths_per_pixel = 4;
  options.interreflection = false;
  return AnalysedScene::analyse(std::move(scene), options, Progress::silent());
}

inline const AnalysedScene& analysed_room() {
  static const std::unique_ptr<AnalysedScene> r = analyse_room();
  return *r;
}

}  // namespace relight::test

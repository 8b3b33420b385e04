// Fuzzes scene.json through load_scene. The input is the scene.json of a
// folder holding a valid photo.exr, geometry.obj, probe.exr (equirect) and
// ball.exr (mirror ball), so every branch of the validation is reachable.
// A scene that loads must load again from its own scene_to_json text.
#include <cmath>

#include "core/vec.h"
#include "fuzz_support.h"
#include "io/image_io.h"
#include "io/scene_io.h"

namespace fs = std::filesystem;
using namespace relight;
using relight::fuzz::check;

namespace {

const fs::path& scene_folder() {
  static const fs::path folder = [] {
    const fs::path dir = fuzz::scratch_folder() / "scene";
    fs::create_directories(dir);
    write_exr(dir / "photo.exr", Image(4, 3, Vec3(0.5f, 0.4f, 0.3f)));
    write_exr(dir / "probe.exr", Image(8, 4, Vec3(1.0f, 0.9f, 0.8f)));
    write_exr(dir / "ball.exr", Image(4, 4, Vec3(0.2f, 0.3f, 0.4f)));
    fuzz::write_input("scene/geometry.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3\nf 1 3 4\n");
    return dir;
  }();
  return folder;
}

bool light_is_valid(const Light& l) {
  const bool finite = is_finite(l.position) && is_finite(l.direction) && is_finite(l.color) &&
                      std::isfinite(l.power) && std::isfinite(l.irradiance);
  const bool positive = l.type == LightType::directional ? l.irradiance > 0.0f : l.power > 0.0f;
  return finite && positive && (l.color.array() >= 0.0f).all() && std::abs(l.direction.norm() - 1.0f) < 1e-3f;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fs::path folder = scene_folder();
  const fs::path path = fuzz::write_input("scene/scene.json", {reinterpret_cast<const char*>(data), size});
  Scene scene;
  if (!fuzz::loads_or_rejects([&] { scene = load_scene(path); })) return 0;

  check(!scene.photo.empty() && !scene.mesh.triangles.empty(), "a loaded scene has a photo and triangles");
  check(scene.camera.width() == scene.photo.width && scene.camera.height() == scene.photo.height,
        "the camera is bound to the photo's size");
  check(is_finite(scene.camera.forward()) && is_finite(scene.background), "the camera and background are finite");
  for (const Light& light : scene.lights) check(light_is_valid(light), "every loaded light is finite and emits");

  const fs::path again_path = fuzz::write_input("scene/again.json", scene_to_json(scene, folder));
  Scene again;
  check(fuzz::loads_or_rejects([&] { again = load_scene(again_path); }), "a loaded scene's own JSON loads again");
  check(again.lights.size() == scene.lights.size() && again.probes.size() == scene.probes.size(),
        "the round trip keeps every light and probe");
  return 0;
}

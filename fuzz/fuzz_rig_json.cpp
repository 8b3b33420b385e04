// Fuzzes rig.json through load_rig. A rig that loads must load again from
// its own rig_to_json text (what `relight rig` writes) with the same lights.
#include <cmath>

#include "fuzz_support.h"
#include "io/scene_io.h"

namespace fs = std::filesystem;
using namespace relight;
using relight::fuzz::check;

namespace {

bool close(const Vec3& a, const Vec3& b) { return (a - b).norm() <= 1e-5f * std::max(1.0f, a.norm()); }
bool close(float a, float b) { return std::abs(a - b) <= 1e-5f * std::max(1.0f, std::abs(a)); }

bool same_light(const Light& a, const Light& b) {
  return a.type == b.type && a.name == b.name && a.enabled == b.enabled && close(a.color, b.color) &&
         close(a.position, b.position) && close(a.direction, b.direction) && close(a.power, b.power) &&
         close(a.irradiance, b.irradiance) && close(a.radius, b.radius) && close(a.blend, b.blend);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fs::path path = fuzz::write_input("rig.json", {reinterpret_cast<const char*>(data), size});
  Rig rig;
  if (!fuzz::loads_or_rejects([&] { rig = load_rig(path); })) return 0;
  check(std::isfinite(rig.environment_scale) && rig.environment_scale >= 0.0f, "environment_scale is >= 0");

  const fs::path again_path = fuzz::write_input("rig_again.json", rig_to_json(rig));
  Rig again;
  check(fuzz::loads_or_rejects([&] { again = load_rig(again_path); }), "a loaded rig's own JSON loads again");
  check(again.lights.size() == rig.lights.size(), "the round trip keeps every light");
  for (size_t i = 0; i < rig.lights.size(); ++i)
    check(same_light(rig.lights[i], again.lights[i]), "the round trip keeps every light's values");
  return 0;
}

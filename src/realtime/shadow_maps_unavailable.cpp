// The OpenGL backend where relight was built without libepoxy: never opens.
#include "realtime/shadow_maps.h"

namespace relight {

struct GlRelighter::State {};

std::unique_ptr<GlRelighter> GlRelighter::open(const TriangleMesh&, const PixelSurfaces&, const ShadowMapOptions&,
                                               std::string& why) {
  why = "relight was built without libepoxy";
  return nullptr;
}

GlRelighter::GlRelighter(std::unique_ptr<State> state) : state_(std::move(state)) {}
GlRelighter::~GlRelighter() = default;
const std::string& GlRelighter::renderer() const {
  static const std::string none = "none";
  return none;
}
bool GlRelighter::shades_by_compute() const { return false; }
void GlRelighter::render(const Light&, Image&) {}

}  // namespace relight

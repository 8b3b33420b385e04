// PhotoRadiance: the radiance a scene point sends out, read from the photo
// or from a light probe that shows it. A diffuse surface sends the same
// radiance every way, so what the camera (or a probe) saw a point send is
// what it sends towards any other surface, whatever its albedo and however
// many times its light bounced (inverse global illumination: Yu et al.
// 1999, Loscos et al. 2000). Light bounced off what the photo or a probe
// shows then needs neither an albedo nor an iteration.
//
// Known only where a pixel shows the point whole and faithfully: all of the
// pixel's samples on the point's surface (no silhouette, crease or
// background mixed in), the pixel not clipped, not showing one of the
// scene's lights (a probe sees them in front of the walls), and the point
// neither hidden from the camera or probe nor seen by it from its other side.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "analysis/albedo.h"
#include "core/image.h"
#include "render/gbuffer.h"
#include "render/integrator.h"
#include "scene/light.h"
#include "scene/probe.h"

namespace relight {

class PhotoRadiance final : public KnownRadiance {
 public:
  // gbuffer: the photo's, made with `camera`. Holds references to camera,
  // gbuffer, photo and probes. `rays` and `lights` are used here only: to
  // find what each probe pixel shows, and the lights' regions in the probes.
  PhotoRadiance(const Camera& camera, const GBuffer& gbuffer, const Image& photo, const std::vector<Probe>& probes,
                const RayScene& rays, const std::vector<Light>& lights);
  std::optional<Vec3> at(const SurfacePoint& p) const override;

  // The albedo of the triangles marked in `wanted` that a probe shows: the
  // radiance the probe shows over the illumination `integrator` finds there
  // (`paths` paths a point), summed over the triangle's usable probe pixels.
  std::vector<TriangleAlbedo> probe_albedo(const Integrator& integrator, const std::vector<uint8_t>& wanted, int paths,
                                           uint64_t seed) const;

  // The share of the pixels that see geometry whose radiance is usable.
  double usable_share() const { return usable_share_; }

 private:
  // What one probe's pixels show: where usable, the surface at its centre.
  struct ProbeView {
    const Probe* probe;
    ProbeFrame frame;
    std::vector<uint8_t> usable;
    std::vector<SurfacePoint> centre;
  };
  static ProbeView view_of(const Probe& probe, const RayScene& rays, const std::vector<Light>& lights);
  std::optional<Vec3> from_probe(const ProbeView& view, const SurfacePoint& p) const;

  const Camera& camera_;
  const GBuffer& gbuffer_;
  const Image& photo_;
  std::vector<uint8_t> usable_;  // per photo pixel
  double usable_share_ = 0.0;
  std::vector<ProbeView> probes_;
};

// The value at which an image is clipped, if it is: the largest channel
// value, when a plateau of pixels (at least 0.05 % of them) reaches it
// exactly. A rendered or merged HDR image has no such plateau.
std::optional<float> photo_clip_level(const Image& image);

}  // namespace relight

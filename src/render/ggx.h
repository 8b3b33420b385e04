// GgxLobe: the specular lobe of a glossy surface (scene/gloss.h) — GGX
// (Walter et al. 2007) with the dielectric's Fresnel term and separable
// Smith shadowing, single scattering, as Blender's Principled BSDF has it in
// Cycles.
#pragma once

#include "core/vec.h"
#include "scene/gloss.h"

namespace relight {

// Below this roughness a lobe is taken as this sharp: a sharper one
// reflects a small lamp as a spot the light samples would rarely find.
inline constexpr float kMinRoughness = 0.05f;

// One gloss's lobe. Directions are unit and point away from the surface;
// n is the shading normal.
class GgxLobe {
 public:
  explicit GgxLobe(const Gloss& gloss);
  float alpha() const { return alpha_; }
  // The BRDF f(l, v) (the same in every channel: a dielectric's highlight
  // takes the light's colour); 0 where l or v is below the surface.
  float brdf(const Vec3& n, const Vec3& l, const Vec3& v) const;
  // The terms of the BRDF that depend on the view alone: worked out once
  // for a view lit from many directions.
  struct ViewTerms {
    float cos_v = 0.0f, shadowing_v = 0.0f;
  };
  ViewTerms view_terms(const Vec3& n, const Vec3& v) const;
  // brdf() with the view's terms given, and its far tail left out: the
  // microfacet distribution less `tail` times its peak, 0 where that is
  // below 0 (the rest of the terms then cost nothing); continuous, so that
  // a highlight shows no edge where its tail is cut.
  float brdf(const Vec3& n, const Vec3& l, const Vec3& v, const ViewTerms& view, float tail = 0.0f) const;
  // A direction l from the lobe's visible normals (Heitz 2018) for view v,
  // u in [0,1)^2; weight = brdf x cos / pdf. False where l is below the
  // surface (the sample brings nothing).
  bool sample(const Vec3& n, const Vec3& v, const Vec2& u, Vec3& l, float& weight) const;
  // The density of sample()'s l, per solid angle.
  float pdf(const Vec3& n, const Vec3& l, const Vec3& v) const;
  // The reflectance at normal incidence.
  float f0() const;

 private:
  float distribution(float cos_h) const;   // D
  float shadowing(float cos_theta) const;  // Smith G1
  float fresnel(float cos_d) const;        // dielectric, unpolarised
  float alpha_, eta_;
};

}  // namespace relight

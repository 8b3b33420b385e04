// Light probes (FORMAT.md "Light probes"): the equirect and mirror-ball
// mappings, their pixel solid angles, and the importance sampling of a probe
// environment.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/sampling.h"
#include "scene/environment.h"
#include "scene/probe.h"

namespace relight {
namespace {

constexpr double kPiD = std::numbers::pi;

// A deliberately non-axis-aligned probe frame, so that mixing up axes fails.
ProbeFrame tilted_frame() {
  const Vec3 forward = Vec3(0.3f, 0.9f, -0.2f).normalized();
  const Vec3 up = Vec3(0.1f, -0.05f, 1.0f);  // not orthogonal to forward
  return ProbeFrame(forward, up);
}

void expect_vec_near(const Vec3& a, const Vec3& b, float tol, const std::string& what = "") {
  EXPECT_LT((a - b).norm(), tol) << what << ": (" << a.transpose() << ") vs (" << b.transpose() << ")";
}

TEST(ProbeFrame, IsOrthonormalRightHandedWithRightEqualForwardCrossUp) {
  const ProbeFrame f = tilted_frame();
  EXPECT_NEAR(f.forward.norm(), 1.0f, 1e-6f);
  EXPECT_NEAR(f.right.norm(), 1.0f, 1e-6f);
  EXPECT_NEAR(f.up.norm(), 1.0f, 1e-6f);
  EXPECT_NEAR(f.forward.dot(f.right), 0.0f, 1e-6f);
  EXPECT_NEAR(f.forward.dot(f.up), 0.0f, 1e-6f);
  EXPECT_NEAR(f.right.dot(f.up), 0.0f, 1e-6f);
  expect_vec_near(f.right, f.forward.cross(f.up), 1e-6f, "right = forward x up");
  // The re-orthogonalised up stays on the side of the given up.
  EXPECT_GT(f.up.dot(Vec3(0.1f, -0.05f, 1.0f)), 0.9f);
  // forward is the given one, normalised.
  expect_vec_near(f.forward, Vec3(0.3f, 0.9f, -0.2f).normalized(), 1e-6f);
}

// ------------------------------------------------------------ round trips

TEST(ProbeMapping, EquirectDirectionToUvToDirectionRoundTrips) {
  const ProbeFrame frame = tilted_frame();
  Rng rng(11, 0);
  for (int i = 0; i < 20000; ++i) {
    const Vec3 d = sample_uniform_sphere(rng.uniform2());
    const Vec2 uv = probe_direction_to_uv(ProbeMapping::equirect, frame, d);
    ASSERT_GE(uv.x(), 0.0f);
    ASSERT_LE(uv.x(), 1.0f);
    ASSERT_GE(uv.y(), 0.0f);
    ASSERT_LE(uv.y(), 1.0f);
    const auto back = probe_uv_to_direction(ProbeMapping::equirect, frame, uv);
    ASSERT_TRUE(back.has_value());
    ASSERT_LT((*back - d).norm(), 1e-4f) << "d = " << d.transpose() << " uv = " << uv.transpose();
  }
}

TEST(ProbeMapping, EquirectUvToDirectionToUvRoundTrips) {
  const ProbeFrame frame = tilted_frame();
  Rng rng(12, 0);
  for (int i = 0; i < 20000; ++i) {
    // Keep away from the poles (u undefined) and the u = 0/1 seam.
    const Vec2 uv(0.01f + 0.98f * rng.uniform(), 0.01f + 0.98f * rng.uniform());
    const auto d = probe_uv_to_direction(ProbeMapping::equirect, frame, uv);
    ASSERT_TRUE(d.has_value());
    EXPECT_NEAR(d->norm(), 1.0f, 1e-5f);
    const Vec2 back = probe_direction_to_uv(ProbeMapping::equirect, frame, *d);
    ASSERT_LT((back - uv).norm(), 1e-4f) << "uv = " << uv.transpose();
  }
}

TEST(ProbeMapping, MirrorballDirectionToUvToDirectionRoundTrips) {
  const ProbeFrame frame = tilted_frame();
  Rng rng(13, 0);
  int tested = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 d = sample_uniform_sphere(rng.uniform2());
    // Straight behind the ball (d = +forward) is the whole rim: singular.
    // Skip directions within 5 degrees of it.
    if (d.dot(frame.forward) > std::cos(radians(5.0f))) continue;
    ++tested;
    const Vec2 uv = probe_direction_to_uv(ProbeMapping::mirrorball, frame, d);
    const float a = 2 * uv.x() - 1, b = 1 - 2 * uv.y();
    ASSERT_LE(a * a + b * b, 1.0f + 1e-5f);
    const auto back = probe_uv_to_direction(ProbeMapping::mirrorball, frame, uv);
    ASSERT_TRUE(back.has_value()) << "uv = " << uv.transpose();
    ASSERT_LT((*back - d).norm(), 1e-4f) << "d = " << d.transpose() << " uv = " << uv.transpose();
  }
  EXPECT_GT(tested, 19000);
}

TEST(ProbeMapping, MirrorballFollowsFormatReflectionFormula) {
  // Independently of the code's inverse: for pixel positions inside the
  // disc, the direction must be d = f - 2 (f.n) n with the ball normal
  // n = a right + b up - sqrt(1 - r^2) forward.
  const ProbeFrame frame = tilted_frame();
  Rng rng(14, 0);
  for (int i = 0; i < 5000; ++i) {
    const Vec2 uv = rng.uniform2();
    const float a = 2 * uv.x() - 1, b = 1 - 2 * uv.y();
    const float r2 = a * a + b * b;
    const auto d = probe_uv_to_direction(ProbeMapping::mirrorball, frame, uv);
    if (r2 > 1.0f) {
      EXPECT_FALSE(d.has_value()) << "outside the disc: uv = " << uv.transpose();
      continue;
    }
    ASSERT_TRUE(d.has_value());
    const Vec3 n = a * frame.right + b * frame.up - std::sqrt(1 - r2) * frame.forward;
    const Vec3 expected = frame.forward - 2 * frame.forward.dot(n) * n;
    expect_vec_near(*d, expected.normalized(), 1e-4f);
  }
}

TEST(ProbeMapping, EquirectFollowsFormatFormula) {
  const ProbeFrame frame = tilted_frame();
  Rng rng(15, 0);
  for (int i = 0; i < 5000; ++i) {
    const Vec3 d = sample_uniform_sphere(rng.uniform2());
    const double x = d.dot(frame.right), y = d.dot(frame.up), z = d.dot(frame.forward);
    const double u = 0.5 + std::atan2(x, z) / (2 * kPiD), v = std::acos(std::clamp(y, -1.0, 1.0)) / kPiD;
    const Vec2 uv = probe_direction_to_uv(ProbeMapping::equirect, frame, d);
    if (std::abs(u - 0.0) < 1e-4 || std::abs(u - 1.0) < 1e-4) continue;  // the seam: 0 and 1 are the same
    EXPECT_NEAR(uv.x(), u, 1e-5);
    EXPECT_NEAR(uv.y(), v, 1e-5);
  }
}

// -------------------------------------------------- FORMAT.md's facts

class ProbeFacts : public ::testing::Test {
 protected:
  // The FORMAT.md example probe: forward +y, up +z, so right = +x.
  ProbeFrame frame{Vec3(0, 1, 0), Vec3(0, 0, 1)};
  const Vec3 forward{0, 1, 0}, up{0, 0, 1}, right{1, 0, 0};
};

TEST_F(ProbeFacts, RightIsForwardCrossUp) { expect_vec_near(frame.right, right, 1e-6f); }

TEST_F(ProbeFacts, EquirectCentreLooksAlongForward) {
  expect_vec_near(*probe_uv_to_direction(ProbeMapping::equirect, frame, Vec2(0.5f, 0.5f)), forward, 1e-5f);
  const Vec2 uv = probe_direction_to_uv(ProbeMapping::equirect, frame, forward);
  EXPECT_NEAR(uv.x(), 0.5f, 1e-6f);
  EXPECT_NEAR(uv.y(), 0.5f, 1e-6f);
}

TEST_F(ProbeFacts, EquirectRowZeroIsStraightUpAndLastRowStraightDown) {
  for (float u : {0.1f, 0.5f, 0.9f}) {
    expect_vec_near(*probe_uv_to_direction(ProbeMapping::equirect, frame, Vec2(u, 0.0f)), up, 1e-5f);
    expect_vec_near(*probe_uv_to_direction(ProbeMapping::equirect, frame, Vec2(u, 1.0f)), -up, 1e-5f);
  }
  EXPECT_NEAR(probe_direction_to_uv(ProbeMapping::equirect, frame, up).y(), 0.0f, 1e-6f);
  EXPECT_NEAR(probe_direction_to_uv(ProbeMapping::equirect, frame, -up).y(), 1.0f, 1e-6f);
  // The horizon is the middle row.
  EXPECT_NEAR(probe_direction_to_uv(ProbeMapping::equirect, frame, right).y(), 0.5f, 1e-6f);
}

TEST_F(ProbeFacts, EquirectUIncreasesTowardsRight) {
  const Vec2 r = probe_direction_to_uv(ProbeMapping::equirect, frame, right);
  const Vec2 l = probe_direction_to_uv(ProbeMapping::equirect, frame, -right);
  EXPECT_NEAR(r.x(), 0.75f, 1e-6f);
  EXPECT_NEAR(l.x(), 0.25f, 1e-6f);
  // A little to the right of forward is a little right of the centre.
  const Vec2 slightly = probe_direction_to_uv(ProbeMapping::equirect, frame, (forward + 0.1f * right).normalized());
  EXPECT_GT(slightly.x(), 0.5f);
  EXPECT_LT(slightly.x(), 0.55f);
  // Straight behind is the left/right edge.
  const Vec2 behind = probe_direction_to_uv(ProbeMapping::equirect, frame, -forward);
  EXPECT_NEAR(std::min(behind.x(), 1.0f - behind.x()), 0.0f, 1e-6f);
  EXPECT_NEAR(behind.y(), 0.5f, 1e-6f);
}

TEST_F(ProbeFacts, MirrorballCentrePixelShowsTowardsTheCamera) {
  // The centre of the ball reflects the camera: light from -forward.
  expect_vec_near(*probe_uv_to_direction(ProbeMapping::mirrorball, frame, Vec2(0.5f, 0.5f)), -forward, 1e-5f);
  const Vec2 uv = probe_direction_to_uv(ProbeMapping::mirrorball, frame, -forward);
  EXPECT_NEAR(uv.x(), 0.5f, 1e-6f);
  EXPECT_NEAR(uv.y(), 0.5f, 1e-6f);
}

TEST_F(ProbeFacts, MirrorballRightAndUpAppearRightAndUp) {
  // At radius 1/sqrt(2) the normal is at 45 degrees and the ball reflects
  // light from 90 degrees off the view axis.
  const float k = 0.5f * (1.0f + std::sqrt(0.5f));
  expect_vec_near(*probe_uv_to_direction(ProbeMapping::mirrorball, frame, Vec2(k, 0.5f)), right, 1e-5f);
  expect_vec_near(*probe_uv_to_direction(ProbeMapping::mirrorball, frame, Vec2(1 - k, 0.5f)), -right, 1e-5f);
  expect_vec_near(*probe_uv_to_direction(ProbeMapping::mirrorball, frame, Vec2(0.5f, 1 - k)), up, 1e-5f);
  expect_vec_near(*probe_uv_to_direction(ProbeMapping::mirrorball, frame, Vec2(0.5f, k)), -up, 1e-5f);
  const Vec2 uv = probe_direction_to_uv(ProbeMapping::mirrorball, frame, right);
  EXPECT_NEAR(uv.x(), k, 1e-6f);
  EXPECT_NEAR(uv.y(), 0.5f, 1e-6f);
  // Straight behind the ball maps to the rim.
  const Vec2 rim = probe_direction_to_uv(ProbeMapping::mirrorball, frame, (forward + Vec3(1e-3f, 0, 0)).normalized());
  EXPECT_NEAR((2 * rim - Vec2(1, 1)).norm(), 1.0f, 1e-3f);
}

TEST_F(ProbeFacts, MirrorballCornersAreOutsideTheDisc) {
  for (const Vec2& uv : {Vec2(0.02f, 0.02f), Vec2(0.98f, 0.02f), Vec2(0.02f, 0.98f), Vec2(0.98f, 0.98f)})
    EXPECT_FALSE(probe_uv_to_direction(ProbeMapping::mirrorball, frame, uv).has_value()) << uv.transpose();
}

// ------------------------------------------------------ solid angles

TEST(ProbeSolidAngle, EquirectPixelsSumToFourPi) {
  const int w = 64, h = 32;
  double sum = 0.0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) sum += probe_pixel_solid_angle(ProbeMapping::equirect, Vec2((x + 0.5f) / w, (y + 0.5f) / h), w, h);
  EXPECT_NEAR(sum, 4 * kPiD, 4 * kPiD * 2e-3);
}

TEST(ProbeSolidAngle, MirrorballPixelsInsideDiscSumToFourPi) {
  const int n = 256;
  const ProbeFrame frame{Vec3(0, 1, 0), Vec3(0, 0, 1)};
  double sum = 0.0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const Vec2 uv((x + 0.5f) / n, (y + 0.5f) / n);
      if (probe_uv_to_direction(ProbeMapping::mirrorball, frame, uv))
        sum += probe_pixel_solid_angle(ProbeMapping::mirrorball, uv, n, n);
    }
  EXPECT_NEAR(sum, 4 * kPiD, 4 * kPiD * 1e-2);
}

TEST(ProbeSolidAngle, MirrorballJacobianMatchesFiniteDifferences) {
  // Solid angle of a tiny square of the image, from the mapping itself:
  // |dd/du x dd/dv| du dv, compared with the constant-Jacobian claim.
  const ProbeFrame frame{Vec3(0, 1, 0), Vec3(0, 0, 1)};
  const int n = 512;
  const double h = 1e-3;
  for (const Vec2& uv : {Vec2(0.5f, 0.5f), Vec2(0.3f, 0.6f), Vec2(0.7f, 0.25f), Vec2(0.5f, 0.1f)}) {
    auto dir = [&](double du, double dv) {
      return probe_uv_to_direction(ProbeMapping::mirrorball, frame, Vec2(float(uv.x() + du), float(uv.y() + dv)))
          ->cast<double>()
          .eval();
    };
    const Eigen::Vector3d du = (dir(h, 0) - dir(-h, 0)) / (2 * h);
    const Eigen::Vector3d dv = (dir(0, h) - dir(0, -h)) / (2 * h);
    const double jacobian = du.cross(dv).norm();  // sr per unit uv area
    EXPECT_NEAR(probe_pixel_solid_angle(ProbeMapping::mirrorball, uv, n, n) * n * n, jacobian, 0.02 * jacobian)
        << uv.transpose();
  }
}

// ------------------------------------------------ importance sampling

// A small synthetic probe: dim everywhere, with one bright rectangle.
Probe synthetic_probe(ProbeMapping mapping, int w, int h, int bx, int by, int bw, int bh) {
  Probe p;
  p.path = "synthetic";
  p.mapping = mapping;
  p.forward = Vec3(0, 1, 0);
  p.up = Vec3(0, 0, 1);
  p.image = Image(w, h, Vec3(0.05f, 0.05f, 0.05f));
  for (int y = by; y < by + bh; ++y)
    for (int x = bx; x < bx + bw; ++x) p.image.at(x, y) = Vec3(40.0f, 30.0f, 20.0f);
  return p;
}

// Integral over the sphere of env.pdf by stratified uniform sampling
// (sample_uniform_sphere is area-preserving, so a jittered grid of (u1, u2)
// is a jittered equal-area grid of directions).
double integrate_pdf_over_sphere(const ProbeEnvironment& env, int grid) {
  Rng rng(99, 0);
  double sum = 0.0;
  for (int i = 0; i < grid; ++i)
    for (int j = 0; j < grid; ++j) {
      const Vec2 u((i + rng.uniform()) / grid, (j + rng.uniform()) / grid);
      sum += env.pdf(sample_uniform_sphere(u));
    }
  return sum / (double(grid) * grid) * 4 * kPiD;
}

void check_sample_matches_pdf(const ProbeEnvironment& env, int n, int& accepted) {
  Rng rng(5, 0);
  int mismatches = 0;
  accepted = 0;
  for (int i = 0; i < n; ++i) {
    Vec3 d;
    float pdf = -1.0f;
    if (!env.sample(rng.uniform2(), d, pdf)) continue;
    ++accepted;
    ASSERT_NEAR(d.norm(), 1.0f, 1e-4f);
    ASSERT_GT(pdf, 0.0f);
    const float expected = env.pdf(d);
    // A sample that lands within float rounding of a pixel edge may map back
    // into the neighbouring pixel; allow a handful of those, no more.
    if (std::abs(pdf - expected) > 2e-3f * expected) ++mismatches;
  }
  EXPECT_LE(mismatches, n / 1000) << "samples whose pdf differs from pdf(direction)";
}

TEST(ProbeEnvironment, EquirectSamplePdfMatchesPdfOfDirection) {
  const ProbeEnvironment env(synthetic_probe(ProbeMapping::equirect, 32, 16, 20, 4, 3, 2));
  int accepted = 0;
  check_sample_matches_pdf(env, 50000, accepted);
  EXPECT_EQ(accepted, 50000);  // every equirect sample is valid
}

TEST(ProbeEnvironment, MirrorballSamplePdfMatchesPdfOfDirection) {
  const ProbeEnvironment env(synthetic_probe(ProbeMapping::mirrorball, 24, 24, 8, 10, 3, 3));
  int accepted = 0;
  check_sample_matches_pdf(env, 50000, accepted);
  EXPECT_GT(accepted, 49000);  // only the disc's rim pixels may fail
}

TEST(ProbeEnvironment, EquirectPdfIntegratesToOne) {
  const ProbeEnvironment env(synthetic_probe(ProbeMapping::equirect, 32, 16, 20, 4, 3, 2));
  EXPECT_NEAR(integrate_pdf_over_sphere(env, 1000), 1.0, 0.02);
}

TEST(ProbeEnvironment, MirrorballPdfIntegratesToOne) {
  const ProbeEnvironment env(synthetic_probe(ProbeMapping::mirrorball, 24, 24, 8, 10, 3, 3));
  EXPECT_NEAR(integrate_pdf_over_sphere(env, 1000), 1.0, 0.02);
}

// A turned sky keeps its sampling table: it samples, weighs and shows
// exactly what the same probe built afresh does, for both mappings.
TEST(ProbeEnvironment, ATurnedProbeIsTheSameProbeBuiltAfresh) {
  for (const ProbeMapping mapping : {ProbeMapping::equirect, ProbeMapping::mirrorball}) {
    const Probe probe = synthetic_probe(mapping, 24, 24, 8, 10, 3, 3);
    Probe turned = probe;
    turned.forward = Vec3(-std::sin(1.0f), std::cos(1.0f), 0.0f);
    const ProbeEnvironment fresh(turned), kept(ProbeEnvironment(probe), turned);
    Rng rng(7, 0);
    for (int i = 0; i < 2000; ++i) {
      const Vec2 u = rng.uniform2();
      Vec3 d_fresh, d_kept;
      float pdf_fresh = 0.0f, pdf_kept = 0.0f;
      ASSERT_EQ(fresh.sample(u, d_fresh, pdf_fresh), kept.sample(u, d_kept, pdf_kept));
      EXPECT_EQ(d_fresh, d_kept);
      EXPECT_EQ(pdf_fresh, pdf_kept);
      const Vec3 d = sample_uniform_sphere(rng.uniform2());
      EXPECT_EQ(fresh.pdf(d), kept.pdf(d));
      EXPECT_EQ(fresh.radiance(d), kept.radiance(d));
    }
    const Environment environment = Environment::from_probes({probe}).turned(turned);
    EXPECT_EQ(environment.probe_for(Vec3::Zero())->probe().forward, turned.forward);
  }
  Probe smaller = synthetic_probe(ProbeMapping::equirect, 12, 6, 1, 1, 2, 2);
  EXPECT_THROW(ProbeEnvironment(ProbeEnvironment(synthetic_probe(ProbeMapping::equirect, 24, 12, 1, 1, 2, 2)), smaller),
               std::invalid_argument);
}

TEST(ProbeEnvironment, SamplesConcentrateOnTheBrightRegion) {
  // Fraction of samples in the bright pixels = their share of
  // luminance x solid angle.
  const int w = 32, h = 16;
  const Probe probe = synthetic_probe(ProbeMapping::equirect, w, h, 20, 4, 3, 2);
  const ProbeEnvironment env(probe);
  const ProbeFrame frame(probe.forward, probe.up);
  double bright = 0.0, total = 0.0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double m = luminance(probe.image.at(x, y)) *
                       probe_pixel_solid_angle(ProbeMapping::equirect, Vec2((x + 0.5f) / w, (y + 0.5f) / h), w, h);
      total += m;
      if (x >= 20 && x < 23 && y >= 4 && y < 6) bright += m;
    }
  Rng rng(6, 0);
  const int n = 100000;
  int hits = 0;
  for (int i = 0; i < n; ++i) {
    Vec3 d;
    float pdf;
    ASSERT_TRUE(env.sample(rng.uniform2(), d, pdf));
    const Vec2 uv = probe_direction_to_uv(ProbeMapping::equirect, frame, d);
    const int x = int(uv.x() * w), y = int(uv.y() * h);
    if (x >= 20 && x < 23 && y >= 4 && y < 6) ++hits;
  }
  const double expected = bright / total;
  EXPECT_GT(expected, 0.9);  // the test probe is what it should be
  EXPECT_NEAR(double(hits) / n, expected, 0.005);
}

TEST(ProbeEnvironment, RadianceIsThePixelSeenInThatDirection) {
  const int w = 32, h = 16;
  Probe probe = synthetic_probe(ProbeMapping::equirect, w, h, 20, 4, 3, 2);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) probe.image.at(x, y) = Vec3(float(x), float(y), 1.0f);
  const ProbeEnvironment env(probe);
  const ProbeFrame frame(probe.forward, probe.up);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Vec3 d = *probe_uv_to_direction(ProbeMapping::equirect, frame, Vec2((x + 0.5f) / w, (y + 0.5f) / h));
      EXPECT_EQ(env.radiance(d), Vec3(float(x), float(y), 1.0f)) << x << "," << y;
    }
  // The environment built from the probe applies its scale.
  Environment all = Environment::from_probes({probe});
  all.set_scale(2.0f);
  const ProbeEnvironment* served = all.probe_for(Vec3(5, 5, 5));
  ASSERT_NE(served, nullptr);
  const Vec3 d = *probe_uv_to_direction(ProbeMapping::equirect, frame, Vec2(3.5f / w, 7.5f / h));
  EXPECT_EQ(all.radiance(served, d), Vec3(6.0f, 14.0f, 2.0f));
}

TEST(Environment, NearestProbeServesAPoint) {
  Probe a = synthetic_probe(ProbeMapping::equirect, 8, 4, 0, 0, 1, 1);
  Probe b = a;
  a.position = Vec3(0, 0, 0);
  b.position = Vec3(10, 0, 0);
  const Environment env = Environment::from_probes({a, b});
  ASSERT_TRUE(env.uses_probes());
  EXPECT_EQ(&env.probe_for(Vec3(1, 0, 0))->probe(), &env.probe_for(Vec3(-3, 2, 0))->probe());
  EXPECT_NE(&env.probe_for(Vec3(1, 0, 0))->probe(), &env.probe_for(Vec3(9, 0, 0))->probe());
  EXPECT_EQ(env.probe_for(Vec3(9, 0, 0))->probe().position, Vec3(10, 0, 0));
}

TEST(Environment, ConstantSamplingIsUniformOverTheSphere) {
  const Environment env = Environment::constant(Vec3(1, 2, 3));
  EXPECT_FALSE(env.is_black());
  EXPECT_FALSE(env.uses_probes());
  Rng rng(3, 0);
  for (int i = 0; i < 100; ++i) {
    Vec3 d;
    float pdf;
    ASSERT_TRUE(env.sample(nullptr, rng.uniform2(), d, pdf));
    EXPECT_NEAR(d.norm(), 1.0f, 1e-5f);
    EXPECT_NEAR(pdf, 1.0 / (4 * kPiD), 1e-7);
    EXPECT_EQ(env.radiance(nullptr, d), Vec3(1, 2, 3));
  }
  EXPECT_TRUE(Environment::constant(Vec3::Zero()).is_black());
}

}  // namespace
}  // namespace relight

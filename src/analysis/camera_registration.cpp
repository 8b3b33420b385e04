#include "analysis/camera_registration.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "analysis/photo_edges.h"
#include "core/error.h"
#include "render/gbuffer.h"

namespace relight {

namespace {

// The mismatch reported: the mean edge distance capped at 8 pixels.
constexpr float kReportCap = 8.0f;

// The photo's edge fields, full resolution first, then halved each level.
std::vector<EdgeField> edge_pyramid(const Image& photo, int levels) {
  std::vector<EdgeField> fields;
  cv::Mat l = log_luminance(photo);
  for (int k = 0, scale = 1; k < levels; ++k, scale *= 2) {
    fields.push_back(edge_field(l, scale));
    cv::Mat half;
    cv::pyrDown(l, half);
    l = half;
  }
  return fields;
}

// The geometry's edges seen through `camera`: wherever two neighbouring
// pixels' centres see different surfaces (or one sees none), the point on
// the nearer surface where it ends, found to 1/16 pixel by bisection along
// the two pixels' centres. On the nearer surface: a silhouette is the
// occluder's edge, and it stays on it when the camera moves. Rows are
// traced a band at a time (each once, and the row after the band), rather
// than kept for the whole photo.
std::vector<Vec3> geometry_edges(const Camera& camera, const RayScene& rays, const std::string& scene_file) {
  const int w = camera.width(), h = camera.height();
  const auto trace_row = [&](int y, std::vector<GBufferSample>& row) {
    row.resize(size_t(w));
    for (int x = 0; x < w; ++x)
      row[size_t(x)].hit =
          y < h && rays.intersect(camera.position(), camera.ray_direction(x + 0.5f, y + 0.5f), row[size_t(x)].surface);
  };
  std::atomic<bool> any_hit{false};
  std::vector<std::vector<Vec3>> rows(h);
  constexpr int kBandRows = 16;
  tbb::parallel_for(tbb::blocked_range<int>(0, h, kBandRows), [&](const tbb::blocked_range<int>& band) {
    std::vector<GBufferSample> row, next;
    trace_row(band.begin(), row);
    for (int y = band.begin(); y < band.end(); ++y, std::swap(row, next)) {
      trace_row(y + 1, next);
      for (int x = 0; x < w; ++x)
        for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
          const int nx = x + dx, ny = y + dy;
          if (nx >= w || ny >= h) continue;
          const GBufferSample &a = row[size_t(x)], &b = dy ? next[size_t(x)] : row[size_t(nx)];
          if (a.hit) any_hit = true;
          if (!GBuffer::edge_between(a, b)) continue;
          const bool a_near = a.hit && (!b.hit || a.surface.distance <= b.surface.distance);
          const SurfacePoint& near = a_near ? a.surface : b.surface;
          Vec2 from = Vec2(x + 0.5f, y + 0.5f), to = Vec2(nx + 0.5f, ny + 0.5f);
          if (!a_near) std::swap(from, to);
          float lo = 0.0f, hi = 1.0f;  // the near surface is seen at lo, not at hi
          Vec3 point = near.position;
          for (int step = 0; step < 4; ++step) {
            const float t = 0.5f * (lo + hi);
            const Vec2 p = from + t * (to - from);
            SurfacePoint s;
            if (rays.intersect(camera.position(), camera.ray_direction(p.x(), p.y()), s) &&
                GBuffer::same_surface(near, s))
              lo = t, point = s.position;
            else
              hi = t;
          }
          rows[y].push_back(point);
        }
    }
  });
  if (!any_hit)
    throw InputError(scene_file, "/camera", "the camera sees no geometry: check position, look_at and the mesh");
  std::vector<Vec3> points;
  for (const auto& r : rows) points.insert(points.end(), r.begin(), r.end());
  return points;
}

// The camera's ten degrees of freedom about a base camera, in physical
// units: a turn about its right, up and forward axes (radians), a move
// along them (m), the log of the change of tan(vfov/2), the shift of the
// principal point (fractions of the width and height) and the change of the
// lens's distortion k1. A change of k1 alone would move every point out
// or in, as a change of the field of view does, and the solve would crawl
// along the valley between them: it comes with the field of view's change
// that keeps points at `pivot_r2` (the edge points' mean square radius, in
// focal lengths) where they were.
constexpr int kParams = 10;
using Params = Eigen::Matrix<double, kParams, 1>;

CameraSpec moved_camera(const Camera& base, const Params& p, double pivot_r2) {
  const CameraSpec& b = base.spec();
  const Vec3 forward = base.forward();
  const Vec3 right = forward.cross(b.up).normalized();
  const Vec3 up = right.cross(forward);
  const Vec3 omega = float(p[0]) * right + float(p[1]) * up + float(p[2]) * forward;
  const float angle = omega.norm();
  const Eigen::Matrix3f turn =
      angle > 0.0f ? Eigen::AngleAxisf(angle, omega / angle).toRotationMatrix() : Eigen::Matrix3f::Identity();
  CameraSpec s = b;
  s.position = b.position + float(p[3]) * right + float(p[4]) * up + float(p[5]) * forward;
  s.look_at = s.position + turn * (b.look_at - b.position);
  s.up = turn * b.up;
  s.vfov_deg =
      2.0f * std::atan(std::tan(radians(b.vfov_deg) * 0.5f) * std::exp(float(p[6] + p[9] * pivot_r2))) * 180.0f / kPi;
  s.principal_point = b.principal_point + Vec2(float(p[7]), float(p[8]));
  s.distortion.x() = b.distortion.x() + float(p[9]);
  return s;
}

// Huber with a cap: quadratic to delta, linear to cap, constant beyond.
double robust_cost(double r, double delta, double cap) {
  r = std::min(r, cap);
  return r <= delta ? 0.5 * r * r : delta * (r - 0.5 * delta);
}
double robust_weight(double r, double delta, double cap) { return r >= cap ? 0.0 : r <= delta ? 1.0 : delta / r; }

// The registration at one level: Levenberg-Marquardt on the capped edge
// distances of the points, in units that move an edge about one of the
// level's pixels, with the position's prior.
class LevelSolve {
 public:
  LevelSolve(const Camera& base, const std::vector<Vec3>& points, const EdgeField& field, float cap,
             const RegistrationOptions& options)
      : base_(base), points_(points), field_(field), cap_(cap) {
    const double s = field.scale, f = 0.5 * base.height() / std::tan(radians(base.spec().vfov_deg) * 0.5);
    const Vec3 right = base.forward().cross(base.spec().up).normalized(), up = right.cross(base.forward());
    std::vector<float> depths;
    double r2_sum = 0.0;  // the points' square radii on the image plane, in focal lengths
    for (const Vec3& p : points) {
      const Vec3 d = p - base.position();
      const float depth = std::max(1e-6f, d.dot(base.forward()));
      depths.push_back(depth);
      r2_sum += (Vec2(d.dot(right), d.dot(up)) / depth).squaredNorm();
    }
    pivot_r2_ = points.empty() ? 0.0 : r2_sum / double(points.size());
    std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
    const double depth = depths.empty() ? 1.0 : std::max(0.01f, depths[depths.size() / 2]);
    // k1 moves a point at radius r (focal lengths) by k1 r^3 focal lengths:
    // a unit moves the corners by a pixel.
    const double corner = std::hypot(0.5 * base.width(), 0.5 * base.height()) / f;
    unit_ << s / f, s / f, s / (0.5 * base.width()), s / f * depth, s / f * depth, s / (0.5 * base.width()) * depth,
        s / (0.5 * base.height()), s / base.width(), s / base.height(), s / (f * std::pow(corner, 3));
    refine_position_ = options.refine_position;
    refine_distortion_ = options.refine_distortion;
    // The priors' weights: a move of sigma costs what every point one pixel off does.
    const double n = double(points.size());
    prior_.setZero();
    for (int k = 3; k < 6; ++k) prior_[k] = n * std::pow(unit_[k] / options.position_sigma_m, 2);
    prior_[7] = n * std::pow(unit_[7] / options.principal_point_sigma, 2);
    prior_[8] = n * std::pow(unit_[8] * base.height() / (base.width() * options.principal_point_sigma), 2);
    prior_[9] = n * std::pow(unit_[9] / options.distortion_sigma, 2);
  }

  Params solve(int max_iterations) {
    Params z = Params::Zero();
    double lambda = 1e-3;
    Eigen::VectorXd r = residuals(z);
    double cost = total_cost(r, z);
    for (int it = 0; it < max_iterations; ++it) {
      // The Jacobian by central differences, half a unit (~half a pixel) each way.
      Eigen::Matrix<double, Eigen::Dynamic, kParams> jac(r.size(), kParams);
      jac.setZero();
      for (int k = 0; k < kParams; ++k) {
        if (!active(k)) continue;
        Params dz = Params::Zero();
        dz[k] = 0.5;
        jac.col(k) = (residuals(z + dz) - residuals(z - dz)) / 1.0;
      }
      Eigen::VectorXd w(r.size());
      for (Eigen::Index i = 0; i < r.size(); ++i) w[i] = robust_weight(std::abs(r[i]), kDelta, cap_);
      Eigen::Matrix<double, kParams, kParams> a = jac.transpose() * w.asDiagonal() * jac;
      Params g = jac.transpose() * w.cwiseProduct(r);
      a.diagonal() += prior_;
      g += prior_.cwiseProduct(z);
      for (int k = 0; k < kParams; ++k)
        if (!active(k)) a.row(k).setZero(), a.col(k).setZero(), a(k, k) = 1.0, g[k] = 0.0;
      bool stepped = false;
      while (lambda < 1e8) {
        Eigen::Matrix<double, kParams, kParams> damped = a;
        damped.diagonal() += lambda * (a.diagonal().array() + 1e-6).matrix();
        const Params next = z - damped.ldlt().solve(g);
        const Eigen::VectorXd rn = residuals(next);
        const double c = total_cost(rn, next);
        if (c < cost) {
          stepped = (next - z).cwiseAbs().maxCoeff() > 1e-3;
          z = next, r = rn, cost = c, lambda = std::max(1e-6, lambda * 0.3);
          break;
        }
        lambda *= 10.0;
      }
      if (!stepped) break;
    }
    return unit_.cwiseProduct(z);
  }

  CameraSpec moved(const Params& p) const { return moved_camera(base_, p, pivot_r2_); }

  // The mean capped distance of the points through the base camera moved by p.
  double mean_distance(const Params& p) const {
    const Eigen::VectorXd r = residuals(p.cwiseQuotient(unit_));
    return r.size() ? r.cwiseAbs().mean() * field_.scale : 0.0;
  }

 private:
  static constexpr double kDelta = 1.0;  // Huber's delta: a pixel of the level
  bool active(int k) const {
    if (k >= 3 && k <= 5) return refine_position_;
    return k != 9 || refine_distortion_;
  }

  Eigen::VectorXd residuals(const Params& z) const {
    const Camera camera(moved(unit_.cwiseProduct(z)), base_.width(), base_.height());
    Eigen::VectorXd r(points_.size());
    for (size_t i = 0; i < points_.size(); ++i) {
      const auto q = camera.project(points_[i]);
      r[Eigen::Index(i)] = q ? field_.residual(*q, cap_) : cap_;
    }
    return r;
  }
  double total_cost(const Eigen::VectorXd& r, const Params& z) const {
    double c = 0.0;
    for (Eigen::Index i = 0; i < r.size(); ++i) c += robust_cost(std::abs(r[i]), kDelta, cap_);
    c += 0.5 * z.dot(prior_.cwiseProduct(z));
    return c;
  }

  const Camera& base_;
  const std::vector<Vec3>& points_;
  const EdgeField& field_;
  float cap_;
  Params unit_;
  bool refine_position_ = true, refine_distortion_ = true;
  Params prior_;
  double pivot_r2_ = 0.0;
};

// The levels, coarsest first: the pyramid level and the distance cap in its
// pixels (the coarsest reaches 32 full-resolution pixels, about 2.5 degrees
// of a 40-degree field over 480 rows), and the re-extractions of the edges.
struct Level {
  int pyramid;
  float cap;
  int rounds;
};
constexpr Level kLevels[] = {{3, 4.0f, 2}, {2, 4.0f, 2}, {1, 4.0f, 2}, {0, 4.0f, 2}};

// The share by which a free k1 must lower the edge mismatch to be kept:
// the pinhole public scenes' moves by 0.7 % or less (docs/benchmarks.md,
// "A lens's distortion"), a lens's 5 % barrel by 3-10 %.
constexpr double kDistortionGain = 0.02;
// The share by which the probe's free k1 (distortion_left) must lower it for
// the levels to run with k1 free: a quarter of the above, as a photo the
// probe passes wrongly costs time, not the match.
constexpr double kDistortionSeen = 0.25 * kDistortionGain;
// The second start of k1: a wide lens's barrel.
constexpr float kBarrelStart = -0.1f;

double mismatch_px(const std::vector<Vec3>& points, const Camera& camera, const EdgeField& full) {
  double sum = 0.0;
  for (const Vec3& p : points) {
    const auto q = camera.project(p);
    sum += q ? std::abs(full.residual(*q, kReportCap)) : kReportCap;
  }
  return points.empty() ? 0.0 : sum / double(points.size());
}

void check_range(const RegistrationResult& r, const Scene& scene, const RegistrationOptions& o) {
  const auto refuse = [&](const std::string& what, float amount, float limit, const char* unit) {
    throw InputError(scene.path.string(), "/camera",
                     fmt::format("registration would {} {:.3g} {} (more than {:.3g}): the photo's edges do not match "
                                 "the geometry's; check the camera and the geometry",
                                 what, amount, unit, limit));
  };
  if (r.turned_deg() > o.max_turn_deg) refuse("turn the camera", r.turned_deg(), o.max_turn_deg, "degrees");
  if (std::abs(r.fov_change()) > o.max_fov_change)
    refuse("change the field of view", 100 * std::abs(r.fov_change()), 100 * o.max_fov_change, "%");
  const float shift = (r.after.principal_point - r.before.principal_point).norm();
  if (shift > o.max_principal_point_shift)
    refuse("shift the principal point", 100 * shift, 100 * o.max_principal_point_shift, "% of the width");
  if (r.moved_m() > o.max_move_m) refuse("move the camera", 100 * r.moved_m(), 100 * o.max_move_m, "cm");
  const float bent = std::abs(r.after.distortion.x() - r.before.distortion.x());
  if (bent > o.max_distortion_change) refuse("change the lens's distortion k1 by", bent, o.max_distortion_change, "");
}

// A camera the levels reached, the geometry's edges it shows and their mismatch.
struct Match {
  Camera camera;
  std::vector<Vec3> points;
  double mismatch;
};

// The pinhole's match with the lens's k1 freed at the finest level, on the
// edges it shows, from k1 as given and from a barrel: the better camera,
// where it lowers their mismatch by kDistortionSeen; else none, and the
// levels do not run with k1 free (twice the pinhole's time). On a pinhole
// photo this solve trades k1 against the field of view within the edges'
// noise (the public scenes: 0.3 % at most; bent 5 %: 1.7-11 %,
// docs/benchmarks.md "A lens's distortion").
std::optional<Camera> distortion_left(const Match& pinhole, const EdgeField& full, const RegistrationOptions& options) {
  RegistrationOptions o = options;
  o.refine_distortion = true;
  const float cap = std::end(kLevels)[-1].cap;
  const int w = pinhole.camera.width(), h = pinhole.camera.height();
  LevelSolve from_pinhole(pinhole.camera, pinhole.points, full, cap, o);
  Params barrel = Params::Zero();
  barrel[9] = kBarrelStart;
  const Camera barrel_start(from_pinhole.moved(barrel), w, h);
  LevelSolve from_barrel(barrel_start, pinhole.points, full, cap, o);
  std::optional<Camera> best;
  double least = (1.0 - kDistortionSeen) * pinhole.mismatch;
  for (LevelSolve* solve : {&from_pinhole, &from_barrel}) {
    const Camera bent(solve->moved(solve->solve(30)), w, h);
    const double mismatch = mismatch_px(pinhole.points, bent, full);
    spdlog::info("register: the pinhole's match with k1 free ({:.4f}): edge mismatch {:.3f} -> {:.3f} px",
                 bent.spec().distortion.x(), pinhole.mismatch, mismatch);
    if (mismatch < least) best = bent, least = mismatch;
  }
  return best;
}

// The levels' solves from `start`, coarse to fine, each round on the
// geometry's edges seen through the camera so far (`points` the start's).
Camera refine_over_levels(const Camera& start, const RayScene& rays, const std::vector<EdgeField>& fields,
                          const RegistrationOptions& options, std::vector<Vec3>& points, const std::string& file,
                          Progress& progress) {
  Camera camera = start;
  for (const Level& level : kLevels)
    for (int round = 0; round < level.rounds; ++round) {
      if (round > 0 || &level != &kLevels[0]) points = geometry_edges(camera, rays, file);
      LevelSolve solve(camera, points, fields[size_t(level.pyramid)], level.cap, options);
      const Params p = solve.solve(30);
      spdlog::info("register: level {} round {}: {} edge points, mean distance {:.3f} -> {:.3f} px", level.pyramid,
                   round, points.size(), solve.mean_distance(Params::Zero()), solve.mean_distance(p));
      camera = Camera(solve.moved(p), camera.width(), camera.height());
      progress.advance();
    }
  return camera;
}

}  // namespace

float RegistrationResult::turned_deg() const {
  const Vec3 f0 = (before.look_at - before.position).normalized(), f1 = (after.look_at - after.position).normalized();
  const Vec3 r0 = f0.cross(before.up).normalized(), r1 = f1.cross(after.up).normalized();
  Eigen::Matrix3f a, b;
  a << r0, r0.cross(f0), f0;
  b << r1, r1.cross(f1), f1;
  const Eigen::AngleAxisf turn(Eigen::Matrix3f(b * a.transpose()));
  return std::abs(turn.angle()) * 180.0f / kPi;
}

float RegistrationResult::fov_change() const { return after.vfov_deg / before.vfov_deg - 1.0f; }

Vec2 RegistrationResult::principal_point_shift_px(int width, int height) const {
  const Vec2 d = after.principal_point - before.principal_point;
  return {d.x() * width, d.y() * height};
}

float RegistrationResult::moved_m() const { return (after.position - before.position).norm(); }

std::string RegistrationResult::what_moved(int width, int height) const {
  const Vec2 shift = principal_point_shift_px(width, height);
  return fmt::format(
      "turned {:.3g} degrees, moved {:.3g} cm, vfov {:.4g} -> {:.4g} degrees ({:+.2f} %), principal point shifted "
      "{:+.2f} {:+.2f} px, distortion k1 {:.3g} -> {:.3g}",
      turned_deg(), 100.0f * moved_m(), before.vfov_deg, after.vfov_deg, 100.0f * fov_change(), shift.x(), shift.y(),
      before.distortion.x(), after.distortion.x());
}

std::vector<std::string> describe_registration(const RegistrationResult& r, int width, int height) {
  if (r.mismatch_after_px >= r.mismatch_before_px)
    return {fmt::format(
        "camera unchanged: no camera near it matches the photo's edges better (edge mismatch {:.3f} px); if it is off "
        "by more than ~2 degrees, correct it by hand first",
        r.mismatch_before_px)};
  return {"camera " + r.what_moved(width, height),
          fmt::format("edge mismatch {:.3f} -> {:.3f} px (mean distance of {} geometry edge pixels to the photo's "
                      "edges, capped at 8 px)",
                      r.mismatch_before_px, r.mismatch_after_px, r.edge_points)};
}

float view_difference_px(const CameraSpec& a, const CameraSpec& b, int width, int height) {
  const Camera ca(a, width, height), cb(b, width, height);
  float most = 0.0f;
  for (int i = 0; i <= 8; ++i)
    for (int j = 0; j <= 8; ++j) {
      const Vec2 pixel(width * i / 8.0f, height * j / 8.0f);
      const auto seen = cb.project(cb.position() + ca.ray_direction(pixel.x(), pixel.y()));
      most = std::max(most, seen ? (*seen - pixel).norm() : float(width));
    }
  return most;
}

double edge_mismatch(const Scene& scene, const RayScene& rays, const Camera& camera) {
  const std::vector<EdgeField> full = edge_pyramid(scene.photo, 1);
  return mismatch_px(geometry_edges(camera, rays, scene.path.string()), camera, full.front());
}

RegistrationResult register_camera(Scene& scene, const RayScene& rays, const RegistrationOptions& options,
                                   Progress& progress) {
  const std::string file = scene.path.string();
  const std::vector<EdgeField> fields = edge_pyramid(scene.photo, int(std::size(kLevels)));
  // Fewer than a row's worth of edge pixels: nothing to register by.
  if (fields.front().edge_pixels() < size_t(scene.photo.width))
    throw TooFewEdges(
        file, "/photo",
        fmt::format("only {} edge pixels: too few to register the camera by", fields.front().edge_pixels()));

  RegistrationResult result;
  result.before = scene.camera.spec();
  std::vector<Vec3> points = geometry_edges(scene.camera, rays, file);
  if (points.size() < 50)
    throw TooFewEdges(
        file, "/camera",
        fmt::format("the geometry shows only {} edge pixels: too few to register the camera by", points.size()));
  result.mismatch_before_px = mismatch_px(points, scene.camera, fields.front());

  // A pinhole first (the given distortion held), then, where its match
  // shows a distortion left (distortion_left), the levels with the lens's
  // k1 free, kept where they meet the photo visibly better: on a pinhole
  // photo a free k1 trades against the field of view within the edges'
  // noise. Each from the given camera (from the pinhole's match, the field
  // of view has already taken what it can of the distortion), k1 from the
  // given and from a wide lens's barrel, and the pinhole's match with k1
  // freed at the finest level, the best kept: the finer levels' capped
  // edges hold k1 in the nearer of two valleys.
  const bool fit_distortion = options.refine_distortion;
  int rounds = 0;
  for (const Level& l : kLevels) rounds += l.rounds;
  progress.begin("register: matching the geometry's edges to the photo's", rounds);
  const auto matched = [&](const Camera& camera) {
    Match m{camera, geometry_edges(camera, rays, file), 0.0};
    m.mismatch = mismatch_px(m.points, m.camera, fields.front());
    return m;
  };
  const auto register_from = [&](const CameraSpec& start, bool free_k1) {
    RegistrationOptions o = options;
    o.refine_distortion = free_k1;
    const Camera from(start, scene.camera.width(), scene.camera.height());
    std::vector<Vec3> start_points = start.distortion == result.before.distortion ? points : std::vector<Vec3>{};
    if (start_points.empty()) start_points = geometry_edges(from, rays, file);
    return matched(refine_over_levels(from, rays, fields, o, start_points, file, progress));
  };
  Match best = register_from(result.before, false);
  progress.end();
  if (const auto left = fit_distortion ? distortion_left(best, fields.front(), options) : std::nullopt) {
    progress.begin("register: the lens's distortion", 2 * rounds);
    CameraSpec barrel = result.before;
    barrel.distortion.x() += kBarrelStart;
    Match bent = matched(*left);
    for (const CameraSpec& start : {result.before, barrel})
      if (Match m = register_from(start, true); m.mismatch < bent.mismatch) bent = std::move(m);
    spdlog::info("register: with the lens's distortion k1 {:.4f}: edge mismatch {:.3f} px, {:.3f} px without",
                 bent.camera.spec().distortion.x(), bent.mismatch, best.mismatch);
    if (bent.mismatch < (1.0 - kDistortionGain) * best.mismatch) best = std::move(bent);
    progress.end();
  }

  const Camera& camera = best.camera;
  result.after = camera.spec();
  result.mismatch_after_px = best.mismatch;
  result.edge_points = best.points.size();
  // No better match (the given camera outside the basin, or already right):
  // the camera stays as it was.
  if (result.mismatch_after_px >= result.mismatch_before_px) {
    result.after = result.before, result.mismatch_after_px = result.mismatch_before_px;
    return result;
  }
  check_range(result, scene, options);
  scene.camera = camera;
  return result;
}

}  // namespace relight

namespace relight {

CameraCheck check_camera(Scene& scene, const RayScene& rays, Progress& progress) {
  const int w = scene.camera.width(), h = scene.camera.height();
  CameraCheck check;
  RegistrationResult r;
  try {
    r = register_camera(scene, rays, RegistrationOptions{}, progress);
  } catch (const TooFewEdges& e) {
    check.kept_because = "not checked against the photo: " + e.message();
    return check;
  } catch (const InputError& e) {
    check.kept_because = e.what();
    check.refused = true;
    return check;
  }
  check.moved_px = view_difference_px(r.before, r.after, w, h);
  if (check.moved_px <= kVisiblyOffPx || r.mismatch_after_px > (1.0f - kVisiblyBetterShare) * r.mismatch_before_px) {
    scene.camera = Camera(r.before, w, h);
    check.kept_because = fmt::format(
        "the photo's edges meet the geometry's (edge mismatch {:.2f} px; a registered camera would see {:.2f} px "
        "from it, its edge mismatch {:.2f} px)",
        r.mismatch_before_px, check.moved_px, r.mismatch_after_px);
    return check;
  }
  check.registered = r;
  return check;
}

std::optional<CameraSpec> register_when_off(Scene& scene, const RayScene& rays, Progress& progress) {
  const CameraCheck check = check_camera(scene, rays, progress);
  if (check.refused) spdlog::warn("{}: the camera is kept as given: {}", scene.path.string(), check.kept_because);
  if (!check.registered) {
    if (!check.refused) spdlog::info("camera kept as given: {}", check.kept_because);
    return std::nullopt;
  }
  const RegistrationResult& r = *check.registered;
  spdlog::warn(
      "{}: the camera was off the photo by up to {:.1f} px (edge mismatch {:.2f} -> {:.2f} px): registered for this "
      "analysis, {}. analysis.json keeps it and every render of the analysis uses it; `relight register` writes it "
      "into a scene, --keep-camera keeps the given one",
      scene.path.string(), check.moved_px, r.mismatch_before_px, r.mismatch_after_px,
      r.what_moved(scene.camera.width(), scene.camera.height()));
  return r.after;
}

}  // namespace relight

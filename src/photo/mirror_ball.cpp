#include "photo/mirror_ball.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>

#include "core/error.h"

namespace relight {

namespace {

cv::Mat luminance(const Image& photo) {
  cv::Mat l(photo.height, photo.width, CV_32F);
  for (int y = 0; y < photo.height; ++y)
    for (int x = 0; x < photo.width; ++x) {
      const Vec3& p = photo.at(x, y);
      l.at<float>(y, x) = 0.2126f * p.x() + 0.7152f * p.y() + 0.0722f * p.z();
    }
  return l;
}

cv::Mat to_8bit(const cv::Mat& values) {
  double lo = 0, hi = 0;
  cv::minMaxLoc(values, &lo, &hi);
  cv::Mat out;
  values.convertTo(out, CV_8U, hi > lo ? 255.0 / (hi - lo) : 1.0, hi > lo ? -lo * 255.0 / (hi - lo) : 0.0);
  return out;
}

float sample(const cv::Mat& image, double x, double y) {  // bilinear, at pixel-centre coordinates
  const int x0 = std::clamp(int(std::floor(x)), 0, image.cols - 2),
            y0 = std::clamp(int(std::floor(y)), 0, image.rows - 2);
  const double fx = std::clamp(x - x0, 0.0, 1.0), fy = std::clamp(y - y0, 0.0, 1.0);
  const auto at = [&](int xx, int yy) { return double(image.at<float>(yy, xx)); };
  return float((1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
               fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1)));
}

// Algebraic (Kasa) least-squares circle through the points.
Circle fit_circle(const std::vector<Eigen::Vector2d>& points) {
  Eigen::MatrixXd a(points.size(), 3);
  Eigen::VectorXd b(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    a.row(i) << points[i].x(), points[i].y(), 1.0;
    b(i) = -points[i].squaredNorm();
  }
  const Eigen::Vector3d s = a.colPivHouseholderQr().solve(b);
  const double cx = -s(0) / 2, cy = -s(1) / 2;
  return {cx, cy, std::sqrt(std::max(cx * cx + cy * cy - s(2), 0.0))};
}

// Along rays from the coarse centre, the position of the strongest edge
// within 25 % of the coarse radius: the centroid of the luminance slope
// within 1.5 px of its largest value (linear luminance: a pixel straddling
// the rim is a linear mix of the two sides, so the centroid is unbiased;
// in log luminance it would lean to the darker side); then a circle fitted to them, refitted without those over 2 px
// off (a highlight's or the ball stand's edge).
Circle refine_circle(const cv::Mat& lum, const Circle& coarse) {
  constexpr int kRays = 360;
  constexpr double kStep = 0.25;
  constexpr int kWindow = 6;  // samples, 1.5 px
  const double start = 0.75 * coarse.r;
  std::vector<Eigen::Vector2d> edges;
  for (int k = 0; k < kRays; ++k) {
    const double angle = 2.0 * kPi * k / kRays, dx = std::cos(angle), dy = std::sin(angle);
    std::vector<double> profile;
    for (double t = start; t <= 1.25 * coarse.r; t += kStep)
      profile.push_back(sample(lum, coarse.cx + t * dx, coarse.cy + t * dy));
    std::vector<double> slope(profile.size(), 0.0);
    for (size_t i = 1; i + 1 < profile.size(); ++i) slope[i] = std::abs(profile[i + 1] - profile[i - 1]);
    const size_t peak = size_t(std::max_element(slope.begin(), slope.end()) - slope.begin());
    if (slope[peak] <= 0 || peak < kWindow || peak + kWindow >= profile.size()) continue;
    double weight = 0, centroid = 0;
    for (size_t i = peak - kWindow; i <= peak + kWindow; ++i) weight += slope[i], centroid += slope[i] * double(i);
    const double t = start + centroid / weight * kStep;
    edges.emplace_back(coarse.cx + t * dx, coarse.cy + t * dy);
  }
  if (edges.size() < 16) return coarse;
  Circle fit = fit_circle(edges);
  std::vector<Eigen::Vector2d> inliers;
  for (const auto& e : edges)
    if (std::abs((e - Eigen::Vector2d(fit.cx, fit.cy)).norm() - fit.r) < 2.0) inliers.push_back(e);
  if (inliers.size() >= 16) fit = fit_circle(inliers);
  return fit;
}

}  // namespace

Circle find_mirror_ball(const Image& photo, const std::string& name) {
  // The Hough transform runs on the log luminance: the ball's outline is then
  // as strong against a dark background as against a bright one.
  const cv::Mat lum = luminance(photo);
  cv::Mat log_l;
  cv::log(cv::max(lum, 1e-6f), log_l);
  cv::Mat grey = to_8bit(log_l);
  cv::GaussianBlur(grey, grey, cv::Size(5, 5), 1.5);
  const int side = std::min(photo.width, photo.height);
  std::vector<cv::Vec3f> circles;
  cv::HoughCircles(grey, circles, cv::HOUGH_GRADIENT, 1, side, 100, 30, std::max(side / 20, 4), side / 2);
  if (circles.empty())
    throw InputError(name, "", "no mirror ball's circle found; give it with --circle cx,cy,r (pixels)");
  // OpenCV's coordinates put pixel centres at whole numbers; Circle's at +0.5.
  const Circle fit = refine_circle(lum, {circles[0][0], circles[0][1], circles[0][2]});
  return {fit.cx + 0.5, fit.cy + 0.5, fit.r};
}

Image crop_mirror_ball(const Image& photo, const Circle& ball) {
  const int side = std::max(int(std::lround(2.0 * ball.r)), 2);
  Image probe(side, side);
  std::vector<cv::Mat> channels(3);
  for (int c = 0; c < 3; ++c) {
    channels[c] = cv::Mat(photo.height, photo.width, CV_32F);
    for (int y = 0; y < photo.height; ++y)
      for (int x = 0; x < photo.width; ++x) channels[c].at<float>(y, x) = photo.at(x, y)[c];
  }
  for (int row = 0; row < side; ++row)
    for (int col = 0; col < side; ++col) {
      const double a = 2.0 * (col + 0.5) / side - 1.0, b = 1.0 - 2.0 * (row + 0.5) / side;
      if (a * a + b * b > 1.0) continue;
      const double x = ball.cx + a * ball.r - 0.5, y = ball.cy - b * ball.r - 0.5;
      for (int c = 0; c < 3; ++c) probe.at(col, row)[c] = sample(channels[c], x, y);
    }
  return probe;
}

}  // namespace relight

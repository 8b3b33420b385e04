#include "photo/hdr_merge.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <opencv2/photo.hpp>
#include <stdexcept>

namespace relight {

namespace {

cv::Mat to_mat(const EncodedImage& image) {
  // A copy: OpenCV's algorithms do not take const data.
  return cv::Mat(image.height, image.width, CV_8UC3, const_cast<uint8_t*>(image.rgb.data())).clone();
}

// Whether the image's median threshold bitmap says anything: not where most
// of it is clipped or black (the median at the end of the codes), whose
// bitmap is noise and whose "shift" would be made up; such a bracket is
// left where it is.
bool has_threshold_bitmap(const cv::Mat& grey) {
  constexpr int kMargin = 8;  // codes from either end
  int histogram[256] = {};
  for (int y = 0; y < grey.rows; ++y)
    for (int x = 0; x < grey.cols; ++x) ++histogram[grey.at<uint8_t>(y, x)];
  const int half = grey.rows * grey.cols / 2;
  int median = 0;
  for (int count = 0; median < 255 && (count += histogram[median]) < half;) ++median;
  return median > kMargin && median < 255 - kMargin;
}

// Shifts every image onto the middle one (the best exposed, usually). Each
// is compared with its neighbour towards the middle, already aligned: two
// exposures a stop or two apart share most of their median threshold
// bitmap, where the darkest and the brightest bracket (half black, half
// clipped) may share little. The border a shift uncovers repeats the edge
// pixels rather than turning black, which the merge would take as shadow.
std::vector<std::array<int, 2>> align_to_middle(std::vector<cv::Mat>& images) {
  // Pyramid levels down to about 32 pixels (OpenCV's default of 6 levels
  // would compare images of a few pixels on a small photo): shifts of up to
  // 2^levels pixels, 64 on a photo of 2000 pixels or more.
  const int side = std::min(images[0].cols, images[0].rows);
  const int levels = std::clamp(int(std::floor(std::log2(side / 32.0))), 1, 6);
  const auto mtb = cv::createAlignMTB(levels);
  const int pivot = int(images.size()) / 2;
  std::vector<cv::Mat> grey(images.size());
  for (size_t i = 0; i < images.size(); ++i) cv::cvtColor(images[i], grey[i], cv::COLOR_RGB2GRAY);
  std::vector<cv::Point> shift(images.size(), cv::Point(0, 0));
  for (int step : {-1, 1})
    for (int i = pivot + step; i >= 0 && i < int(images.size()); i += step)
      if (has_threshold_bitmap(grey[i]) && has_threshold_bitmap(grey[i - step]))
        shift[i] = shift[i - step] + mtb->calculateShift(grey[i - step], grey[i]);
  std::vector<std::array<int, 2>> shifts;
  for (size_t i = 0; i < images.size(); ++i) {
    shifts.push_back({shift[i].x, shift[i].y});
    if (shift[i] == cv::Point(0, 0)) continue;
    const cv::Mat translate = (cv::Mat_<double>(2, 3) << 1, 0, shift[i].x, 0, 1, shift[i].y);
    cv::Mat moved;
    cv::warpAffine(images[i], moved, translate, images[i].size(), cv::INTER_NEAREST, cv::BORDER_REPLICATE);
    images[i] = moved;
  }
  return shifts;
}

// Debevec and Malik's hat weight, 0 at the ends: a code of 0 or 255 is
// clipped and says only "darker" or "brighter".
float hat_weight(int code) { return float(code <= 127 ? code : 255 - code); }

// ln E per channel, each bracket weighted by its own code in that channel.
// (OpenCV's MergeDebevec weighs all three channels by the mean of their
// weights, so a channel clipped in a bracket counts as much as the others
// are trusted: on the outdoor reference scene it left pixels 30 % dark.)
// Where every bracket is clipped, the shortest exposure's value (the
// brightest the brackets can tell); where every one is black, the longest's.
Image merge_channels(const std::vector<cv::Mat>& images, const std::vector<float>& times,
                     const std::array<std::vector<float>, 3>& log_response) {
  const auto shortest = size_t(std::min_element(times.begin(), times.end()) - times.begin());
  const auto longest = size_t(std::max_element(times.begin(), times.end()) - times.begin());
  Image radiance(images[0].cols, images[0].rows);
  for (int y = 0; y < radiance.height; ++y)
    for (int x = 0; x < radiance.width; ++x)
      for (int c = 0; c < 3; ++c) {
        double sum = 0, weight = 0;
        for (size_t j = 0; j < images.size(); ++j) {
          const int z = images[j].at<cv::Vec3b>(y, x)[c];
          const double w = hat_weight(z);
          sum += w * (log_response[c][z] - std::log(times[j]));
          weight += w;
        }
        if (weight == 0) {
          const size_t j = images[shortest].at<cv::Vec3b>(y, x)[c] == 255 ? shortest : longest;
          sum = log_response[c][images[j].at<cv::Vec3b>(y, x)[c]] - std::log(times[j]);
          weight = 1;
        }
        radiance.at(x, y)[c] = float(std::exp(sum / weight));
      }
  return radiance;
}

}  // namespace

MergedBrackets merge_brackets(const std::vector<EncodedImage>& brackets, const std::vector<float>& times, bool align) {
  if (brackets.size() < 2 || times.size() != brackets.size())
    throw std::invalid_argument("merge_brackets: at least two brackets, one time each");
  std::vector<cv::Mat> images;
  for (const EncodedImage& b : brackets) images.push_back(to_mat(b));
  MergedBrackets merged;
  merged.shifts = align ? align_to_middle(images) : std::vector<std::array<int, 2>>(images.size(), {0, 0});

  const cv::Mat exposure_times(int(times.size()), 1, CV_32F, const_cast<float*>(times.data()));
  cv::Mat response;  // 256x1 CV_32FC3: the exposure E*t of each code, exp(g)
  cv::createCalibrateDebevec()->process(images, response, exposure_times);
  for (int c = 0; c < 3; ++c) {
    merged.log_response[c].resize(256);
    for (int z = 0; z < 256; ++z) merged.log_response[c][z] = std::log(response.at<cv::Vec3f>(z)[c]);
  }
  merged.radiance = merge_channels(images, times, merged.log_response);
  return merged;
}

}  // namespace relight

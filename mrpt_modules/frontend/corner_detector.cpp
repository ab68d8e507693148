#include "mrpt_modules/frontend/corner_detector.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace rpvio {

void CornerDetector::computeMinEigenvalues(const cv::Mat& image) {
  // cv::cornerMinEigenVal(image, ·, 3, 3) step by step, into kept buffers: Sobel gradients scaled
  // by 1 / (2^(aperture-1) · block · 255), their products summed over the 3x3 block (boxFilter
  // works channel by channel, so one plane per product gives the same sums), and the smaller
  // eigenvalue of the summed matrix [[xx, xy], [xy, yy]] as (a + c) - sqrt((a - c)² + b²) with
  // a = xx / 2, b = xy, c = yy / 2. Planes keep the loops vectorizable.
  const double scale = 1.0 / (4 * 3 * 255.0);
  cv::Sobel(image, dx_, CV_32F, 1, 0, 3, scale, 0, cv::BORDER_DEFAULT);
  cv::Sobel(image, dy_, CV_32F, 0, 1, 3, scale, 0, cv::BORDER_DEFAULT);
  for (cv::Mat& m : products_) m.create(image.size(), CV_32F);
  for (int y = 0; y < image.rows; ++y) {
    const float* gx = dx_.ptr<float>(y);
    const float* gy = dy_.ptr<float>(y);
    float* xx = products_[0].ptr<float>(y);
    float* xy = products_[1].ptr<float>(y);
    float* yy = products_[2].ptr<float>(y);
    for (int x = 0; x < image.cols; ++x) {
      xx[x] = gx[x] * gx[x];
      xy[x] = gx[x] * gy[x];
      yy[x] = gy[x] * gy[x];
    }
  }
  for (cv::Mat& m : products_)
    cv::boxFilter(m, m, CV_32F, cv::Size(3, 3), cv::Point(-1, -1), false, cv::BORDER_DEFAULT);
  min_eigenvalue_.create(image.size(), CV_32F);
  for (int y = 0; y < image.rows; ++y) {
    const float* xx = products_[0].ptr<float>(y);
    const float* xy = products_[1].ptr<float>(y);
    const float* yy = products_[2].ptr<float>(y);
    float* out = min_eigenvalue_.ptr<float>(y);
    for (int x = 0; x < image.cols; ++x) {
      const float a = xx[x] * 0.5f, b = xy[x], c = yy[x] * 0.5f;
      out[x] = (a + c) - std::sqrt((a - c) * (a - c) + b * b);
    }
  }
}

void CornerDetector::collectLocalMaxima(const cv::Mat& allowed, float threshold) {
  // goodFeaturesToTrack zeroes responses <= threshold, then keeps allowed non-zero pixels equal to
  // their 3x3 dilation (image border rows and columns excluded): with a positive threshold (see
  // detect), a response above it that no neighbour exceeds (a zeroed neighbour never does).
  candidates_.clear();
  const int width = min_eigenvalue_.cols;
  for (int y = 1; y + 1 < min_eigenvalue_.rows; ++y) {
    const uint8_t* ok = allowed.ptr<uint8_t>(y);
    const float* above = min_eigenvalue_.ptr<float>(y - 1);
    const float* row = min_eigenvalue_.ptr<float>(y);
    const float* below = min_eigenvalue_.ptr<float>(y + 1);
    for (int x = 1; x + 1 < width; ++x) {
      const float v = row[x];
      if (!ok[x] || !(v > threshold)) continue;
      if (v < row[x - 1] || v < row[x + 1] || v < above[x - 1] || v < above[x] ||
          v < above[x + 1] || v < below[x - 1] || v < below[x] || v < below[x + 1])
        continue;
      candidates_.push_back({v, y * width + x});
    }
  }
}

std::vector<cv::Point2f> CornerDetector::takeStrongestSpaced(cv::Size size, int max_corners,
                                                             double min_distance) {
  // Strongest first; equal responses: the later pixel first (goodFeaturesToTrack's pointer order).
  const auto stronger = [](const Candidate& a, const Candidate& b) {
    return a.response > b.response || (a.response == b.response && a.index > b.index);
  };
  // Accepted corners are binned in cells of side min_distance: a closer one is in a neighbour cell.
  const int cell = cvRound(min_distance);
  const int grid_width = (size.width + cell - 1) / cell;
  const int grid_height = (size.height + cell - 1) / cell;
  grid_.resize(static_cast<size_t>(grid_width) * grid_height);
  for (auto& c : grid_) c.clear();
  const double min_distance_sq = min_distance * min_distance;
  const auto isolated = [&](int x, int y) {
    const int cx = x / cell, cy = y / cell;
    for (int gy = std::max(0, cy - 1); gy <= std::min(grid_height - 1, cy + 1); ++gy)
      for (int gx = std::max(0, cx - 1); gx <= std::min(grid_width - 1, cx + 1); ++gx)
        for (const cv::Point2f& p : grid_[static_cast<size_t>(gy) * grid_width + gx]) {
          const float ex = static_cast<float>(x) - p.x, ey = static_cast<float>(y) - p.y;
          if (ex * ex + ey * ey < min_distance_sq) return false;
        }
    return true;
  };
  std::vector<cv::Point2f> corners;
  // Sorted a growing chunk at a time: usually the first chunk fills max_corners.
  auto begin = candidates_.begin();
  auto chunk = static_cast<std::ptrdiff_t>(8) * max_corners;
  while (begin != candidates_.end() && static_cast<int>(corners.size()) < max_corners) {
    const auto end = candidates_.end() - begin > chunk ? begin + chunk : candidates_.end();
    if (end != candidates_.end()) std::nth_element(begin, end, candidates_.end(), stronger);
    std::sort(begin, end, stronger);
    for (auto it = begin; it != end && static_cast<int>(corners.size()) < max_corners; ++it) {
      const int y = it->index / size.width, x = it->index % size.width;
      if (!isolated(x, y)) continue;
      const cv::Point2f corner(static_cast<float>(x), static_cast<float>(y));
      grid_[static_cast<size_t>(y / cell) * grid_width + x / cell].push_back(corner);
      corners.push_back(corner);
    }
    begin = end;
    chunk *= 2;
  }
  return corners;
}

std::vector<cv::Point2f> CornerDetector::detect(const cv::Mat& image, const cv::Mat& allowed,
                                                int max_corners, double quality_level,
                                                double min_distance) {
  CV_Assert(image.type() == CV_8UC1 && allowed.type() == CV_8UC1 &&
            allowed.size() == image.size() && min_distance >= 1 && quality_level > 0);
  if (image.empty() || max_corners <= 0) return {};
  computeMinEigenvalues(image);
  double strongest = 0;
  cv::minMaxLoc(min_eigenvalue_, nullptr, &strongest, nullptr, nullptr, allowed);
  if (strongest <= 0) return {};  // a flat (or fully masked) image has no corner
  // cv::threshold compares float images with the threshold cast to float.
  collectLocalMaxima(allowed, static_cast<float>(strongest * quality_level));
  return takeStrongestSpaced(image.size(), max_corners, min_distance);
}

}  // namespace rpvio

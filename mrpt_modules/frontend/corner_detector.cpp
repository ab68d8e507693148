#include "mrpt_modules/frontend/corner_detector.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <opencv2/imgproc.hpp>

#include "mrpt_modules/frontend/simd_clones.h"

namespace rpvio {

namespace {

/// Index of BORDER_REFLECT_101 (cv::BORDER_DEFAULT) for i in [-1, n].
int reflect101(int i, int n) {
  if (n == 1) return 0;
  return i < 0 ? -i : i >= n ? 2 * n - 2 - i : i;
}

}  // namespace

void CornerDetector::findSpans(const cv::Mat& allowed) {
  // near[y][c]: chunk c of row y holds an allowed pixel or borders one (one column beyond).
  const int rows = allowed.rows, cols = allowed.cols, chunks = (cols + kChunk - 1) / kChunk;
  const size_t cells = static_cast<size_t>(rows) * chunks;
  near_allowed_.resize(cells);
  for (int y = 0; y < rows; ++y) {
    const uint8_t* ok = allowed.ptr<uint8_t>(y);
    uint8_t* near = &near_allowed_[static_cast<size_t>(y) * chunks];
    for (int c = 0; c < chunks; ++c) {
      const int begin = c * kChunk, end = std::min(cols, begin + kChunk);
      uint8_t any = (begin > 0 ? ok[begin - 1] : 0) | (end < cols ? ok[end] : 0);
      if (end - begin == kChunk) {
        static_assert(kChunk == 2 * sizeof(uint64_t), "a full chunk is read as two words");
        uint64_t first, second;
        std::memcpy(&first, ok + begin, sizeof first);
        std::memcpy(&second, ok + begin + 8, sizeof second);
        any |= static_cast<uint8_t>((first | second) != 0);
      } else {
        for (int x = begin; x < end; ++x) any |= ok[x];
      }
      near[c] = any;
    }
  }
  // Flags of rows y − 1 ... y + 1 or'ed into row y.
  const auto widenByOneRow = [&](const std::vector<uint8_t>& in, std::vector<uint8_t>& out) {
    out.resize(cells);
    for (int y = 0; y < rows; ++y) {
      const uint8_t* above = &in[static_cast<size_t>(std::max(0, y - 1)) * chunks];
      const uint8_t* row = &in[static_cast<size_t>(y) * chunks];
      const uint8_t* below = &in[static_cast<size_t>(std::min(rows - 1, y + 1)) * chunks];
      uint8_t* o = &out[static_cast<size_t>(y) * chunks];
      for (int c = 0; c < chunks; ++c) o[c] = above[c] | row[c] | below[c];
    }
  };
  // Runs of consecutive flagged chunks, row by row.
  const auto collect = [&](const std::vector<uint8_t>& flags, RowSpans& out) {
    out.first.assign(static_cast<size_t>(rows) + 1, 0);
    out.spans.clear();
    for (int y = 0; y < rows; ++y) {
      out.first[y] = static_cast<int>(out.spans.size());
      const uint8_t* flag = &flags[static_cast<size_t>(y) * chunks];
      for (int c = 0; c < chunks;) {
        if (!flag[c]) {
          ++c;
          continue;
        }
        const int begin = c;
        while (c < chunks && flag[c]) ++c;
        out.spans.push_back({begin * kChunk, std::min(cols, c * kChunk)});
      }
    }
    out.first[rows] = static_cast<int>(out.spans.size());
  };
  // A response is read at an allowed pixel and its eight neighbours (the 3x3 local maximum); it
  // sums the products of the rows above and below.
  widenByOneRow(near_allowed_, within_one_row_);
  collect(within_one_row_, responses_);
  widenByOneRow(within_one_row_, within_two_rows_);
  collect(within_two_rows_, products_);
}

RPVIO_AVX2_CLONES float CornerDetector::computeMinEigenvalues(const cv::Mat& image,
                                                              const cv::Mat& allowed) {
  // cv::cornerMinEigenVal(image, ·, 3, 3) in one pass over kept buffers, where responses are
  // read (findSpans): Sobel gradients scaled by 1 / (2^(aperture-1) · block · 255), their float
  // products gx², gx·gy, gy² summed over the 3x3 block (border reflected), and the smaller
  // eigenvalue of [[xx, xy], [xy, yy]] as (a + c) - sqrt((a - c)² + b²) with a = xx / 2, b = xy,
  // c = yy / 2.
  // cv::boxFilter sums float images in double and rounds the sum to float. A non-zero product is
  // within [s²/2, 2^21 s²] (s the scale; 8-bit Sobel responses are integers below 2^10), so as
  // floats the nine of a block are multiples of one power of two and their sum stays below 2^50
  // of it: the double sum is exact in any order and rounds to boxFilter's float bit for bit.
  findSpans(allowed);
  const double scale = 1.0 / (4 * 3 * 255.0);
  cv::Sobel(image, dx_, CV_32F, 1, 0, 3, scale, 0, cv::BORDER_DEFAULT);
  cv::Sobel(image, dy_, CV_32F, 0, 1, 3, scale, 0, cv::BORDER_DEFAULT);
  const int rows = image.rows, cols = image.cols;
  // Products of the three rows around y, in a ring of three rows per product (slot = row % 3):
  // small enough to stay in cache, each row computed once, over its spans and one column beyond.
  for (auto& ring : product_rows_) ring.resize(3 * static_cast<size_t>(cols));
  std::array<int, 3> row_in_slot{-1, -1, -1};
  const auto productRow = [&](size_t product, int row) {
    return product_rows_[product].data() + static_cast<size_t>(row % 3) * cols;
  };
  const auto computeProducts = [&](int row) {
    if (row_in_slot[row % 3] == row) return;
    row_in_slot[row % 3] = row;
    const float* gx = dx_.ptr<float>(row);
    const float* gy = dy_.ptr<float>(row);
    float* xx = productRow(0, row);
    float* xy = productRow(1, row);
    float* yy = productRow(2, row);
    for (const Span& span : products_.of(row))
      for (int x = std::max(0, span.begin - 1), end = std::min(cols, span.end + 1); x < end; ++x) {
        xx[x] = gx[x] * gx[x];
        xy[x] = gx[x] * gy[x];
        yy[x] = gy[x] * gy[x];
      }
  };
  // Column sums of the three rows around y, one padded row of doubles per product.
  for (auto& sums : column_sums_) sums.resize(static_cast<size_t>(cols) + 2);
  // Responses outside the spans are never read; zeros until a first frame writes them.
  if (min_eigenvalue_.size() != image.size())
    min_eigenvalue_ = cv::Mat::zeros(image.size(), CV_32F);
  std::array<float, 8> lane_maxima{};
  for (int y = 0; y < rows; ++y) {
    if (responses_.of(y).empty()) continue;
    const int above = reflect101(y - 1, rows), below = reflect101(y + 1, rows);
    for (const int row : {above, y, below}) computeProducts(row);
    float* out = min_eigenvalue_.ptr<float>(y);
    const uint8_t* ok = allowed.ptr<uint8_t>(y);
    for (const Span& span : responses_.of(y)) {
      for (size_t p = 0; p < product_rows_.size(); ++p) {
        const float* r0 = productRow(p, above);
        const float* r1 = productRow(p, y);
        const float* r2 = productRow(p, below);
        double* sums = column_sums_[p].data() + 1;
        for (int x = std::max(0, span.begin - 1), end = std::min(cols, span.end + 1); x < end; ++x)
          sums[x] = static_cast<double>(r0[x]) + static_cast<double>(r1[x]) + r2[x];
        if (span.begin == 0) sums[-1] = sums[reflect101(-1, cols)];
        if (span.end == cols) sums[cols] = sums[reflect101(cols, cols)];
      }
      const double* sxx = column_sums_[0].data() + 1;
      const double* sxy = column_sums_[1].data() + 1;
      const double* syy = column_sums_[2].data() + 1;
      for (int x = span.begin; x < span.end; ++x) {
        const float a = static_cast<float>(sxx[x - 1] + sxx[x] + sxx[x + 1]) * 0.5f;
        const float b = static_cast<float>(sxy[x - 1] + sxy[x] + sxy[x + 1]);
        const float c = static_cast<float>(syy[x - 1] + syy[x] + syy[x + 1]) * 0.5f;
        out[x] = (a + c) - std::sqrt((a - c) * (a - c) + b * b);
      }
      // Eight independent running maxima: no single chain of dependent max operations.
      int x = span.begin;
      for (; x + 8 <= span.end; x += 8)
        for (int k = 0; k < 8; ++k)
          lane_maxima[k] = std::max(lane_maxima[k], ok[x + k] ? out[x + k] : 0.0f);
      for (; x < span.end; ++x) lane_maxima[0] = std::max(lane_maxima[0], ok[x] ? out[x] : 0.0f);
    }
  }
  return *std::max_element(lane_maxima.begin(), lane_maxima.end());
}

RPVIO_AVX2_CLONES void CornerDetector::collectLocalMaxima(const cv::Mat& allowed, float threshold) {
  // goodFeaturesToTrack zeroes responses <= threshold, then keeps allowed non-zero pixels equal to
  // their 3x3 dilation (image border rows and columns excluded): with a positive threshold (see
  // detect), a response above it that no neighbour exceeds (a zeroed neighbour never does).
  // Allowed pixels and their neighbours lie in the responses' spans.
  candidates_.clear();
  const int width = min_eigenvalue_.cols;
  column_maxima_.resize(static_cast<size_t>(width));
  is_candidate_.resize(static_cast<size_t>(width));
  float* column_max = column_maxima_.data();
  uint8_t* candidate = is_candidate_.data();
  for (int y = 1; y + 1 < min_eigenvalue_.rows; ++y) {
    const uint8_t* ok = allowed.ptr<uint8_t>(y);
    const float* above = min_eigenvalue_.ptr<float>(y - 1);
    const float* row = min_eigenvalue_.ptr<float>(y);
    const float* below = min_eigenvalue_.ptr<float>(y + 1);
    for (const Span& span : responses_.of(y)) {
      const int begin = std::max(1, span.begin), end = std::min(width - 1, span.end);
      // Branch-free, so both loops vectorize: v is a local maximum when it equals the maximum of
      // its 3x3 neighbourhood.
      for (int x = begin - 1; x < end + 1; ++x)
        column_max[x] = std::max(std::max(above[x], row[x]), below[x]);
      for (int x = begin; x < end; ++x) {
        const float neighbourhood =
            std::max(std::max(column_max[x - 1], column_max[x]), column_max[x + 1]);
        candidate[x] =
            static_cast<uint8_t>((ok[x] != 0) & (row[x] > threshold) & (row[x] >= neighbourhood));
      }
      for (int x = begin; x < end; ++x) {
        // Candidates are sparse: skip eight pixels at a time.
        if (x + 8 < end) {
          uint64_t eight;
          std::memcpy(&eight, candidate + x, sizeof eight);
          if (eight == 0) {
            x += 7;
            continue;
          }
        }
        if (candidate[x]) candidates_.push_back({row[x], y * width + x});
      }
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
  const float strongest = computeMinEigenvalues(image, allowed);
  if (strongest <= 0) return {};  // a flat (or fully masked) image has no corner
  // cv::threshold compares float images with the threshold cast to float.
  collectLocalMaxima(allowed, static_cast<float>(static_cast<double>(strongest) * quality_level));
  return takeStrongestSpaced(image.size(), max_corners, min_distance);
}

}  // namespace rpvio

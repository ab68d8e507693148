#include "mrpt_modules/frontend/plane_feature_budget.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

namespace rpvio {

std::map<int, DensePlane> densePlanes(const cv::Mat& mask, const cv::Mat& detectable,
                                      int min_features, double min_distance, double min_spacing) {
  CV_Assert(mask.type() == CV_8UC1 && detectable.type() == CV_8UC1 &&
            mask.size() == detectable.size());
  std::map<int, DensePlane> dense;
  if (min_features <= 0) return dense;
  struct Extent {
    int area = 0, x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  };
  std::array<Extent, 256> extent{};
  // Row by row, in runs of one label (detectable pixels only; 0 otherwise): one extent update per
  // run. The row's labels are gathered first (a loop that vectorizes), then runs are followed
  // eight pixels at a time while a whole word repeats the run's label.
  const int cols = mask.cols;
  std::vector<uint8_t> labels(static_cast<size_t>(cols));
  for (int y = 0; y < mask.rows; ++y) {
    const uint8_t* __restrict label = mask.ptr<uint8_t>(y);
    const uint8_t* __restrict ok = detectable.ptr<uint8_t>(y);
    uint8_t* __restrict row = labels.data();
    for (int x = 0; x < cols; ++x) row[x] = label[x] & static_cast<uint8_t>(-(ok[x] != 0));
    for (int x = 0; x < cols;) {
      const uint8_t l = row[x];
      const uint64_t repeated = 0x0101010101010101ull * l;
      int end = x + 1;
      for (uint64_t word; end + 8 <= cols; end += 8) {
        std::memcpy(&word, row + end, sizeof word);
        if (word != repeated) break;
      }
      while (end < cols && row[end] == l) ++end;
      if (l != 0) {
        Extent& e = extent[l];
        if (e.area == 0) {
          e.x0 = x;
          e.y0 = y;
        }
        e.area += end - x;
        e.x0 = std::min(e.x0, x);
        e.x1 = std::max(e.x1, end - 1);
        e.y1 = y;
      }
      x = end;
    }
  }
  for (int label = 1; label < 255; ++label) {
    const Extent& e = extent[label];
    if (e.area == 0 || e.area >= min_features * min_distance * min_distance) continue;
    const double spacing = std::max(min_spacing, std::sqrt(e.area / double(min_features)));
    dense[label] = {std::min(spacing, min_distance),
                    cv::Rect(e.x0, e.y0, e.x1 - e.x0 + 1, e.y1 - e.y0 + 1)};
  }
  return dense;
}

}  // namespace rpvio

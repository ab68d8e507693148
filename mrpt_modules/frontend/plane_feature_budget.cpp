#include "mrpt_modules/frontend/plane_feature_budget.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

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
  for (int y = 0; y < mask.rows; ++y) {
    const uint8_t* label = mask.ptr<uint8_t>(y);
    const uint8_t* ok = detectable.ptr<uint8_t>(y);
    for (int x = 0; x < mask.cols; ++x) {
      if (!ok[x]) continue;
      Extent& e = extent[label[x]];
      if (e.area++ == 0) {
        e.x0 = e.x1 = x;
        e.y0 = e.y1 = y;
      }
      e.x0 = std::min(e.x0, x);
      e.x1 = std::max(e.x1, x);
      e.y1 = y;
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

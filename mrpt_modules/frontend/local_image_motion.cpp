#include "mrpt_modules/frontend/local_image_motion.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace rpvio {

std::optional<cv::Matx22d> localImageMotion(const std::vector<PixelMotion>& motions, size_t i,
                                            size_t neighbours, double reach_px) {
  std::vector<std::pair<double, size_t>> near;
  for (size_t k = 0; k < motions.size(); ++k) {
    const double d = cv::norm(motions[k].from - motions[i].from);
    if (k != i && d < reach_px) near.push_back({d, k});
  }
  if (near.size() < 3) return std::nullopt;
  const size_t n = std::min(near.size(), neighbours);
  std::partial_sort(near.begin(), near.begin() + n, near.end());
  cv::Matx22d moved_from = cv::Matx22d::zeros(), from_from = cv::Matx22d::zeros();
  for (size_t k = 0; k < n; ++k) {
    const PixelMotion& m = motions[near[k].second];
    const cv::Vec2d a(m.from.x - motions[i].from.x, m.from.y - motions[i].from.y);
    const cv::Vec2d b(m.to.x - motions[i].to.x, m.to.y - motions[i].to.y);
    moved_from += b * a.t();
    from_from += a * a.t();
  }
  // Eigenvalues of the 2x2 scatter: λ = tr/2 ± √(tr²/4 − det).
  const double half_trace = 0.5 * cv::trace(from_from);
  const double root =
      std::sqrt(std::max(0.0, half_trace * half_trace - cv::determinant(from_from)));
  const double largest = half_trace + root, smallest = half_trace - root;
  if (largest <= 0 || smallest < kMinNeighbourSpreadRatio * largest) return std::nullopt;
  return moved_from * from_from.inv();
}

}  // namespace rpvio

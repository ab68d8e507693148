#include "mrpt_modules/core/feature_frame.h"

#include <unordered_map>

namespace rpvio {

double averageParallax(const FeatureFrame& a, const FeatureFrame& b, double virtual_focal) {
  std::unordered_map<int, Eigen::Vector2d> in_a;
  for (const auto& f : a.features) in_a[f.id] = f.normalized;
  double sum = 0;
  size_t n = 0;
  for (const auto& f : b.features) {
    const auto it = in_a.find(f.id);
    if (it == in_a.end()) continue;
    sum += virtual_focal * (f.normalized - it->second).norm();
    ++n;
  }
  return n ? sum / n : 0.0;
}

size_t commonFeatures(const FeatureFrame& a, const FeatureFrame& b) {
  std::unordered_map<int, bool> in_a;
  for (const auto& f : a.features) in_a[f.id] = true;
  size_t n = 0;
  for (const auto& f : b.features) n += in_a.count(f.id);
  return n;
}

}  // namespace rpvio

#include "evaluation/plane_visibility.h"

#include <algorithm>
#include <array>
#include <set>

#include "rawlog_io/uniform_plane_region.h"

namespace rpvio::eval {

void PlaneVisibility::addMask(double t, const cv::Mat& mask) {
  times_.push_back(t);
  uniformPlaneRegion(mask, 2 * window_margin_ + 1, 1, lowest_, highest_, trackable_);
  std::array<int, 256> seen{}, trackable{};
  for (int r = 0; r < mask.rows; ++r) {
    const uint8_t* label = mask.ptr<uint8_t>(r);
    const uint8_t* uniform = trackable_.ptr<uint8_t>(r);
    for (int c = 0; c < mask.cols; ++c) {
      ++seen[label[c]];
      if (uniform[c]) ++trackable[label[c]];
    }
  }
  for (int label = 1; label < 255; ++label) {
    if (seen[label] >= min_pixels_) ++seen_frames_[label];
    if (trackable[label] >= min_pixels_) ++trackable_frames_[label];
  }
}

std::map<int, LabelVisibility> PlaneVisibility::seconds() const {
  std::vector<double> intervals;
  for (size_t k = 1; k < times_.size(); ++k) intervals.push_back(times_[k] - times_[k - 1]);
  double frame_s = 0;
  if (!intervals.empty()) {
    std::nth_element(intervals.begin(), intervals.begin() + intervals.size() / 2, intervals.end());
    frame_s = intervals[intervals.size() / 2];
  }
  std::map<int, LabelVisibility> out;
  for (const auto& [label, frames] : seen_frames_) out[label].seen_s = frames * frame_s;
  for (const auto& [label, frames] : trackable_frames_) out[label].trackable_s = frames * frame_s;
  return out;
}

MissingPlanes missingPlanes(const PlaneMapAccuracy& accuracy, const std::vector<Plane>& truth,
                            const std::map<int, LabelVisibility>& visible, double min_seconds) {
  std::set<int> in_map;
  for (const auto& p : accuracy.planes) in_map.insert(p.true_id);
  MissingPlanes out;
  for (const Plane& p : truth) {
    const auto v = visible.find(p.id);
    if (p.moving || v == visible.end() || in_map.count(p.id)) continue;
    if (v->second.trackable_s > min_seconds)
      out.missing.push_back({p.id, v->second});
    else if (v->second.seen_s > min_seconds)
      out.untrackable.push_back({p.id, v->second});
  }
  return out;
}

}  // namespace rpvio::eval

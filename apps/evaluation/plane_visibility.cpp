#include "apps/evaluation/plane_visibility.h"

#include <algorithm>
#include <array>
#include <set>

#include "rawlog_io/rawlog_labels.h"
#include "rawlog_io/rawlog_reader.h"

namespace rpvio::eval {

void PlaneVisibility::addMask(double t, const cv::Mat& mask) {
  times_.push_back(t);
  std::array<int, 256> pixels{};
  for (int r = 0; r < mask.rows; ++r) {
    const uint8_t* row = mask.ptr<uint8_t>(r);
    for (int c = 0; c < mask.cols; ++c) ++pixels[row[c]];
  }
  for (int label = 1; label < 255; ++label)
    if (pixels[label] >= min_pixels_) ++frames_[label];
}

std::map<int, double> PlaneVisibility::seconds() const {
  std::vector<double> intervals;
  for (size_t k = 1; k < times_.size(); ++k) intervals.push_back(times_[k] - times_[k - 1]);
  double frame_s = 0;
  if (!intervals.empty()) {
    std::nth_element(intervals.begin(), intervals.begin() + intervals.size() / 2, intervals.end());
    frame_s = intervals[intervals.size() / 2];
  }
  std::map<int, double> out;
  for (const auto& [label, frames] : frames_) out[label] = frames * frame_s;
  return out;
}

std::map<int, double> planeVisibleSeconds(const std::string& rawlog, int min_pixels) {
  RawlogReader reader(rawlog);
  PlaneVisibility visibility(min_pixels);
  while (const auto obs = reader.next()) {
    if (obs->sensorLabel != labels::kPlaneMask) continue;
    const auto* image = dynamic_cast<const mrpt::obs::CObservationImage*>(obs.get());
    if (!image) continue;
    visibility.addMask(toSeconds(obs->timestamp), loadGrayImage(*image, reader));
  }
  return visibility.seconds();
}

std::vector<MissingPlane> missingPlanes(const PlaneMapAccuracy& accuracy,
                                        const std::vector<Plane>& truth,
                                        const std::map<int, double>& visible_s,
                                        double min_seconds) {
  std::set<int> in_map;
  for (const auto& p : accuracy.planes) in_map.insert(p.true_id);
  std::vector<MissingPlane> out;
  for (const Plane& p : truth) {
    const auto v = visible_s.find(p.id);
    if (v != visible_s.end() && v->second > min_seconds && !in_map.count(p.id))
      out.push_back({p.id, v->second});
  }
  return out;
}

}  // namespace rpvio::eval

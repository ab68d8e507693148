// SlidingWindowEstimator's screening of each frame (sliding_window_estimator.h): the gyroscope's
// rotation since the previous frame, the discovered planes' labels (rpvio-auto) and the mask planes
// found moving, which leave the window.
#include <vector>

#include "mrpt_modules/estimator/sliding_window_estimator.h"
#include "planes_map/plane.h"

namespace rpvio {
namespace {

/// The frame's features with (`ground` true) or without the ground's tracks (ground_tracks.h),
/// which the screening passes as they are: the ground's alignment has already judged them.
FeatureFrame groundTracks(const FeatureFrame& frame, bool ground) {
  FeatureFrame part{frame.t, frame.image_t, {}};
  for (const TrackedFeature& f : frame.features)
    if ((f.plane_id == kGroundLabel) == ground) part.features.push_back(f);
  return part;
}

FeatureFrame withGroundTracks(FeatureFrame screened, const FeatureFrame& frame) {
  const FeatureFrame ground = groundTracks(frame, true);
  screened.features.insert(screened.features.end(), ground.features.begin(), ground.features.end());
  return screened;
}

}  // namespace

FeatureFrame SlidingWindowEstimator::screenedNow(const FeatureFrame& frame) const {
  const FeatureFrame others = groundTracks(frame, false);
  return withGroundTracks(
      plane_verifier_.withoutRejected(options_.discover_planes ? plane_discovery_.labelled(others)
                                                               : others),
      frame);
}

std::optional<Eigen::Quaterniond> SlidingWindowEstimator::rotationSincePreviousFrame(
    double t, const std::vector<ImuSample>& imu) {
  static const double kNoBias[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  // A corrected time offset moved this frame's time against the previous one's: start again.
  const bool same_clock = screened_offset_ == bootstrapper_.timeOffset();
  screened_offset_ = bootstrapper_.timeOffset();
  std::optional<Eigen::Quaterniond> rotation;
  if (const auto pre =
          screened_until_t_ < 0 || !same_clock
              ? nullptr
              : imu_link_.preintegrate(imu, screened_until_t_, t,
                                       initialized_ ? window_.back()->speed_bias : kNoBias)) {
    const Eigen::Quaterniond q_BC(calib_.T_BC.linear());
    rotation = q_BC.inverse() * pre->deltaQ() * q_BC;
  }
  screened_until_t_ = t;
  return rotation;
}

void SlidingWindowEstimator::dropPlaneFromWindow(int plane_id) {
  auto& tracks = features_.tracks();
  for (auto it = tracks.begin(); it != tracks.end();)
    it = it->second.plane_id == plane_id ? tracks.erase(it) : std::next(it);
}

FeatureFrame SlidingWindowEstimator::screenPlanes(const FeatureFrame& frame,
                                                  const std::vector<ImuSample>& imu) {
  if (!options_.verify_planes && !options_.discover_planes) return frame;
  const auto rotation = rotationSincePreviousFrame(frame.t, imu);
  const size_t known_rejections = plane_verifier_.rejections().size();
  const size_t known_discoveries = plane_discovery_.events().size();
  const FeatureFrame others = groundTracks(frame, false);
  FeatureFrame kept = options_.discover_planes ? plane_discovery_.label(others, rotation) : others;
  kept = withGroundTracks(plane_verifier_.filter(kept, rotation), frame);
  std::vector<int> dropped;
  for (size_t i = known_rejections; i < plane_verifier_.rejections().size(); ++i)
    dropped.push_back(plane_verifier_.rejections()[i].plane_id);
  for (size_t i = known_discoveries; i < plane_discovery_.events().size(); ++i)
    if (!plane_discovery_.events()[i].accepted)
      dropped.push_back(plane_discovery_.events()[i].plane_id);
  for (const int plane : dropped) dropPlaneFromWindow(plane);
  if (initialized_ && !dropped.empty()) forgetUnseenPlanes();
  return kept;
}

}  // namespace rpvio

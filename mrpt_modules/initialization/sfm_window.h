#pragma once
// The up-to-scale structure of an initialization window: a camera pose per frame (in the reference
// frame r), the feature tracks with their 3D points, and the planes n·X = d (reference frame).
#include <map>
#include <optional>
#include <vector>

#include "mrpt_modules/core/feature_frame.h"
#include "mrpt_modules/initialization/camera_pose.h"

namespace rpvio {

struct SfmObservation {
  size_t frame;
  Eigen::Vector2d u;  // normalized coordinates
};

struct SfmTrack {
  int feature_id = -1;
  int plane_id = 0;
  std::vector<SfmObservation> observations;  // increasing frame order
  std::optional<Eigen::Vector3d> X_r;        // once triangulated or intersected with its plane
};

struct SfmPlane {
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ();  // unit
  double d = 1;
};

struct SfmWindow {
  std::vector<std::optional<CameraPose>> cameras;  // one per frame, empty until solved
  std::vector<SfmTrack> tracks;
  std::map<int, SfmPlane> planes;  // planes whose geometry is known (RP-VIO mode)

  /// Tracks of the features of `frames` (features with fewer than two observations included).
  static SfmWindow fromFrames(const std::vector<FeatureFrame>& frames);
};

}  // namespace rpvio

#pragma once
// What a keyframe looks like to the loop closure: upright ORB descriptors (Rublee et al., ICCV
// 2011, with the orientation held at 0: gravity bounds the camera's roll, as VINS-Mono's BRIEF
// assumes) at corners detected over the whole image and at the keyframe's tracked features; a
// tracked feature the window triangulated carries its world point.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "common/sensor_types.h"

namespace rpvio {

struct AppearancePoint {
  Eigen::Vector2d normalized = Eigen::Vector2d::Zero();  // undistorted, z = 1
  std::optional<Eigen::Vector3d> world;                  // tracked and triangulated only
  int plane = 0;  // the persistent plane (map id) of a tracked feature on one; 0: none known
};

struct KeyframeAppearance {
  std::vector<AppearancePoint> points;
  cv::Mat descriptors;  // row i (32 bytes) describes points[i]
};

/// A keyframe as the loop closure keeps it: its time, its body pose in the world, its appearance.
struct StoredKeyframe {
  double t = 0;
  Eigen::Isometry3d body = Eigen::Isometry3d::Identity();
  KeyframeAppearance appearance;
};

/// Describes `image` at up to `corners` FAST corners (Harris-ranked, one scale) and at every
/// `tracked` feature; points too close to the border for a descriptor are left out.
KeyframeAppearance describeKeyframe(const cv::Mat& image,
                                    const std::vector<AppearancePoint>& tracked,
                                    const CameraIntrinsics& camera, int corners);

}  // namespace rpvio

#pragma once
// Two views of the scene with the rotation between them known (from the gyroscope): the geometry
// the plane verifier and the plane discovery share. Bearings b have z = 1 (normalized image
// coordinates); the rotation R_kj turns directions of camera j into camera k.
#include <Eigen/Core>
#include <deque>
#include <optional>
#include <unordered_map>
#include <vector>

#include <Eigen/Geometry>

#include "mrpt_modules/core/feature_frame.h"

namespace rpvio {

/// A feature seen in both frames: its bearing in j turned into k's orientation, and in k.
struct BearingPair {
  Eigen::Vector3d rotated_j, k;
};

/// The bearing pairs of the features of k also seen in j (`ids`: their feature ids, in order).
std::vector<BearingPair> bearingPairs(const FeatureFrame& j, const FeatureFrame& k,
                                      const Eigen::Matrix3d& R_kj, std::vector<int>* ids = nullptr);

/// Rotation-compensated parallax of a pair, in the normalized image plane.
double parallax(const BearingPair& p);

/// Distance of b_k from the epipolar line of t through R_kj b_j (l = t × R_kj b_j), in the
/// normalized image plane.
double epipolarDistance(const BearingPair& p, const Eigen::Vector3d& t);

/// The translation direction that best satisfies tᵀ (R_kj b_j × b_k) = 0 for all pairs: the right
/// singular vector of the smallest singular value of the stacked, normalized constraints.
Eigen::Vector3d translationDirection(const std::vector<BearingPair>& pairs);

/// The median of a non-empty list.
double median(std::vector<double> v);

/// The frames of the last span seconds with their gyroscope orientations, to compare the newest
/// frame with one at least span seconds older.
class RotatedFrameHistory {
 public:
  struct Past {
    FeatureFrame frame;
    Eigen::Quaterniond orientation;  // camera, relative to the first frame given
  };
  /// Adds a frame. `R_previous_current`: the camera's rotation from the previous frame to this
  /// one (camera k in camera k-1); none (no IMU between them): the history starts again here.
  void push(const FeatureFrame& frame, const std::optional<Eigen::Quaterniond>& R_previous_current);
  /// The newest frame but the last at least `span_s` older than it, or none.
  const Past* reference(double span_s) const;
  /// R_kj of the newest frame k and a past frame j.
  Eigen::Matrix3d rotationFrom(const Past& j) const;
  /// Drops what a later reference(span_s) cannot return.
  void trim(double span_s);
  /// Oldest first; the newest frame last.
  const std::deque<Past>& frames() const { return frames_; }

 private:
  std::deque<Past> frames_;
};

}  // namespace rpvio

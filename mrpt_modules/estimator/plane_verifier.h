#pragma once
// Verification of the mask planes (issue #34): a plane whose features do not move with the camera
// (a pallet truck, a sliding door, a segmentation network's mistake) is excluded for the rest of
// the run, before the initializer or the window see it.
//
// The test needs only the gyroscope. With the rotation R_kj between frames j and k known, every
// static point satisfies the epipolar constraint with one translation direction t shared by the
// whole scene:  tᵀ (R_kj b_j × b_k) = 0  (b: bearings). Each plane with enough features and
// rotation-compensated parallax proposes its own t (the null vector of its stacked constraints);
// the proposal with the least truncated squared epipolar distance over all features (MSAC,
// truncated at moving_px) is the camera's, provided most features lie within static_px of its
// epipolar lines. A plane whose median distance exceeds moving_px and moving_noise_ratio times
// the check's noise disagrees (below static_px it agrees); one that disagrees on reject_after
// consecutive checks is rejected. Surfaces moving along the camera's own
// translation keep its epipoles and pass (a limit of any two-view test).
#include <Eigen/Geometry>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "mrpt_modules/core/feature_frame.h"
#include "mrpt_modules/estimator/estimator_types.h"
#include "mrpt_modules/estimator/two_view_bearings.h"

namespace rpvio {

struct PlaneVerifierOptions {
  bool enabled = false;
  double span_s = 0.3;            // frames this far apart are compared
  double min_parallax_px = 4;     // rotation-compensated, median over the plane's features
  size_t min_features = 8;        // common to both frames, per plane
  double static_px = 0.5;         // median epipolar distance: agrees with the camera's motion
  double moving_px = 1.0;         // ... disagrees, and more than
  double moving_noise_ratio = 8;  // ... times the check's noise (all features' median distance)
  int reject_after = 3;           // consecutive disagreements
  double focal_px = 460;          // pixel scale of the thresholds
};

class PlaneVerifier {
 public:
  explicit PlaneVerifier(const PlaneVerifierOptions& options) : options_(options) {}

  /// The frame without the features of rejected planes. `R_previous_current`: the camera's
  /// rotation from the previous frame given here to this one (camera k in camera k-1), from the
  /// gyroscope; ignored on the first frame; none (no IMU between them): the comparisons start
  /// again from this frame.
  FeatureFrame filter(const FeatureFrame& frame,
                      const std::optional<Eigen::Quaterniond>& R_previous_current);

  /// A frame given earlier without the features of the planes rejected since (the initializer's
  /// buffered frames, screened again).
  FeatureFrame withoutRejected(const FeatureFrame& frame) const;

  const std::vector<PlaneRejection>& rejections() const { return rejections_; }
  const std::set<int>& rejected() const { return rejected_; }
  /// Planes a check has found static at least once (and not rejected since); a plane too small or
  /// too far to be judged never is. With homography factors on every plane, only these get them.
  const std::set<int>& judgedStatic() const { return judged_static_; }

  struct CheckResult {
    std::map<int, double> distance_px;  // per judged plane: median epipolar distance
    double noise_px = 0;                // median over all judged features
  };
  /// One check of frame k against frame j (R_kj: bearings of j turned into k's orientation) of
  /// the planes not rejected: nothing judged without two of them to compare or a consensus.
  CheckResult check(const FeatureFrame& j, const FeatureFrame& k,
                    const Eigen::Matrix3d& R_kj) const;

 private:
  PlaneVerifierOptions options_;
  RotatedFrameHistory history_;
  std::map<int, int> disagreements_;  // consecutive, per plane
  std::set<int> rejected_, judged_static_;
  std::vector<PlaneRejection> rejections_;
};

}  // namespace rpvio

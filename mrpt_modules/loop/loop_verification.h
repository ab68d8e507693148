#pragma once
// The geometric check of a revisit found by appearance (after VINS-Mono's): the query keyframe's
// triangulated points, matched by descriptor to the old keyframe's points, place the old camera
// by PnP-RANSAC in the query's world; accepted with enough inliers and a tilt that agrees with the
// odometry's (gravity is observable, so a true revisit differs in yaw and position only) and,
// where both keyframes' matched points lie on persistent planes, the same planes.
#include <Eigen/Geometry>
#include <string>

#include "common/options.h"
#include "mrpt_modules/loop/keyframe_appearance.h"

namespace rpvio {

struct LoopCheckOptions {
  int loop_max_hamming = 50;      // bits of 256: a descriptor match at most this far ...
  double loop_match_ratio = 0.8;  // ... and nearer than this times the second best
  int loop_min_inliers = 25;      // PnP-RANSAC inliers to accept
  double loop_ransac_px = 3;      // px at a 460 px focal length: PnP-RANSAC's inlier threshold
  double loop_max_tilt_deg = 5;   // roll/pitch disagreement with the odometry
  // The plane check: with at least this many inliers on persistent planes in both keyframes, most
  // must be on the same plane in both (0: no plane check).
  int loop_plane_pairs = 10;

  template <class Visitor>
  void fields(Visitor& v) {
    RPVIO_OPTION(v, loop_max_hamming);
    RPVIO_OPTION(v, loop_match_ratio);
    RPVIO_OPTION(v, loop_min_inliers);
    RPVIO_OPTION(v, loop_ransac_px);
    RPVIO_OPTION(v, loop_max_tilt_deg);
    RPVIO_OPTION(v, loop_plane_pairs);
  }
};

struct LoopCheck {
  bool accepted = false;
  std::string why;  // when rejected
  int matches = 0;  // descriptor matches of triangulated query points
  int inliers = 0;
  int plane_pairs = 0;       // inliers on persistent planes in both keyframes ...
  int same_plane_pairs = 0;  // ... on the same one
  // The old keyframe's body in the query's world, as the PnP places it (accepted checks).
  Eigen::Isometry3d old_body = Eigen::Isometry3d::Identity();
};

/// `query`/`old`: the two keyframes' appearances; `old_body_odometry`: the old keyframe's body pose
/// as the odometry had it; `T_BC`: the camera in the body.
LoopCheck verifyLoop(const KeyframeAppearance& query, const KeyframeAppearance& old,
                     const Eigen::Isometry3d& old_body_odometry, const Eigen::Isometry3d& T_BC,
                     const LoopCheckOptions& options);

}  // namespace rpvio

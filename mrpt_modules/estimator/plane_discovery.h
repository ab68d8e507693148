#pragma once
// Plane discovery without masks (mode rpvio-auto, issue #34): groups the features tracked over the
// whole image into static planes, which the estimator then uses as it uses mask planes.
//
// Each frame k is compared with the newest frame j at least span_s older, the rotation R_kj known
// from the gyroscope (x = R_kj b_j, y = b_k; bearings with z = 1):
//  1. The camera's translation direction t: every static point satisfies tᵀ (x × y) = 0, so two
//     points give t = (x₁ × y₁) × (x₂ × y₂). MSAC over such pairs (epipolar distance truncated at
//     epipolar_px), refined over its inliers together with a small correction of the gyroscope's
//     rotation (its bias is unknown before initialization); features farther than epipolar_px
//     from their epipolar line move against the camera (people, vehicles) and are set aside.
//  2. Planes among the static features: a point of the plane n·X_j = d satisfies
//     y ~ x + t (mᵀ x) with m = |T| R_kj n / d (the homography H = R + T nᵀ/d with R and the
//     direction of T known), i.e. (y × t)(xᵀ m) = −(y × x): linear in m, three points determine
//     it. Sequential RANSAC (samples drawn among a point's image neighbours, a plane being a
//     region) takes the largest plane within the transfer error limit, refines m by least
//     squares, removes its features and repeats. The limit is plane_sigmas standard deviations
//     of the tracks' noise, σ = median epipolar distance / 0.6745 of the static features (the
//     median absolute deviation of a zero-mean normal), capped at plane_px: a feature slightly
//     off the plane, or whose KLT window straddles an edge, stays off it when the tracks are
//     precise.
//  3. Planes found in a check are matched to the segments of earlier checks by their features'
//     labels (the segment most of them carry, if at least a third of the plane's features do),
//     else start a new segment. A segment becomes a static plane once found in confirm_after
//     checks; it is rejected as moving once most of its features were off their epipolar lines
//     in reject_after consecutive checks.
//  4. Tracks younger than span_s (not in the reference frame) are judged against the confirmed
//     segments over the longest span they have (adopt_young): frame k and the oldest frame j'
//     holding them. t and the gyroscope's correction come from the segments' labelled features
//     there; each segment with min_features of them and min_parallax_px (their median) gets its
//     m' (step 2's least squares over them), and a young track within epipolar_px of its
//     epipolar line and within the plane limit of a segment's m' joins the one it fits best
//     (judged again every frame, over a longer span, until a check judges it as any track).
//  5. With static_points, the features on no plane that were on their epipolar line the last time
//     they were compared (in a check or step 4) are passed on too, with plane id 0: reprojection
//     factors only, as in vins-mono. Without masks the planes a forward-moving camera can group
//     hold few tracks (docs/notes/2026-12-05-real-street-images.md); the epipolar test still sets
//     aside what moves across the scene's motion.
// Discovered planes get labels from kFirstDiscoveredLabel on (mask labels are 8-bit): the map
// tells their origin.
#include <Eigen/Geometry>
#include <map>
#include <optional>
#include <set>
#include <unordered_map>
#include <vector>

#include "mrpt_modules/core/feature_frame.h"
#include "mrpt_modules/estimator/estimator_types.h"
#include "mrpt_modules/estimator/two_view_bearings.h"
#include "planes_map/plane.h"

namespace rpvio {

struct PlaneDiscoveryOptions {
  bool enabled = false;
  double span_s = 0.3;         // frames this far apart are compared
  double min_parallax_px = 4;  // rotation-compensated, median over the compared features
  double epipolar_px = 0.5;    // farther from its epipolar line: the feature moves
  double plane_px = 0.5;       // transfer error within which a feature lies on a plane ...
  double plane_sigmas = 3;     // ... and within this many σ of the tracks' noise (0: plane_px)
  size_t min_features = 10;    // per plane and check
  int max_planes = 4;          // found per check
  int confirm_after = 3;       // checks finding a segment before it is a static plane
  int reject_after = 3;        // consecutive checks with most of its features moving
  int iterations = 200;        // RANSAC samples per model
  int sample_neighbours = 12;  // a plane's samples: a feature and two of its nearest neighbours
  bool adopt_young = true;     // step 4
  bool static_points = false;  // step 5
  double focal_px = 460;       // pixel scale of the thresholds
};

/// The plane m of y ~ x + t (mᵀ x) through the given pairs, by least squares over
/// (y × t)(xᵀ m) = −(y × x) (three rows each; three pairs determine it); none when degenerate.
std::optional<Eigen::Vector3d> planeThroughPairs(const std::vector<BearingPair>& pairs,
                                                 const std::vector<size_t>& members,
                                                 const Eigen::Vector3d& t);

class PlaneDiscovery {
 public:
  explicit PlaneDiscovery(const PlaneDiscoveryOptions& options) : options_(options) {}

  /// The features of the frame on static discovered planes, labelled with their plane ids
  /// (others are dropped). `R_previous_current`: the camera's rotation from the previous frame
  /// given here to this one (camera k in camera k-1), from the gyroscope; none (no IMU between
  /// them): the comparisons start again from this frame.
  FeatureFrame label(const FeatureFrame& frame,
                     const std::optional<Eigen::Quaterniond>& R_previous_current);

  /// A frame given earlier with the labels known now (features not on a static plane dropped, or
  /// with static_points those not judged static).
  FeatureFrame labelled(const FeatureFrame& frame) const;

  struct FoundPlane {
    Eigen::Vector3d m;          // y ~ x + t (mᵀ x)
    std::vector<int> features;  // ids
  };
  struct CheckResult {
    bool judged = false;                          // enough parallax and a translation consensus
    Eigen::Vector3d t = Eigen::Vector3d::Zero();  // unit; points in front have mᵀx > 0
    std::vector<int> compared;                    // ids seen in both frames
    std::vector<int> moving;                      // ids off their epipolar lines
    std::vector<FoundPlane> planes;               // largest first
  };
  /// One comparison of frame k with frame j (R_kj: bearings of j turned into k's orientation).
  CheckResult check(const FeatureFrame& j, const FeatureFrame& k,
                    const Eigen::Matrix3d& R_kj) const;

  const std::vector<PlaneDiscoveryEvent>& events() const { return events_; }
  size_t segmentsFound() const { return segments_.size(); }

 private:
  struct Segment {
    int found = 0;          // checks that found it
    int moving_streak = 0;  // consecutive checks with most of its features moving
    bool confirmed = false, rejected = false;
  };
  struct Label {
    int segment = 0;
    bool static_in_last_check = true;
    double last_seen_t = 0;
  };
  void update(const CheckResult& result, const FeatureFrame& frame);
  /// Step 4 for the features of k not in `reference`.
  void adoptYoungTracks(const FeatureFrame& k, const FeatureFrame& reference);
  /// Step 4 for `young`, seen in j and k, not before j; planes fitted over labelled `judged`.
  void adopt(const FeatureFrame& j, const FeatureFrame& k, const Eigen::Matrix3d& R_kj,
             const std::set<int>& judged, const std::set<int>& young);

  PlaneDiscoveryOptions options_;
  RotatedFrameHistory history_;
  std::map<int, Segment> segments_;
  std::unordered_map<int, Label> labels_;  // feature id → its segment
  struct Judgement {
    bool on_epipolar_line = false;
    double last_seen_t = 0;
  };
  std::unordered_map<int, Judgement> judged_;  // feature id → its last comparison (step 5)
  int next_id_ = kFirstDiscoveredLabel;
  std::vector<PlaneDiscoveryEvent> events_;
};

}  // namespace rpvio

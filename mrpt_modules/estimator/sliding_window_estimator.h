#pragma once
// RP-VIO's sliding-window estimator (DESIGN.md §1 steps 4-5), a pure C++ class fed with the
// front-end's FeatureFrames and the IMU samples between them.
//
// Window: the last `window_size` keyframes plus the newest frame, each with pose and
// [velocity, biases]; the features' inverse depths (FeatureManager); plane parameters (normal on
// the sphere, distance; world frame) taken from / written back to the PlanesMap. A plane stays a
// state while its label is seen: the homography factors of a marginalized keyframe leave their
// information on it in the prior (so it remembers its whole stay); it is marginalized out of the
// prior when it leaves the window. Gauge: the oldest keyframe's yaw and position are held. Factors:
// IMU, inverse-depth reprojection and planar homography (every observation of a planar feature
// paired with its anchor observation; both weighted virtual_focal / pixel_sigma and robustified by
// a Cauchy loss, so the homography speaks in the same units of image error as the reprojection),
// and the marginalization prior. Each frame is optimized (Dogleg, DENSE_SCHUR); then the oldest
// keyframe is marginalized when the second newest frame is a keyframe (parallax or few common
// tracks), else the second newest is dropped (its IMU merged into the newest, its visual
// measurements discarded). The planes' covariances are computed on every
// plane_covariance_every-th keyframe that marginalizes. A keyframe whose solve took more than
// max_iterations_before_deferring iterations, or whose covariances are due (with
// defer_plane_covariances), leaves its covariances (if due) and the marginalization to the start
// of the next frame, so that no frame pays for a whole-window solve and both. With
// motion_only_between_keyframes, a frame whose second newest is not a keyframe solves only the two
// newest frames against the rest of the window held.
//
// Modes: every tracked feature (the front-end restricts them to the plane masks or not) has
// reprojection factors; homography factors on no plane (vins-mono, mask-vins), the largest plane
// (rpvio-single) or every plane (rpvio-multi). Failures (implausible biases, jumps, too long
// without features) reset the estimator, which re-initializes; each reset is logged with its cause.
//
// Files: this one the window's life cycle (start, frames tracked, failure, reset); window_solve.cpp
// the solves; window_keyframes.cpp the keyframe schedule, marginalization and what leaves to the
// map; window_screening.cpp each frame's plane screening.
#include <ceres/problem.h>
#include <deque>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "common/sensor_types.h"
#include "mrpt_modules/core/run_messages.h"
#include "mrpt_modules/estimator/batch_refinement.h"
#include "mrpt_modules/estimator/bootstrapper.h"
#include "mrpt_modules/estimator/estimator_options.h"
#include "mrpt_modules/estimator/estimator_types.h"
#include "mrpt_modules/estimator/feature_manager.h"
#include "mrpt_modules/estimator/ground_in_window.h"
#include "mrpt_modules/estimator/map_sink.h"
#include "mrpt_modules/estimator/plane_verifier.h"
#include "mrpt_modules/estimator/window_planes.h"
#include "mrpt_modules/factors/marginalization.h"
#include "mrpt_modules/imu/imu_link.h"
#include "mrpt_modules/initialization/initializer.h"
#include "planes_map/planes_map.h"

namespace rpvio {

class SlidingWindowEstimator {
 public:
  /// `map`: where planes and keyframes go as they leave the window (the map builder), and where
  /// the planes of labels seen again come from.
  SlidingWindowEstimator(const Calibration& calibration, const EstimatorOptions& options,
                         MapSink& map);
  SlidingWindowEstimator(const SlidingWindowEstimator&) = delete;  // the bootstrapper refers to
  SlidingWindowEstimator& operator=(const SlidingWindowEstimator&) = delete;  // the IMU link

  /// A new frame (IMU clock) with the IMU samples since the previous frame (first sample at or
  /// before the previous frame's time, last at or before this frame's). Returns the body poses
  /// this frame gave, oldest first: none while initializing, else the frame's own; at a late
  /// initialization (an undecided time offset's wait) those of the frames since its window too.
  std::vector<StateEstimate> addFrame(const FeatureFrame& frame,
                                      const std::vector<ImuSample>& imu_since_previous);

  bool initialized() const { return initialized_; }
  size_t resets() const { return reset_log_.size(); }
  const std::vector<ResetEvent>& resetLog() const { return reset_log_; }
  /// "tracking", "reset: <cause>" or the initializer's status (changes when the reason does).
  const std::string& status() const { return status_; }
  /// The status with its figures (e.g. "too little parallax (12.3 px)"): for the log.
  const std::string& statusDetail() const { return status_detail_; }
  const FrameReport& lastReport() const { return report_; }
  /// How many times the planes' covariances were computed (plane_covariance_every).
  size_t covarianceUpdates() const { return covariance_updates_; }
  const PlaneEstimates& planes() const { return planes_.estimates(); }
  /// t_imu = t_frame + timeOffset(): the calibration's offset plus the estimated correction.
  double timeOffset() const { return bootstrapper_.timeOffset(); }
  /// What the time-offset estimation found ("" before it ran).
  const std::string& timeOffsetNote() const { return bootstrapper_.timeOffsetNote(); }
  /// The mask planes found moving so far (with verify_planes), in the order they were.
  const std::vector<PlaneRejection>& planeRejections() const {
    return plane_verifier_.rejections();
  }
  /// The discovered planes accepted as static or rejected as moving so far (rpvio-auto), in order.
  const std::vector<PlaneDiscoveryEvent>& planeDiscoveries() const {
    return plane_discovery_.events();
  }
  size_t planesDiscovered() const { return plane_discovery_.segmentsFound(); }
  /// Once, at the end of a run: the window's current planes and keyframes to the map, then
  /// WindowFinished (the map merges its duplicates and runs the batch refinement).
  void finishMap();

 private:
  /// The window's current planes to the map (done as keyframes leave the window).
  void flushPlanes();
  /// The gyroscope's rotation from the previous frame given here to this one (camera k in camera
  /// k-1); none on the first frame, without IMU between them or after a time-offset correction.
  std::optional<Eigen::Quaterniond> rotationSincePreviousFrame(double t,
                                                               const std::vector<ImuSample>& imu);
  /// The frame's features on static planes: discovered ones (rpvio-auto, plane_discovery.h), and
  /// without those of mask planes found moving (plane_verifier.h); planes newly rejected either
  /// way also leave the window.
  FeatureFrame screenPlanes(const FeatureFrame& frame, const std::vector<ImuSample>& imu);
  void dropPlaneFromWindow(int plane_id);
  /// With verify_planes and homography factors on every plane, the planes a check found static
  /// (the only ones that may get homography factors and map entries: a plane too small to be judged
  /// could be a moving one); else none given: every plane may. The largest plane is judged
  /// whenever a check judges anything; requiring it (hard seed-1 C8) made rpvio-single worse.
  const std::set<int>* homographyEligible() const {
    return options_.verify_planes && options_.homography_planes == HomographyPlanes::kAll
               ? &plane_verifier_.judgedStatic()
               : nullptr;
  }
  struct Frame {
    uint64_t id = 0;
    FeatureFrame features;
    std::vector<ImuSample> imu;  // from the previous window frame to this one
    std::shared_ptr<ImuPreintegration> imu_from_previous;
    double pose[7] = {0, 0, 0, 0, 0, 0, 1};
    double speed_bias[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  };

  /// The window an initializer gave (the bootstrapper's), placed in the old world when it
  /// reconnects, then triangulated and optimized.
  void startWindow(const InitializedWindow& init);
  /// The states of the window just started, oldest first: its keyframes and, with
  /// publish_init_window, the frames between them (IMU-predicted); the newest keyframe only
  /// without.
  std::vector<StateEstimate> startedWindowStates(const InitializedWindow& init) const;
  /// A frame buffered earlier (as given to the bootstrapper) as the screening sees it now: with
  /// the labels discovered so far (rpvio-auto), without the planes found moving so far.
  FeatureFrame screenedNow(const FeatureFrame& frame) const;
  /// A frame to the bootstrapper while not initialized; on an initialization, the window
  /// started and the poses it gives appended to `states` (a late one's frames since tracked).
  void bootstrap(const FeatureFrame& frame, const std::vector<ImuSample>& imu_since_previous,
                 std::vector<StateEstimate>& states);
  /// A frame (screened) on the initialized window: its pose, or none when the window is reset.
  std::optional<StateEstimate> track(const FeatureFrame& frame,
                                     const std::vector<ImuSample>& imu_since_previous);
  void moveWindow(const WorldShift& shift);
  Eigen::Isometry3d camera(uint64_t frame_id) const;
  CameraPoseLookup cameraLookup() const;
  enum class WindowSolve {
    kWindow,
    kWindowAndPlaneCovariances,  // a keyframe's, before the marginalization: then, if due,
                                 // the covariance of every plane with factors (what the planes
                                 // map weighs a visit by)
    kNewestFrames,               // the two newest frames against the rest held (motion only)
    kPlaneCovariances,           // no solve: the covariances only, at the window's state
  };
  /// Reprojection and homography weight of a plane's tracks: virtual_focal / pixel_sigma, or
  /// ground_pixel_sigma for the ground's tracks.
  double trackWeight(int plane_id) const;
  /// One solve of the window.
  void optimize(WindowSolve solve);
  /// The ground among `planes` (those with homography factors), when the camera's height is known.
  std::optional<GroundInWindow> chooseGround(const std::set<int>& planes) const;
  /// A keyframe's camera-height factor on ground_ (camera_height_factor.h).
  ceres::CostFunction* cameraHeightFactor() const;
  /// The first keyframe's accelerometer-bias prior (accel_bias_prior_factor.h).
  ceres::CostFunction* accelBiasPriorFactor() const;
  void rejectDepthOutliers();
  std::string failure(const double* predicted_pose) const;
  void marginalizeOldest();
  /// Whether this keyframe computes the planes' covariances (plane_covariance_every).
  bool covariancesDue() const {
    return keyframes_since_covariances_ >= options_.plane_covariance_every;
  }
  /// The covariances and marginalization a long keyframe solve left, if any (then true).
  bool finishKeyframeWork();
  /// A keyframe leaving the window to the map, with its IMU link to the next one.
  void archiveKeyframe(const Frame& frame, const Frame* next);
  void forgetUnseenPlanes();
  void dropSecondNewest();
  bool secondNewestIsKeyframe() const;
  /// The window dropped; the bootstrapper starts again, from the last good state and the IMU
  /// samples since.
  void reset(const std::string& cause, const std::vector<ImuSample>& imu_since_good);

  Calibration calib_;
  EstimatorOptions options_;
  ImuLink imu_link_;  // with calib_.imu inflated for the window's factors
  Bootstrapper bootstrapper_;
  double mount_[7];  // T_BC as a (constant) pose block
  bool initialized_ = false;
  std::string status_ = "collecting frames";
  std::string status_detail_ = status_;
  std::vector<ResetEvent> reset_log_;
  FrameReport report_;
  std::deque<std::unique_ptr<Frame>> window_;
  uint64_t next_frame_id_ = 0;
  FeatureManager features_;
  std::shared_ptr<const MarginalizationPrior> prior_;
  // The accelerometer-bias prior of the first window, on its oldest keyframe until that keyframe
  // is marginalized (then it is in prior_).
  std::optional<Eigen::Vector3d> accel_bias_prior_;
  bool keyframe_work_deferred_ = false;  // the planes' covariances (if due) and the oldest
                                         // keyframe's marginalization, left to the next frame
  // Marginalizing keyframes since the planes' covariances were computed (none counted without
  // homography factors).
  int keyframes_since_covariances_ = 0;
  size_t covariance_updates_ = 0;
  WindowPlanes planes_;
  std::optional<GroundInWindow> ground_;  // of the last solve, when camera-height factors held it
  PlaneVerifier plane_verifier_;
  PlaneDiscovery plane_discovery_;
  double screened_until_t_ = -1;  // the last frame screenPlanes saw
  double screened_offset_ = 0;    // ... and the time offset then
  MapSink& map_;
  double last_seen_features_t_ = 0;
};

}  // namespace rpvio

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
// measurements discarded).
//
// Modes: every tracked feature (the front-end restricts them to the plane masks or not) has
// reprojection factors; homography factors on no plane (vins-mono, mask-vins), the largest plane
// (rpvio-single) or every plane (rpvio-multi). Failures (implausible biases, jumps, too long
// without features) reset the estimator, which re-initializes; each reset is logged with its cause.
#include <ceres/problem.h>
#include <deque>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "common/options.h"
#include "common/sensor_types.h"
#include "mrpt_modules/core/run_messages.h"
#include "mrpt_modules/estimator/batch_refinement.h"
#include "mrpt_modules/estimator/estimator_types.h"
#include "mrpt_modules/estimator/feature_manager.h"
#include "mrpt_modules/factors/marginalization.h"
#include "mrpt_modules/imu/imu_link.h"
#include "mrpt_modules/initialization/initializer.h"
#include "planes_map/planes_map.h"

namespace rpvio {

enum class HomographyPlanes { kNone, kLargest, kAll };
inline const OptionNames<HomographyPlanes> kHomographyPlanesNames = {
    {"none", HomographyPlanes::kNone},
    {"largest", HomographyPlanes::kLargest},
    {"all", HomographyPlanes::kAll}};
inline const OptionNames<InitializerMethod> kInitializerMethodNames = {
    {"homography", InitializerMethod::kPlanarHomography},
    {"essential", InitializerMethod::kEssentialMatrix}};

struct EstimatorOptions {
  size_t window_size = 10;           // keyframes
  double keyframe_parallax_px = 10;  // at the virtual focal length
  size_t keyframe_min_tracks = 20;   // fewer common tracks: keyframe
  double max_keyframe_gap_s = 0.3;   // a keyframe at least this often
  HomographyPlanes homography_planes = HomographyPlanes::kLargest;
  double pixel_sigma = 1.5;   // factor weight: virtual_focal / pixel_sigma
  double cauchy_scale = 1.0;  // robust loss scale, in units of pixel_sigma
  // The window's IMU factors use the calibration's noise densities and random walks times this
  // factor (VINS-Mono's configs inflate them likewise). Measured with tracked features on the
  // 80 s simulated sequences, rpvio-single: ATE static / C1 / C4 0.23 / 0.40 / 0.41 m at 3,
  // 0.41 / 0.42 / 0.52 m at 10, 0.68 m on C1 at 30. (Exact features, tests/estimator: 0.03 m over
  // 20 s at 3 with pixel_sigma 0.5.)
  double imu_noise_inflation = 3;
  // IMU gaps: a step between samples longer than this (s) makes the interval's IMU factor this
  // many times noisier (white-noise densities) and keeps it out of the marginalization prior; so
  // does a saturated sensor (for its own noise): an axis with the same value, at least this large,
  // on three consecutive samples.
  double max_imu_step_s = 0.05;
  double imu_gap_noise_inflation = 30;
  double min_saturated_accel = 11.8;  // m/s² (1.2 g: never a quantized value at rest)
  double min_saturated_gyro = 0.1;    // rad/s
  int max_iterations = 8;
  double max_solver_time_s = 0;  // 0: no time budget (a budget makes runs machine-dependent)
  double min_triangulation_angle_deg = 1.0;
  // Failure detection.
  double max_accel_bias = 2.5;  // m/s²
  double max_gyro_bias = 1.0;   // rad/s
  double max_jump_m = 5.0;      // optimized newest pose vs its IMU prediction
  double max_jump_deg = 50.0;
  size_t min_features = 4;     // features in use in the newest frame ...
  double max_blind_s = 2.5;    // ... not reached for this long (IMU only meanwhile: a 2 s
                               // blackout is bridged at 1.2x the fault-free ATE)
  double virtual_focal = 460;  // px; parallax thresholds and factor weights refer to it
  // First initialization: the method (homography: RP-VIO's, on the largest plane; essential:
  // VINS-Mono's 5-point SfM), the window's time span (s: baseline and IMU excitation for the
  // scale) and the rotation-compensated parallax (px at virtual_focal) it needs.
  InitializerMethod initializer = InitializerMethod::kPlanarHomography;
  double init_window_s = 2.0;
  double init_parallax_px = 30.0;
  // Re-initialization after a reset: mid-flight accelerations make the scale less observable
  // than the take-off, so the alignment's scale may be this uncertain (the window refines it) ...
  double reinit_max_scale_sigma = 0.10;
  // ... by this method: the homography initializer's structure fails mid-flight on the simulator
  // (bundle adjustment diverges), the essential-matrix one (on the same, masked features) works.
  InitializerMethod reinitializer = InitializerMethod::kEssentialMatrix;
  // When the homography initializer's two-view geometry or structure fails (its bundle adjustment
  // diverges on some windows, e.g. with an unknown 30 ms camera-IMU offset), the same window is
  // tried with the essential-matrix method, same thresholds.
  bool init_fallback = true;
  double init_fallback_after_s = 0;  // ... once it has failed for this long (0: at once)
  // ... and the new window is placed in the old world by dead reckoning from the last good state
  // when the reset was at most this long ago (else the trajectory continues in a new world).
  double max_reconnect_s = 20;
  size_t init_window_frames = 41;  // frames kept while initializing (2 s at 20 Hz)
  // Camera-IMU time offset, estimated once from the first initialization window's rotations
  // (time_offset.h), searched within ±max_time_offset_s. When at least min_time_offset_s and 3
  // sigma, the window is initialized again on the corrected frame times, and the correction kept
  // if that succeeds. On the simulator without an offset the masked modes estimate -4.3 to +5.3 ms
  // (sigma 0.8-1.1 ms: the gyroscope's random walk is not white), the unmasked one up to -18 ms
  // (moving features); 30 ms comes out at 32 ms.
  bool estimate_time_offset = true;
  double min_time_offset_s = 0.010;
  double max_time_offset_s = 0.05;
  // At the end of a run, one bundle adjustment over all keyframes (batch_refinement.h): the plane
  // map's final (n, d) and trajectory_refined.tum. It keeps every keyframe's observations until
  // then (about 1 MB per minute at 20 Hz) and costs about 20 s per 80 s simulated sequence.
  bool batch_refinement = true;
  // ... skipped (and said so) beyond this many keyframes: its memory grows with them (355 MB peak
  // for the 459 keyframes of an 80 s sequence with rpvio-multi, against 91 MB without).
  size_t batch_refinement_max_keyframes = 2000;
  PlanesMapOptions planes_map;  // its own section, [PlanesMap]

  template <class Visitor>
  void fields(Visitor& v) {
    RPVIO_OPTION(v, window_size);
    RPVIO_OPTION(v, keyframe_parallax_px);
    RPVIO_OPTION(v, keyframe_min_tracks);
    RPVIO_OPTION(v, max_keyframe_gap_s);
    RPVIO_OPTION_CHOICE(v, homography_planes, kHomographyPlanesNames);
    RPVIO_OPTION(v, pixel_sigma);
    RPVIO_OPTION(v, cauchy_scale);
    RPVIO_OPTION(v, imu_noise_inflation);
    RPVIO_OPTION(v, max_imu_step_s);
    RPVIO_OPTION(v, imu_gap_noise_inflation);
    RPVIO_OPTION(v, min_saturated_accel);
    RPVIO_OPTION(v, min_saturated_gyro);
    RPVIO_OPTION(v, max_iterations);
    RPVIO_OPTION(v, max_solver_time_s);
    RPVIO_OPTION(v, min_triangulation_angle_deg);
    RPVIO_OPTION(v, max_accel_bias);
    RPVIO_OPTION(v, max_gyro_bias);
    RPVIO_OPTION(v, max_jump_m);
    RPVIO_OPTION(v, max_jump_deg);
    RPVIO_OPTION(v, min_features);
    RPVIO_OPTION(v, max_blind_s);
    RPVIO_OPTION(v, virtual_focal);
    RPVIO_OPTION_CHOICE(v, initializer, kInitializerMethodNames);
    RPVIO_OPTION(v, init_window_s);
    RPVIO_OPTION(v, init_parallax_px);
    RPVIO_OPTION(v, init_window_frames);
    RPVIO_OPTION(v, init_fallback);
    RPVIO_OPTION(v, init_fallback_after_s);
    RPVIO_OPTION_CHOICE(v, reinitializer, kInitializerMethodNames);
    RPVIO_OPTION(v, reinit_max_scale_sigma);
    RPVIO_OPTION(v, max_reconnect_s);
    RPVIO_OPTION(v, estimate_time_offset);
    RPVIO_OPTION(v, min_time_offset_s);
    RPVIO_OPTION(v, max_time_offset_s);
    RPVIO_OPTION(v, batch_refinement);
    RPVIO_OPTION(v, batch_refinement_max_keyframes);
  }
  void validate(const OptionsLoader& loader) const;
  ImuLinkOptions imuLinkOptions() const;
  /// The first initializer's options (the others are variants of it).
  InitializerOptions initializerOptions() const;
};

class SlidingWindowEstimator {
 public:
  SlidingWindowEstimator(const Calibration& calibration, const EstimatorOptions& options);

  /// A new frame (IMU clock) with the IMU samples since the previous frame (first sample at or
  /// before the previous frame's time, last at or before this frame's). Returns the frame's body
  /// pose once initialized.
  std::optional<StateEstimate> addFrame(const FeatureFrame& frame,
                                        const std::vector<ImuSample>& imu_since_previous);

  bool initialized() const { return initialized_; }
  size_t resets() const { return reset_log_.size(); }
  const std::vector<ResetEvent>& resetLog() const { return reset_log_; }
  /// "tracking", "reset: <cause>" or the initializer's status (changes when the reason does).
  const std::string& status() const { return status_; }
  /// The status with its figures (e.g. "too little parallax (12.3 px)"): for the log.
  const std::string& statusDetail() const { return status_detail_; }
  const FrameReport& lastReport() const { return report_; }
  const PlaneEstimates& planes() const { return planes_; }
  const PlanesMap& planesMap() const { return planes_map_; }
  /// t_imu = t_frame + timeOffset(): the calibration's offset plus the estimated correction.
  double timeOffset() const { return time_offset_; }
  /// What the time-offset estimation found ("" before it ran).
  const std::string& timeOffsetNote() const { return time_offset_note_; }
  /// Once, at the end of a run: the window's current planes into the map (the visits under way
  /// end), then the map's duplicates merged (a plane whose visit started too far from its entry to
  /// be associated got a new one; their estimates have converged since), then the batch
  /// refinement (`batch_refinement`).
  void finishMap();
  /// After finishMap(): the keyframes' body poses from the batch refinement (empty if it did not
  /// run or failed), and its summary.
  const std::vector<StateEstimate>& refinedTrajectory() const { return refined_trajectory_; }
  const std::string& refinementReport() const { return refinement_report_; }
  double refinementSeconds() const { return refinement_seconds_; }

 private:
  /// Writes the window's current planes into the map (done as keyframes leave the window).
  void flushPlanes();
  /// The batch refinement over the archived keyframes (batch_refinement.h): the map's planes and
  /// refinedTrajectory().
  void refineBatch();
  struct Frame {
    uint64_t id = 0;
    FeatureFrame features;
    std::vector<ImuSample> imu;  // from the previous window frame to this one
    std::shared_ptr<ImuPreintegration> imu_from_previous;
    double pose[7] = {0, 0, 0, 0, 0, 0, 1};
    double speed_bias[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  };

  void tryInitialize();
  /// The time offset estimated on the initialized window when significant, else 0 (once).
  double significantTimeOffset(const InitializationResult& init);
  /// The IMU samples of the initialization buffer, in time order, once each.
  std::vector<ImuSample> initBufferSamples() const;
  /// Moves the buffered frames (and the offset) by dt and deals their IMU samples out again.
  void moveInitBuffer(double dt);
  /// Moves a re-initialized window (and its planes) into the world of the last good state by the
  /// yaw and translation that put its first keyframe on the IMU's dead reckoning.
  /// False (the window stays in a new world) when the IMU does not reach the first keyframe.
  bool reconnect();
  Eigen::Isometry3d camera(uint64_t frame_id) const;
  CameraPoseLookup cameraLookup() const;
  bool inUse(const FeatureTrack& track) const;
  /// Labels of the planes with kMinPlanePoints tracks in use or more: only they get homography
  /// factors (fewer leave directions of (n, d) unobserved, which a solve then moves at will).
  std::set<int> constrainedPlanes() const;
  /// The plane whose homography factors the track's observations get (one of `constrained`), or
  /// nullptr.
  PlaneEstimate* homographyPlane(const FeatureTrack& track, const std::set<int>& constrained);
  void choosePlanes();
  void initializePlanes();
  /// One solve of the window; with `plane_covariances`, the covariance of every plane with
  /// factors then (what the planes map weighs a visit by).
  void optimize(bool plane_covariances = false);
  void updatePlaneCovariances(ceres::Problem& problem, const std::set<int>& planes);
  void rejectDepthOutliers();
  std::string failure(const double* predicted_pose) const;
  void marginalizeOldest();
  /// A keyframe into the archive the batch refinement solves, with its IMU link to the next one.
  void archiveKeyframe(const Frame& frame, const Frame* next);
  void forgetUnseenPlanes();
  void dropSecondNewest();
  bool secondNewestIsKeyframe() const;
  void reset(const std::string& cause);

  Calibration calib_;
  EstimatorOptions options_;
  ImuNoise window_imu_noise_;  // calib_.imu inflated for the window's factors
  ImuLink imu_link_;
  Initializer initializer_;
  Initializer fallback_initializer_;  // when the configured method's geometry fails
  Initializer reinitializer_;         // after a reset
  double mount_[7];                   // T_BC as a (constant) pose block
  bool initialized_ = false;
  std::string status_ = "collecting frames";
  std::string status_detail_ = status_;
  std::vector<ResetEvent> reset_log_;
  FrameReport report_;
  std::deque<std::pair<FeatureFrame, std::vector<ImuSample>>> init_buffer_;
  std::deque<std::unique_ptr<Frame>> window_;
  uint64_t next_frame_id_ = 0;
  FeatureManager features_;
  std::shared_ptr<const MarginalizationPrior> prior_;
  PlaneEstimates planes_;      // by mask id: planes in the current window
  std::set<int> used_planes_;  // mask ids whose features (and homographies) are in use
  PlanesMap planes_map_;
  KeyframeArchive keyframe_archive_;
  std::vector<StateEstimate> refined_trajectory_;
  std::string refinement_report_;
  double refinement_seconds_ = 0;
  uint64_t plane_visits_ = 0;  // planes that entered the window so far
  double last_seen_features_t_ = 0;
  double time_offset_ = 0;
  bool time_offset_estimated_ = false;
  std::string time_offset_note_;
  double first_geometry_failure_t_ = -1;  // of the configured initializer (for the fallback)
  struct GoodState {
    double t = 0;
    double pose[7];
    double speed_bias[9];
  };
  std::optional<GoodState> last_good_;     // newest state reported; kept through a reset
  std::vector<ImuSample> imu_since_good_;  // from last_good_ on, while re-initializing
};

}  // namespace rpvio

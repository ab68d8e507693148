#pragma once
// The options of the sliding-window estimator (section [SlidingWindowEstimatorModule]).
#include "common/options.h"
#include "mrpt_modules/estimator/plane_discovery.h"
#include "mrpt_modules/estimator/plane_verifier.h"
#include "mrpt_modules/imu/imu_link.h"
#include "mrpt_modules/initialization/initializer.h"

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
  // The planes without homography factors go to the planes map too, as a fit of their
  // triangulated features (with verify_planes, only those a check found static).
  bool map_all_planes = false;
  double pixel_sigma = 1.5;  // factor weight: virtual_focal / pixel_sigma
  // The same for the ground's tracks (ground_features): points carried by one aligned homography
  // per image pair, whose errors are shared and several pixels large at speed.
  double ground_pixel_sigma = 6;
  double cauchy_scale = 1.0;  // robust loss scale, in units of pixel_sigma
  // The window's IMU factors use the calibration's noise densities and random walks times this
  // factor (VINS-Mono's configs inflate them likewise).
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
  // A frame whose second newest frame is not a keyframe (dropped after the solve) moves only the
  // two newest frames, the rest of the window, its depths and planes held: the window is solved
  // on keyframes only.
  bool motion_only_between_keyframes = true;
  double max_solver_time_s = 0;  // 0: no time budget (a budget makes runs machine-dependent)
  // A keyframe's whole-window solve that takes more iterations than this leaves the planes'
  // covariances (if due) and the oldest keyframe's marginalization to the start of the next
  // frame, so that no frame pays for a long solve and both. max_iterations or more: never.
  int max_iterations_before_deferring = 2;
  // The planes' covariances (what the planes map weighs a visit by) are computed on every
  // plane_covariance_every-th keyframe that marginalizes (the next one if they could not be),
  // and at the end of the run; the map gets the last ones in between. With
  // defer_plane_covariances, they and the marginalization are left to the start of the next
  // frame, off the keyframe's.
  int plane_covariance_every = 3;
  bool defer_plane_covariances = true;
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
  // Tried when no pair reaches init_parallax_px; 8 px at virtual_focal 460: 1°, the angle a
  // feature needs to be triangulated (min_triangulation_angle_deg).
  double init_fallback_parallax_px = 8.0;
  // With calib.ini's [ground] camera_height: the window's ground plane (ground_in_window.h) holds
  // every keyframe's camera this high above it, with this standard deviation (m; 0: not used).
  double camera_height_sigma = 0.05;
  // The standard deviation (m/s²; 0: none) of a prior on the first keyframe's accelerometer bias
  // at the initializer's estimate (accel_bias_prior_factor.h).
  double accel_bias_prior_sigma = 0.3;
  // The alignment's scale standard deviation relative to the scale (from its residual) may be at
  // most this: above it the window's accelerations do not make the scale observable. As after a
  // reset, the window refines the scale: the paper suite starts as with 0.03 (its take-off push
  // gives < 3 %), a drone cruising at 5 m/s starts at 2 s instead of 38 s, a ground robot among
  // characters (13.8 % at its first attempt) at 2 s instead of never.
  double init_max_scale_sigma = 0.15;
  // Before the first initialization, after an attempt fails in its geometry or alignment (not for
  // want of frames, features or parallax, which is cheap to find), the next attempt waits this
  // long (s). Re-initializations after a reset try every frame.
  double init_retry_s = 0.25;
  // Re-initialization after a reset: mid-flight accelerations make the scale less observable
  // than the take-off, so the alignment's scale may be this uncertain (the window refines it) ...
  double reinit_max_scale_sigma = 0.10;
  // ... unless its window starts within this long (s) of the last good state: the velocity dead
  // reckoned from that state is then taken as the window's first velocity, which gives the scale
  // without excitation. Off (0): it re-initializes sooner, but the dead reckoning's velocity error
  // (~0.03 m/s per second without vision) made both measured cases less accurate
  // (docs/notes/2026-11-29-hard-scale-drift.md).
  double reinit_known_velocity_s = 0;
  // ... by this method: the homography initializer's structure fails mid-flight on the simulator
  // (bundle adjustment diverges), the essential-matrix one (on the same, masked features) works.
  InitializerMethod reinitializer = InitializerMethod::kEssentialMatrix;
  // When the homography initializer's two-view geometry or structure fails (its bundle adjustment
  // diverges on some windows, e.g. with an unknown 30 ms camera-IMU offset), or it finds no plane
  // with the features and parallax for it, the same window is tried with the essential-matrix
  // method, same thresholds.
  bool init_fallback = true;
  double init_fallback_after_s = 0;  // ... once it has failed for this long (0: at once)
  // ... and the new window is placed in the old world by dead reckoning from the last good state
  // when the reset was at most this long ago (else the trajectory continues in a new world).
  double max_reconnect_s = 20;
  // At an initialization, a pose for every frame of its window, not only the newest: the
  // keyframes as solved, the frames between them predicted by the IMU from the keyframe before.
  bool publish_init_window = true;
  size_t init_window_frames = 41;  // frames kept while initializing (2 s at 20 Hz; more when
                                   // they span less than init_window_s)
  // Camera-IMU time offset, estimated once from the first initialization window's rotations
  // (time_offset.h), searched within ±max_time_offset_s. When at least min_time_offset_s, 3
  // sigma (sigma allowing for the residuals' correlation) and time_offset_systematic_margin times
  // the offset the fit's residual could fake (its `systematic` scale), the window is initialized
  // again on the corrected frame times, and the correction kept if that succeeds. With the margin
  // at 2, an error of that size still leaves the corrected times closer to the truth.
  // Beyond 3 sigma but within the margin, the first initialization waits until the window spans
  // time_offset_window_s, and the estimate on that window decides
  // (docs/notes/2026-11-28-time-offset-guard.md: what it estimates on the simulator).
  bool estimate_time_offset = true;
  double min_time_offset_s = 0.010;
  double time_offset_systematic_margin = 2;
  double time_offset_window_s = 3.5;
  double max_time_offset_s = 0.05;
  // Mask planes that move against the camera's motion are excluded (plane_verifier.h): frames
  // verify_span_s apart are compared, judging planes with verify_min_features common features
  // and verify_min_parallax_px of rotation-compensated parallax. A plane whose median epipolar
  // distance (px at virtual_focal) from the consensus translation exceeds verify_moving_px and
  // verify_moving_noise_ratio times the check's noise on verify_reject_after consecutive checks
  // is rejected for the run; one within verify_static_px agrees, which clears its count.
  bool verify_planes = false;
  double verify_span_s = 0.3;
  double verify_min_parallax_px = 4;
  size_t verify_min_features = 8;
  double verify_static_px = 0.5;
  double verify_moving_px = 1.0;
  double verify_moving_noise_ratio = 8;
  int verify_reject_after = 3;
  // Mode rpvio-auto: static planes are discovered among the features of the whole image
  // (plane_discovery.h) and only their features are used (discover_static_points: and the
  // static ones off them); mask labels are ignored. Frames
  // discover_span_s apart with discover_min_parallax_px of rotation-compensated parallax are
  // compared; a feature farther than discover_epipolar_px (px at virtual_focal) from its epipolar
  // line moves; discover_plane_px is the transfer error within which a feature lies on a plane of
  // at least discover_min_features, at most discover_plane_sigmas standard deviations of the
  // check's track noise (0: discover_plane_px alone). A plane found in discover_confirm_after
  // checks is static; one whose features mostly moved in discover_reject_after consecutive checks
  // is rejected. discover_adopt_young: tracks younger than discover_span_s join a confirmed
  // plane they fit over the longest span they have. discover_static_points: the features on no
  // plane that were on their epipolar line when last compared are used too (reprojection only).
  bool discover_planes = false;
  double discover_span_s = 0.3;
  double discover_min_parallax_px = 4;
  double discover_epipolar_px = 0.5;
  double discover_plane_px = 0.5;
  double discover_plane_sigmas = 3;
  size_t discover_min_features = 10;
  int discover_max_planes = 4;
  int discover_confirm_after = 3;
  int discover_reject_after = 3;
  bool discover_adopt_young = true;
  bool discover_static_points = false;

  template <class Visitor>
  void fields(Visitor& v) {
    RPVIO_OPTION(v, window_size);
    RPVIO_OPTION(v, keyframe_parallax_px);
    RPVIO_OPTION(v, keyframe_min_tracks);
    RPVIO_OPTION(v, max_keyframe_gap_s);
    RPVIO_OPTION_CHOICE(v, homography_planes, kHomographyPlanesNames);
    RPVIO_OPTION(v, map_all_planes);
    RPVIO_OPTION(v, pixel_sigma);
    RPVIO_OPTION(v, ground_pixel_sigma);
    RPVIO_OPTION(v, cauchy_scale);
    RPVIO_OPTION(v, imu_noise_inflation);
    RPVIO_OPTION(v, max_imu_step_s);
    RPVIO_OPTION(v, imu_gap_noise_inflation);
    RPVIO_OPTION(v, min_saturated_accel);
    RPVIO_OPTION(v, min_saturated_gyro);
    RPVIO_OPTION(v, max_iterations);
    RPVIO_OPTION(v, motion_only_between_keyframes);
    RPVIO_OPTION(v, max_solver_time_s);
    RPVIO_OPTION(v, max_iterations_before_deferring);
    RPVIO_OPTION(v, plane_covariance_every);
    RPVIO_OPTION(v, defer_plane_covariances);
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
    RPVIO_OPTION(v, init_fallback_parallax_px);
    RPVIO_OPTION(v, camera_height_sigma);
    RPVIO_OPTION(v, accel_bias_prior_sigma);
    RPVIO_OPTION(v, init_max_scale_sigma);
    RPVIO_OPTION(v, init_retry_s);
    RPVIO_OPTION(v, publish_init_window);
    RPVIO_OPTION(v, init_window_frames);
    RPVIO_OPTION(v, init_fallback);
    RPVIO_OPTION(v, init_fallback_after_s);
    RPVIO_OPTION_CHOICE(v, reinitializer, kInitializerMethodNames);
    RPVIO_OPTION(v, reinit_max_scale_sigma);
    RPVIO_OPTION(v, reinit_known_velocity_s);
    RPVIO_OPTION(v, max_reconnect_s);
    RPVIO_OPTION(v, estimate_time_offset);
    RPVIO_OPTION(v, min_time_offset_s);
    RPVIO_OPTION(v, time_offset_systematic_margin);
    RPVIO_OPTION(v, time_offset_window_s);
    RPVIO_OPTION(v, max_time_offset_s);
    RPVIO_OPTION(v, verify_planes);
    RPVIO_OPTION(v, verify_span_s);
    RPVIO_OPTION(v, verify_min_parallax_px);
    RPVIO_OPTION(v, verify_min_features);
    RPVIO_OPTION(v, verify_static_px);
    RPVIO_OPTION(v, verify_moving_px);
    RPVIO_OPTION(v, verify_moving_noise_ratio);
    RPVIO_OPTION(v, verify_reject_after);
    RPVIO_OPTION(v, discover_planes);
    RPVIO_OPTION(v, discover_span_s);
    RPVIO_OPTION(v, discover_min_parallax_px);
    RPVIO_OPTION(v, discover_epipolar_px);
    RPVIO_OPTION(v, discover_plane_px);
    RPVIO_OPTION(v, discover_plane_sigmas);
    RPVIO_OPTION(v, discover_min_features);
    RPVIO_OPTION(v, discover_max_planes);
    RPVIO_OPTION(v, discover_confirm_after);
    RPVIO_OPTION(v, discover_reject_after);
    RPVIO_OPTION(v, discover_adopt_young);
    RPVIO_OPTION(v, discover_static_points);
  }
  void validate(const OptionsLoader& loader) const;
  ImuLinkOptions imuLinkOptions() const;
  PlaneVerifierOptions planeVerifierOptions() const;
  PlaneDiscoveryOptions planeDiscoveryOptions() const;
  /// The first initializer's options (the others are variants of it).
  InitializerOptions initializerOptions() const;
};

}  // namespace rpvio

#pragma once
// The initializer facade (DESIGN.md §1 step 3): from a window of tracked frames and the IMU
// preintegrations between them, the metric, gravity-aligned initial state of every frame.
//
//  kPlanarHomography (rpvio-single / rpvio-multi): the frame pair (l, r) best conditioned
//    (parallax × √features of their largest common plane), its homography decomposed and
//    disambiguated by the gyroscope, plane features placed on the plane, other features
//    triangulated, PnP for the other frames, bundle adjustment with reprojection + homography
//    residuals; the other planes' distances from their own decompositions once the motion is
//    metric.
//  kEssentialMatrix (vins-mono / mask-vins): the best-conditioned pair (parallax × √features),
//    its 5-point essential matrix, the same SfM without planes.
// Then both: visual-inertial alignment (gyro bias, velocities, gravity, scale, accelerometer bias
// held near zero by a prior) and the gravity-aligned world.
//
// World frame of the result: z up (gravity (0, 0, −g)), origin at the body of the window's first
// frame, yaw of that body 0 (its x axis projected on the horizontal plane is the world x axis).
#include <mrpt/system/COutputLogger.h>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/sensor_types.h"
#include "mrpt_modules/core/feature_frame.h"
#include "mrpt_modules/imu/imu_preintegration.h"

namespace rpvio {

enum class InitializerMethod { kPlanarHomography, kEssentialMatrix };

/// Why the window does not give an initial state (yet); kSuccess when it does.
enum class InitStatus {
  kSuccess,
  kCollectingFrames,        // window too short
  kTooFewPlaneFeatures,     // planar: largest plane shared by too few features with the last frame
  kTooFewFeatures,          // essential: too few correspondences with the last frame
  kTooLittleParallax,       // no pair moves fallback_parallax_px (rotation compensated)
  kTooLittleImuExcitation,  // accelerations too uniform: the alignment's scale is uncertain
  kGeometryFailed,          // homography/essential/PnP failed or disagrees with the gyroscope
  kAlignmentRejected,       // scale ≤ 0, gravity magnitude off
};
const char* toString(InitStatus status);

struct InitializerOptions {
  InitializerMethod method = InitializerMethod::kPlanarHomography;
  size_t min_frames = 10;
  double min_window_s = 2.0;  // time span of the window: baseline and IMU excitation for the scale
  double virtual_focal = 460.0;   // px; thresholds below are at this focal length
  double min_parallax_px = 30.0;  // mean rotation-compensated displacement in the pair
  // When no pair reaches min_parallax_px, the pairs down to this are tried: the gyroscope's
  // agreement, the bundle adjustment and the scale's precision then decide.
  double fallback_parallax_px = 8.0;
  size_t min_plane_features = 20;  // planar: largest plane's features common to the pair
  size_t min_features = 30;        // essential: features common to the pair
  // Wider than the front-end's 1 px frame to frame: tracks drift a little over the pair's baseline.
  double homography_ransac_px = 2.5;
  double essential_ransac_px = 1.0;
  double max_gyro_disagreement_deg = 5.0;  // homography/essential rotation vs the gyroscope's
  // The alignment's scale standard deviation (from its residual) relative to the scale: above
  // it, the window's accelerations do not make the scale observable (too little excitation).
  double max_relative_scale_sigma = 0.03;
  // Planar, with the calibration's camera_height: a plane counts as the ground when its normal is
  // within this of gravity (the scale then comes from the height).
  double max_ground_tilt_deg = 10.0;
  double pixel_sigma = 1.5;    // BA weight virtual_focal / pixel_sigma
  double max_ba_rms_px = 2.0;  // structure rejected above this residual RMS
};

/// A plane n·X = d in the world frame (n unit).
struct WorldPlane {
  Eigen::Vector3d n;
  double d;
};

/// Depth of a feature in the camera of its first observation in the window.
struct FeatureDepth {
  size_t frame;
  double depth;  // m
};

struct InitializationResult {
  InitStatus status = InitStatus::kCollectingFrames;
  std::string reason;  // human-readable, with the numbers behind the status

  // On success, one entry per window frame:
  std::vector<Eigen::Isometry3d> T_w_b;                 // body pose in the world
  std::vector<Eigen::Vector3d> v_w;                     // body velocity in the world
  std::vector<std::shared_ptr<ImuPreintegration>> imu;  // copies repropagated with ba, bg
  Eigen::Vector3d ba = Eigen::Vector3d::Zero(), bg = Eigen::Vector3d::Zero();
  std::map<int, WorldPlane> planes;    // planar: the initialization plane and the others decided
  int reference_plane = -1;            // planar: the plane of the homography
  std::map<int, FeatureDepth> depths;  // by feature id
  size_t pair_first = 0, pair_last = 0;
  double scale = 0;                       // metres per SfM unit (plane distance, or pair baseline)
  bool scale_from_camera_height = false;  // the scale from the ground and the camera's height

  bool ok() const { return status == InitStatus::kSuccess; }
};

/// The body's orientation and velocity at the window's first frame, known from before a reset
/// (IMU dead reckoning from the last good state): the alignment then takes its velocity as given,
/// and needs no excitation for the scale.
struct KnownStart {
  Eigen::Matrix3d R_w_b = Eigen::Matrix3d::Identity();
  Eigen::Vector3d v_w = Eigen::Vector3d::Zero();
};

class Initializer : public mrpt::system::COutputLogger {
 public:
  Initializer(const Calibration& calibration, const InitializerOptions& options);

  /// frames[k] and imu[k] (IMU from frame k−1 to k; imu[0] is ignored and may be null). The
  /// caller's preintegrations are not modified. Logs the reason (INFO) when the status changes.
  InitializationResult tryInitialize(const std::vector<FeatureFrame>& frames,
                                     const std::vector<std::shared_ptr<ImuPreintegration>>& imu,
                                     const std::optional<KnownStart>& start = {});

  const InitializerOptions& options() const { return options_; }

 private:
  InitializationResult attempt(const std::vector<FeatureFrame>& frames,
                               const std::vector<std::shared_ptr<ImuPreintegration>>& imu,
                               const std::optional<KnownStart>& start) const;

  Calibration calibration_;
  InitializerOptions options_;
  std::optional<InitStatus> last_status_;  // the reason is logged when the status changes
};

}  // namespace rpvio

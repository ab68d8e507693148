#pragma once
// RP-VIO's sliding-window estimator (DESIGN.md §1 step 4), first version: keyframes with pose,
// velocity and biases, IMU factors between consecutive keyframes, homography factors of the plane
// features between consecutive observations, plane parameters (n on the sphere, d) kept in a map
// that outlives the window. Instead of a marginalization prior (not built yet), the oldest keyframe
// is tied to its last estimate by fixed standard deviations. Failures (implausible speed or biases)
// reset and re-initialize.
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "mrpt_modules/estimator/planar_initializer.h"
#include "rawlog_io/rawlog_writer.h"

namespace rpvio {

struct EstimatorOptions {
  size_t window_size = 10;
  double keyframe_parallax_px = 10;  // at the virtual focal length
  double max_keyframe_gap_s = 0.3;
  bool all_planes = false;   // rpvio-multi; false = rpvio-single (largest plane only)
  double pixel_sigma = 1.5;  // homography residual weight: virtual_focal / pixel_sigma
  double cauchy_scale = 10;  // robust loss scale, in units of pixel_sigma
  int max_iterations = 8;
  size_t init_window_frames = 41;  // frames kept while initializing (2 s at 20 Hz)
  PlanarInitOptions init;
};

struct StateEstimate {
  double t = 0;
  double pose[7] = {0, 0, 0, 0, 0, 0, 1};
  bool keyframe = false;
};

class SlidingWindowEstimator {
 public:
  SlidingWindowEstimator(const Calibration& calibration, const EstimatorOptions& options);

  /// A new frame with the IMU samples since the previous frame (first sample at or before the
  /// previous frame's time, last at or before this frame's). Returns the frame's body pose once
  /// initialized.
  std::optional<StateEstimate> addFrame(const FeatureFrame& frame,
                                        const std::vector<ImuSample>& imu_since_previous);

  bool initialized() const { return initialized_; }
  size_t resets() const { return resets_; }
  const std::string& status() const { return status_; }
  const PlaneEstimates& planes() const { return planes_; }

 private:
  struct Record {
    FeatureFrame features;
    std::vector<ImuSample> imu;  // since the previous record
  };
  std::shared_ptr<ImuPreintegration> preintegrate(const std::vector<ImuSample>& samples,
                                                  const Eigen::Vector3d& ba,
                                                  const Eigen::Vector3d& bg) const;
  void tryInitialize();
  void optimize();
  void initializeMissingPlanes();
  bool healthy() const;
  void reset(const std::string& cause);
  StateEstimate predict(double t) const;

  Calibration calib_;
  EstimatorOptions options_;
  bool initialized_ = false;
  size_t resets_ = 0;
  std::string status_ = "collecting frames";
  std::deque<Record> init_buffer_;
  std::deque<WindowFrame> window_;
  std::vector<ImuSample> pending_imu_;  // since the newest keyframe
  PlaneEstimates planes_;
};

}  // namespace rpvio

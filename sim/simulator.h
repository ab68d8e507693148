#pragma once
// The in-memory simulator: ground truth, IMU, images and masks of a warehouse sequence at any time.
// Tests of every stage (front-end, initialization, estimator, planes map) stand on this API.
//
// Times are on the IMU clock (seconds from the start of the flight). A camera frame taken at IMU
// time τ carries the camera timestamp τ − time_offset.
#include <optional>
#include <vector>

#include "sim/sim_config.h"

namespace rpvio::sim {

class Simulator {
 public:
  explicit Simulator(const SimConfig& config);

  const SimConfig& config() const { return config_; }
  const PinholeCamera& camera() const { return camera_; }
  Calibration calibration() const { return config_.calibration(); }
  const WarehouseScene& scene() const { return scene_; }

  FlightState state(double t) const { return flight_.at(t); }
  Eigen::Isometry3d bodyPose(double t) const;    // T_WB
  Eigen::Isometry3d cameraPose(double t) const;  // T_WC = T_WB T_BC

  /// IMU times of the camera frames: k / camera_rate for k = 0 .. duration * camera_rate.
  std::vector<double> frameTimes() const;
  /// Image and mask at IMU time t; `frame_index` seeds the image noise and mask degradation.
  /// The image integrates [t − e/2, t + e/2] (exposure_time e) and carries the auto-exposure gain.
  RenderedFrame render(double t, int frame_index);
  /// Sensor gain of the frame at IMU time t: 1, or the auto-exposure loop's (auto_exposure.h).
  double exposureGain(double t);
  /// What pixel (u, v) sees at IMU time t (hit point, plane id / character label).
  SceneHit castPixel(double t, double u, double v);
  /// Pixel of world point X at IMU time t, if in front of the camera.
  std::optional<Eigen::Vector2d> project(double t, const Eigen::Vector3d& X) const;
  /// Fraction of the image whose pixel centres see a moving thing at IMU time t, counted on every
  /// `stride`-th pixel of every `stride`-th row (stride 1: the rendered frame's `dynamic` layer).
  double dynamicFraction(double t, int stride);
  /// Distance from X to the nearest character surface at IMU time t (∞ without characters).
  double distanceToCharacters(double t, const Eigen::Vector3d& X);

  /// The noisy (or noise-free, per config) IMU stream over the whole duration.
  std::vector<ImuSample> imuStream(std::vector<ImuBiasState>* true_biases = nullptr) const;

 private:
  SimConfig config_;
  PinholeCamera camera_;    // config_.camera's
  Eigen::Isometry3d T_BC_;  // config_.camera's
  FlightTrajectory flight_;
  WarehouseScene scene_;
  AutoExposure auto_exposure_;
  double posed_time_ = 0;
  void poseAt(double t);
};

}  // namespace rpvio::sim

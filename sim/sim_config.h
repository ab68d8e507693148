#pragma once
// Everything a simulated sequence depends on. Loaded from an INI file (config/sim/warehouse.ini
// documents every key and its default); every key is optional.
#include <string>

#include "common/sensor_types.h"
#include "sim/auto_exposure.h"
#include "sim/crowd.h"
#include "sim/fault_injection.h"
#include "sim/flight_trajectory.h"
#include "sim/imu_simulator.h"
#include "sim/mask_degradation.h"
#include "sim/renderer.h"
#include "sim/warehouse_scene.h"

namespace rpvio::sim {

struct SimConfig {
  std::string profile_name = "paper";  // the built-in profile these values started from
  double duration = 80.0;              // s
  double camera_rate = 20.0;           // Hz, images and masks
  double time_offset = 0.0;            // s, true camera-IMU offset: t_imu = t_cam + time_offset
  uint64_t seed = 1;                   // scene layout, textures, all noise
  FlightParams flight;
  SceneParams scene;  // scene.characters = number of characters
  CrowdParams crowd;  // who the characters are and how they move
  PinholeCamera camera = pinholeCamera(640, 480, 90);
  Eigen::Isometry3d T_BC = defaultCameraMount();
  RenderOptions render;
  double exposure_time = 0;  // s, shutter open over [t − e/2, t + e/2] (motion blur); 0: sharp
  AutoExposureParams auto_exposure;
  ImuNoise imu;  // noise densities, random walks, rate, gravity
  bool imu_noise = true;
  ImuBiasState initial_bias = defaultInitialBias();
  MaskDegradation mask;
  FaultInjection faults;  // off by default; set by rpvio-sim's fault options

  /// Image size and horizontal field of view (deg); principal point at the image centre.
  static PinholeCamera pinholeCamera(int width, int height, double hfov_deg);
  /// Camera looking along body x, 10 cm ahead and 5 cm above the IMU (camera z = body x, camera
  /// x = −body y, camera y = −body z).
  static Eigen::Isometry3d defaultCameraMount();
  static ImuBiasState defaultInitialBias();
  /// The built-in profiles: "paper" (the defaults: the paper's RPVIO-Sim warehouse) and "hard"
  /// (a lower flight through a crowd that fills the view, CNN-like masks; docs/configuration.md).
  /// Throws std::invalid_argument on another name.
  static SimConfig profile(const std::string& name);
  /// `base` with the keys of an INI file over it. Throws InputError naming the file and line on a
  /// bad value or an unknown key.
  static SimConfig load(const std::string& ini_path, const SimConfig& base);
  static SimConfig load(const std::string& ini_path) { return load(ini_path, SimConfig()); }
  Calibration calibration() const;
};

}  // namespace rpvio::sim

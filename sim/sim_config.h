#pragma once
// Everything a simulated sequence depends on. Loaded from an INI file (config/sim/warehouse.ini
// documents every key and its default); every key is optional.
#include <string>

#include "common/sensor_types.h"
#include "sim/auto_exposure.h"
#include "sim/camera_rig.h"
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
  CameraRig camera;
  RenderOptions render;
  double exposure_time = 0;  // s, shutter open over [t − e/2, t + e/2] (motion blur); 0: sharp
  AutoExposureParams auto_exposure;
  ImuNoise imu;  // noise densities, random walks, rate, gravity
  bool imu_noise = true;
  ImuBiasState initial_bias = defaultInitialBias();
  MaskDegradation mask;
  FaultInjection faults;  // off by default; set by rpvio-sim's fault options

  /// The scene file's sections: section(name, fields) for each, fields(visitor) visiting its keys
  /// (the options pattern of common/options.h; a key is its field's name).
  template <class Section>
  void sections(Section&& section) {
    section("sequence", [this](auto& v) {
      RPVIO_OPTION(v, duration);
      RPVIO_OPTION(v, camera_rate);
      RPVIO_OPTION(v, time_offset);
      RPVIO_OPTION(v, seed);
      v("characters", scene.characters);
    });
    section("flight", [this](auto& v) { flight.fields(v); });
    section("scene", [this](auto& v) { scene.fields(v); });
    section("crowd", [this](auto& v) { crowd.fields(v); });
    section("camera", [this](auto& v) { camera.fields(v); });
    section("image", [this](auto& v) {
      render.fields(v);
      RPVIO_OPTION(v, exposure_time);
    });
    section("auto_exposure", [this](auto& v) { auto_exposure.fields(v); });
    section("imu", [this](auto& v) {
      imu.fields(v);
      v("noise", imu_noise);
      v("gyro_bias", initial_bias.gyro);
      v("accel_bias", initial_bias.accel);
    });
    section("mask", [this](auto& v) { mask.fields(v); });
  }

  static ImuBiasState defaultInitialBias();
  /// `base` (the defaults, profile_name set) with the motion of that platform.
  static SimConfig platform(SimConfig base);
  /// The built-in profiles: "paper" (the defaults: the paper's RPVIO-Sim warehouse), "hard"
  /// (a lower flight through a crowd that fills the view, CNN-like masks) and the platforms'
  /// motions "handheld", "drone", "ground-robot" and "car" (docs/configuration.md).
  /// Throws std::invalid_argument on another name.
  static SimConfig profile(const std::string& name);
  /// `base` with the keys of an INI file over it. Throws InputError naming the file and line on a
  /// bad value or an unknown key.
  static SimConfig load(const std::string& ini_path, const SimConfig& base);
  static SimConfig load(const std::string& ini_path) { return load(ini_path, SimConfig()); }
  /// Every key as a scene file: load(file) over any base gives this configuration back.
  std::string describe() const;
  Calibration calibration() const;
};

}  // namespace rpvio::sim

#include "sim/sim_config.h"

#include <cmath>

#include "common/ini_file.h"
#include "common/input_error.h"

namespace rpvio::sim {

ImuBiasState SimConfig::defaultInitialBias() {
  ImuBiasState b;
  b.gyro = Eigen::Vector3d(0.003, -0.002, 0.004);  // rad/s, consumer MEMS turn-on bias
  b.accel = Eigen::Vector3d(0.05, -0.04, 0.06);    // m/s^2
  return b;
}

SimConfig SimConfig::profile(const std::string& name) {
  SimConfig c;
  if (name == "paper") return c;
  c.profile_name = name;
  if (name == "handheld" || name == "drone" || name == "ground-robot" || name == "car")
    return platform(c);
  if (name != "hard")
    throw std::invalid_argument("unknown profile '" + name +
                                "' (paper, hard, handheld, drone, ground-robot or car)");
  // People 1.6-1.9 m tall must fill the view: fly at chest height (0.6 m at the start, 1.0-1.6 m
  // once a 0.4 m push is done), a gentler wave in height.
  c.flight.height = 0.9;
  c.flight.height_amplitude = 0.3;
  c.flight.start_push = 0.4;
  c.crowd.layout = CrowdLayout::Flight;
  // Masks as a segmentation network gives them (levels: docs/configuration.md).
  c.mask.boundary_bleed_px = 3;
  c.mask.missed_plane_rate = 0.03;
  c.mask.split_plane_id = 1;
  c.mask.spurious_blob_rate = 0.2;
  // A real sensor: a 10 ms exposure (indoor light) blurs what moves, an auto-exposure loop reacts
  // to bright windows on the walls and saturates them.
  c.exposure_time = 0.01;
  c.auto_exposure.enabled = true;
  c.scene.light_panels = 5;
  return c;
}

SimConfig SimConfig::platform(SimConfig c) {
  // No take-off push: initialization must not depend on one. Characters walk around the camera
  // (the crowd's flight layout) wherever the platform goes.
  FlightParams& f = c.flight;
  f.start_push = 0;
  c.crowd.layout = CrowdLayout::Flight;
  const std::string& name = c.profile_name;
  if (name == "handheld") {
    // A phone carried at walking speed around the crates, head turns of ±0.8 rad peaking at
    // 3 rad/s (0.8 · 2π/4.6 s · 2.60, the square wave's peak slope, + the walk's 0.16 rad/s).
    c.camera_rate = 30;
    c.camera.width = 1280;
    c.camera.height = 720;
    c.camera.hfov_deg = 60;
    f.radius = 9;
    f.speed = 1.4;
    f.speed_ramp = 1.0;
    f.height = 1.5;
    f.height_amplitude = 0.15;
    f.height_period = 6;
    f.tilt_amplitude = 0.08;
    f.yaw_swing = 0.8;
    f.yaw_swing_period = 4.6;
    f.bob_amplitude = 0.02;
  } else if (name == "drone") {
    // 5 m/s around the circle, sharp yaw turns of ±0.5 rad peaking at 2 rad/s
    // (0.5 · 2π/4.9 s · 2.60 + the circle's 0.33 rad/s).
    f.speed = 5;
    f.tilt_amplitude = 0.08;
    f.yaw_swing = 0.5;
    f.yaw_swing_period = 4.9;
  } else if (name == "ground-robot") {
    // Planar, looking ahead, 0.5-1 m/s with near-constant stretches; camera 0.8 m above the floor.
    c.camera_rate = 30;
    c.camera.width = 848;
    c.camera.height = 480;
    c.camera.hfov_deg = 70;
    f.radius = 9;
    f.speed = 0.75;
    f.speed_swing = 0.25;
    f.speed_ramp = 2;
    f.height = 0.75;
    f.height_amplitude = 0;
    f.tilt_amplitude = 0.005;
    f.look = LookDirection::Forward;
  } else {  // car
    // KITTI-like: 10 Hz, 1241 x 376, fx = 718 px; 0 -> 10 m/s, a 90° turn; camera 1.65 m above
    // the ground. The room becomes a 400 m yard (coarser texels keep its floor texture ~130 MB).
    c.camera_rate = 10;
    c.camera.width = 1241;
    c.camera.height = 376;
    c.camera.hfov_deg = 81.6;
    f.path = PathShape::Road;
    f.look = LookDirection::Forward;
    f.speed = 10;
    f.speed_ramp = 6;
    f.height = 1.6;
    f.height_amplitude = 0;
    f.tilt_amplitude = 0.005;
    c.scene.room_half_size = 200;
    c.scene.ceiling = false;
    c.scene.crates = 0;
    c.scene.texel_size = 0.08;
  }
  return c;
}

SimConfig SimConfig::load(const std::string& path, const SimConfig& base) {
  const IniFile ini(path);
  SimConfig c = base;
  c.sections([&](const char* name, auto&& fields) {
    OptionsLoader loader(ini, name);
    fields(loader);
  });
  const OptionsLoader sequence(ini, "sequence");
  sequence.require(c.duration > 0, "duration", "must be positive");
  sequence.require(c.camera_rate > 0, "camera_rate", "must be positive");
  sequence.require(c.scene.characters >= 0, "characters", "must not be negative");
  c.flight.validate(OptionsLoader(ini, "flight"));
  c.scene.validate(OptionsLoader(ini, "scene"));
  c.crowd.validate(OptionsLoader(ini, "crowd"));
  c.camera.validate(OptionsLoader(ini, "camera"));
  OptionsLoader(ini, "image")
      .require(c.exposure_time >= 0, "exposure_time", "must not be negative");
  c.auto_exposure.validate(OptionsLoader(ini, "auto_exposure"));
  OptionsLoader(ini, "imu").require(c.imu.rate_hz > 0, "rate_hz", "must be positive");
  const auto unknown = ini.unreadKeys();
  if (!unknown.empty())
    throw InputError(
        path, "line " + std::to_string(unknown.front().line),
        "unknown key '" + unknown.front().key + "' in [" + unknown.front().section + "]");
  return c;
}

std::string SimConfig::describe() const {
  SimConfig copy = *this;
  std::string text;
  copy.sections([&](const char* name, auto&& fields) {
    OptionsDescriber describer;
    fields(describer);
    text += (text.empty() ? "[" : "\n[") + std::string(name) + "]\n" + describer.text();
  });
  return text;
}

Calibration SimConfig::calibration() const {
  Calibration calib;
  const PinholeCamera pinhole = camera.intrinsics();
  calib.camera.width = pinhole.width;
  calib.camera.height = pinhole.height;
  calib.camera.fx = pinhole.fx;
  calib.camera.fy = pinhole.fy;
  calib.camera.cx = pinhole.cx;
  calib.camera.cy = pinhole.cy;
  calib.T_BC = camera.T_BC();
  calib.time_offset = 0.0;  // what a user would know before calibrating; the truth is time_offset
  calib.imu = imu;
  // A platform whose camera keeps its height above the floor (no wave, bob or push) knows it.
  if (flight.height_amplitude == 0 && flight.bob_amplitude == 0 && flight.start_push == 0)
    calib.camera_height = flight.height + camera.T_BC_translation.z();
  return calib;
}

}  // namespace rpvio::sim

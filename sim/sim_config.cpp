#include "sim/sim_config.h"

#include <cmath>

#include "common/ini_file.h"
#include "common/input_error.h"

namespace rpvio::sim {

PinholeCamera SimConfig::pinholeCamera(int width, int height, double hfov_deg) {
  PinholeCamera c;
  c.width = width;
  c.height = height;
  c.fx = c.fy = 0.5 * width / std::tan(0.5 * hfov_deg * M_PI / 180);
  c.cx = 0.5 * (width - 1);
  c.cy = 0.5 * (height - 1);
  return c;
}

Eigen::Isometry3d SimConfig::defaultCameraMount() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() << 0, 0, 1,  //
      -1, 0, 0,           //
      0, -1, 0;           // columns: camera x, y, z axes in the body frame
  T.translation() = Eigen::Vector3d(0.10, 0.0, 0.05);
  return T;
}

ImuBiasState SimConfig::defaultInitialBias() {
  ImuBiasState b;
  b.gyro = Eigen::Vector3d(0.003, -0.002, 0.004);  // rad/s, consumer MEMS turn-on bias
  b.accel = Eigen::Vector3d(0.05, -0.04, 0.06);    // m/s^2
  return b;
}

SimConfig SimConfig::profile(const std::string& name) {
  SimConfig c;
  if (name == "paper") return c;
  if (name != "hard") throw std::invalid_argument("unknown profile '" + name + "' (paper or hard)");
  c.profile_name = name;
  // People 1.6-1.9 m tall must fill the view: fly at chest height (0.6 m at the start, 1.0-1.6 m
  // once a 0.4 m push is done), a gentler wave in height.
  c.flight.height = 0.9;
  c.flight.height_amplitude = 0.3;
  c.flight.start_push = 0.4;
  c.crowd.layout = "flight";
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

SimConfig SimConfig::load(const std::string& path, const SimConfig& base) {
  const IniFile ini(path);
  SimConfig c = base;
  auto num = [&](const char* section, const char* key, double& value) {
    value = ini.numberOr(section, key, value);
  };
  auto vec = [&](const char* section, const char* key, Eigen::Vector3d& value) {
    if (!ini.has(section, key)) return;
    const auto v = ini.numbers(section, key, 3);
    value = Eigen::Vector3d(v[0], v[1], v[2]);
  };
  auto positive = [&](const char* section, const char* key, double value) {
    if (!(value > 0))
      throw InputError(path, "line " + std::to_string(ini.line(section, key)),
                       std::string("'") + key + "' must be positive");
  };
  double seed = static_cast<double>(c.seed), characters = c.scene.characters;
  num("sequence", "duration", c.duration);
  num("sequence", "camera_rate", c.camera_rate);
  num("sequence", "time_offset", c.time_offset);
  num("sequence", "seed", seed);
  num("sequence", "characters", characters);
  positive("sequence", "duration", c.duration);
  positive("sequence", "camera_rate", c.camera_rate);
  c.seed = static_cast<uint64_t>(seed);
  c.scene.characters = static_cast<int>(characters);

  FlightParams& f = c.flight;
  num("flight", "radius", f.radius);
  num("flight", "speed", f.speed);
  num("flight", "speed_ramp", f.speed_ramp);
  num("flight", "height", f.height);
  num("flight", "height_amplitude", f.height_amplitude);
  num("flight", "height_period", f.height_period);
  num("flight", "start_push", f.start_push);
  num("flight", "start_push_time", f.start_push_time);
  num("flight", "tilt_amplitude", f.tilt_amplitude);
  positive("flight", "radius", f.radius);

  SceneParams& s = c.scene;
  double crates = s.crates, trucks = s.pallet_trucks, panels = s.sliding_panels;
  num("scene", "room_half_size", s.room_half_size);
  num("scene", "room_height", s.room_height);
  num("scene", "crates", crates);
  num("scene", "texel_size", s.texel_size);
  num("scene", "character_ring_radius", s.character_ring_radius);
  num("scene", "character_height", s.character_height);
  double lights = s.light_panels;
  num("scene", "light_panels", lights);
  num("scene", "light_intensity", s.light_intensity);
  s.light_panels = static_cast<int>(lights);
  num("scene", "pallet_trucks", trucks);
  num("scene", "sliding_panels", panels);
  num("scene", "moving_speed", s.moving_speed);
  s.crates = static_cast<int>(crates);
  s.pallet_trucks = static_cast<int>(trucks);
  s.sliding_panels = static_cast<int>(panels);
  s.ceiling = ini.flagOr("scene", "ceiling", s.ceiling);
  s.racks = ini.flagOr("scene", "racks", s.racks);
  positive("scene", "texel_size", s.texel_size);
  positive("scene", "moving_speed", s.moving_speed);
  if (s.pallet_trucks < 0 || s.sliding_panels < 0 ||
      s.pallet_trucks * kPalletTruckFaces + s.sliding_panels * kSlidingPanelFaces >
          kMovingPlaneIdLast - kMovingPlaneIdFirst + 1)
    throw InputError(path, "line " + std::to_string(ini.line("scene", "pallet_trucks")),
                     "pallet_trucks (10 faces each) and sliding_panels (2 faces each) need more "
                     "than the 40 plane ids 200..239");

  if (ini.has("camera", "width") || ini.has("camera", "height") || ini.has("camera", "hfov_deg")) {
    double width = c.camera.width, height = c.camera.height,
           hfov_deg = 2 * std::atan(0.5 * width / c.camera.fx) * 180 / M_PI;
    num("camera", "width", width);
    num("camera", "height", height);
    num("camera", "hfov_deg", hfov_deg);
    positive("camera", "hfov_deg", hfov_deg);
    c.camera = pinholeCamera(static_cast<int>(width), static_cast<int>(height), hfov_deg);
  }
  Eigen::Vector3d mount = c.T_BC.translation();
  vec("camera", "T_BC_translation", mount);
  c.T_BC.translation() = mount;

  num("image", "noise_sigma", c.render.noise_sigma);
  num("image", "vignetting", c.render.vignetting);
  double ss = c.render.supersampling;
  num("image", "supersampling", ss);
  c.render.supersampling = static_cast<int>(ss);
  num("image", "exposure_time", c.exposure_time);
  if (c.exposure_time < 0)
    throw InputError(path, "line " + std::to_string(ini.line("image", "exposure_time")),
                     "'exposure_time' must not be negative");
  AutoExposureParams& ae = c.auto_exposure;
  ae.enabled = ini.flagOr("image", "auto_exposure", ae.enabled);
  num("image", "exposure_target", ae.target);
  num("image", "exposure_time_constant", ae.time_constant);
  num("image", "initial_gain", ae.initial_gain);
  num("image", "min_gain", ae.min_gain);
  num("image", "max_gain", ae.max_gain);
  positive("image", "exposure_target", ae.target);
  positive("image", "exposure_time_constant", ae.time_constant);
  positive("image", "initial_gain", ae.initial_gain);
  positive("image", "min_gain", ae.min_gain);
  if (ae.max_gain < ae.min_gain)
    throw InputError(path, "line " + std::to_string(ini.line("image", "max_gain")),
                     "'max_gain' must not be below 'min_gain'");

  num("imu", "rate_hz", c.imu.rate_hz);
  num("imu", "gyro_noise_density", c.imu.gyro_noise_density);
  num("imu", "accel_noise_density", c.imu.accel_noise_density);
  num("imu", "gyro_random_walk", c.imu.gyro_random_walk);
  num("imu", "accel_random_walk", c.imu.accel_random_walk);
  num("imu", "gravity", c.imu.gravity);
  positive("imu", "rate_hz", c.imu.rate_hz);
  c.imu_noise = ini.flagOr("imu", "noise", c.imu_noise);
  vec("imu", "gyro_bias", c.initial_bias.gyro);
  vec("imu", "accel_bias", c.initial_bias.accel);

  CrowdParams& crowd = c.crowd;
  crowd.layout = ini.textOr("crowd", "layout", crowd.layout);
  if (crowd.layout != "ring" && crowd.layout != "flight")
    throw InputError(path, "line " + std::to_string(ini.line("crowd", "layout")),
                     "'layout' must be ring or flight, not '" + crowd.layout + "'");
  num("crowd", "person_height_min", crowd.person_height_min);
  num("crowd", "person_height_max", crowd.person_height_max);
  num("crowd", "walking_speed", crowd.walking_speed);
  num("crowd", "crossing_depth_min", crowd.crossing_depth_min);
  num("crowd", "crossing_depth_max", crowd.crossing_depth_max);
  num("crowd", "companion_depth_min", crowd.companion_depth_min);
  num("crowd", "companion_depth_max", crowd.companion_depth_max);
  num("crowd", "companion_hold", crowd.companion_hold);
  num("crowd", "companion_close_in", crowd.companion_close_in);
  num("crowd", "companion_gap", crowd.companion_gap);
  num("crowd", "dancer_depth", crowd.dancer_depth);
  positive("crowd", "crossing_depth_min", crowd.crossing_depth_min);
  positive("crowd", "companion_depth_min", crowd.companion_depth_min);

  double bleed = c.mask.boundary_bleed_px, split = c.mask.split_plane_id;
  num("mask", "boundary_bleed_px", bleed);
  num("mask", "missed_plane_rate", c.mask.missed_plane_rate);
  num("mask", "split_plane_id", split);
  num("mask", "spurious_blob_rate", c.mask.spurious_blob_rate);
  c.mask.boundary_bleed_px = static_cast<int>(bleed);
  c.mask.split_plane_id = static_cast<int>(split);
  const auto unknown = ini.unreadKeys();
  if (!unknown.empty())
    throw InputError(
        path, "line " + std::to_string(unknown.front().line),
        "unknown key '" + unknown.front().key + "' in [" + unknown.front().section + "]");
  return c;
}

Calibration SimConfig::calibration() const {
  Calibration calib;
  calib.camera.width = camera.width;
  calib.camera.height = camera.height;
  calib.camera.fx = camera.fx;
  calib.camera.fy = camera.fy;
  calib.camera.cx = camera.cx;
  calib.camera.cy = camera.cy;
  calib.T_BC = T_BC;
  calib.time_offset = 0.0;  // what a user would know before calibrating; the truth is time_offset
  calib.imu = imu;
  return calib;
}

}  // namespace rpvio::sim

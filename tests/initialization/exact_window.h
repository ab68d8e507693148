#pragma once
// A window of frames with exact features: simulator scene points (static planes only, with their
// plane ids) projected into each frame, optional pixel noise, and IMU preintegrations of the
// noise-free analytic flight plus a constant gyro bias (test helper).
#include <memory>
#include <random>
#include <vector>

#include "mrpt_modules/core/feature_frame.h"
#include "mrpt_modules/imu/imu_preintegration.h"
#include "sim/simulator.h"

namespace rpvio::test {

struct ExactWindow {
  std::vector<FeatureFrame> frames;
  std::vector<std::shared_ptr<ImuPreintegration>> imu;  // imu[0] null
  std::vector<double> times;                            // IMU clock
};

/// Frames every 1 / camera_rate from t0 to t1; new points seeded every 5 frames on a jittered
/// pixel grid, each visible for at most `track_life` frames.
inline ExactWindow exactWindow(sim::Simulator& sim, double t0, double t1,
                               const Eigen::Vector3d& gyro_bias, double pixel_noise = 0,
                               size_t track_life = 40, uint64_t seed = 1) {
  const sim::SimConfig& config = sim.config();
  const sim::PinholeCamera& camera = sim.camera();
  const double fx = camera.fx, fy = camera.fy;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> jitter(0, 1);
  std::normal_distribution<double> noise(0, 1);
  struct Point {
    Eigen::Vector3d X;
    int plane;
    size_t born;
  };
  std::vector<Point> points;
  std::vector<ImuSample> imu = sim.imuStream();
  for (auto& s : imu) s.gyro += gyro_bias;
  ExactWindow w;
  const int n = static_cast<int>(std::lround((t1 - t0) * config.camera_rate));
  for (int k = 0; k <= n; ++k) {
    const double t = t0 + k / config.camera_rate;
    w.times.push_back(t);
    if (k % 5 == 0)
      for (int gy = 0; gy < 8; ++gy)
        for (int gx = 0; gx < 10; ++gx) {
          const sim::SceneHit hit = sim.castPixel(t, camera.width * (gx + jitter(rng)) / 10,
                                                  camera.height * (gy + jitter(rng)) / 8);
          if (hit.label > 0 && hit.label < sim::kMaskNothing)
            points.push_back({hit.point, hit.label, static_cast<size_t>(k)});
        }
    FeatureFrame frame;
    frame.t = t - config.time_offset;
    for (size_t i = 0; i < points.size(); ++i) {
      if (k - points[i].born >= track_life) continue;
      const auto pixel = sim.project(t, points[i].X);
      if (!pixel || pixel->x() < 0 || pixel->y() < 0 || pixel->x() > camera.width ||
          pixel->y() > camera.height)
        continue;
      TrackedFeature f;
      f.id = static_cast<int>(i);
      f.plane_id = points[i].plane;
      f.pixel = *pixel + pixel_noise * Eigen::Vector2d(noise(rng), noise(rng));
      f.normalized =
          Eigen::Vector2d((f.pixel.x() - camera.cx) / fx, (f.pixel.y() - camera.cy) / fy);
      frame.features.push_back(f);
    }
    w.frames.push_back(frame);
    if (k == 0) {
      w.imu.push_back(nullptr);
      continue;
    }
    const size_t a = std::lround(w.times[k - 1] * config.imu.rate_hz);
    const size_t b = std::lround(t * config.imu.rate_hz);
    auto pre = std::make_shared<ImuPreintegration>(
        imu[a].accel, imu[a].gyro, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), config.imu);
    for (size_t j = a + 1; j <= b; ++j)
      pre->push(imu[j].t - imu[j - 1].t, imu[j].accel, imu[j].gyro);
    w.imu.push_back(pre);
  }
  return w;
}

}  // namespace rpvio::test

// The initializer's geometry on exact features (floor points projected by the simulator) and the
// simulator's noisy IMU: what remains is the alignment's own error.
#include <gtest/gtest.h>

#include <random>

#include "mrpt_modules/estimator/planar_initializer.h"
#include "rawlog_io/sim/simulator.h"

namespace rpvio {
namespace {

TEST(PlanarInitializer, ExactFeaturesGiveMetricScaleAndGravity) {
  sim::SimConfig config;
  config.duration = 3.0;
  sim::Simulator sim(config);
  const auto imu = sim.imuStream();
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Eigen::Vector3d> floor_points;
  for (int k = 0; k < 300; ++k) {
    const auto hit = sim.castPixel(0.0, 640 * u(rng), 240 + 240 * u(rng));
    if (hit.label == 1) floor_points.push_back(hit.point);
  }
  std::vector<WindowFrame> frames;
  size_t previous = 0;
  for (int k = 0; k <= 40; ++k) {
    const double t = k * 0.05;
    WindowFrame frame;
    frame.features.t = t;
    for (size_t i = 0; i < floor_points.size(); ++i) {
      const Eigen::Vector3d c = sim.cameraPose(t).inverse() * floor_points[i];
      const Eigen::Vector2d x = c.head<2>() / c.z();
      if (c.z() < 0.1 || std::abs(x.x()) > 1 || std::abs(x.y()) > 0.75) continue;
      TrackedFeature f;
      f.id = static_cast<int>(i);
      f.plane_id = 1;
      f.normalized = x;
      frame.features.features.push_back(f);
    }
    const size_t now = static_cast<size_t>(std::llround(t * config.imu.rate_hz));
    if (k > 0) {
      frame.imu_from_previous = std::make_shared<ImuPreintegration>(
          imu[previous].accel, imu[previous].gyro, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
          config.imu);
      for (size_t j = previous + 1; j <= now; ++j)
        frame.imu_from_previous->push(imu[j].t - imu[j - 1].t, imu[j].accel, imu[j].gyro);
    }
    previous = now;
    frames.push_back(frame);
  }
  std::string why;
  const auto plane = initializeFromPlane(frames, sim.calibration(), {}, &why);
  ASSERT_TRUE(plane) << why;
  const Eigen::Vector3d p0(frames.front().pose), p1(frames.back().pose);
  const double scale = (p1 - p0).norm() / (sim.state(2.0).p - sim.state(0.0).p).norm();
  const Eigen::Quaterniond q0(frames.front().pose[6], frames.front().pose[3],
                              frames.front().pose[4], frames.front().pose[5]);
  const double gravity_error =
      std::acos(std::min(1.0, (q0.inverse() * Eigen::Vector3d::UnitZ())
                                  .dot(sim.state(0).R_wb.transpose() * Eigen::Vector3d::UnitZ()))) *
      180 / M_PI;
  std::printf("exact features: scale error %.2f%%, gravity error %.3f deg\n",
              100 * std::abs(scale - 1), gravity_error);
  // Issue 6's targets. The scale keeps ~1.5% of error here: the alignment holds the accelerometer
  // bias near zero (a constant body-frame acceleration, like the circle's centripetal one, looks
  // like a bias over 2 s), and the simulated IMU has a 0.05 m/s² bias.
  EXPECT_LT(std::abs(scale - 1), 0.03);
  EXPECT_LT(gravity_error, 0.5);
  // The floor, in the gravity-aligned world, is horizontal: its normal is ±z.
  EXPECT_GT(std::abs(plane->second.normal[2]), std::cos(1.0 * M_PI / 180));
}

}  // namespace
}  // namespace rpvio

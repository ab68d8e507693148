// The sliding-window estimator fed with exact projections of simulated scene points (no
// rendering, no tracking noise) and the simulator's noisy IMU: what remains is the estimator's
// own error (initialization, marginalization, IMU noise). Fast: rays only.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "mrpt_modules/estimator/sliding_window_estimator.h"
#include "rawlog_io/sim/simulator.h"

namespace rpvio {
namespace {

struct Landmark {
  Eigen::Vector3d point;
  int plane = 0;
  double born = 0;
};

struct RunResult {
  double ate_rmse = 0;  // m, after rigid alignment
  size_t poses = 0, frames = 0, resets = 0;
};

RunResult run(HomographyPlanes homography, double duration) {
  sim::SimConfig config;
  config.duration = duration;
  sim::Simulator sim(config);
  const Calibration calib = sim.calibration();
  const auto imu = sim.imuStream();
  const auto times = sim.frameTimes();
  EstimatorOptions options;
  options.pixel_sigma = 0.5;  // the features are exact: the default 1.5 px under-weights them
  options.homography_planes = homography;
  SlidingWindowEstimator estimator(calib, options);
  // Every second, a 12x10 grid of pixels cast into the scene gives landmarks seen for 3 s.
  std::vector<Landmark> landmarks;
  const double kLifetime = 3.0;
  std::vector<Eigen::Vector3d> estimated, truth;
  size_t previous_imu = 0;
  RunResult result;
  for (size_t k = 0; k < times.size(); ++k) {
    const double t = times[k];
    if (k % 20 == 0)
      for (int i = 0; i < 12; ++i)
        for (int j = 0; j < 10; ++j) {
          const sim::SceneHit hit = sim.castPixel(t, 30 + 50.0 * i + 5 * (k % 3), 30 + 45.0 * j);
          if (hit.label > 0) landmarks.push_back({hit.point, hit.label, t});
        }
    FeatureFrame frame;
    frame.t = t;
    const Eigen::Isometry3d C = sim.cameraPose(t).inverse();
    for (size_t id = 0; id < landmarks.size(); ++id) {
      if (t - landmarks[id].born > kLifetime) continue;
      const Eigen::Vector3d c = C * landmarks[id].point;
      const Eigen::Vector2d u = c.head<2>() / c.z();
      if (c.z() < 0.2 || std::abs(u.x()) > 1 || std::abs(u.y()) > 0.75) continue;
      TrackedFeature f;
      f.id = static_cast<int>(id);
      f.plane_id = landmarks[id].plane;
      f.normalized = u;
      f.pixel = Eigen::Vector2d(320 + 320 * u.x(), 240 + 320 * u.y());
      frame.features.push_back(f);
    }
    const size_t now = static_cast<size_t>(std::llround(t * config.imu.rate_hz));
    std::vector<ImuSample> samples;
    if (k > 0) samples.assign(imu.begin() + previous_imu, imu.begin() + now + 1);
    previous_imu = now;
    const auto state = estimator.addFrame(frame, samples);
    if (!state) continue;
    estimated.emplace_back(state->pose[0], state->pose[1], state->pose[2]);
    truth.push_back(sim.bodyPose(t).translation());
  }
  result.frames = times.size();
  result.poses = estimated.size();
  result.resets = estimator.resets();
  if (estimated.size() < 3) return result;
  Eigen::Matrix3Xd E(3, estimated.size()), G(3, truth.size());
  for (size_t k = 0; k < estimated.size(); ++k) E.col(k) = estimated[k], G.col(k) = truth[k];
  const Eigen::Matrix4d T = Eigen::umeyama(E, G, false);
  const Eigen::Matrix3Xd aligned =
      (T.topLeftCorner<3, 3>() * E).colwise() + T.topRightCorner<3, 1>();
  result.ate_rmse = std::sqrt((aligned - G).colwise().squaredNorm().mean());
  return result;
}

TEST(EstimatorExactFeatures, RpvioSingleTracksTwentySeconds) {
  const RunResult r = run(HomographyPlanes::kLargest, 20.0);
  std::printf("exact features, rpvio-single, 20 s: %zu/%zu poses, ATE %.3f m, resets %zu\n",
              r.poses, r.frames, r.ate_rmse, r.resets);
  EXPECT_EQ(r.resets, 0u);
  EXPECT_GT(r.poses, r.frames * 85 / 100);  // initialized within 3 s, then every frame
  EXPECT_LT(r.ate_rmse, 0.10);
}

TEST(EstimatorExactFeatures, WithoutHomographyFactors) {
  const RunResult r = run(HomographyPlanes::kNone, 20.0);
  std::printf("exact features, no homography, 20 s: %zu/%zu poses, ATE %.3f m, resets %zu\n",
              r.poses, r.frames, r.ate_rmse, r.resets);
  EXPECT_EQ(r.resets, 0u);
  EXPECT_GT(r.poses, r.frames * 85 / 100);
  EXPECT_LT(r.ate_rmse, 0.10);
}

}  // namespace
}  // namespace rpvio

// The initializer facade on exact features (simulator geometry, no tracker) and the noise-free IMU
// with a constant gyro bias: what remains is the method's own error. Also its reasons to wait.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "mrpt_modules/initialization/initializer.h"
#include "tests/initialization/exact_window.h"

namespace rpvio {
namespace {

const Eigen::Vector3d kGyroBias(0.003, -0.002, 0.004);

sim::SimConfig noiseFreeConfig(double duration) {
  sim::SimConfig config;
  config.duration = duration;
  config.imu_noise = false;
  return config;
}

struct Errors {
  double scale = 0, drift = 0, gravity_deg = 0, bias = 0, plane_normal_deg = 0, plane_d = 0;
};

/// Errors of a result against the truth, in the frame of the window's first body.
Errors compare(const InitializationResult& r, sim::Simulator& sim, const test::ExactWindow& w) {
  Errors e;
  const Eigen::Isometry3d true_b0 = sim.bodyPose(w.times.front());
  const Eigen::Isometry3d est_b0 = r.T_w_b.front();
  const Eigen::Vector3d true_last =
      (true_b0.inverse() * sim.bodyPose(w.times.back())).translation();
  e.scale =
      std::abs((est_b0.inverse() * r.T_w_b.back()).translation().norm() / true_last.norm() - 1);
  for (size_t k = 0; k < w.times.size(); ++k) {
    const Eigen::Vector3d p_true = (true_b0.inverse() * sim.bodyPose(w.times[k])).translation();
    const Eigen::Vector3d p_est = (est_b0.inverse() * r.T_w_b[k]).translation();
    e.drift = std::max(e.drift, (p_est - p_true).norm() / true_last.norm());
    const Eigen::Vector3d up_est = r.T_w_b[k].linear().transpose() * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d up_true =
        sim.bodyPose(w.times[k]).linear().transpose() * Eigen::Vector3d::UnitZ();
    e.gravity_deg =
        std::max(e.gravity_deg, std::acos(std::min(1.0, up_est.dot(up_true))) * 180 / M_PI);
  }
  e.bias = (r.bg - kGyroBias).norm() / kGyroBias.norm();
  if (r.reference_plane >= 0) {
    const sim::ScenePlane* plane = sim.scene().plane(r.reference_plane);
    const WorldPlane& est = r.planes.at(r.reference_plane);
    // Both planes in the first body frame, oriented so that the body is on the positive side.
    auto inBody = [](const Eigen::Isometry3d& T_wb, const Eigen::Vector3d& n, double d) {
      const Eigen::Vector3d n_b = T_wb.linear().transpose() * n;
      const double d_b = d - n.dot(T_wb.translation());
      return d_b < 0 ? std::make_pair(Eigen::Vector3d(-n_b), -d_b) : std::make_pair(n_b, d_b);
    };
    const auto [n_true, d_true] = inBody(true_b0, plane->normal, plane->distance());
    const auto [n_est, d_est] = inBody(est_b0, est.n, est.d);
    e.plane_normal_deg = std::acos(std::min(1.0, n_true.dot(n_est))) * 180 / M_PI;
    e.plane_d = std::abs(d_est / d_true - 1);
  }
  return e;
}

void print(const char* what, const InitializationResult& r, const Errors& e) {
  std::printf(
      "%s: %s\n  scale %.3f%%, drift %.3f%%, gravity %.3f deg, gyro bias %.2f%%, plane normal "
      "%.3f deg, plane distance %.3f%%\n",
      what, r.reason.c_str(), 100 * e.scale, 100 * e.drift, e.gravity_deg, 100 * e.bias,
      e.plane_normal_deg, 100 * e.plane_d);
}

class InitializerExact : public ::testing::TestWithParam<InitializerMethod> {};

TEST_P(InitializerExact, RecoversTheTrueStateFromExactFeatures) {
  sim::Simulator sim(noiseFreeConfig(3.0));
  const test::ExactWindow w = test::exactWindow(sim, 0.0, 2.0, kGyroBias);
  InitializerOptions options;
  options.method = GetParam();
  Initializer initializer(sim.calibration(), options);
  const InitializationResult r = initializer.tryInitialize(w.frames, w.imu);
  ASSERT_TRUE(r.ok()) << r.reason;
  const Errors e = compare(r, sim, w);
  print(GetParam() == InitializerMethod::kPlanarHomography ? "planar" : "essential", r, e);
  EXPECT_LT(e.scale, 0.005);
  EXPECT_LT(e.drift, 0.005);
  EXPECT_LT(e.gravity_deg, 0.05);
  EXPECT_LT(e.bias, 0.02);
  ASSERT_EQ(r.T_w_b.size(), w.frames.size());
  // The world frame's convention: origin and yaw at the first body, z up.
  EXPECT_LT(r.T_w_b.front().translation().norm(), 1e-9);
  const Eigen::Vector3d x0 = r.T_w_b.front().linear().col(0);
  EXPECT_NEAR(std::atan2(x0.y(), x0.x()), 0.0, 1e-9);
  // Feature depths agree with the truth.
  double worst_depth = 0;
  for (const auto& [id, depth] : r.depths) {
    const auto& f =
        *std::find_if(w.frames[depth.frame].features.begin(), w.frames[depth.frame].features.end(),
                      [&](const TrackedFeature& x) { return x.id == id; });
    const sim::SceneHit hit = sim.castPixel(w.times[depth.frame], f.pixel.x(), f.pixel.y());
    const double true_depth = (sim.cameraPose(w.times[depth.frame]).inverse() * hit.point).z();
    worst_depth = std::max(worst_depth, std::abs(depth.depth / true_depth - 1));
  }
  std::printf("  %zu feature depths, worst relative error %.3f%%\n", r.depths.size(),
              100 * worst_depth);
  EXPECT_GT(r.depths.size(), 50u);
  EXPECT_LT(worst_depth, 0.01);
  if (GetParam() == InitializerMethod::kPlanarHomography) {
    EXPECT_LT(e.plane_normal_deg, 0.1);
    EXPECT_LT(e.plane_d, 0.005);
    EXPECT_GE(r.planes.size(), 2u) << "other planes from their decompositions";
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, InitializerExact,
                         ::testing::Values(InitializerMethod::kPlanarHomography,
                                           InitializerMethod::kEssentialMatrix));

TEST(InitializerReasons, WaitsWithAReasonLoggedOncePerChange) {
  sim::Simulator sim(noiseFreeConfig(3.0));
  const test::ExactWindow w = test::exactWindow(sim, 0.0, 2.0, kGyroBias);
  Initializer initializer(sim.calibration(), InitializerOptions{});
  std::vector<std::string> logged;
  initializer.logRegisterCallback([&](std::string_view text, mrpt::system::VerbosityLevel,
                                      std::string_view,
                                      mrpt::Clock::time_point) { logged.emplace_back(text); });
  initializer.logging_enable_console_output = false;
  // Growing window: collecting frames until 2 s, then initialized.
  std::vector<FeatureFrame> frames;
  std::vector<std::shared_ptr<ImuPreintegration>> imu;
  InitializationResult r;
  for (size_t k = 0; k < w.frames.size(); ++k) {
    frames.push_back(w.frames[k]);
    imu.push_back(w.imu[k]);
    r = initializer.tryInitialize(frames, imu);
    if (k + 1 < w.frames.size()) {
      EXPECT_EQ(r.status, InitStatus::kCollectingFrames);
    }
  }
  EXPECT_TRUE(r.ok()) << r.reason;
  ASSERT_EQ(logged.size(), 2u);
  EXPECT_NE(logged[0].find("collecting frames"), std::string::npos);
  EXPECT_NE(logged[1].find("initialized"), std::string::npos);

  // Without plane labels the planar initializer has nothing to work on.
  std::vector<FeatureFrame> unlabelled = w.frames;
  for (auto& f : unlabelled)
    for (auto& x : f.features) x.plane_id = 0;
  EXPECT_EQ(initializer.tryInitialize(unlabelled, w.imu).status, InitStatus::kTooFewPlaneFeatures);
  // A camera that does not move: the same frame over and over.
  std::vector<FeatureFrame> still(w.frames.size(), w.frames.front());
  for (size_t k = 0; k < still.size(); ++k) still[k].t = w.frames[k].t;
  EXPECT_EQ(initializer.tryInitialize(still, w.imu).status, InitStatus::kTooLittleParallax);
  EXPECT_EQ(logged.size(), 4u);
}

TEST(InitializerParallax, BelowTheThresholdThePairsAboveTheFallbackAreTried) {
  sim::Simulator sim(noiseFreeConfig(3.0));
  const test::ExactWindow w = test::exactWindow(sim, 0.0, 2.0, kGyroBias);
  InitializerOptions options;
  // Neither threshold reached: the reason names the best pair's parallax.
  options.min_parallax_px = options.fallback_parallax_px = 1e4;
  const InitializationResult none =
      Initializer(sim.calibration(), options).tryInitialize(w.frames, w.imu);
  ASSERT_EQ(none.status, InitStatus::kTooLittleParallax) << none.reason;
  const double best = std::stod(none.reason.substr(none.reason.find('(') + 1));
  ASSERT_GT(best, 30.0) << none.reason;
  // No pair reaches min_parallax_px: those above the fallback initialize, as accurately.
  options.fallback_parallax_px = 0.5 * best;
  const InitializationResult fallback =
      Initializer(sim.calibration(), options).tryInitialize(w.frames, w.imu);
  ASSERT_TRUE(fallback.ok()) << fallback.reason;
  const Errors e = compare(fallback, sim, w);
  EXPECT_LT(e.scale, 0.005);
  EXPECT_LT(e.drift, 0.005);
  // Pairs reach min_parallax_px: a lower fallback changes nothing.
  options.min_parallax_px = options.fallback_parallax_px = 0.5 * best;
  const InitializationResult at_threshold =
      Initializer(sim.calibration(), options).tryInitialize(w.frames, w.imu);
  options.fallback_parallax_px = 0.1 * best;
  const InitializationResult with_fallback =
      Initializer(sim.calibration(), options).tryInitialize(w.frames, w.imu);
  ASSERT_TRUE(at_threshold.ok()) << at_threshold.reason;
  EXPECT_EQ(with_fallback.reason, at_threshold.reason);
  EXPECT_TRUE(with_fallback.T_w_b.back().isApprox(at_threshold.T_w_b.back(), 1e-12));
}

}  // namespace
}  // namespace rpvio

// Camera–IMU time offset from an initialization window's rotations (time_offset.h), on the
// simulator's flight and IMU (noise and biases on): the frames carry camera stamps, their
// orientations are the true ones at the IMU-clock times stamp + td, with visual noise.
#include <gtest/gtest.h>

#include <random>

#include "mrpt_modules/initialization/time_offset.h"
#include "sim/simulator.h"

namespace rpvio {
namespace {

struct Window {
  std::vector<double> t;
  std::vector<Eigen::Matrix3d> R;
  std::vector<ImuSample> imu;
};

/// `frames` frames at 20 Hz (2 s) from `start`, orientations perturbed by `noise_deg` per axis.
Window window(const sim::Simulator& sim, const std::vector<ImuSample>& stream, double start,
              double td, double noise_deg, int frames = 41) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0, noise_deg * M_PI / 180);
  Window w;
  for (int k = 0; k < frames; ++k) {
    const double stamp = start + 0.05 * k;
    w.t.push_back(stamp);
    const Eigen::Vector3d e(noise(rng), noise(rng), noise(rng));
    w.R.push_back(sim.bodyPose(stamp + td).linear() *
                  Eigen::AngleAxisd(e.norm(), e.normalized()).toRotationMatrix());
  }
  // What the estimator holds while initializing: samples up to the last frame's stamp.
  for (const ImuSample& s : stream)
    if (s.t >= start - 0.1 && s.t <= w.t.back()) w.imu.push_back(s);
  return w;
}

/// The simulator and its IMU stream (default sequence; noise on or off).
struct Flight {
  explicit Flight(bool imu_noise)
      : sim([&] {
          sim::SimConfig c;
          c.imu_noise = imu_noise;
          return c;
        }()),
        imu(sim.imuStream()) {}
  sim::Simulator sim;
  std::vector<ImuSample> imu;
};

TEST(TimeOffset, ExactFromANoiseFreeImuAndExactRotations) {
  const Flight flight(false);
  for (double td : {-0.03, 0.0, 0.03}) {
    const Window w = window(flight.sim, flight.imu, 0.4, td, 0);
    const auto e = estimateTimeOffset(w.t, w.R, w.imu, Eigen::Vector3d::Zero(), 0.05);
    ASSERT_TRUE(e) << td;
    EXPECT_NEAR(e->td, td, 2e-4);
    EXPECT_LT(e->gyro_bias.norm(), 1e-5) << e->gyro_bias.transpose();  // no bias without noise
    EXPECT_LT(e->rms_deg, 1e-3);
    // The last frame is left out: its interval moved by +max_offset leaves the samples.
    EXPECT_EQ(e->frames, 40u);
  }
}

TEST(TimeOffset, RecoveredFromTheTakeOffWindowWithNoise) {
  // Gyroscope noise and bias walk as simulated; rotations with 0.005 deg of noise per axis (the
  // estimator's take-off window fits to 0.007 deg rms).
  const Flight flight(true);
  for (double td : {-0.03, 0.0, 0.01, 0.03}) {
    const Window w = window(flight.sim, flight.imu, 0.4, td, 0.005);
    const auto e = estimateTimeOffset(w.t, w.R, w.imu, Eigen::Vector3d::Zero(), 0.05);
    ASSERT_TRUE(e) << td;
    std::printf("td %+.3f s: estimate %+.4f s, sigma %.4f s\n", td, e->td, e->sigma);
    EXPECT_NEAR(e->td, td, 0.0035);
    EXPECT_LT(std::abs(e->td - td), 4 * e->sigma);
    EXPECT_LT(e->sigma, 0.010 / 3);  // the bootstrapper's 10 ms floor is significant
    EXPECT_LT((e->gyro_bias - flight.sim.config().initial_bias.gyro).norm(), 1e-3);
    // The scale: what a residual-sized error along the offset's signature could fake: 30 ms is
    // within twice it on this 2 s window (undecided), beyond it on the 3.5 s one (decided).
    const Window longer = window(flight.sim, flight.imu, 0.4, td, 0.005, 71);
    const auto l =
        estimateTimeOffset(longer.t, longer.R, longer.imu, Eigen::Vector3d::Zero(), 0.05);
    ASSERT_TRUE(l) << td;
    std::printf("  systematic %.4f s; over 3.5 s: estimate %+.4f s, systematic %.4f s\n",
                e->systematic, l->td, l->systematic);
    EXPECT_GT(2 * e->systematic, 0.03);
    EXPECT_LT(2 * l->systematic, 0.03);
    EXPECT_NEAR(l->td, td, 0.0035);
  }
}

/// The standard deviation of td if the residuals were independent: their variance times (JᵀJ)⁻¹,
/// with J by central differences of the rotation residuals (reference: the first frame).
double independentResidualsSigma(const Window& w, const TimeOffsetEstimate& e) {
  const size_t n = e.frames;  // the first n frames are the ones used (the last ones may not be)
  auto residuals = [&](const Eigen::Vector4d& x) {
    Eigen::VectorXd r(3 * (n - 1));
    for (size_t k = 1; k < n; ++k) {
      Eigen::Matrix3d gyro = Eigen::Matrix3d::Identity();
      for (const ImuSample& s : w.imu)  // rectangle rule over the samples' intervals
        if (s.t >= w.t[0] + x(3) && s.t < w.t[k] + x(3))
          gyro = gyro * Eigen::AngleAxisd(((s.gyro - x.head<3>()) * 0.005).norm(),
                                          (s.gyro - x.head<3>()).normalized())
                            .toRotationMatrix();
      const Eigen::AngleAxisd error(gyro.transpose() * w.R[0].transpose() * w.R[k]);
      r.segment<3>(3 * (k - 1)) = error.angle() * error.axis();
    }
    return r;
  };
  Eigen::Vector4d x;
  x << e.gyro_bias, e.td;
  Eigen::MatrixXd J(3 * (n - 1), 4);
  for (int c = 0; c < 4; ++c) {
    const double h = c < 3 ? 1e-5 : 2.5e-3;  // td: half a sample interval (the rule is stepwise)
    Eigen::Vector4d plus = x, minus = x;
    plus(c) += h;
    minus(c) -= h;
    J.col(c) = (residuals(plus) - residuals(minus)) / (2 * h);
  }
  const double variance = std::pow(e.rms_deg * M_PI / 180, 2) * (n - 1) / (3.0 * (n - 1) - 4);
  return std::sqrt(variance * (J.transpose() * J).inverse()(3, 3));
}

TEST(TimeOffset, SmoothlyDriftingRotationErrorsAreNotCalledAnOffset) {
  // No offset; the rotations' errors drift as a random walk (0.002 deg per frame and axis, as
  // structure from motion's errors do), not independent from frame to frame. Counted over 40
  // windows: how often |td| > 3 sigma, the bootstrapper's test (with its 10 ms floor left out).
  const Flight flight(true);
  int called = 0, called_as_independent = 0, beyond_systematic = 0;
  for (int trial = 0; trial < 40; ++trial) {
    std::mt19937 rng(100 + trial);
    std::normal_distribution<double> step(0, 0.002 * M_PI / 180);
    Window w = window(flight.sim, flight.imu, 0.4 + 0.5 * trial, 0, 0);
    Eigen::Vector3d drift = Eigen::Vector3d::Zero();
    for (Eigen::Matrix3d& R : w.R) {
      drift += Eigen::Vector3d(step(rng), step(rng), step(rng));
      R = R * Eigen::AngleAxisd(drift.norm(), drift.normalized()).toRotationMatrix();
    }
    const auto e = estimateTimeOffset(w.t, w.R, w.imu, Eigen::Vector3d::Zero(), 0.05);
    ASSERT_TRUE(e) << trial;
    called += std::abs(e->td) > 3 * e->sigma;
    called_as_independent += std::abs(e->td) > 3 * independentResidualsSigma(w, *e);
    beyond_systematic += std::abs(e->td) > 3 * e->sigma && std::abs(e->td) > 2 * e->systematic;
  }
  std::printf(
      "offset called in %d of 40 windows (%d with independent residuals assumed, %d beyond twice "
      "the systematic scale too)\n",
      called, called_as_independent, beyond_systematic);
  // A 3-sigma test would call 0.3 %; the AR(1) model of a random walk leaves 4 of 40, a fifth of
  // what the residuals taken as independent give.
  EXPECT_LE(called, 4);
  EXPECT_GE(called_as_independent, 16);
  // A drift is the systematic error the scale stands for: no window gets past it.
  EXPECT_EQ(beyond_systematic, 0);
}

TEST(TimeOffsetDegenerate, ConstantAngularRateDoesNotConstrainTheOffset) {
  // Constant rate about a fixed axis: shifting the times changes no rotation.
  const Eigen::Vector3d w(0.1, -0.2, 0.3);
  std::vector<ImuSample> imu;
  for (int k = 0; k <= 600; ++k) imu.push_back({k * 0.005, w, Eigen::Vector3d::Zero()});
  std::vector<double> t;
  std::vector<Eigen::Matrix3d> R;
  for (int k = 2; k <= 58; ++k) {
    t.push_back(k * 0.05);
    R.push_back(Eigen::AngleAxisd(w.norm() * t.back(), w.normalized()).toRotationMatrix());
  }
  std::string why;
  EXPECT_FALSE(estimateTimeOffset(t, R, imu, Eigen::Vector3d::Zero(), 0.05, &why));
  EXPECT_NE(why.find("do not constrain"), std::string::npos) << why;
  EXPECT_FALSE(estimateTimeOffset({0.5, 0.6, 0.7}, {R[0], R[1], R[2]}, imu, Eigen::Vector3d::Zero(),
                                  0.05, &why));
  EXPECT_NE(why.find("3 frames"), std::string::npos) << why;
}

}  // namespace
}  // namespace rpvio

// The bootstrapper does not repeat an initialization attempt that failed in its alignment on
// every frame (init_retry_s): exact features of the paper flight, its IMU with the accelerometer
// 1.5x too sensitive, so every alignment finds a gravity of the wrong magnitude.
#include <gtest/gtest.h>

#include "mrpt_modules/estimator/bootstrapper.h"
#include "tests/estimator/imu_since.h"
#include "tests/initialization/exact_window.h"

namespace rpvio {
namespace {

struct Attempts {
  size_t expensive_failures = 0;
  bool initialized = false;
  std::string status;
};

Attempts feed(double init_retry_s) {
  const sim::SimConfig config;
  sim::Simulator sim(config);
  const test::ExactWindow w = test::exactWindow(sim, 0, 3.5, Eigen::Vector3d::Zero());
  std::vector<ImuSample> imu = sim.imuStream();
  for (ImuSample& s : imu) s.accel *= 1.5;
  EstimatorOptions options;
  options.init_retry_s = init_retry_s;
  options.init_fallback = false;
  options.estimate_time_offset = false;
  const Calibration calibration = sim.calibration();
  const ImuLink link(calibration.imu, 9.81, ImuLinkOptions{});
  Bootstrapper bootstrapper(calibration, options, link);
  Attempts out;
  size_t next = 0;
  for (const FeatureFrame& frame : w.frames) {
    const std::vector<ImuSample> since_previous = test::imuUpTo(imu, next, frame.t);
    out.initialized |= bootstrapper.addFrame(frame, since_previous).has_value();
  }
  out.expensive_failures = bootstrapper.expensiveFailures();
  out.status = bootstrapper.status();
  return out;
}

TEST(BootstrapperRetry, AFailedAlignmentWaitsBeforeTheNextAttempt) {
  const Attempts every_frame = feed(0), throttled = feed(0.25);
  std::printf("failed alignments over 1.5 s: %zu on every frame, %zu with 0.25 s between (%s)\n",
              every_frame.expensive_failures, throttled.expensive_failures,
              throttled.status.c_str());
  EXPECT_FALSE(every_frame.initialized);
  EXPECT_FALSE(throttled.initialized);
  EXPECT_GE(every_frame.expensive_failures, 25u);  // 2.0 s .. 3.5 s at 20 Hz: 31 frames
  EXPECT_LE(throttled.expensive_failures, 7u);     // one per 0.25 s
  EXPECT_GE(throttled.expensive_failures, 5u);
  EXPECT_EQ(throttled.status, every_frame.status);
}

}  // namespace
}  // namespace rpvio

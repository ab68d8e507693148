// The bootstrapper's fallback (init_fallback) takes a full window on which the planar initializer
// finds no plane: exact features of the paper flight with their plane labels removed (as plane
// discovery leaves the frames of a forward-moving car without masks early on) initialize with
// the essential-matrix method, at the first full window; without the fallback they do not.
#include <gtest/gtest.h>

#include "mrpt_modules/estimator/bootstrapper.h"
#include "tests/estimator/imu_since.h"
#include "tests/initialization/exact_window.h"

namespace rpvio {
namespace {

struct Outcome {
  double initialized_after = -1;  // s from the first frame, -1: never
  std::string status;
};

Outcome feed(bool init_fallback) {
  const sim::SimConfig config;
  sim::Simulator sim(config);
  test::ExactWindow w = test::exactWindow(sim, 0, 3.0, Eigen::Vector3d::Zero());
  for (FeatureFrame& frame : w.frames)
    for (TrackedFeature& f : frame.features) f.plane_id = 0;
  const std::vector<ImuSample> imu = sim.imuStream();
  EstimatorOptions options;
  options.initializer = InitializerMethod::kPlanarHomography;
  options.init_fallback = init_fallback;
  options.estimate_time_offset = false;
  const Calibration calibration = sim.calibration();
  const ImuLink link(calibration.imu, 9.81, ImuLinkOptions{});
  Bootstrapper bootstrapper(calibration, options, link);
  Outcome out;
  size_t next = 0;
  for (const FeatureFrame& frame : w.frames) {
    const std::vector<ImuSample> since_previous = test::imuUpTo(imu, next, frame.t);
    if (bootstrapper.addFrame(frame, since_previous) && out.initialized_after < 0)
      out.initialized_after = frame.t - w.frames.front().t;
  }
  out.status = bootstrapper.status();
  return out;
}

TEST(BootstrapperFallback, AWindowWithoutPlanesInitializesWithTheEssentialMatrix) {
  const Outcome with = feed(true), without = feed(false);
  EXPECT_GE(with.initialized_after, 0) << with.status;
  // At the first full window (init_window_s, 2 s) or a few frames later.
  EXPECT_LE(with.initialized_after, 2.2);
  EXPECT_LT(without.initialized_after, 0);
  EXPECT_EQ(without.status, "too few plane features");
}

}  // namespace
}  // namespace rpvio

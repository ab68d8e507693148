// Auto-exposure: the gain loop's dynamics on a synthetic meter, and the simulator's camera adapting
// from the dark to a view with bright windows.
#include <gtest/gtest.h>

#include <cmath>

#include "sim/simulator.h"

namespace rpvio::sim {
namespace {

constexpr double kRate = 20;  // Hz

/// A uniform view whose radiance steps from `before` to `after` at t = 1 s, metered through
/// 8-bit saturation.
AutoExposure::Meter uniformStep(double before, double after) {
  return [=](double t, double gain) { return std::min(255.0, gain * (t < 1.0 ? before : after)); };
}

AutoExposureParams loop() {
  AutoExposureParams p;
  p.enabled = true;
  p.target = 100;
  p.time_constant = 0.2;  // 4 frames
  p.initial_gain = 2.5;   // adapted to the dark view: 2.5 x 40 = target
  p.min_gain = 0.01;
  p.max_gain = 100;
  return p;
}

TEST(AutoExposure, GainFollowsAStepWithTheTimeConstant) {
  AutoExposure ae(loop(), kRate);
  const auto meter = uniformStep(40, 100);  // 2.5 x 100 = 250: no saturation
  EXPECT_DOUBLE_EQ(ae.gain(0.95, meter), 2.5);
  EXPECT_DOUBLE_EQ(ae.gain(1.0, meter), 2.5);  // the step frame keeps the previous frame's gain
  // Log error log(g L / target) decays as e^{−t/τ} from the frame after the step.
  auto error = [&](double t) {
    return std::log(ae.gain(t, meter));
  };  // log(g L / target), L = target
  const double e0 = error(1.0);
  EXPECT_NEAR(error(1.2) / e0, std::exp(-1.0), 1e-9);  // one time constant later
  EXPECT_NEAR(error(1.4) / e0, std::exp(-2.0), 1e-9);
  EXPECT_NEAR(ae.gain(3.0, meter), 1.0, 1e-3);
}

TEST(AutoExposure, BrightStepSaturatesThenConverges) {
  AutoExposure ae(loop(), kRate);
  const auto meter = uniformStep(40, 400);  // 2.5 x 400: the image saturates at the step
  EXPECT_DOUBLE_EQ(meter(1.0, ae.gain(1.0, meter)), 255);
  double previous = ae.gain(1.0, meter);
  for (int k = 21; k <= 60; ++k) {
    const double gain = ae.gain(k / kRate, meter);
    EXPECT_LT(gain, previous) << "frame " << k;  // monotone toward the target
    EXPECT_GT(gain, 0.25 - 1e-9);                // no overshoot past target / radiance
    previous = gain;
  }
  EXPECT_NEAR(meter(3.0, ae.gain(3.0, meter)), 100, 1.0);
}

TEST(AutoExposure, GainIsAFunctionOfTimeOnly) {
  const auto meter = uniformStep(40, 400);
  AutoExposure in_order(loop(), kRate), out_of_order(loop(), kRate);
  for (int k = 0; k <= 40; ++k) in_order.gain(k / kRate, meter);
  for (double t : {2.0, 0.35, 1.05, 2.0})
    EXPECT_EQ(out_of_order.gain(t, meter), in_order.gain(t, meter)) << t;
  AutoExposureParams clamped = loop();
  clamped.min_gain = 0.5;
  EXPECT_DOUBLE_EQ(AutoExposure(clamped, kRate).gain(2.0, meter), 0.5);
}

SimConfig windowsConfig() {
  SimConfig c;
  c.scene.texel_size = 0.05;
  c.scene.light_panels = 5;  // on wall 4, in view at the start
  c.auto_exposure.enabled = true;
  c.auto_exposure.initial_gain = 3;  // coming from the dark
  c.auto_exposure.time_constant = 0.2;
  return c;
}

double mean(const cv::Mat& image) { return cv::mean(image)[0]; }

TEST(AutoExposure, CameraAdaptsFromTheDarkToBrightWindows) {
  const SimConfig config = windowsConfig();
  Simulator sim(config);
  const double target = config.auto_exposure.target;
  const RenderedFrame first = sim.render(0.0, 0);
  EXPECT_DOUBLE_EQ(sim.exposureGain(0.0), 3.0);
  EXPECT_GT(mean(first.image), target + 50);  // overexposed
  // The gain falls toward the target's while the view is still (the flight then moves on).
  double previous = 3.0;
  for (int k = 1; k <= 20; ++k) {
    const double gain = sim.exposureGain(k / config.camera_rate);
    EXPECT_LT(gain, previous) << "frame " << k;
    previous = gain;
  }
  const RenderedFrame adapted = sim.render(30 / config.camera_rate, 30);  // 7.5 τ later
  const double gain = sim.exposureGain(30 / config.camera_rate);
  std::printf("mean grey level: first frame %.1f, frame 30 %.1f (gain %.3f), target %.0f\n",
              mean(first.image), mean(adapted.image), gain, target);
  EXPECT_NEAR(mean(adapted.image), target, 0.1 * target);
  int window = 0, saturated = 0;
  for (int r = 0; r < adapted.mask.rows; ++r)
    for (int c = 0; c < adapted.mask.cols; ++c)
      if (adapted.mask.at<uint8_t>(r, c) >= 180 && adapted.mask.at<uint8_t>(r, c) < 200) {
        ++window;
        saturated += adapted.image.at<uint8_t>(r, c) == 255;
      }
  ASSERT_GT(window, 2000);
  EXPECT_GT(saturated, 0.95 * window);  // the windows clip at 255

  // The gain at a frame does not depend on what was rendered before.
  Simulator fresh(config);
  EXPECT_EQ(fresh.exposureGain(30 / config.camera_rate), gain);
}

TEST(AutoExposure, WindowsInViewLowerTheGain) {
  SimConfig dark = windowsConfig();
  dark.scene.light_panels = 0;
  Simulator with_windows(windowsConfig()), without(dark);
  // At 2 s the windows on wall 4 are in view; at 20 s the camera looks the other way.
  EXPECT_LT(with_windows.exposureGain(2.0), 0.97 * without.exposureGain(2.0));
  EXPECT_NEAR(with_windows.exposureGain(20.0), without.exposureGain(20.0), 1e-9);
}

TEST(AutoExposure, OffMeansGainOneAndTodaysImage) {
  SimConfig config = windowsConfig();
  config.auto_exposure.enabled = false;
  Simulator sim(config);
  EXPECT_EQ(sim.exposureGain(5.0), 1.0);
  const RenderedFrame frame = sim.render(5.0, 7);
  const RenderedFrame reference =
      renderFrame(sim.scene(), config.camera.intrinsics(), sim.cameraPose(5.0), config.render,
                  config.seed * 1000003ULL + 7);
  EXPECT_EQ(cv::norm(frame.image, reference.image, cv::NORM_INF), 0);
}

}  // namespace
}  // namespace rpvio::sim

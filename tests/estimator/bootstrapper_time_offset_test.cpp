// The bootstrapper's undecided time offset (time_offset_window_s): exact features of the paper
// flight whose frame stamps are 30 ms early, and a systematic margin so large that every
// estimate is undecided on the 2 s window. The first initialization waits for a 3.5 s window and
// decides there; a blank frame while it waits restarts the window, and the wait ends (nothing
// applied, the window back to 2 s) once no window has initialized for time_offset_window_s; when
// the longer windows fail but the buffer still reaches back to the undecided window, that window
// initializes at the wait's end with the frames since to be tracked on it.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "mrpt_modules/estimator/bootstrapper.h"
#include "tests/estimator/imu_since.h"
#include "tests/initialization/exact_window.h"

namespace rpvio {
namespace {

struct Start {
  double initialized_at = -1;            // frame time of the first initialized window
  double window_span = 0;                // its keyframes' span
  std::map<double, double> buffer_span;  // frame time: the buffered frames' span after it
  std::string note;
  double time_offset = 0;
  double newest_keyframe_t = -1;
  // The frames to be tracked on the window at once: times, their first and last IMU samples,
  // their features.
  std::vector<std::array<double, 4>> frames_after;
};

bool endsWith(const std::string& s, const std::string& end) {
  return s.size() >= end.size() && s.compare(s.size() - end.size(), end.size(), end) == 0;
}

/// 7 s of the flight's frames (optionally one blank at `blank_t`) into a bootstrapper until it
/// initializes; `screen` for what the initializers see.
Start start(double blank_t = -1, Bootstrapper::FrameScreen screen = {}) {
  const sim::SimConfig config;
  sim::Simulator sim(config);
  test::ExactWindow w = test::exactWindow(sim, 0, 7, Eigen::Vector3d::Zero());
  const std::vector<ImuSample> imu = sim.imuStream();
  EstimatorOptions options;
  options.time_offset_systematic_margin = 1e6;
  const Calibration calibration = sim.calibration();
  const ImuLink link(calibration.imu, 9.81, ImuLinkOptions{});
  Bootstrapper bootstrapper(calibration, options, link);
  if (screen) bootstrapper.setFrameScreen(screen);
  Start out;
  size_t next = 0;
  for (FeatureFrame frame : w.frames) {
    const std::vector<ImuSample> since_previous = test::imuUpTo(imu, next, frame.t);
    if (std::abs(frame.t - blank_t) < 0.025) frame.features.clear();
    frame.t -= 0.03;  // the camera's stamps: t_imu = t_frame + 0.03
    const auto window = bootstrapper.addFrame(frame, since_previous);
    out.buffer_span[frame.t] = bootstrapper.bufferSpan();
    if (window) {
      out.initialized_at = frame.t;
      out.window_span = window->keyframes.back().features.t - window->keyframes.front().features.t;
      out.newest_keyframe_t = window->keyframes.back().features.t;
      for (const auto& [later, samples] : window->frames_after)
        out.frames_after.push_back({later.t, samples.empty() ? NAN : samples.front().t,
                                    samples.empty() ? NAN : samples.back().t,
                                    static_cast<double>(later.features.size())});
      break;
    }
  }
  out.note = bootstrapper.timeOffsetNote();
  out.time_offset = bootstrapper.timeOffset();
  return out;
}

/// The buffered span after the last frame at or before t.
double spanAt(const Start& s, double t) { return std::prev(s.buffer_span.upper_bound(t))->second; }

TEST(BootstrapperTimeOffset, AnUndecidedOffsetWaitsForTheLongerWindowWhichDecides) {
  const Start s = start();
  std::printf("initialized at %.2f s, keyframes over %.2f s: %s\n", s.initialized_at, s.window_span,
              s.note.c_str());
  EXPECT_GE(s.initialized_at, 3.5 - 0.03 - 1e-6);
  EXPECT_LT(s.initialized_at, 4.0);
  EXPECT_GT(s.window_span, 3.0);   // keyframes evenly spaced over the 3.5 s window
  EXPECT_GT(spanAt(s, 3.0), 2.9);  // the window grew past init_window_s
  EXPECT_NE(s.note.find("over 2.0 s"), std::string::npos) << s.note;
  EXPECT_NE(s.note.find("undecided, estimated again on a longer window; then"), std::string::npos)
      << s.note;
  EXPECT_NE(s.note.find("over 3.5 s"), std::string::npos) << s.note;
  // Within the (huge) margin on 3.5 s too: decided, not applied.
  EXPECT_TRUE(endsWith(s.note, "): not applied")) << s.note;
  EXPECT_EQ(s.time_offset, 0);
  EXPECT_TRUE(s.frames_after.empty());  // initialized on its newest frame
}

TEST(BootstrapperTimeOffset, WhenNoLongerWindowInitializesTheUndecidedOneIsTakenLate) {
  // The initializers see no features on the frames of 2.4–2.6 s: every window holding them
  // fails, the 3.5 s ones up to 6.1 s, beyond the wait's end at 2.0 + 3.5 s.
  const Start s = start(-1, [](const FeatureFrame& f) {
    FeatureFrame seen = f;
    if (f.t > 2.4 && f.t < 2.6) seen.features.clear();
    return seen;
  });
  std::printf("initialized at %.2f s on the window ending at %.2f s, %zu frames after it: %s\n",
              s.initialized_at, s.newest_keyframe_t, s.frames_after.size(), s.note.c_str());
  EXPECT_GT(s.initialized_at, s.newest_keyframe_t + 3.5);
  EXPECT_LT(s.initialized_at, s.newest_keyframe_t + 3.5 + 0.06);  // the first frame past the wait
  EXPECT_NEAR(s.newest_keyframe_t, 2.0 - 0.03, 0.06);             // the undecided 2 s window
  EXPECT_NEAR(s.window_span, 2.0, 0.06);
  ASSERT_FALSE(s.frames_after.empty());
  EXPECT_EQ(s.frames_after.back()[0], s.initialized_at);  // this frame last
  // Every frame since the window.
  EXPECT_EQ(s.frames_after.size(),
            static_cast<size_t>(std::lround((s.initialized_at - s.newest_keyframe_t) / 0.05)));
  double previous_t = s.newest_keyframe_t;
  for (const auto& [t, first_sample, last_sample, features] : s.frames_after) {
    EXPECT_GT(features, 20) << t;  // as given: the screen the initializers see is not applied
    EXPECT_NEAR(t - previous_t, 0.05, 1e-6);
    // Its samples as given (the IMU clock is 30 ms ahead; 200 Hz).
    EXPECT_NEAR(first_sample, previous_t + 0.03, 0.006);
    EXPECT_NEAR(last_sample, t + 0.03, 0.006);
    previous_t = t;
  }
  EXPECT_TRUE(endsWith(s.note, ": no initialization on a longer window, not applied")) << s.note;
  EXPECT_EQ(s.time_offset, 0);
}

TEST(BootstrapperTimeOffset, AWaitThatNoWindowEndsGivesUpAndTheWindowShrinksBack) {
  // The blank frame at 2.5 s clears the window the wait grows: no 3.5 s window before 6.0 s, and
  // the wait ends at 2.0 + 3.5 s. (This flight then has too little excitation to initialize
  // again within the 7 s.)
  const Start s = start(2.5);
  std::printf("spans at 5.4 / 5.6 s: %.2f / %.2f s: %s\n", spanAt(s, 5.4), spanAt(s, 5.6),
              s.note.c_str());
  EXPECT_LT(spanAt(s, 2.5), 0.01);  // cleared by the blank frame
  EXPECT_GT(spanAt(s, 5.4), 2.8);   // still growing, from 2.5 s on
  EXPECT_NEAR(spanAt(s, 5.6), 2.0, 0.06);
  EXPECT_TRUE(endsWith(s.note, ": no initialization on a longer window, not applied")) << s.note;
  EXPECT_EQ(s.note.find("over 3.5 s"), std::string::npos) << s.note;
  EXPECT_EQ(s.time_offset, 0);
}

}  // namespace
}  // namespace rpvio

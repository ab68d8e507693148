// The initializer on simulated sequences (rendered images through the front-end, noisy IMU with
// biases): RP-VIO's planar initialization must succeed on the static scene and with 4 and 8
// dancing characters within the first 5 s, with scale error < 3%, gravity direction error < 0.5°
// and gyro bias error < 20% (issue 6). The VINS-style initializer's outcome is reported.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <memory>

#include "mrpt_modules/initialization/initializer.h"
#include "tests/initialization/sim_window.h"

namespace rpvio {
namespace {

struct Outcome {
  bool initialized = false;
  double t = 0, scale_error = 0, gravity_error_deg = 0, bias_error = 0;
  std::string reason;
};

// The estimator's default initialization window: 2 s at 20 Hz.
const size_t kWindowFrames = 41;

/// The first 5 s of a simulated sequence through the front-end, and the simulator behind it.
struct Recording {
  std::unique_ptr<test::SimWindowSource> source;
  std::vector<test::WindowFrame> frames;
};

Recording record(int characters) {
  sim::SimConfig config;
  config.duration = 5.0;
  config.scene.characters = characters;
  Recording r;
  r.source = std::make_unique<test::SimWindowSource>(config);
  while (!r.source->done()) r.frames.push_back(r.source->next());
  return r;
}

/// Slides a 2 s window over the recording, trying to initialize at every frame; features for
/// which `dropped(id)` holds are removed first.
Outcome initializeOn(
    Recording& recording, InitializerMethod method,
    const std::function<bool(int)>& dropped = [](int) { return false; }) {
  sim::Simulator& sim = recording.source->simulator();
  const sim::SimConfig& config = sim.config();
  InitializerOptions options;
  options.method = method;
  options.min_window_s = (kWindowFrames - 1) / config.camera_rate;
  Initializer initializer(sim.calibration(), options);
  initializer.setMinLoggingLevel(mrpt::system::LVL_WARN);
  std::vector<FeatureFrame> frames;
  std::vector<std::shared_ptr<ImuPreintegration>> imu;
  Outcome out;
  for (const test::WindowFrame& frame : recording.frames) {
    frames.push_back(frame.features);
    auto& features = frames.back().features;
    features.erase(std::remove_if(features.begin(), features.end(),
                                  [&](const TrackedFeature& f) { return dropped(f.id); }),
                   features.end());
    imu.push_back(frame.imu_from_previous);
    if (frames.size() > kWindowFrames) frames.erase(frames.begin()), imu.erase(imu.begin());
    const InitializationResult r = initializer.tryInitialize(frames, imu);
    out.reason = r.reason;
    if (!r.ok()) continue;
    const double t0 = frames.front().t, t1 = frames.back().t;
    const double true_distance = (sim.state(t1).p - sim.state(t0).p).norm();
    out.initialized = true;
    out.t = t1;
    out.scale_error = std::abs(
        (r.T_w_b.back().translation() - r.T_w_b.front().translation()).norm() / true_distance - 1);
    const Eigen::Vector3d up_est = r.T_w_b.back().linear().transpose() * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d up_true = sim.state(t1).R_wb.transpose() * Eigen::Vector3d::UnitZ();
    out.gravity_error_deg = std::acos(std::min(1.0, up_est.dot(up_true))) * 180 / M_PI;
    out.bias_error = (r.bg - config.initial_bias.gyro).norm() / config.initial_bias.gyro.norm();
    return out;
  }
  return out;
}

Outcome runOnSimulator(int characters, InitializerMethod method) {
  Recording recording = record(characters);
  return initializeOn(recording, method);
}

void expectPlanarInitialization(int characters) {
  const Outcome o = runOnSimulator(characters, InitializerMethod::kPlanarHomography);
  ASSERT_TRUE(o.initialized) << "C" << characters << " not initialized within 5 s: " << o.reason;
  std::printf(
      "rpvio C%d: initialized at t=%.2f s: scale error %.2f%%, gravity error %.3f deg, gyro bias "
      "error %.1f%%\n",
      characters, o.t, 100 * o.scale_error, o.gravity_error_deg, 100 * o.bias_error);
  EXPECT_LT(o.scale_error, 0.03);
  EXPECT_LT(o.gravity_error_deg, 0.5);
  EXPECT_LT(o.bias_error, 0.2);
}

TEST(InitializerOnSimulator, PlanarStaticScene) { expectPlanarInitialization(0); }
TEST(InitializerOnSimulator, PlanarFourCharacters) { expectPlanarInitialization(4); }
TEST(InitializerOnSimulator, PlanarEightCharacters) { expectPlanarInitialization(8); }

TEST(InitializerOnSimulator, EssentialStaticSceneAndReportOnCharacters) {
  const Outcome o = runOnSimulator(0, InitializerMethod::kEssentialMatrix);
  ASSERT_TRUE(o.initialized) << o.reason;
  std::printf("vins C0: t=%.2f s scale error %.2f%% gravity error %.3f deg bias error %.1f%%\n",
              o.t, 100 * o.scale_error, o.gravity_error_deg, 100 * o.bias_error);
  EXPECT_LT(o.scale_error, 0.05);
  EXPECT_LT(o.gravity_error_deg, 1.0);
  for (int characters : {4, 8}) {
    const Outcome c = runOnSimulator(characters, InitializerMethod::kEssentialMatrix);
    if (c.initialized)
      std::printf("vins C%d: t=%.2f s scale error %.2f%% gravity error %.3f deg\n", characters, c.t,
                  100 * c.scale_error, c.gravity_error_deg);
    else
      std::printf("vins C%d: not initialized within 5 s: %s\n", characters, c.reason.c_str());
  }
}

// The initial pair must not hinge on which borderline tracks the front-end keeps: with any fifth
// of the tracks removed, the VINS-style initializer still initializes on the static scene, its
// scale within three of the standard deviations it accepts (the first 2 s determine the scale to
// 2.5-3.2%, so a fixed 5% bound would be only 1.7 sigma).
TEST(InitializerOnSimulator, EssentialStaticSceneWithAFifthOfTheTracksRemoved) {
  Recording recording = record(0);
  for (int fifth = 0; fifth < 5; ++fifth) {
    const Outcome o = initializeOn(recording, InitializerMethod::kEssentialMatrix,
                                   [fifth](int id) { return id % 5 == fifth; });
    ASSERT_TRUE(o.initialized) << "tracks with id % 5 == " << fifth << " removed: " << o.reason;
    std::printf("vins C0 without id %% 5 == %d: t=%.2f s scale error %.2f%%\n", fifth, o.t,
                100 * o.scale_error);
    EXPECT_LT(o.scale_error, 3 * InitializerOptions{}.max_relative_scale_sigma);
  }
}

}  // namespace
}  // namespace rpvio

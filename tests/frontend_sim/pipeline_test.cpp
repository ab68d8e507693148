// The module pipeline built from a mode's INI file, playing a simulated rawlog.
#include <gtest/gtest.h>

#include "common/input_error.h"
#include "mrpt_modules/core/pipeline.h"
#include "mrpt_modules/estimator/estimator_module.h"
#include "mrpt_modules/estimator/map_sink.h"
#include "mrpt_modules/frontend/feature_tracker_module.h"
#include "rawlog_io/calibration.h"
#include "sim/sequence_writer.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

TEST(Pipeline, RpvioConfigTracksASimulatedRawlog) {
  test::TempDir dir;
  sim::SimConfig config;
  config.duration = 1.0;
  config.scene.characters = 2;
  config.scene.texel_size = 0.05;
  sim::writeSequence(config, dir.path().string());
  for (const char* mode : {"rpvio-single", "vins-mono"}) {
    Pipeline pipeline(std::string(RPVIO_SOURCE_DIR) + "/config/" + mode + ".ini",
                      loadCalibration(dir.file("calib.ini")));
    std::vector<FeatureFrame> frames;
    pipeline.context().bus.subscribe<FeatureFrame>(
        [&](const FeatureFrame& f) { frames.push_back(f); });
    pipeline.play(dir.file("seq.rawlog"));
    ASSERT_EQ(frames.size(), 21u) << mode;
    EXPECT_GT(frames.back().features.size(), 100u) << mode;
    for (size_t k = 1; k < frames.size(); ++k) EXPECT_GT(frames[k].t, frames[k - 1].t);
    const bool masked = std::string(mode) != "vins-mono";
    for (const auto& f : frames.back().features) EXPECT_EQ(f.plane_id > 0, masked);
  }
}

TEST(Pipeline, TheEstimatorRunsWithoutAMapBuilder) {
  // No MapBuilderModule: the keyframes and planes leaving the window go nowhere, no plane is
  // taken from a map, and the estimator tracks all the same.
  test::TempDir dir;
  sim::SimConfig config;
  config.duration = 4.0;
  sim::writeSequence(config, dir.path().string());
  test::writeText(dir.file("mode.ini"),
                  "[Pipeline]\nmodules = FeatureTrackerModule, SlidingWindowEstimatorModule\n");
  Pipeline pipeline(dir.file("mode.ini"), loadCalibration(dir.file("calib.ini")),
                    mrpt::system::LVL_WARN);
  size_t poses = 0, keyframes_left = 0;
  bool summary = false;
  pipeline.context().bus.subscribe<StateEstimate>([&](const StateEstimate&) { ++poses; });
  pipeline.context().bus.subscribe<KeyframeLeft>([&](const KeyframeLeft&) { ++keyframes_left; });
  pipeline.context().bus.subscribe<EstimatorSummary>([&](const EstimatorSummary& s) {
    summary = true;
    EXPECT_EQ(s.status, "tracking");
  });
  pipeline.play(dir.file("seq.rawlog"));
  EXPECT_GT(poses, 30u);           // initialized after 2 s, every frame afterwards
  EXPECT_GT(keyframes_left, 10u);  // marginalized keyframes and the final window
  EXPECT_TRUE(summary);
}

TEST(Pipeline, UnknownModuleIsABadConfig) {
  test::TempDir dir;
  test::writeText(dir.file("bad.ini"), "[Pipeline]\nmodules = FeatureTrackerModule, Nonsense\n");
  try {
    Pipeline(dir.file("bad.ini"), Calibration{});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.ini:line 2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("Nonsense"), std::string::npos) << e.what();
  }
}

/// The InputError text of building a pipeline from `config_text` ("" when it builds).
std::string pipelineError(const test::TempDir& dir, const std::string& config_text) {
  test::writeText(dir.file("mode.ini"), config_text);
  try {
    Pipeline(dir.file("mode.ini"), Calibration{});
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Pipeline, UnknownKeyIsABadConfigNamingItsLine) {
  test::TempDir dir;
  const std::string modules = "[Pipeline]\nmodules = FeatureTrackerModule\n";
  EXPECT_EQ(pipelineError(dir, modules + "[FeatureTrackerModule]\nklt_min_eigenvalue = 5e-3\n"),
            "");
  EXPECT_EQ(
      pipelineError(dir, modules + "[FeatureTrackerModule]\nklt_min_eigenvalu = 5e-3\n"),
      dir.file("mode.ini") + ":line 4: unknown key 'klt_min_eigenvalu' in [FeatureTrackerModule]");
  // A section no listed module reads: its keys are unknown too, and the message says why.
  const std::string unread =
      pipelineError(dir, modules + "[SlidingWindowEstimatorModule]\nwindow_size = 10\n");
  EXPECT_NE(unread.find("mode.ini:line 4: unknown key 'window_size'"), std::string::npos) << unread;
  EXPECT_NE(unread.find("no module of [Pipeline] modules reads that section"), std::string::npos)
      << unread;
  // A key given twice, and a bad value of a known key.
  EXPECT_NE(pipelineError(dir, modules + "[FeatureTrackerModule]\nclahe = true\nclahe = false\n")
                .find("mode.ini:line 5: 'clahe' given twice"),
            std::string::npos);
  EXPECT_NE(pipelineError(dir, modules + "[FeatureTrackerModule]\nmax_features = 1.5\n")
                .find("mode.ini:line 4: max_features must be a whole number"),
            std::string::npos);
}

TEST(Pipeline, EffectiveConfigHasEveryKeyAndReadsBackToItself) {
  test::TempDir dir;
  for (const char* mode : {"vins-mono", "mask-vins", "rpvio-single", "rpvio-multi"}) {
    const Pipeline pipeline(std::string(RPVIO_SOURCE_DIR) + "/config/" + mode + ".ini",
                            Calibration{}, mrpt::system::LVL_WARN);
    const std::string effective = pipeline.effectiveConfig();
    EXPECT_NE(effective.find("\n[FeatureTrackerModule]\nuse_masks = "), std::string::npos);
    EXPECT_NE(effective.find("\nklt_min_eigenvalue = 0.005\n"), std::string::npos) << effective;
    EXPECT_NE(effective.find("\n[PlanesMap]\nmax_normal_angle_deg = 8\n"), std::string::npos);
    // Played back as a config, it is the same configuration.
    test::writeText(dir.file("used.ini"), effective);
    EXPECT_EQ(
        Pipeline(dir.file("used.ini"), Calibration{}, mrpt::system::LVL_WARN).effectiveConfig(),
        effective)
        << mode;
  }
  // What tells the modes apart.
  const auto effective = [&](const char* mode) {
    return Pipeline(std::string(RPVIO_SOURCE_DIR) + "/config/" + mode + ".ini", Calibration{},
                    mrpt::system::LVL_WARN)
        .effectiveConfig();
  };
  EXPECT_NE(effective("vins-mono").find("use_masks = false"), std::string::npos);
  EXPECT_NE(effective("vins-mono").find("initializer = essential"), std::string::npos);
  EXPECT_NE(effective("mask-vins").find("homography_planes = none"), std::string::npos);
  EXPECT_NE(effective("rpvio-single").find("homography_planes = largest"), std::string::npos);
  EXPECT_NE(effective("rpvio-multi").find("homography_planes = all"), std::string::npos);
  EXPECT_NE(effective("rpvio-multi").find("initializer = homography"), std::string::npos);
}

}  // namespace
}  // namespace rpvio

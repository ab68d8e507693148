// The module pipeline built from a mode's INI file, playing a simulated rawlog.
#include <gtest/gtest.h>

#include "mrpt_modules/core/pipeline.h"
#include "mrpt_modules/estimator/estimator_module.h"
#include "mrpt_modules/frontend/feature_tracker_module.h"
#include "rawlog_io/input_error.h"
#include "rawlog_io/sim/sequence_writer.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

TEST(Pipeline, RpvioConfigTracksASimulatedRawlog) {
  registerFrontendModules();
  registerEstimatorModules();
  test::TempDir dir;
  sim::SimConfig config;
  config.duration = 1.0;
  config.scene.characters = 2;
  config.scene.texel_size = 0.05;
  sim::writeSequence(config, dir.path().string());
  for (const char* mode : {"rpvio-single", "vins-mono"}) {
    Pipeline pipeline(std::string(RPVIO_SOURCE_DIR) + "/config/" + mode + ".ini",
                      Calibration::load(dir.file("calib.ini")));
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

TEST(Pipeline, UnknownModuleIsABadConfig) {
  registerFrontendModules();
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

}  // namespace
}  // namespace rpvio

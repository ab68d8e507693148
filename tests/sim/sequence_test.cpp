// Written sequences: complete, readable by the rawlog reader, deterministic per seed.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/input_error.h"
#include "common/json_text.h"
#include "rawlog_io/calibration.h"
#include "rawlog_io/rawlog_summary.h"
#include "rawlog_io/trajectory_io.h"
#include "sim/sequence_writer.h"
#include "sim/sim_config.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;

namespace rpvio::sim {
namespace {

SimConfig shortConfig(uint64_t seed) {
  SimConfig c;
  c.duration = 0.5;
  c.seed = seed;
  c.scene.characters = 2;
  c.scene.texel_size = 0.05;
  return c;
}

/// Every file of the folder (recursively), by relative path → bytes.
std::map<std::string, std::string> folderContents(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = test::readFile(e.path());
  return files;
}

TEST(Sequence, WritesAReadableDataset) {
  test::TempDir dir;
  const SequenceStats stats = writeSequence(shortConfig(3), dir.path().string());
  EXPECT_EQ(stats.frames, 11u);  // 0.5 s at 20 Hz, both ends
  const RawlogSummary summary = summarizeRawlog(dir.file("seq.rawlog"));
  EXPECT_EQ(summary.observations_per_label.at("CAM0"), 11u);
  EXPECT_EQ(summary.observations_per_label.at("PLANE_MASK"), 11u);
  EXPECT_EQ(summary.observations_per_label.at("IMU"), 101u);
  EXPECT_EQ(summary.observations_per_label.at("GROUND_TRUTH"), 101u);
  EXPECT_EQ(readTum(dir.file("groundtruth.tum")).size(), 101u);
  const Calibration calib = loadCalibration(dir.file("calib.ini"));
  EXPECT_EQ(calib.camera.width, 640);
  EXPECT_NEAR(calib.camera.fx, 320.0, 1e-9);
  // One coverage line per frame; sequence.json summarizes them.
  std::istringstream csv(test::readFile(dir.file("dynamic_fraction.csv")));
  std::string line;
  std::getline(csv, line);  // header
  size_t lines = 0;
  for (; std::getline(csv, line); ++lines) {
    const double fraction = std::stod(line.substr(line.find(',') + 1));
    EXPECT_GT(fraction, 0.0);  // two characters in view
    EXPECT_LT(fraction, 0.1);
  }
  EXPECT_EQ(lines, 11u);
  const std::string json = test::readFile(dir.file("sequence.json"));
  EXPECT_NEAR(jsonNumber(json, "dynamic_fraction_median"), stats.coverage.median, 1e-5);
  EXPECT_EQ(jsonNumber(json, "characters"), 2);
  EXPECT_NE(json.find("\"profile\": \"paper\""), std::string::npos) << json;
}

TEST(Sequence, CoverageSummaryPercentiles) {
  std::vector<CoverageSample> samples;
  for (int k = 0; k <= 100; ++k) samples.push_back({0.1 * k, k / 100.0});  // 0 .. 1 over 10 s
  const CoverageSummary s = summarizeCoverage(samples);
  EXPECT_NEAR(s.median, 0.5, 1e-12);
  EXPECT_NEAR(s.p90, 0.9, 1e-12);
  EXPECT_NEAR(s.peak, 1.0, 1e-12);
  EXPECT_NEAR(s.mean, 0.5, 1e-12);
  EXPECT_NEAR(s.first_2s_mean, 0.095, 1e-12);  // t < 2 s: 0 .. 0.19
}

TEST(Sequence, SameSeedSameBytesDifferentSeedDifferentNoise) {
  test::TempDir a, b, c;
  writeSequence(shortConfig(5), a.path().string());
  writeSequence(shortConfig(5), b.path().string());
  writeSequence(shortConfig(6), c.path().string());
  const auto files_a = folderContents(a.path());
  EXPECT_GT(files_a.size(), 20u);
  EXPECT_TRUE(files_a == folderContents(b.path()));
  // Another seed: other noise (and another scene layout).
  EXPECT_NE(test::readFile(a.path() / "groundtruth_biases.csv"),
            test::readFile(c.path() / "groundtruth_biases.csv"));
  EXPECT_NE(test::readFile(a.path() / "seq.rawlog"), test::readFile(c.path() / "seq.rawlog"));
}

TEST(Sequence, ConfigFileDocumentsTheBuiltInDefaults) {
  const SimConfig file =
      SimConfig::load(std::string(RPVIO_SOURCE_DIR) + "/config/sim/warehouse.ini");
  EXPECT_EQ(file.describe(), SimConfig().describe());
  EXPECT_EQ(file.camera.intrinsics().fx, SimConfig().camera.intrinsics().fx);
}

TEST(SimConfig, DescribedConfigurationLoadsBackOverAnyBase) {
  SimConfig hard = SimConfig::profile("hard");
  hard.camera.T_BC_translation = Eigen::Vector3d(0.1, -0.02, 1.0 / 3);
  hard.seed = 12345678901ULL;
  test::TempDir dir;
  test::writeText(dir.file("scene.ini"), hard.describe());
  const SimConfig back = SimConfig::load(dir.file("scene.ini"), SimConfig::profile("paper"));
  EXPECT_EQ(back.describe(), hard.describe());
  EXPECT_EQ(back.crowd.layout, CrowdLayout::Flight);
  EXPECT_EQ(back.camera.T_BC_translation, hard.camera.T_BC_translation);  // exact digits
  EXPECT_EQ(back.seed, hard.seed);
  EXPECT_NE(SimConfig::profile("paper").describe(), hard.describe());
}

TEST(SimConfig, BadValueNamesTheLine) {
  test::TempDir dir;
  for (const char* bad :
       {"[camera]\nwidth = 640.5\n", "[sequence]\nduration = 0\n", "[camera]\nhfov_deg = 180\n",
        "[auto_exposure]\nmin_gain = 2\nmax_gain = 1\n", "[imu]\ngyro_bias = 1 2\n",
        "[scene]\npallet_trucks = 5\n"}) {
    test::writeText(dir.file("scene.ini"), bad);
    try {
      SimConfig::load(dir.file("scene.ini"));
      ADD_FAILURE() << "no error for " << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(":line "), std::string::npos) << e.what();
    }
  }
}

TEST(SimConfig, HardProfileChangesTheCrowdFlightAndMasksAndAFileOverridesIt) {
  const SimConfig paper = SimConfig::profile("paper"), hard = SimConfig::profile("hard");
  EXPECT_EQ(paper.crowd.layout, CrowdLayout::Ring);
  EXPECT_EQ(hard.crowd.layout, CrowdLayout::Flight);
  EXPECT_LT(hard.flight.height, paper.flight.height);
  EXPECT_TRUE(hard.mask.enabled());
  EXPECT_FALSE(paper.mask.enabled());
  EXPECT_EQ(hard.flight.radius, paper.flight.radius);
  EXPECT_EQ(hard.profile_name, "hard");
  test::TempDir dir;
  test::writeText(dir.file("over.ini"), "[flight]\nspeed = 2\n[mask]\nsplit_plane_id = 0\n");
  const SimConfig over = SimConfig::load(dir.file("over.ini"), hard);
  EXPECT_EQ(over.flight.speed, 2);
  EXPECT_EQ(over.mask.split_plane_id, 0);
  EXPECT_EQ(over.crowd.layout, CrowdLayout::Flight);
  EXPECT_EQ(over.mask.boundary_bleed_px, hard.mask.boundary_bleed_px);
  EXPECT_EQ(over.camera.hfov_deg, hard.camera.hfov_deg);
  EXPECT_THROW(SimConfig::profile("easy"), std::invalid_argument);
}

TEST(SimConfig, UnknownCrowdLayoutNamesTheLine) {
  test::TempDir dir;
  test::writeText(dir.file("scene.ini"), "[crowd]\nlayout = square\n");
  try {
    SimConfig::load(dir.file("scene.ini"));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(":line 2:"), std::string::npos) << e.what();
  }
}

TEST(Sequence, UnknownKeyInTheSceneFileIsABadConfig) {
  test::TempDir dir;
  test::writeText(dir.file("scene.ini"), "[flight]\nradius = 12\nspeeed = 3\n");
  try {
    SimConfig::load(dir.file("scene.ini"));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              dir.file("scene.ini") + ":line 3: unknown key 'speeed' in [flight]");
  }
}

TEST(SimApp, BadArgumentsExitTwo) {
  std::string out;
  EXPECT_EQ(test::runCommand(
                test::binDir() + "/rpvio-sim --characters 2 --duration -1 --out /tmp/x", out),
            2)
      << out;
  EXPECT_EQ(test::runCommand(test::binDir() + "/rpvio-sim --characters 2 --config /nonexistent.ini "
                                              "--out /tmp/x",
                             out),
            2)
      << out;
  EXPECT_NE(out.find("/nonexistent.ini"), std::string::npos) << out;
  EXPECT_EQ(test::runCommand(
                test::binDir() + "/rpvio-sim --characters 2 --profile easy --out /tmp/x", out),
            2)
      << out;
  EXPECT_NE(out.find("--profile"), std::string::npos) << out;
}

}  // namespace
}  // namespace rpvio::sim

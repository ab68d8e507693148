// Written sequences: complete, readable by the rawlog reader, deterministic per seed.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/input_error.h"
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
  const SimConfig builtin;
  EXPECT_EQ(file.duration, builtin.duration);
  EXPECT_EQ(file.flight.radius, builtin.flight.radius);
  EXPECT_EQ(file.flight.speed, builtin.flight.speed);
  EXPECT_EQ(file.scene.character_ring_radius, builtin.scene.character_ring_radius);
  EXPECT_EQ(file.scene.ceiling, builtin.scene.ceiling);
  EXPECT_NEAR(file.camera.fx, builtin.camera.fx, 1e-9);
  EXPECT_TRUE(file.T_BC.isApprox(builtin.T_BC));
  EXPECT_EQ(file.imu.gyro_noise_density, builtin.imu.gyro_noise_density);
  EXPECT_TRUE(file.initial_bias.accel.isApprox(builtin.initial_bias.accel));
  EXPECT_EQ(file.render.noise_sigma, builtin.render.noise_sigma);
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
}

}  // namespace
}  // namespace rpvio::sim

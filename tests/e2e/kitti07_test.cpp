// Real street images as a user runs them (issue #69): ../shared/data/kitti07_vio (160 real KITTI
// frames at 10 Hz, a car turning two corners at up to 8 m/s, an IMU made from the real motion)
// imported with rpvio-import euroc, rpvio-slam in vins-mono and rpvio-auto, rpvio-eval with an
// SE(3) alignment. Both keep the track from their first full initialization window on (coverage
// at least 87 %, no reset) and rpvio-auto is within the 0.9 m and no worse than vins-mono.
// The stamps of the outputs (stamps of 1.6e9 s) read back as the input's to the microsecond.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "common/json_text.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

const std::string kData = test::dataDir() + "/kitti07_vio";

struct Evaluated {
  double coverage = 0, ate = 0;
  int resets = -1;
};

Evaluated run(const test::TempDir& dir, const std::string& mode) {
  std::string out;
  const std::string result = dir.file(mode);
  EXPECT_EQ(test::runCommand(test::binDir() + "/rpvio-slam --config " + RPVIO_SOURCE_DIR +
                                 "/config/" + mode + ".ini --calib " + dir.file("calib.ini") +
                                 " --rawlog " + dir.file("k07.rawlog") + " --quiet --out " + result,
                             out),
            0)
      << out;
  EXPECT_EQ(test::runCommand(
                test::binDir() + "/rpvio-eval --gt " + kData + "/groundtruth.tum --est " + result +
                    "/trajectory.tum --align se3 --max-dt 0.05 --json " + result + "/eval.json",
                out),
            0)
      << out;
  const std::string eval = test::readFile(result + "/eval.json");
  const std::string summary = test::readFile(result + "/summary.json");
  Evaluated e;
  e.coverage = jsonNumber(eval, "coverage");
  e.ate = jsonNumber(eval.substr(eval.find("\"ate\"")), "rmse");
  e.resets = static_cast<int>(jsonNumber(summary, "resets"));
  std::printf("%s on kitti07_vio: coverage %.1f %%, ATE %.3f m, %d resets\n", mode.c_str(),
              100 * e.coverage, e.ate, e.resets);
  return e;
}

TEST(Kitti07, RpvioAutoAndVinsMonoKeepTheTrackOnRealStreetImages) {
  test::TempDir dir("kitti07");
  std::string out;
  ASSERT_EQ(
      test::runCommand(test::binDir() + "/rpvio-import euroc --mav0 " + kData + "/mav0 --gt " +
                           kData + "/groundtruth.tum --out " + dir.file("k07.rawlog"),
                       out),
      0)
      << out;
  const Evaluated vins = run(dir, "vins-mono"), automatic = run(dir, "rpvio-auto");
  // Every frame stamp of the EuRoC folder (ns) is a row of stats.csv, and initialized_at is one.
  std::ifstream csv(kData + "/mav0/cam0/data.csv");
  std::set<long long> input_us;
  for (std::string line; std::getline(csv, line);)
    if (!line.empty() && line[0] != '#') input_us.insert(std::llround(std::stoll(line) / 1e3));
  ASSERT_EQ(input_us.size(), 160u);
  std::ifstream stats(dir.file("rpvio-auto/stats.csv"));
  std::string line;
  std::getline(stats, line);  // header
  std::set<long long> output_us;
  while (std::getline(stats, line)) output_us.insert(std::llround(std::stod(line) * 1e6));
  EXPECT_EQ(output_us, input_us);
  const double initialized_at =
      jsonNumber(test::readFile(dir.file("rpvio-auto/summary.json")), "initialized_at");
  EXPECT_TRUE(input_us.count(std::llround(initialized_at * 1e6))) << std::to_string(initialized_at);
  for (const Evaluated& e : {vins, automatic}) {
    EXPECT_GE(e.coverage, 0.87);
    EXPECT_EQ(e.resets, 0);
  }
  EXPECT_LE(automatic.ate, 0.9);
  EXPECT_LE(automatic.ate, vins.ate);
}

}  // namespace
}  // namespace rpvio

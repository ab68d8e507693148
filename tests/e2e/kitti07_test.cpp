// Real street images as a user runs them (issue #69): ../shared/data/kitti07_vio (160 real KITTI
// frames at 10 Hz, a car turning two corners at up to 8 m/s, an IMU made from the real motion)
// imported with rpvio-import euroc, rpvio-slam in vins-mono and rpvio-auto, rpvio-eval with an
// SE(3) alignment. Both keep the track from their first full initialization window on (coverage
// at least 87 %, no reset) and rpvio-auto is within the 0.9 m and no worse than vins-mono.
// The stamps of the outputs (stamps of 1.6e9 s) read back as the input's to the microsecond. The
// same sequence started 4 s later, the car at 4.5 m/s: the road is mapped within 2 s of the start.
// The same images at 40 % of their contrast, with noise: rpvio-auto still starts within 3 s.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <opencv2/imgcodecs.hpp>
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

Evaluated run(const test::TempDir& dir, const std::string& mode, const std::string& config = "",
              const std::string& calib = "calib.ini",
              const std::string& ground_truth = kData + "/groundtruth.tum") {
  std::string out;
  const std::string result = dir.file(mode);
  const std::string config_file =
      config.empty() ? std::string(RPVIO_SOURCE_DIR) + "/config/" + mode + ".ini" : config;
  EXPECT_EQ(test::runCommand(test::binDir() + "/rpvio-slam --config " + config_file + " --calib " +
                                 dir.file(calib) + " --rawlog " + dir.file("k07.rawlog") +
                                 " --quiet --out " + result,
                             out),
            0)
      << out;
  EXPECT_EQ(test::runCommand(test::binDir() + "/rpvio-eval --gt " + ground_truth + " --est " +
                                 result + "/trajectory.tum --align se3 --max-dt 0.05 --json " +
                                 result + "/eval.json",
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

/// k07.rawlog and calib.ini in `dir`, by rpvio-import euroc of `mav0` and `ground_truth`.
void importKitti07(const test::TempDir& dir, const std::string& mav0 = kData + "/mav0",
                   const std::string& ground_truth = kData + "/groundtruth.tum") {
  std::string out;
  ASSERT_EQ(test::runCommand(test::binDir() + "/rpvio-import euroc --mav0 " + mav0 + " --gt " +
                                 ground_truth + " --out " + dir.file("k07.rawlog"),
                             out),
            0)
      << out;
}

/// The lines of `from` whose first number (ns, or s when `seconds`) is at `t0_ns` or later, the
/// comment lines kept.
void copyFrom(const std::string& from, const std::string& to, long long t0_ns, bool seconds) {
  std::ifstream in(from);
  std::ofstream out(to);
  for (std::string line; std::getline(in, line);) {
    const bool keep = line.empty() || line[0] == '#' ||
                      (seconds ? std::llround(std::stod(line) * 1e9) >= t0_ns - 1000
                               : std::stoll(line) >= t0_ns - 5000000);  // the IMU sample before
    if (keep) out << line << '\n';
  }
}

/// kitti07_vio from its frame `first` on, as an EuRoC folder in `dir`: the images linked, or
/// written as `reimage` makes them of the original (with the frame's index); the ground truth's
/// path.
std::string copiedKitti07(const test::TempDir& dir, int first,
                          const std::function<cv::Mat(const cv::Mat&, int)>& reimage = nullptr) {
  namespace fs = std::filesystem;
  const fs::path mav0 = dir.file("mav0");
  fs::create_directories(mav0 / "cam0" / "data");
  fs::create_directories(mav0 / "imu0");
  std::ifstream frames(kData + "/mav0/cam0/data.csv");
  std::ofstream kept((mav0 / "cam0" / "data.csv").string());
  long long t0 = -1;
  int index = 0;
  for (std::string line; std::getline(frames, line);) {
    if (line.empty() || line[0] == '#') {
      kept << line << '\n';
      continue;
    }
    if (index++ < first) continue;
    if (t0 < 0) t0 = std::stoll(line);
    kept << line << '\n';
    const std::string name = line.substr(line.find(',') + 1);
    const std::string original = kData + "/mav0/cam0/data/" + name;
    if (reimage)
      cv::imwrite((mav0 / "cam0" / "data" / name).string(),
                  reimage(cv::imread(original, cv::IMREAD_GRAYSCALE), index));
    else
      fs::create_symlink(original, mav0 / "cam0" / "data" / name);
  }
  for (const char* yaml : {"cam0/sensor.yaml", "imu0/sensor.yaml"})
    fs::copy_file(kData + "/mav0/" + yaml, mav0 / yaml);
  copyFrom(kData + "/mav0/imu0/data.csv", (mav0 / "imu0" / "data.csv").string(), t0, false);
  copyFrom(kData + "/groundtruth.tum", dir.file("groundtruth.tum"), t0, true);
  return dir.file("groundtruth.tum");
}

/// The plane of `planes.yaml` with the ground tracks' label: its tilt from level (deg) and the
/// body's mean height above it over the poses of `trajectory_refined.tum` (the batch refinement
/// that ends the run moves the map with its keyframes) while it was seen.
struct Road {
  bool found = false;
  double tilt_deg = 0, body_height = 0;
};

Road roadOf(const std::string& out, double* first_seen = nullptr) {
  const std::string yaml = test::readFile(out + "/planes.yaml");
  Road road;
  for (size_t at = yaml.find("  - id: "); at != std::string::npos;
       at = yaml.find("  - id: ", at + 1)) {
    const std::string block = yaml.substr(at, yaml.find("  - id: ", at + 1) - at);
    if (block.find("mask_ids: [1048576]") == std::string::npos) continue;
    double n[3], d, first, last;
    std::sscanf(block.substr(block.find("normal: [")).c_str(), "normal: [%lf, %lf, %lf]", &n[0],
                &n[1], &n[2]);
    std::sscanf(block.substr(block.find("\n    d: ")).c_str(), "\n    d: %lf", &d);
    std::sscanf(block.substr(block.find("first_seen: ")).c_str(), "first_seen: %lf", &first);
    std::sscanf(block.substr(block.find("last_seen: ")).c_str(), "last_seen: %lf", &last);
    std::ifstream trajectory(out + "/trajectory_refined.tum");
    double sum = 0;
    int count = 0;
    for (std::string line; std::getline(trajectory, line);) {
      if (line.empty() || line[0] == '#') continue;
      double t, x, y, z;
      std::istringstream(line) >> t >> x >> y >> z;
      if (t < first || t > last) continue;
      sum += std::abs(n[0] * x + n[1] * y + n[2] * z - d);
      ++count;
    }
    road = {count > 0, std::acos(std::min(1.0, std::abs(n[2]))) * 180 / M_PI, sum / count};
    if (first_seen) *first_seen = first;
  }
  return road;
}

TEST(Kitti07, RpvioAutoAndVinsMonoKeepTheTrackOnRealStreetImages) {
  test::TempDir dir("kitti07");
  ASSERT_NO_FATAL_FAILURE(importKitti07(dir));
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
  // rpvio-auto maps the road (its ground tracks): level within issue #69's 2°, the body 1.55 m
  // above it in the ground truth (measured 1.63 m: the 5 cm is not reached).
  const Road road = roadOf(dir.file("rpvio-auto"));
  ASSERT_TRUE(road.found);
  EXPECT_LE(road.tilt_deg, 2.0);
  EXPECT_NEAR(road.body_height, 1.55, 0.08);
}

TEST(Kitti07, TheCameraHeightHoldsTheScaleOverTheRoad) {
  // rpvio-auto with calib.ini's [ground] camera_height = 1.65 (KITTI's camera): the cameras held
  // at their height over the road the ground tracks map, issue #69's 0.45 m, in the window and
  // in the batch refinement.
  test::TempDir dir("kitti07_height");
  ASSERT_NO_FATAL_FAILURE(importKitti07(dir));
  test::writeText(dir.file("calib_height.ini"),
                  test::readFile(dir.file("calib.ini")) + "\n[ground]\ncamera_height = 1.65\n");
  const Evaluated e = run(dir, "rpvio-auto", "", "calib_height.ini");
  EXPECT_GE(e.coverage, 0.87);
  EXPECT_EQ(e.resets, 0);
  EXPECT_LE(e.ate, 0.45);
  const std::string summary = test::readFile(dir.file("rpvio-auto/summary.json"));
  EXPECT_GT(jsonNumber(summary, "camera_height_frames"), 100);  // of 160
  const Road road = roadOf(dir.file("rpvio-auto"));
  ASSERT_TRUE(road.found);
  EXPECT_LE(road.tilt_deg, 2.0);
  // The batch refinement keeps the height too: the body within the 5 cm of the truth's
  // 1.55 m over the mapped road (measured 1.558 m; 1.606 m when only the window held it).
  EXPECT_NEAR(road.body_height, 1.55, 0.05);
}

TEST(Kitti07, TheRoadIsMappedSoonAfterALaterStart) {
  // From frame 40 on (4.2 s in, the car at 4.5 m/s): the ground tracks live 4 images, and the
  // road's plane gets parameters from tracks seen twice. Seen 3 times, as other planes need, it
  // entered the map 6.8 s after the initialization.
  test::TempDir dir("kitti07_later");
  const std::string ground_truth = copiedKitti07(dir, 40);
  ASSERT_NO_FATAL_FAILURE(importKitti07(dir, dir.file("mav0"), ground_truth));
  const Evaluated e = run(dir, "rpvio-auto", "", "calib.ini", ground_truth);
  EXPECT_GE(e.coverage, 0.87);
  EXPECT_EQ(e.resets, 0);
  EXPECT_LE(e.ate, 0.9);  // measured 0.74 m
  double first_seen = 0;
  const Road road = roadOf(dir.file("rpvio-auto"), &first_seen);
  ASSERT_TRUE(road.found);
  EXPECT_LE(road.tilt_deg, 2.0);
  const double initialized_at =
      jsonNumber(test::readFile(dir.file("rpvio-auto/summary.json")), "initialized_at");
  EXPECT_LE(first_seen - initialized_at, 2.0);  // measured 0.9 s
}

TEST(Kitti07, RpvioAutoStartsOnDimNoisyImages) {
  // Every image at 40 % of its contrast (I' = 0.4 I + 50) with Gaussian noise of 3 grey levels:
  // short tracks, so the initialization window's frames see few of the points its first pair
  // triangulated. Those with too few for a PnP are placed by their position alone, with the
  // gyroscope's rotation; before, the structure was lost at such a frame until 8.1 s (coverage
  // 76 %).
  test::TempDir dir("kitti07_dim");
  const std::string ground_truth = copiedKitti07(dir, 0, [](const cv::Mat& image, int index) {
    cv::Mat dim, noise(image.size(), CV_32F);
    image.convertTo(dim, CV_32F, 0.4, 50);
    cv::RNG(index).fill(noise, cv::RNG::NORMAL, 0, 3);
    dim += noise;
    dim.convertTo(dim, CV_8U);
    return dim;
  });
  ASSERT_NO_FATAL_FAILURE(importKitti07(dir, dir.file("mav0"), ground_truth));
  const Evaluated e = run(dir, "rpvio-auto", "", "calib.ini", ground_truth);
  const double initialized_at =
      jsonNumber(test::readFile(dir.file("rpvio-auto/summary.json")), "initialized_at");
  EXPECT_LE(initialized_at - 1600000000.0, 3.0);  // the first frame's stamp; measured 2.80 s
  EXPECT_GE(e.coverage, 0.87);                    // measured 100 %
  EXPECT_EQ(e.resets, 0);
  EXPECT_LE(e.ate, 0.9);  // measured 0.56 m
}

}  // namespace
}  // namespace rpvio

// rpvio-slam --save-map then --map: a second run of the warehouse flight (20 s of it, from 9 s on)
// (so its odometry's world is another one) relocalizes in the first run's map and publishes its
// poses and planes in the map's frame; a damaged map, a map of another camera and a config without
// the loop closure are refused with one line, exit 2, before anything is written.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <regex>

#include "mrpt_modules/loop/keyframe_map_file.h"
#include "planes_map/plane_map_exporters.h"
#include "rawlog_io/calibration.h"
#include "rawlog_io/trajectory_io.h"
#include "sim/sequence_writer.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

std::string slamCommand(const std::string& mode, const std::string& calib,
                        const std::string& sequence_dir, const std::string& out) {
  return test::binDir() + "/rpvio-slam --config " + RPVIO_SOURCE_DIR + "/config/" + mode +
         ".ini --calib " + calib + " --rawlog " + sequence_dir + "/seq.rawlog --quiet --out " + out;
}

/// Distances between the map's keyframes and the trajectory's poses at the same times from `t0`.
std::vector<double> offMap(const KeyframeMap& map, const Trajectory& trajectory, double t0) {
  std::vector<double> off;
  for (const StoredKeyframe& k : map.keyframes) {
    if (k.t < t0) continue;
    const auto at = std::find_if(trajectory.begin(), trajectory.end(),
                                 [&](const StampedPose& p) { return std::abs(p.t - k.t) < 1e-6; });
    if (at != trajectory.end()) off.push_back((at->p - k.body.translation()).norm());
  }
  std::sort(off.begin(), off.end());
  return off;
}

/// The warehouse flight without people, `duration` s of it.
sim::SimConfig staticFlight(double duration) {
  sim::SimConfig config;
  config.duration = duration;
  config.scene.characters = 0;
  return config;
}

TEST(MapReuse, ASecondRunStartedElsewhereRelocalizesInTheFirstRunsMap) {
  test::TempDir dir;
  sim::SimConfig config = staticFlight(50);
  sim::writeSequence(config, dir.file("first"));
  config.duration = 30;
  config.faults.dropped_bursts.push_back({0, 9});  // the camera starts at 9 s
  sim::writeSequence(config, dir.file("second"));
  const std::string calib = dir.file("first/calib.ini");
  std::string out;
  ASSERT_EQ(test::runCommand(slamCommand("rpvio-auto", calib, dir.file("first"), dir.file("a")) +
                                 " --save-map " + dir.file("map"),
                             out),
            0)
      << out;
  const KeyframeMap map = readKeyframeMap(keyframeMapPath(dir.file("map")));
  ASSERT_GT(map.keyframes.size(), 100u);
  ASSERT_EQ(test::runCommand(slamCommand("rpvio-auto", calib, dir.file("second"), dir.file("b")) +
                                 " --map " + dir.file("map") + " --save-map " + dir.file("map2"),
                             out),
            0)
      << out;

  const std::string summary = test::readFile(dir.file("b/summary.json"));
  const double initialized = test::jsonNumber(summary, "initialized_at");
  const double relocalized = test::jsonNumber(summary, "relocalized_t");
  ASSERT_TRUE(std::isfinite(relocalized)) << summary;
  EXPECT_LT(relocalized - initialized, 2.0) << summary;
  EXPECT_EQ(test::jsonNumber(summary, "map_keyframes"), static_cast<double>(map.keyframes.size()));
  EXPECT_NE(summary.find("\"map\": true"), std::string::npos);
  // The odometry is in its own world; from the relocalization on, the corrected poses are where
  // the map has the same places.
  const auto odometry = offMap(map, readTum(dir.file("b/trajectory.tum")), relocalized);
  const auto corrected = offMap(map, readTum(dir.file("b/trajectory_loop.tum")), relocalized);
  ASSERT_GT(corrected.size(), 50u);
  EXPECT_GT(odometry[odometry.size() / 2], 5.0);
  const double median = corrected[corrected.size() / 2];
  std::printf(
      "relocalized %.2f s after initializing; off the map's keyframes: median %.3f m, "
      "p90 %.3f m, max %.3f m (odometry median %.1f m)\n",
      relocalized - initialized, median, corrected[corrected.size() * 9 / 10], corrected.back(),
      odometry[odometry.size() / 2]);
  EXPECT_LT(median, 0.03);
  EXPECT_LT(corrected.back(), 0.15);
  // The plane map follows: the second run's planes, in its own world in planes.yaml, are moved
  // into the map's frame and merged with the map's planes (the same surfaces: none added).
  const auto map_planes = readPlanesYaml(mapPlanesPath(dir.file("map")));
  const auto own_planes = readPlanesYaml(dir.file("b/planes.yaml"));
  const auto merged_planes = readPlanesYaml(dir.file("b/planes_loop.yaml"));
  ASSERT_GE(map_planes.size(), 2u);
  ASSERT_FALSE(own_planes.empty());
  EXPECT_EQ(merged_planes.size(), map_planes.size());
  const auto nearest_offset = [&](const Plane& p) {
    double best = 1e9;
    for (const Plane& m : map_planes)
      if (std::abs(m.normal.dot(p.normal)) > std::cos(2 * M_PI / 180))
        best = std::min(best,
                        std::abs(m.distance - (m.normal.dot(p.normal) > 0 ? 1 : -1) * p.distance));
    return best;
  };
  double own_offset = 0;
  for (const Plane& p : own_planes) own_offset = std::max(own_offset, nearest_offset(p));
  for (const Plane& p : merged_planes) EXPECT_LT(nearest_offset(p), 0.05) << p.id;
  EXPECT_GT(own_offset, 0.5);
  EXPECT_EQ(test::readFile(dir.file("b/planes_loop.yaml")),
            test::readFile(mapPlanesPath(dir.file("map2"))));
  // The second run's map holds the first's keyframes, unmoved, and its own.
  const KeyframeMap merged = readKeyframeMap(keyframeMapPath(dir.file("map2")));
  ASSERT_GT(merged.keyframes.size(), map.keyframes.size() + 50);
  for (size_t k = 0; k < map.keyframes.size(); ++k)
    ASSERT_TRUE(merged.keyframes[k].body.isApprox(map.keyframes[k].body, 0)) << k;
}

TEST(MapReuse, ADamagedMapAnotherCameraAndNoLoopClosureAreRefusedBeforeAnythingIsWritten) {
  test::TempDir dir;
  sim::writeSequence(staticFlight(3), dir.file("seq"));
  const std::string calib = dir.file("seq/calib.ini");
  std::string out;
  // A map to damage: a valid one, written by hand.
  KeyframeMap map;
  map.camera = loadCalibration(calib).camera;
  map.T_BC = loadCalibration(calib).T_BC;
  std::filesystem::create_directories(dir.file("map"));
  writeKeyframeMap(keyframeMapPath(dir.file("map")), map);
  const auto refused = [&](const std::string& command, const std::string& why) {
    EXPECT_EQ(test::runCommand(command, out), 2) << out;
    EXPECT_NE(out.find(why), std::string::npos) << out;
    EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;
    EXPECT_FALSE(std::filesystem::exists(dir.file("out"))) << command;
  };
  std::string bytes = test::readFile(keyframeMapPath(dir.file("map")));
  bytes[20] ^= 1;
  std::filesystem::create_directories(dir.file("damaged"));
  test::writeText(keyframeMapPath(dir.file("damaged")), bytes);
  refused(slamCommand("vins-mono", calib, dir.file("seq"), dir.file("out")) + " --map " +
              dir.file("damaged"),
          "keyframes.rpvmap:byte ");
  std::string other_calib = test::readFile(calib);
  other_calib = std::regex_replace(other_calib, std::regex("\ncx = [0-9.]+"), "\ncx = 300");
  test::writeText(dir.file("other.ini"), other_calib);
  refused(slamCommand("vins-mono", dir.file("other.ini"), dir.file("seq"), dir.file("out")) +
              " --map " + dir.file("map"),
          "saved with another calibration");
  refused(slamCommand("mask-vins", calib, dir.file("seq"), dir.file("out")) + " --map " +
              dir.file("map"),
          "need LoopClosureModule");
  refused(slamCommand("vins-mono", calib, dir.file("seq"), dir.file("out")) + " --map " +
              dir.file("nowhere"),
          "cannot open the map");
}

}  // namespace
}  // namespace rpvio

// rpvio-slam with the loop closure on a simulated flight that comes back to its start (the
// warehouse circle: one lap takes ~38 s), with a camera-IMU offset to find: revisits found and all
// true, the corrected trajectory nearer the truth where it revisits, the same output on every run,
// the odometry left as it was.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <regex>

#include "evaluation/trajectory_metrics.h"
#include "rawlog_io/trajectory_io.h"
#include "sim/sequence_writer.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

std::string slamCommand(const std::string& config, const std::string& sequence_dir) {
  return test::binDir() + "/rpvio-slam --config " + config + " --calib " + sequence_dir +
         "/calib.ini --rawlog " + sequence_dir + "/seq.rawlog --quiet --out ";
}

/// The pose of `trajectory` nearest to `t`.
const StampedPose& nearest(const Trajectory& trajectory, double t) {
  return *std::min_element(trajectory.begin(), trajectory.end(), [t](const auto& a, const auto& b) {
    return std::abs(a.t - t) < std::abs(b.t - t);
  });
}

/// Where the body at `t` is in the body frame at `t_old`: frame-free, so trajectories in other
/// worlds compare.
Eigen::Vector3d seenFrom(const Trajectory& trajectory, double t_old, double t) {
  const StampedPose& a = nearest(trajectory, t_old);
  return a.q.conjugate() * (nearest(trajectory, t).p - a.p);
}

TEST(LoopClosure, RevisitsOfTheFirstLapAreFoundTrueAndCorrectTheTrajectory) {
  test::TempDir dir;
  sim::SimConfig config;
  config.duration = 50;
  config.scene.characters = 0;
  // A camera-IMU offset the calibration does not know: the estimator finds it and moves its
  // frames' times, the keyframes' images must still be found.
  config.time_offset = 0.03;
  sim::writeSequence(config, dir.file("seq"));
  const std::string mode = std::string(RPVIO_SOURCE_DIR) + "/config/vins-mono.ini";
  std::string out;
  ASSERT_EQ(test::runCommand(slamCommand(mode, dir.file("seq")) + dir.file("a"), out), 0) << out;
  ASSERT_EQ(test::runCommand(slamCommand(mode, dir.file("seq")) + dir.file("b"), out), 0) << out;
  EXPECT_EQ(test::readFile(dir.file("a/trajectory_loop.tum")),
            test::readFile(dir.file("b/trajectory_loop.tum")));

  const std::string summary = test::readFile(dir.file("a/summary.json"));
  ASSERT_GT(std::abs(test::jsonNumber(summary, "time_offset_s")), 0.02) << summary;
  EXPECT_GT(test::jsonNumber(summary, "loop_keyframes"), 100) << summary;
  const Trajectory truth = readTum(dir.file("seq/groundtruth.tum"));
  EXPECT_GE(test::jsonNumber(summary, "loops_accepted"), 10) << summary;
  // Every accepted revisit is a true one: the two keyframes' bodies within 3 m. Where the
  // revisiting body is seen from the first visit's, the corrected trajectory is nearer the truth
  // than the odometry (the drift of a lap, which the revisit measures).
  const Trajectory odometry = readTum(dir.file("a/trajectory.tum"));
  const Trajectory corrected = readTum(dir.file("a/trajectory_loop.tum"));
  const std::regex accepted(
      R"(\{"t": ([0-9.]+), "t_old": ([0-9.]+), "score": [0-9.e-]+, "accepted": true)");
  size_t checked = 0;
  double odometry_error = 0, corrected_error = 0;
  for (auto it = std::sregex_iterator(summary.begin(), summary.end(), accepted);
       it != std::sregex_iterator(); ++it, ++checked) {
    const double t = std::stod((*it)[1]), t_old = std::stod((*it)[2]);
    const Eigen::Vector3d truly = seenFrom(truth, t_old, t);
    EXPECT_LT(truly.norm(), 3.0) << t << " -> " << t_old;
    odometry_error += (seenFrom(odometry, t_old, t) - truly).norm();
    corrected_error += (seenFrom(corrected, t_old, t) - truly).norm();
  }
  EXPECT_EQ(static_cast<double>(checked), test::jsonNumber(summary, "loops_accepted"));
  std::printf(
      "%zu revisits: the revisiting body seen from the first visit's %.4f m (odometry), "
      "%.4f m (corrected) from the truth on average\n",
      checked, odometry_error / checked, corrected_error / checked);
  EXPECT_LT(corrected_error, odometry_error);

  eval::EvalOptions options;
  options.align = eval::AlignMode::SE3;
  const auto odometry_ate = eval::evaluate(truth, odometry, options);
  const auto corrected_ate = eval::evaluate(truth, corrected, options);
  std::printf("ATE odometry %.4f m, with loop closure %.4f m\n", odometry_ate.ate.rmse,
              corrected_ate.ate.rmse);
  EXPECT_EQ(odometry_ate.times.size(), corrected_ate.times.size());

  // Without the module the odometry is the same, byte for byte.
  std::string without = test::readFile(mode);
  without = std::regex_replace(without, std::regex("LoopClosureModule, "), "");
  test::writeText(dir.file("without.ini"), without);
  ASSERT_EQ(
      test::runCommand(slamCommand(dir.file("without.ini"), dir.file("seq")) + dir.file("c"), out),
      0)
      << out;
  EXPECT_EQ(test::readFile(dir.file("a/trajectory.tum")),
            test::readFile(dir.file("c/trajectory.tum")));
  EXPECT_FALSE(std::filesystem::exists(dir.file("c/trajectory_loop.tum")));
}

}  // namespace
}  // namespace rpvio

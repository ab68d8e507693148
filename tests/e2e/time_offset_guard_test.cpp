// The camera-IMU time-offset guard on the paper flight, whose 2 s take-off window has so little
// change of angular rate that structure from motion's rotation errors pass for 10-15 ms of offset
// (docs/notes/2026-11-28-time-offset-guard.md). An estimate beyond 3 sigma but within twice its
// systematic scale is undecided: the first initialization waits for a 3.5 s window, whose
// estimate decides. The two sequences are those whose 2 s estimates were the worst: seed-2 C8
// without offset read +12.2 ms (mask-vins, applied before the scale's test), seed-4 static with 30
// ms read +14.6 ms (vins-mono); their first 5 s, rendered here, read the same. When no longer
// window initializes (the hard suite's seed-1 MP: vins-mono's 3.5 s window fails among the moving
// objects), the undecided 2 s window is taken at the wait's end, uncorrected.
#include <gtest/gtest.h>

#include "evaluation/trajectory_metrics.h"
#include "rawlog_io/trajectory_io.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

/// summary.json of `mode` on a sequence of `args` (5 s unless they say).
std::string run(const test::TempDir& dir, const std::string& args, const std::string& mode) {
  std::string output;
  EXPECT_EQ(
      test::runCommand(
          test::binDir() + "/rpvio-sim --duration 5 " + args + " --out " + dir.file("seq"), output),
      0)
      << output;
  EXPECT_EQ(test::runCommand(test::binDir() + "/rpvio-slam --config config/" + mode +
                                 ".ini --calib " + dir.file("seq/calib.ini") + " --rawlog " +
                                 dir.file("seq/seq.rawlog") + " --quiet --out " + dir.file("out"),
                             output),
            0)
      << output;
  return test::readFile(dir.file("out/summary.json"));
}

TEST(TimeOffsetGuard, NoOffsetReadFromTheTakeOffIsDecidedOnTheLongerWindowAndNotApplied) {
  const test::TempDir dir("time-offset-guard-0");
  const std::string summary = run(dir, "--sequence C8 --seed 2", "mask-vins");
  EXPECT_EQ(test::jsonNumber(summary, "time_offset_s"), 0) << summary;
  EXPECT_NE(summary.find("undecided, estimated again on a longer window"), std::string::npos)
      << summary;
  EXPECT_NE(summary.find("over 3.5 s"), std::string::npos) << summary;
  EXPECT_GE(test::jsonNumber(summary, "initialized_at"), 3.5) << summary;
}

TEST(TimeOffsetGuard, ATrueOffsetUnderestimatedOnTheTakeOffIsCorrectedOnTheLongerWindow) {
  const test::TempDir dir("time-offset-guard-30");
  const std::string summary =
      run(dir, "--sequence static --seed 4 --time-offset 0.03", "vins-mono");
  EXPECT_NEAR(test::jsonNumber(summary, "time_offset_s"), 0.03, 0.003) << summary;
  EXPECT_NE(summary.find("undecided, estimated again on a longer window"), std::string::npos)
      << summary;
  EXPECT_NE(summary.find("over 3.5 s"), std::string::npos) << summary;
  EXPECT_NE(summary.find("frame times corrected"), std::string::npos) << summary;
  EXPECT_GE(test::jsonNumber(summary, "initialized_at"), 3.4) << summary;
  EXPECT_LT(test::jsonNumber(summary, "initialized_at"), 4.0) << summary;
}

TEST(TimeOffsetGuard, WhenNoLongerWindowInitializesTheUndecidedOneIsTakenAtTheWaitsEnd) {
  const test::TempDir dir("time-offset-guard-late");
  const std::string summary =
      run(dir, "--profile hard --sequence MP --seed 1 --duration 8", "vins-mono");
  EXPECT_EQ(test::jsonNumber(summary, "time_offset_s"), 0) << summary;
  EXPECT_NE(summary.find("undecided, estimated again on a longer window: no initialization on a "
                         "longer window, not applied"),
            std::string::npos)
      << summary;
  // Initialized at the wait's end (2.0 + 3.5 s) on the undecided window (0 ... 2.0 s), with
  // every frame's pose from its first on.
  EXPECT_GE(test::jsonNumber(summary, "initialized_at"), 5.5) << summary;
  const auto trajectory = readTum(dir.file("out/trajectory.tum"));
  ASSERT_FALSE(trajectory.empty());
  EXPECT_NEAR(trajectory.front().t, 0.0, 0.026);
  EXPECT_EQ(trajectory.size(), 161u);  // 0 ... 8.0 s at 20 Hz
  // 0.016 m measured; before, no initialization within the 8 s.
  EXPECT_LT(eval::evaluate(readTum(dir.file("seq/groundtruth.tum")), trajectory, {}).ate.rmse,
            0.05);
}

}  // namespace
}  // namespace rpvio

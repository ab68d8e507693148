// A camera-IMU offset found at the first initialization whose corrected window fails for its own
// reasons: the hand-held profile's first window at 2.0 s loses its structure whatever the times,
// the next one (2.27 s) initializes. The offset is estimated again on that window and applied,
// instead of being dropped for the whole run (it was: ATE 0.10 m against 0.01 m over 8 s).
#include <gtest/gtest.h>

#include "tests/test_util.h"

namespace rpvio {
namespace {

TEST(TimeOffsetRetry, ACorrectedWindowThatFailsIsTriedAgainOnTheNextOne) {
  const test::TempDir dir("time-offset-retry");
  std::string output;
  ASSERT_EQ(test::runCommand(test::binDir() +
                                 "/rpvio-sim --profile handheld --sequence static --duration 3 "
                                 "--time-offset 0.03 --out " +
                                 dir.file("seq"),
                             output),
            0)
      << output;
  ASSERT_EQ(test::runCommand(test::binDir() + "/rpvio-slam --config config/rpvio-single.ini " +
                                 "--calib " + dir.file("seq/calib.ini") + " --rawlog " +
                                 dir.file("seq/seq.rawlog") + " --quiet --out " + dir.file("out"),
                             output),
            0)
      << output;
  const std::string summary = test::readFile(dir.file("out/summary.json"));
  EXPECT_NEAR(test::jsonNumber(summary, "time_offset_s"), 0.03, 0.005) << summary;
  EXPECT_LT(test::jsonNumber(summary, "initialized_at"), 2.6) << summary;
  EXPECT_NE(summary.find("frame times corrected"), std::string::npos) << summary;
}

}  // namespace
}  // namespace rpvio

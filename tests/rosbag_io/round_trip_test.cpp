// A simulated sequence exported to a ROS1 bag (rpvio-export rosbag) and imported back
// (rpvio-import rosbag --preset rpvio-sim) gives a rawlog on which rpvio-slam runs
// byte-identically.
#include <gtest/gtest.h>

#include "tests/test_util.h"

namespace rpvio {
namespace {

/// rpvio-slam's outputs of rpvio-multi on `folder`/seq.rawlog, in `folder`/out.
void runSlam(const std::string& folder) {
  std::string output;
  ASSERT_EQ(
      test::runCommand(test::binDir() + "/rpvio-slam --config config/rpvio-multi.ini --calib " +
                           folder + "/calib.ini --rawlog " + folder + "/seq.rawlog --quiet --out " +
                           folder + "/out",
                       output),
      0)
      << output;
}

void expectSameRun(const std::string& direct, const std::string& back) {
  for (const char* file : {"trajectory.tum", "trajectory_refined.tum", "planes.yaml"}) {
    const std::string expected = test::readFile(direct + "/out/" + file);
    EXPECT_GT(expected.size(), 100u) << file;
    EXPECT_EQ(test::readFile(back + "/out/" + file), expected) << file;
  }
}

/// Runs `import_command` --out `back`/seq.rawlog, then rpvio-slam on it: every entry, the same
/// calib.ini and the same run as on `direct`.
void importAndCompare(const std::string& import_command, const std::string& direct,
                      const std::string& back) {
  std::string output;
  ASSERT_EQ(
      test::runCommand(
          "mkdir -p " + back + " && " + import_command + " --out " + back + "/seq.rawlog", output),
      0)
      << output;
  EXPECT_NE(output.find("101 CAM0, 101 PLANE_MASK, 1001 IMU, 1001 GROUND_TRUTH"), std::string::npos)
      << output;
  EXPECT_EQ(test::readFile(back + "/calib.ini"), test::readFile(direct + "/calib.ini"));
  runSlam(back);
  expectSameRun(direct, back);
}

class RoundTrip : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir("round_trip");
    std::string output;
    ASSERT_EQ(test::runCommand(test::binDir() + "/rpvio-sim --characters 2 --duration 5 --out " +
                                   dir_->file("seq"),
                               output),
              0)
        << output;
    runSlam(dir_->file("seq"));
  }
  static void TearDownTestSuite() { delete dir_; }
  static test::TempDir* dir_;
};
test::TempDir* RoundTrip::dir_ = nullptr;

TEST_F(RoundTrip, ThroughARosBag) {
  const std::string bin = test::binDir(), seq = dir_->file("seq"), bag_dir = dir_->file("bag"),
                    back = dir_->file("from_bag");
  std::string output;
  ASSERT_EQ(test::runCommand("mkdir -p " + bag_dir + " " + back + " && " + bin +
                                 "/rpvio-export rosbag --rawlog " + seq + "/seq.rawlog --out " +
                                 bag_dir + "/seq.bag",
                             output),
            0)
      << output;
  EXPECT_NE(output.find("101 /image, 101 /mask, 1001 /imu; 1001 ground-truth poses"),
            std::string::npos)
      << output;
  importAndCompare(bin + "/rpvio-import rosbag --bag " + bag_dir +
                       "/seq.bag --preset rpvio-sim --calib " + bag_dir + "/calib.ini",
                   seq, back);
}

TEST_F(RoundTrip, ThroughAnEurocFolder) {
  const std::string bin = test::binDir(), seq = dir_->file("seq"), euroc = dir_->file("euroc"),
                    back = dir_->file("from_euroc");
  std::string output;
  ASSERT_EQ(test::runCommand(
                bin + "/rpvio-export euroc --rawlog " + seq + "/seq.rawlog --out " + euroc, output),
            0)
      << output;
  // A second export never writes into an existing folder.
  EXPECT_EQ(test::runCommand(
                bin + "/rpvio-export euroc --rawlog " + seq + "/seq.rawlog --out " + euroc, output),
            2)
      << output;
  importAndCompare(bin + "/rpvio-import euroc --mav0 " + euroc + "/mav0 --masks " + euroc +
                       "/masks --gt " + euroc + "/mav0/state_groundtruth_estimate0/data.csv",
                   seq, back);
}

}  // namespace
}  // namespace rpvio

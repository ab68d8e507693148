// A simulated sequence exported to a ROS1 bag (rpvio-export rosbag) and imported back
// (rpvio-import rosbag --preset rpvio-sim) gives a rawlog on which rpvio-slam runs
// byte-identically.
#include <gtest/gtest.h>

#include "tests/test_util.h"

namespace rpvio {
namespace {

TEST(BagRoundTrip, ExportedAndImportedSequenceRunsIdentically) {
  test::TempDir dir;
  const std::string bin = test::binDir(), seq = dir.file("seq"), bag_dir = dir.file("bag"),
                    back = dir.file("back");
  std::string output;
  ASSERT_EQ(test::runCommand("mkdir -p " + bag_dir + " " + back + " && " + bin +
                                 "/rpvio-sim --characters 2 --duration 5 --out " + seq,
                             output),
            0)
      << output;
  ASSERT_EQ(test::runCommand(bin + "/rpvio-export rosbag --rawlog " + seq + "/seq.rawlog --out " +
                                 bag_dir + "/seq.bag",
                             output),
            0)
      << output;
  EXPECT_NE(output.find("101 /image, 101 /mask, 1001 /imu; 1001 ground-truth poses"),
            std::string::npos)
      << output;
  ASSERT_EQ(test::runCommand(bin + "/rpvio-import rosbag --bag " + bag_dir +
                                 "/seq.bag --preset rpvio-sim --calib " + bag_dir +
                                 "/calib.ini --out " + back + "/seq.rawlog",
                             output),
            0)
      << output;
  EXPECT_NE(output.find("101 CAM0, 101 PLANE_MASK, 1001 IMU, 1001 GROUND_TRUTH"), std::string::npos)
      << output;
  EXPECT_EQ(test::readFile(back + "/calib.ini"), test::readFile(seq + "/calib.ini"));
  for (const std::string& folder : {seq, back})
    ASSERT_EQ(test::runCommand(bin + "/rpvio-slam --config config/rpvio-multi.ini --calib " +
                                   folder + "/calib.ini --rawlog " + folder +
                                   "/seq.rawlog --quiet --out " + folder + "/out",
                               output),
              0)
        << output;
  for (const char* file : {"trajectory.tum", "trajectory_refined.tum", "planes.yaml"}) {
    const std::string direct = test::readFile(seq + "/out/" + file);
    EXPECT_GT(direct.size(), 100u) << file;
    EXPECT_EQ(test::readFile(back + "/out/" + file), direct) << file;
  }
}

}  // namespace
}  // namespace rpvio

// calib.ini save/load round trip for both distortion models, and the optional camera height.
#include <gtest/gtest.h>

#include "rawlog_io/calibration.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

Calibration sample(DistortionModel model) {
  Calibration c;
  c.camera = {752, 480, 458.654, 457.296, 367.215, 248.375, model, {-0.28, 0.074, 1.9e-4, 1.7e-5}};
  c.T_BC.linear() = Eigen::Quaterniond(0.7, 0.1, -0.3, 0.2).normalized().toRotationMatrix();
  c.T_BC.translation() = Eigen::Vector3d(-0.0216, -0.0647, 0.0098);
  c.time_offset = 0.03;
  c.imu = {1.6968e-4, 2.0e-3, 1.9393e-5, 3.0e-3, 200, 9.81};
  return c;
}

TEST(Calibration, RoundTripsBothDistortionModels) {
  for (auto model :
       {DistortionModel::RadTan, DistortionModel::Equidistant, DistortionModel::None}) {
    test::TempDir dir;
    const Calibration a = sample(model);
    saveCalibration(dir.file("calib.ini"), a);
    const Calibration b = loadCalibration(dir.file("calib.ini"));
    EXPECT_EQ(b.camera.model, model);
    EXPECT_EQ(b.camera.width, 752);
    EXPECT_DOUBLE_EQ(b.camera.fy, a.camera.fy);
    if (model != DistortionModel::None) {
      for (int i = 0; i < 4; ++i) EXPECT_DOUBLE_EQ(b.camera.distortion[i], a.camera.distortion[i]);
    }
    EXPECT_TRUE(b.T_BC.isApprox(a.T_BC, 1e-15));
    EXPECT_DOUBLE_EQ(b.time_offset, 0.03);
    EXPECT_DOUBLE_EQ(b.imu.gyro_random_walk, a.imu.gyro_random_walk);
    EXPECT_DOUBLE_EQ(b.imu.gravity, 9.81);
  }
}

TEST(Calibration, TheCameraHeightIsOptionalAndNeverNegative) {
  test::TempDir dir;
  Calibration a = sample(DistortionModel::None);
  saveCalibration(dir.file("without.ini"), a);
  EXPECT_EQ(test::readFile(dir.file("without.ini")).find("[ground]"), std::string::npos);
  EXPECT_EQ(loadCalibration(dir.file("without.ini")).camera_height, 0);  // unknown
  a.camera_height = 1.65;
  saveCalibration(dir.file("with.ini"), a);
  EXPECT_DOUBLE_EQ(loadCalibration(dir.file("with.ini")).camera_height, 1.65);
  test::writeText(dir.file("negative.ini"),
                  test::readFile(dir.file("without.ini")) + "\n[ground]\ncamera_height = -1\n");
  try {
    loadCalibration(dir.file("negative.ini"));
    FAIL();
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("camera_height must not be negative"), std::string::npos)
        << e.what();
  }
}

TEST(Calibration, MissingKeyIsNamed) {
  test::TempDir dir;
  test::writeText(dir.file("c.ini"), "[camera]\nwidth = 10\n");
  try {
    loadCalibration(dir.file("c.ini"));
    FAIL();
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("missing key 'height'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rpvio

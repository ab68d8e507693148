// Write a rawlog with all four labels, stream it back, compare content.
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/core.hpp>

#include "common/input_error.h"
#include "rawlog_io/rawlog_labels.h"
#include "rawlog_io/rawlog_reader.h"
#include "rawlog_io/rawlog_writer.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

Calibration smallCalibration() {
  Calibration c;
  c.camera.width = 64;
  c.camera.height = 48;
  c.camera.fx = c.camera.fy = 50;
  c.camera.cx = 32;
  c.camera.cy = 24;
  c.T_BC.translation() = Eigen::Vector3d(0.1, 0.0, -0.05);
  return c;
}

cv::Mat randomImage(int seed) {
  cv::Mat img(48, 64, CV_8UC1);
  cv::RNG rng(seed);
  rng.fill(img, cv::RNG::UNIFORM, 0, 256);
  return img;
}

struct WrittenDataset {
  std::vector<cv::Mat> images, masks;
  std::vector<ImuSample> imu;
  std::vector<StampedPose> poses;
};

WrittenDataset writeDataset(const std::string& path) {
  WrittenDataset d;
  RawlogWriter writer(path, smallCalibration());
  for (int frame = 0; frame < 3; ++frame) {
    for (int k = 0; k < 10; ++k) {
      ImuSample s;
      s.t = 100.0 + frame * 0.05 + k * 0.005;
      s.gyro = Eigen::Vector3d(0.01 * k, -0.02, 0.03 * frame);
      s.accel = Eigen::Vector3d(0.1, 9.81, -0.2 * k);
      writer.addImu(s);
      d.imu.push_back(s);
      StampedPose p;
      p.t = s.t;
      p.p = Eigen::Vector3d(frame, k, 0.5);
      p.q = Eigen::Quaterniond(Eigen::AngleAxisd(0.1 * k, Eigen::Vector3d::UnitZ()));
      writer.addGroundTruth(p);
      d.poses.push_back(p);
    }
    const double t = 100.0 + frame * 0.05 + 0.05;
    d.images.push_back(randomImage(frame));
    d.masks.push_back(randomImage(100 + frame));
    writer.addImage(t, d.images.back());
    writer.addMask(t, d.masks.back());
  }
  writer.close();
  return d;
}

/// Changes the working directory for its lifetime.
class CurrentDirectory {
 public:
  explicit CurrentDirectory(const std::filesystem::path& dir)
      : previous_(std::filesystem::current_path()) {
    std::filesystem::current_path(dir);
  }
  ~CurrentDirectory() { std::filesystem::current_path(previous_); }

 private:
  std::filesystem::path previous_;
};

bool sameImage(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::countNonZero(a != b) == 0;
}

TEST(RawlogRoundTrip, AllFourLabelsReadBackEqual) {
  test::TempDir dir;
  const std::string path = dir.file("seq.rawlog");
  const WrittenDataset written = writeDataset(path);
  ASSERT_TRUE(std::filesystem::exists(path));
  ASSERT_FALSE(std::filesystem::exists(path + ".tmp"));
  ASSERT_TRUE(std::filesystem::is_directory(dir.file("seq_Images")));

  // Read from another working directory through a relative path with a folder part (the case
  // MRPT 2.5.8's images-folder detection gets wrong): the images must still be found.
  const CurrentDirectory in_parent(dir.path().parent_path());
  RawlogReader reader((dir.path().filename() / "seq.rawlog").string());
  size_t n_img = 0, n_mask = 0, n_imu = 0, n_gt = 0;
  while (auto obs = reader.next()) {
    if (auto img = std::dynamic_pointer_cast<mrpt::obs::CObservationImage>(obs)) {
      const cv::Mat loaded = loadGrayImage(*img, reader);
      // MRPT's own lazy loading finds the file too (through setLazyLoadPathBase).
      EXPECT_EQ(img->image.getWidth(), 64u);
      img->image.unload();
      EXPECT_EQ(img->cameraParams.ncols, 64u);
      EXPECT_NEAR(img->cameraPose.x(), 0.1, 1e-12);
      if (obs->sensorLabel == labels::kCamera) {
        ASSERT_LT(n_img, written.images.size());
        EXPECT_TRUE(sameImage(loaded, written.images[n_img++]));
      } else {
        ASSERT_EQ(obs->sensorLabel, labels::kPlaneMask);
        ASSERT_LT(n_mask, written.masks.size());
        EXPECT_TRUE(sameImage(loaded, written.masks[n_mask++]));
      }
    } else if (auto imu = std::dynamic_pointer_cast<mrpt::obs::CObservationIMU>(obs)) {
      const ImuSample s = toImuSample(*imu, reader);
      const ImuSample& w = written.imu.at(n_imu++);
      EXPECT_NEAR(s.t, w.t, 1e-6);
      EXPECT_TRUE(s.gyro.isApprox(w.gyro, 1e-12));
      EXPECT_TRUE(s.accel.isApprox(w.accel, 1e-12));
    } else if (auto gt = std::dynamic_pointer_cast<mrpt::obs::CObservationRobotPose>(obs)) {
      const StampedPose p = toStampedPose(*gt);
      const StampedPose& w = written.poses.at(n_gt++);
      EXPECT_NEAR(p.t, w.t, 1e-6);
      EXPECT_LT((p.p - w.p).norm(), 1e-9);
      EXPECT_LT(p.q.angularDistance(w.q), 1e-9);
    }
  }
  EXPECT_EQ(n_img, 3u);
  EXPECT_EQ(n_mask, 3u);
  EXPECT_EQ(n_imu, written.imu.size());
  EXPECT_EQ(n_gt, written.poses.size());
}

TEST(RawlogWriter, AbandonedWriterLeavesNothingUnderFinalName) {
  test::TempDir dir;
  const std::string path = dir.file("seq.rawlog");
  {
    RawlogWriter writer(path, smallCalibration());
    writer.addImage(1.0, randomImage(1));
  }
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  EXPECT_FALSE(std::filesystem::exists(dir.file("seq_Images")));
}

TEST(RawlogWriter, RejectsTimeGoingBackwards) {
  test::TempDir dir;
  RawlogWriter writer(dir.file("seq.rawlog"), smallCalibration());
  ImuSample s;
  s.t = 2.0;
  writer.addImu(s);
  s.t = 1.0;
  EXPECT_THROW(writer.addImu(s), std::invalid_argument);
}

}  // namespace
}  // namespace rpvio

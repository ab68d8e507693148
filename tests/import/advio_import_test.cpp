// ADVIO raw import on small sequences written here: a .mov written by OpenCV (stored sideways as
// ADVIO's iPhone videos are), CSVs in the dataset's layout and units; the accelerometer's units
// and sign detected; bad input refused with exit code 2 and nothing written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "common/input_error.h"
#include "rawlog_io/advio_import.h"
#include "rawlog_io/calibration.h"
#include "rawlog_io/rawlog_reader.h"
#include "rawlog_io/rawlog_summary.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;

namespace rpvio {
namespace {

constexpr double kG = 9.80665;

/// An advio-NN folder: `frames` video frames of `size` (stored), frame k with a white square in
/// the stored top-left corner and a grey level of 20 k elsewhere, stamped 1 + k / 60 s; IMU at
/// 100 Hz from 0.9 to 1.3 s with the given accelerometer reading and a constant rotation rate
/// (the batch's biases added); five ground-truth poses.
struct FakeAdvio {
  test::TempDir root{"fake_advio"};
  fs::path dir;
  Eigen::Vector3d gyro_rate{0.1, 0.2, 0.3};

  explicit FakeAdvio(const std::string& name = "advio-05", int frames = 12,
                     cv::Size size = {1280, 720},
                     const Eigen::Vector3d& accel_reading = Eigen::Vector3d(0, -1, 0),
                     bool add_bias = true)
      : dir(root.path() / name) {
    fs::create_directories(dir / "iphone");
    fs::create_directories(dir / "ground-truth");
    cv::VideoWriter video((dir / "iphone/frames.mov").string(),
                          cv::VideoWriter::fourcc('m', 'p', '4', 'v'), 60, size, true);
    EXPECT_TRUE(video.isOpened()) << "OpenCV cannot write mp4v";
    std::ofstream stamps(dir / "iphone/frames.csv");
    for (int k = 0; k < frames; ++k) {
      cv::Mat frame(size, CV_8UC3, cv::Scalar::all(20 * k));
      frame(cv::Rect(0, 0, 96, 96)).setTo(cv::Scalar::all(255));
      video.write(frame);
      stamps << 1.0 + k / 60.0 << "," << k << "\n";
    }
    // Batch 1's biases (sequences 1-12), in the files' units.
    const Eigen::Vector3d accel_bias =
        add_bias ? Eigen::Vector3d(0.0407, -0.0623, 0.1017) : Eigen::Vector3d::Zero();
    const Eigen::Vector3d gyro_bias =
        add_bias ? Eigen::Vector3d(-0.0067, 0.0070, -0.0065) : Eigen::Vector3d::Zero();
    std::ofstream accel(dir / "iphone/accelerometer.csv"), gyro(dir / "iphone/gyro.csv");
    accel.precision(10);
    gyro.precision(10);
    for (int i = 0; i <= 40; ++i) {
      const double t = 0.9 + i * 0.01;
      const Eigen::Vector3d a = accel_reading + accel_bias, w = gyro_rate + gyro_bias;
      accel << t << "," << a.x() << "," << a.y() << "," << a.z() << "\n";
      gyro << t + 0.004 << "," << w.x() << "," << w.y() << "," << w.z() << "\n";
    }
    std::ofstream pose(dir / "ground-truth/pose.csv");
    for (int i = 0; i < 5; ++i) pose << 1.0 + 0.05 * i << "," << i << ",0,0,1,0,0,0\n";
  }
  AdvioImportOptions options(const std::string& out) const {
    AdvioImportOptions opt;
    opt.sequence_dir = dir.string();
    opt.output_rawlog = out;
    return opt;
  }
};

std::vector<cv::Mat> importedImages(const std::string& rawlog) {
  RawlogReader reader(rawlog);
  std::vector<cv::Mat> images;
  while (auto obs = reader.next())
    if (auto image = std::dynamic_pointer_cast<mrpt::obs::CObservationImage>(obs))
      images.push_back(loadGrayImage(*image, reader));
  return images;
}

std::vector<ImuSample> importedImu(const std::string& rawlog) {
  RawlogReader reader(rawlog);
  std::vector<ImuSample> imu;
  while (auto obs = reader.next())
    if (auto sample = std::dynamic_pointer_cast<mrpt::obs::CObservationIMU>(obs))
      imu.push_back(toImuSample(*sample, reader));
  return imu;
}

TEST(AdvioImport, TurnsThinsAndConvertsCoreMotionUnits) {
  const FakeAdvio advio;
  test::TempDir out;
  AdvioImportOptions opt = advio.options(out.file("seq.rawlog"));
  opt.every = 2;
  const AdvioImportCounts counts = importAdvio(opt);
  EXPECT_EQ(counts.images, 6u);
  EXPECT_EQ(counts.groundtruth, 5u);
  EXPECT_EQ(counts.batch, 1);
  EXPECT_DOUBLE_EQ(counts.accel_scale, -kG);  // readings in g, CoreMotion's sign
  EXPECT_EQ(counts.frames_without_stamp + counts.stamps_without_frame, 0u);

  const std::vector<cv::Mat> images = importedImages(opt.output_rawlog);
  ASSERT_EQ(images.size(), 6u);
  for (size_t j = 0; j < images.size(); ++j) {
    ASSERT_EQ(images[j].size(), cv::Size(720, 1280));
    // Turned clockwise: the stored top-left corner is now the top-right one.
    EXPECT_GT(cv::mean(images[j](cv::Rect(720 - 80, 0, 80, 80)))[0], 230) << j;
    EXPECT_LT(cv::mean(images[j](cv::Rect(0, 0, 80, 80)))[0], 230) << j;
    // Every second frame, in order: grey level 20 * (2 j).
    EXPECT_NEAR(cv::mean(images[j](cv::Rect(200, 400, 300, 400)))[0], 40.0 * j, 4) << j;
  }
  const std::vector<ImuSample> imu = importedImu(opt.output_rawlog);
  ASSERT_EQ(imu.size(), counts.imu);
  ASSERT_GT(imu.size(), 70u);  // both sensors' stamps over their common 0.396 s
  for (const ImuSample& s : imu) {
    // Bias removed, CoreMotion's -1 g along the phone's y became +9.81 m/s^2 of specific force.
    EXPECT_LT((s.accel - Eigen::Vector3d(0, kG, 0)).norm(), 1e-6);
    EXPECT_LT((s.gyro - advio.gyro_rate).norm(), 1e-6);
  }
  const Calibration calib = loadCalibration(out.file("calib.ini"));
  EXPECT_EQ(calib.camera.width, 720);
  EXPECT_EQ(calib.camera.height, 1280);
  EXPECT_DOUBLE_EQ(calib.camera.fx, 1077.2);
  EXPECT_EQ(calib.camera.model, DistortionModel::RadTan);
  // The back camera of an upright phone: optical axis along the IMU's -z, image down along -y.
  EXPECT_LT(calib.T_BC.linear().col(2).z(), -0.999);
  EXPECT_LT(calib.T_BC.linear().col(1).y(), -0.999);
  EXPECT_NEAR(calib.imu.rate_hz, 100, 0);
}

TEST(AdvioImport, ReadingsInMetresPerSecondSquaredAreKept) {
  const FakeAdvio advio("advio-14", 3, {1280, 720}, Eigen::Vector3d(0, kG, 0), false);
  test::TempDir out;
  AdvioImportOptions opt = advio.options(out.file("seq.rawlog"));
  opt.subtract_batch_bias = false;
  const AdvioImportCounts counts = importAdvio(opt);
  EXPECT_EQ(counts.batch, 2);
  EXPECT_DOUBLE_EQ(counts.accel_scale, 1.0);
  EXPECT_DOUBLE_EQ(loadCalibration(out.file("calib.ini")).camera.fx, 1082.4);
}

TEST(AdvioImport, AccelerometerScaleDetection) {
  const Eigen::Matrix3d R_BC = advioCalibration(1).T_BC.linear();
  std::string reason;
  // Specific force along the phone's +y (up in an upright image), in g and in m/s^2.
  EXPECT_DOUBLE_EQ(detectAccelScale({{0.05, 0.98, -0.2}}, R_BC, "a.csv", reason), kG);
  EXPECT_DOUBLE_EQ(detectAccelScale({{0.5, 9.7, -2.0}}, R_BC, "a.csv", reason), 1.0);
  EXPECT_DOUBLE_EQ(detectAccelScale({{0.05, -0.98, -0.2}}, R_BC, "a.csv", reason), -kG);
  try {
    detectAccelScale({{0, 3.0, 0}}, R_BC, "a.csv", reason);
    FAIL() << "3 units is neither g nor m/s^2";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot tell the units"), std::string::npos) << e.what();
  }
  try {  // gravity along the optical axis: the image's vertical says nothing
    detectAccelScale({{0.0, 0.1, 0.99}}, R_BC, "a.csv", reason);
    FAIL() << "no vertical direction in the image";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot tell the sign"), std::string::npos) << e.what();
  }
}

TEST(AdvioImport, GivenCalibrationReplacesTheBatchsBiasesToo) {
  const FakeAdvio advio("advio-05", 3);  // readings carry batch 1's biases
  test::TempDir out;
  AdvioImportOptions opt = advio.options(out.file("seq.rawlog"));
  opt.calibration = advioCalibration(5);
  const AdvioImportCounts counts = importAdvio(opt);
  EXPECT_EQ(counts.batch, 0);
  const std::vector<ImuSample> imu = importedImu(opt.output_rawlog);
  ASSERT_FALSE(imu.empty());
  // The gyroscope's bias stays in: (0.1, 0.2, 0.3) + (-0.0067, 0.0070, -0.0065).
  EXPECT_LT((imu[0].gyro - Eigen::Vector3d(0.0933, 0.207, 0.2935)).norm(), 1e-9);
}

TEST(AdvioImport, VideoLongerThanItsStampsIsCut) {
  const FakeAdvio advio("advio-02", 6);
  std::ofstream(advio.dir / "iphone/frames.csv") << "1.0,0\n1.0166,1\n1.0333,2\n1.05,3\n";
  test::TempDir out;
  const AdvioImportCounts counts = importAdvio(advio.options(out.file("seq.rawlog")));
  EXPECT_EQ(counts.images, 4u);
  EXPECT_EQ(counts.frames_without_stamp, 2u);
  EXPECT_EQ(counts.stamps_without_frame, 0u);
}

TEST(AdvioImportBadInput, OneLineErrorAndNothingWritten) {
  struct Case {
    std::string what, args, expected;
    std::function<void(const FakeAdvio&)> spoil;
  };
  const std::vector<Case> cases = {
      {"unknown batch", "", "batch is unknown", nullptr},
      {"truncated accelerometer line", "", "accelerometer.csv:line 3",
       [](const FakeAdvio& a) {
         std::ofstream(a.dir / "iphone/accelerometer.csv") << "0.9,0,-1,0\n0.91,0,-1,0\n0.92,0.1\n";
       }},
      {"wrong turn", "--rotate none", "once turned, the calibration says 720x1280", nullptr},
      {"missing video", "", "frames.mov: file not found",
       [](const FakeAdvio& a) { fs::remove(a.dir / "iphone/frames.mov"); }},
      {"damaged video", "", "cannot be decoded",
       [](const FakeAdvio& a) {
         const fs::path video = a.dir / "iphone/frames.mov";
         std::fstream f(video, std::ios::in | std::ios::out | std::ios::binary);
         f.seekp(fs::file_size(video) / 4);
         const std::string zeros(fs::file_size(video) / 2, '\0');
         f.write(zeros.data(), zeros.size());
       }},
      {"stamps backwards", "", "frames.csv:line 2: timestamps not increasing",
       [](const FakeAdvio& a) { std::ofstream(a.dir / "iphone/frames.csv") << "1.0,0\n0.9,1\n"; }},
  };
  for (const Case& c : cases) {
    const FakeAdvio advio(c.what == "unknown batch" ? "phone-run" : "advio-03",
                          c.what == "damaged video" ? 60 : 3);
    if (c.spoil) c.spoil(advio);
    test::TempDir out;
    std::string output;
    const int rc =
        test::runCommand(std::string(RPVIO_BIN_DIR) + "/rpvio-import advio --seq " +
                             advio.dir.string() + " " + c.args + " --out " + out.file("seq.rawlog"),
                         output);
    EXPECT_EQ(rc, 2) << c.what << ": " << output;
    EXPECT_NE(output.find(c.expected), std::string::npos) << c.what << ": " << output;
    EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << c.what << ": " << output;
    EXPECT_TRUE(fs::is_empty(out.path())) << c.what << ": output left behind";
  }
}

}  // namespace
}  // namespace rpvio

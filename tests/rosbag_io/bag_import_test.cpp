// importBag on small bags written here with the same library: encodings, mask pairing, IMU
// decimation, exact stamps, and bad input (one error naming the bag and the message, no output).
#include <geometry_msgs/PoseStamped.h>
#include <gtest/gtest.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/Imu.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <opencv2/imgproc.hpp>

#include "common/input_error.h"
#include "rawlog_io/calibration.h"
#include "rawlog_io/rawlog_reader.h"
#include "rawlog_io/rawlog_summary.h"
#include "rosbag_io/bag_import.h"
#include "rosbag_io/stamps.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

namespace fs = std::filesystem;

constexpr double kStart = 1600000000.0;  // s, a real bag's epoch stamps

sensor_msgs::Image colourImage(const std::string& encoding, const ros::Time& stamp,
                               const cv::Scalar& rgb, int width = 64, int height = 48) {
  int type = CV_8UC3;
  cv::Scalar value = rgb;
  if (encoding == "bgr8") value = cv::Scalar(rgb[2], rgb[1], rgb[0]);
  if (encoding == "rgba8") type = CV_8UC4, value = cv::Scalar(rgb[0], rgb[1], rgb[2], 255);
  if (encoding == "bgra8") type = CV_8UC4, value = cv::Scalar(rgb[2], rgb[1], rgb[0], 255);
  if (encoding == "mono16") type = CV_16UC1, value = cv::Scalar(rgb[0] * 256);
  if (encoding == "mono8" || encoding == "yuv422") type = CV_8UC1;
  const cv::Mat pixels(height, width, type, value);
  sensor_msgs::Image msg;
  msg.header.stamp = stamp;
  msg.width = static_cast<uint32_t>(width);
  msg.height = static_cast<uint32_t>(height);
  msg.encoding = encoding;
  msg.step = static_cast<uint32_t>(pixels.step);
  msg.data.assign(pixels.data, pixels.data + pixels.total() * pixels.elemSize());
  return msg;
}

sensor_msgs::Imu imuMessage(const ros::Time& stamp, double gyro_x) {
  sensor_msgs::Imu msg;
  msg.header.stamp = stamp;
  msg.angular_velocity.x = gyro_x;
  msg.linear_acceleration.z = 9.81;
  return msg;
}

Calibration calibration() {
  Calibration c;
  c.camera.width = 64;
  c.camera.height = 48;
  c.camera.fx = c.camera.fy = 50;
  c.camera.cx = 31.5;
  c.camera.cy = 23.5;
  return c;
}

BagImportOptions options(const test::TempDir& dir) {
  BagImportOptions opt;
  opt.bag_path = dir.file("in.bag");
  opt.output_rawlog = dir.file("out.rawlog");
  opt.topics = {"/cam0/image_raw", "/imu0", "/cam0/planes", "", ""};
  opt.calibration = calibration();
  opt.imu_rate_hz = 200;
  return opt;
}

/// 1 s of IMU at 1 kHz and five images at 5 Hz in `encoding`, each with its mask but the last;
/// one mask without an image; record times shuffled a little against the stamps.
void writeBag(const std::string& path, const std::string& encoding,
              rosbag::compression::CompressionType compression) {
  rosbag::Bag bag(path, rosbag::bagmode::Write);
  bag.setCompression(compression);
  for (int k = 0; k <= 1000; ++k) {
    const ros::Time stamp(kStart + k * 0.001);
    bag.write("/imu0", stamp, imuMessage(stamp, k * 0.001));
  }
  for (int k = 0; k < 5; ++k) {
    const ros::Time stamp(kStart + 0.1 + k * 0.2);
    const ros::Time recorded = stamp + ros::Duration(0.03);
    if (k < 4) {  // the mask first, as some recorders do
      bag.write("/cam0/planes", recorded, colourImage("mono8", stamp, cv::Scalar(k + 1)));
    }
    bag.write("/cam0/image_raw", recorded + ros::Duration(0.001),
              colourImage(encoding, stamp, cv::Scalar(200, 100, 50)));
  }
  const ros::Time lonely(kStart + 0.95);
  bag.write("/cam0/planes", lonely, colourImage("mono8", lonely, cv::Scalar(9)));
}

TEST(BagImport, EveryEncodingGivesGreyImagesPairedMasksAndADecimatedImu) {
  for (const std::string encoding : {"rgb8", "bgr8", "rgba8", "bgra8", "mono16", "mono8"}) {
    test::TempDir dir;
    writeBag(dir.file("in.bag"), encoding,
             encoding == "bgr8" ? rosbag::compression::BZ2 : rosbag::compression::LZ4);
    const BagImportCounts counts = importBag(options(dir));
    EXPECT_EQ(counts.images, 5u) << encoding;
    EXPECT_EQ(counts.masks, 4u) << encoding;
    EXPECT_EQ(counts.unpaired_masks, 1u) << encoding;
    EXPECT_EQ(counts.imu, 201u) << encoding;  // 1 kHz over 1 s at 200 Hz
    RawlogReader reader(dir.file("out.rawlog"));
    double last_imu = -1;
    int images = 0;
    for (auto obs = reader.next(); obs; obs = reader.next()) {
      const double t = toSeconds(obs->timestamp) - kStart;
      if (obs->sensorLabel == "IMU") {
        if (last_imu >= 0) {
          EXPECT_NEAR(t - last_imu, 0.005, 1e-6);
        }
        last_imu = t;
      } else if (obs->sensorLabel == "CAM0") {
        EXPECT_NEAR(t, 0.1 + 0.2 * images++, 1e-6);
        const cv::Mat gray =
            loadGrayImage(dynamic_cast<const mrpt::obs::CObservationImage&>(*obs), reader);
        // ITU-R BT.601 luma of (200, 100, 50): 0.299 R + 0.587 G + 0.114 B = 124.3
        const double expected = encoding.rfind("mono", 0) == 0 ? 200 : 124.3;
        EXPECT_NEAR(gray.at<uint8_t>(10, 10), expected, 1.0) << encoding;
      } else if (obs->sensorLabel == "PLANE_MASK") {
        const cv::Mat mask =
            loadGrayImage(dynamic_cast<const mrpt::obs::CObservationImage&>(*obs), reader);
        EXPECT_EQ(mask.at<uint8_t>(0, 0), images) << "the mask of image " << images;
      }
    }
    EXPECT_EQ(images, 5);
    EXPECT_TRUE(fs::exists(dir.file("calib.ini")));
  }
}

TEST(BagImport, StampsKeepTheirTicks) {
  for (const double t : {0.0, 0.05, 0.15, 12.345, 1600000000.123456789}) {
    const ros::Time stamp = rosStamp(fromSeconds(t));
    EXPECT_EQ(fromSeconds(rawlogSeconds(stamp)), fromSeconds(t)) << t;
  }
}

TEST(BagImport, ViodePresetTurnsClassColoursIntoPlanesInBothEncodingsAndOdometryIntoGroundTruth) {
  const BagPreset viode = bagPreset("viode");
  for (const std::string encoding : {"rgb8", "bgr8"}) {
    test::TempDir dir;
    {
      rosbag::Bag bag(dir.file("in.bag"), rosbag::bagmode::Write);
      for (int k = 0; k <= 200; ++k) {
        const ros::Time stamp(kStart + k * 0.005);
        bag.write("/imu0", stamp, imuMessage(stamp, 0));
      }
      for (int k = 0; k < 3; ++k) {
        const ros::Time stamp(kStart + 0.2 * k);
        bag.write("/cam0/image_raw", stamp, colourImage("mono8", stamp, cv::Scalar(90)));
        // Quarters: ground, wall, road, and the colour of something else.
        sensor_msgs::Image segmentation = colourImage(encoding, stamp, cv::Scalar(10, 20, 30));
        const int quarter = 64 * 48 / 4;
        for (int q = 0; q < 3; ++q)
          for (int i = q * quarter; i < (q + 1) * quarter; ++i)
            for (int c = 0; c < 3; ++c)
              segmentation.data[3 * i + c] =
                  viode.mask_colours[q].rgb[encoding == "rgb8" ? c : 2 - c];
        bag.write("/cam0/segmentation", stamp, segmentation);
        nav_msgs::Odometry odometry;
        odometry.header.stamp = stamp;
        odometry.pose.pose.position.x = k;
        odometry.pose.pose.orientation.w = 1;
        bag.write("/odometry", stamp, odometry);
      }
    }
    BagImportOptions opt = options(dir);
    opt.topics = viode.topics;
    opt.mask_colours = viode.mask_colours;
    const BagImportCounts counts = importBag(opt);
    EXPECT_EQ(counts.masks, 3u) << encoding;
    EXPECT_EQ(counts.groundtruth, 3u) << encoding;
    RawlogReader reader(dir.file("out.rawlog"));
    int masks = 0, poses = 0;
    for (auto obs = reader.next(); obs; obs = reader.next()) {
      if (obs->sensorLabel == "PLANE_MASK") {
        const cv::Mat mask =
            loadGrayImage(dynamic_cast<const mrpt::obs::CObservationImage&>(*obs), reader);
        // Rows of 64 px: the quarters are 12 rows each.
        EXPECT_EQ(mask.at<uint8_t>(5, 10), 1) << encoding;
        EXPECT_EQ(mask.at<uint8_t>(17, 10), 2) << encoding;
        EXPECT_EQ(mask.at<uint8_t>(29, 10), 3) << encoding;
        EXPECT_EQ(mask.at<uint8_t>(41, 10), 0) << encoding;
        ++masks;
      } else if (obs->sensorLabel == "GROUND_TRUTH") {
        EXPECT_NEAR(
            toStampedPose(dynamic_cast<const mrpt::obs::CObservationRobotPose&>(*obs)).p.x(),
            poses++, 1e-12);
      }
    }
    EXPECT_EQ(masks, 3);
    EXPECT_EQ(poses, 3);
  }
}

TEST(BagImport, OpenLorisPresetMergesTheSplitAccelerometerAndGyroscope) {
  // Gyroscope at 400 Hz, accelerometer at 250 Hz, both linear in time: interpolation is exact.
  const BagPreset openloris = bagPreset("openloris");
  test::TempDir dir;
  auto gyro_x = [](double t) { return 0.5 + 2 * t; };
  auto accel_z = [](double t) { return 9.0 + 3 * t; };
  {
    rosbag::Bag bag(dir.file("in.bag"), rosbag::bagmode::Write);
    for (int k = 0; k <= 400; ++k) {  // 0 .. 1 s
      sensor_msgs::Imu msg;
      msg.header.stamp = ros::Time(kStart + k / 400.0);
      msg.angular_velocity.x = gyro_x(k / 400.0);
      bag.write(openloris.topics.imu, msg.header.stamp, msg);
    }
    for (int k = 1; k <= 200; ++k) {  // 0.004 .. 0.8 s
      sensor_msgs::Imu msg;
      msg.header.stamp = ros::Time(kStart + k / 250.0);
      msg.linear_acceleration.z = accel_z(k / 250.0);
      bag.write(openloris.topics.accel, msg.header.stamp, msg);
    }
    const ros::Time stamp(kStart + 0.4);
    bag.write(openloris.topics.image, stamp, colourImage("rgb8", stamp, cv::Scalar(1, 2, 3)));
    geometry_msgs::PoseStamped pose;
    pose.header.stamp = stamp;
    pose.pose.orientation.w = 1;
    bag.write(openloris.topics.groundtruth, stamp, pose);
  }
  BagImportOptions opt = options(dir);
  opt.topics = openloris.topics;
  opt.imu_rate_hz = 0;
  const BagImportCounts counts = importBag(opt);
  // The stamps of either sensor within 0.004 .. 0.8 s (both cover it): gyroscope k = 2..320,
  // accelerometer k = 1..200, 40 of them shared (the multiples of 20 ms).
  EXPECT_EQ(counts.imu, 319u + 200u - 40u);
  EXPECT_EQ(counts.groundtruth, 1u);
  RawlogReader reader(dir.file("out.rawlog"));
  size_t imu = 0;
  double last = -1;
  for (auto obs = reader.next(); obs; obs = reader.next()) {
    if (obs->sensorLabel != "IMU") continue;
    const ImuSample s = toImuSample(dynamic_cast<const mrpt::obs::CObservationIMU&>(*obs), reader);
    const double t = s.t - kStart;
    EXPECT_GT(t, last);
    last = t;
    EXPECT_GE(t, 0.004 - 1e-6);
    EXPECT_LE(t, 0.8 + 1e-6);
    EXPECT_NEAR(s.gyro.x(), gyro_x(t), 1e-5) << t;
    EXPECT_NEAR(s.accel.z(), accel_z(t), 1e-5) << t;
    ++imu;
  }
  EXPECT_EQ(imu, counts.imu);
}

TEST(BagImport, AdvioPresetReadsTheAuthorsPortraitBagsWithMasks) {
  const BagPreset advio = bagPreset("advio");
  test::TempDir dir;
  {
    rosbag::Bag bag(dir.file("in.bag"), rosbag::bagmode::Write);
    for (int k = 0; k <= 30; ++k) {  // the iPhone's 100 Hz
      const ros::Time stamp(kStart + k * 0.01);
      bag.write(advio.topics.imu, stamp, imuMessage(stamp, 0.1));
    }
    for (int k = 0; k < 3; ++k) {
      const ros::Time stamp(kStart + 0.05 + k * 0.1);
      bag.write(advio.topics.image, stamp, colourImage("mono8", stamp, cv::Scalar(70), 720, 1280));
      bag.write(advio.topics.mask, stamp, colourImage("mono8", stamp, cv::Scalar(2), 720, 1280));
    }
  }
  BagImportOptions opt = options(dir);
  opt.topics = advio.topics;
  opt.calibration = *advio.calibration;
  opt.imu_rate_hz = advio.imu_rate_hz;
  const BagImportCounts counts = importBag(opt);
  EXPECT_EQ(counts.images, 3u);
  EXPECT_EQ(counts.masks, 3u);
  EXPECT_EQ(counts.imu, 31u);  // every sample kept
  const Calibration calib = loadCalibration(dir.file("calib.ini"));
  EXPECT_EQ(calib.camera.width, 720);
  EXPECT_EQ(calib.camera.height, 1280);
  EXPECT_EQ(calib.camera.model, DistortionModel::RadTan);
}

/// importBag's InputError text, and that nothing was written.
std::string importError(const BagImportOptions& opt) {
  try {
    importBag(opt);
  } catch (const InputError& e) {
    EXPECT_FALSE(fs::exists(opt.output_rawlog)) << e.what();
    EXPECT_FALSE(fs::exists(fs::path(opt.output_rawlog).parent_path() / "calib.ini")) << e.what();
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return "";
}

TEST(BagImport, BadInputIsOneErrorAndNoOutput) {
  test::TempDir dir;
  writeBag(dir.file("in.bag"), "rgb8", rosbag::compression::LZ4);
  BagImportOptions opt = options(dir);
  opt.topics.imu = "/imu";
  const std::string missing = importError(opt);
  EXPECT_NE(missing.find("no messages on /imu (the bag has: "), std::string::npos) << missing;
  EXPECT_NE(missing.find("/imu0 (sensor_msgs/Imu)"), std::string::npos) << missing;

  opt = options(dir);
  opt.topics.imu = "/cam0/image_raw";
  EXPECT_NE(importError(opt).find("carries sensor_msgs/Image, not sensor_msgs/Imu"),
            std::string::npos);

  test::TempDir yuv;
  writeBag(yuv.file("in.bag"), "yuv422", rosbag::compression::Uncompressed);
  const std::string encoding = importError(options(yuv));
  EXPECT_NE(encoding.find("/cam0/image_raw message 1: image encoding 'yuv422' is not supported"),
            std::string::npos)
      << encoding;

  test::TempDir sizes;
  {
    rosbag::Bag bag(sizes.file("in.bag"), rosbag::bagmode::Write);
    const ros::Time stamp(kStart);
    bag.write("/imu0", stamp, imuMessage(stamp, 0));
    bag.write("/cam0/image_raw", stamp, colourImage("mono8", stamp, cv::Scalar(1)));
    bag.write("/cam0/planes", stamp, colourImage("mono8", stamp, cv::Scalar(1), 32, 24));
  }
  EXPECT_NE(importError(options(sizes)).find("mask 32x24 differs from its image 64x48"),
            std::string::npos);

  test::TempDir backwards;
  {
    rosbag::Bag bag(backwards.file("in.bag"), rosbag::bagmode::Write);
    for (const double t : {0.0, 0.002, 0.001}) {
      const ros::Time stamp(kStart + t);
      bag.write("/imu0", ros::Time(kStart + 1), imuMessage(stamp, 0));
    }
    bag.write("/cam0/image_raw", ros::Time(kStart), colourImage("mono8", ros::Time(kStart), {}));
  }
  opt = options(backwards);
  opt.topics.mask.clear();
  const std::string order = importError(opt);
  EXPECT_NE(order.find("/imu0 message 3: stamp t=1600000000.00"), std::string::npos) << order;
  EXPECT_NE(order.find("is not after the previous one"), std::string::npos) << order;

  test::TempDir twice;
  {
    rosbag::Bag bag(twice.file("in.bag"), rosbag::bagmode::Write);
    const ros::Time stamp(kStart);
    bag.write("/imu0", stamp, imuMessage(stamp, 0));
    for (int k = 0; k < 2; ++k)
      bag.write("/cam0/image_raw", stamp, colourImage("mono8", stamp, cv::Scalar(k)));
  }
  opt = options(twice);
  opt.topics.mask.clear();
  EXPECT_NE(importError(opt).find("image stamps go backwards or repeat"), std::string::npos);

  test::TempDir in_g;  // accelerations written in g
  {
    rosbag::Bag bag(in_g.file("in.bag"), rosbag::bagmode::Write);
    for (int k = 0; k < 3; ++k) {
      const ros::Time stamp(kStart + 0.005 * k);
      sensor_msgs::Imu imu = imuMessage(stamp, 0);
      imu.linear_acceleration.z = 1.0;
      bag.write("/imu0", stamp, imu);
    }
    bag.write("/cam0/image_raw", ros::Time(kStart), colourImage("mono8", ros::Time(kStart), {}));
  }
  opt = options(in_g);
  opt.topics.mask.clear();
  const std::string units = importError(opt);
  EXPECT_NE(units.find(":/imu0: median |linear_acceleration| is 1.000, not about gravity"),
            std::string::npos)
      << units;
  opt.accel_scale = 9.80665;  // said to be in g: imported
  EXPECT_EQ(importBag(opt).imu, 3u);

  test::TempDir truncated;
  writeBag(truncated.file("in.bag"), "mono8", rosbag::compression::Uncompressed);
  fs::resize_file(truncated.file("in.bag"), fs::file_size(truncated.file("in.bag")) / 2);
  const std::string cut = importError(options(truncated));
  EXPECT_NE(cut.find(truncated.file("in.bag")), std::string::npos) << cut;
}

uint32_t u32At(const std::string& bytes, size_t pos) {
  uint32_t value;
  std::memcpy(&value, bytes.data() + pos, 4);
  return value;
}

void setU32(std::string& bytes, size_t pos, uint32_t value) {
  std::memcpy(bytes.data() + pos, &value, 4);
}

/// Where rosbag::Bag starts reading the index: the file header's index_pos.
size_t indexPos(const std::string& bag) {
  uint64_t pos;
  std::memcpy(&pos, bag.data() + bag.find("index_pos=") + 10, 8);
  return pos;
}

// Found by tests/fuzz/rosbag_fuzz.cpp, or by reading rosbag::Bag, which trusts the bag's lengths
// and offsets: each damage is one InputError naming the bag and the byte, before rosbag reads it.
TEST(BagImport, DamagedRecordsAreOneErrorBeforeRosbagReadsThem) {
  struct Case {
    std::string what, expected;
    std::function<void(std::string&)> damage;
  };
  const std::vector<Case> cases = {
      // The connections read, then a throw out of rosbag::Bag's constructor leaked them.
      {"cut in the chunk infos", "runs past the end",
       [](std::string& bag) { bag.resize(bag.size() - 10); }},
      // rosbag allocated the connection header's length (here 2 GB) before reading it.
      {"connection header length", "connection header of 2147483647 bytes",
       [](std::string& bag) {
         const size_t at = indexPos(bag);
         setU32(bag, at + 4 + u32At(bag, at), 0x7fffffff);
       }},
      // The uncompressed size a chunk claims was allocated (up to 4 GB).
      {"chunk size", "chunk of more than 1 GiB",
       [](std::string& bag) {
         setU32(bag, bag.find(std::string("\x09\0\0\0size=", 9)) + 9, 0xfffffff0);
       }},
      // An index entry's offset was read in the decompressed chunk unchecked.
      {"index entry offset", "a message (index entry) beyond the end",
       [](std::string& bag) {
         // The first index record follows the first chunk. Its header's last field is "ver",
         // then come the data length and the entries (time, offset).
         const size_t ver = bag.find("ver=", bag.find(std::string("op=\x04", 4)));
         setU32(bag, ver + 4 + 4 + 4 + 8, 0x7fffffff);
       }},
  };
  for (const Case& c : cases) {
    test::TempDir dir;
    writeBag(dir.file("in.bag"), "mono8", rosbag::compression::LZ4);
    std::string bytes = test::readFile(dir.file("in.bag"));
    c.damage(bytes);
    std::ofstream(dir.file("in.bag"), std::ios::binary) << bytes;
    const std::string error = importError(options(dir));
    EXPECT_EQ(error.rfind(dir.file("in.bag") + ":", 0), 0u) << c.what << ": " << error;
    EXPECT_NE(error.find("byte "), std::string::npos) << c.what << ": " << error;
    EXPECT_NE(error.find(c.expected), std::string::npos) << c.what << ": " << error;
  }
}

TEST(BagImport, ImageDataLongerThanItsMessageIsOneError) {
  // Deserializing allocated the pixel array's length (here 4 GB) before finding it too long.
  test::TempDir dir;
  writeBag(dir.file("in.bag"), "mono8", rosbag::compression::Uncompressed);
  std::string bytes = test::readFile(dir.file("in.bag"));
  const std::string pixels = std::string("\0\x0c\0\0", 4) + std::string(4, '\xc8');  // 3072 x 200
  setU32(bytes, bytes.find(pixels), 0xffffff00);
  std::ofstream(dir.file("in.bag"), std::ios::binary) << bytes;
  const std::string error = importError(options(dir));
  EXPECT_NE(error.find("/cam0/image_raw message 1: image data of 4294967040 bytes in a message of"),
            std::string::npos)
      << error;
}

TEST(BagImport, PresetsCarryAUsableCalibration) {
  for (const std::string name : {"rpvio-sim", "viode", "openloris", "advio"}) {
    const BagPreset preset = bagPreset(name);
    ASSERT_TRUE(preset.calibration) << name;
    const Calibration& c = *preset.calibration;
    const Eigen::Matrix3d R = c.T_BC.linear();
    EXPECT_LT((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 1e-12) << name;
    EXPECT_NEAR(R.determinant(), 1, 1e-12) << name;
    for (double density : {c.imu.accel_noise_density, c.imu.gyro_noise_density,
                           c.imu.accel_random_walk, c.imu.gyro_random_walk})
      EXPECT_TRUE(density > 0 && std::isfinite(density)) << name;
    EXPECT_GT(c.imu.gravity, 9.7) << name;
    // The principal point inside the image.
    EXPECT_TRUE(c.camera.cx > 0 && c.camera.cx < c.camera.width) << name;
    EXPECT_TRUE(c.camera.cy > 0 && c.camera.cy < c.camera.height) << name;
  }
  // OpenLORIS' D435i: the colour camera 2 cm from the IMU, axes nearly aligned.
  const Calibration openloris = *bagPreset("openloris").calibration;
  EXPECT_EQ(openloris.camera.width, 848);
  EXPECT_NEAR(openloris.T_BC.translation().norm(), 0.0237, 1e-3);
  EXPECT_GT(openloris.T_BC.linear().trace(), 2.99);
}

}  // namespace
}  // namespace rpvio

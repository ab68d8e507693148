// Fuzzes the ROS1 bag import (rosbag_io/bag_import.h) the way `rpvio-import rosbag` runs it: the
// bag's records, chunks (plain, LZ4, BZ2), connections and message bodies (sensor_msgs/Image and
// Imu, nav_msgs/Odometry, geometry_msgs/PoseStamped), in two topic layouts: image, mono8 mask ids,
// one IMU topic and a ground-truth topic; or image, class-colour segmentation, gyroscope and
// accelerometer apart. The import must succeed or throw InputError. Its rawlog, images and
// calib.ini go to the input's per-process folder, removed after each input.
#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "rosbag_io/bag_import.h"
#include "tests/fuzz/fuzz_util.h"

using namespace rpvio;

namespace {

BagImportOptions options(const fuzz::InputFile& bag, const BagTopics& topics) {
  BagImportOptions opt;
  opt.bag_path = bag.path();
  opt.output_rawlog = (std::filesystem::path(bag.path()).parent_path() / "out.rawlog").string();
  opt.topics = topics;
  return opt;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fuzz::InputFile bag(data, size, "in.bag");
  fuzz::readExpectingOnlyInputError([&] {
    importBag(options(bag, {"/cam", "/imu", "/mask", "/gt", ""}));
  });
  fuzz::readExpectingOnlyInputError([&] {
    BagImportOptions opt = options(bag, {"/cam", "/gyro", "/seg", "", "/accel"});
    opt.mask_colours = bagPreset("viode").mask_colours;
    opt.imu_rate_hz = 100;
    importBag(opt);
  });
  return 0;
}

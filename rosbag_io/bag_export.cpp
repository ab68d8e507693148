#include "rosbag_io/bag_export.h"

#include <rosbag/bag.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/Imu.h>

#include <filesystem>

#include "common/atomic_file.h"
#include "common/input_error.h"
#include "rawlog_io/rawlog_labels.h"
#include "rawlog_io/rawlog_reader.h"
#include "rawlog_io/trajectory_io.h"
#include "rosbag_io/ros_image.h"
#include "rosbag_io/stamps.h"

namespace fs = std::filesystem;

namespace rpvio {
namespace {

/// A bag refuses record times before ros::TIME_MIN (a sequence starting at t = 0); the header
/// stamps keep the exact times.
ros::Time recordTime(const ros::Time& stamp) { return std::max(stamp, ros::TIME_MIN); }

sensor_msgs::Imu imuMessage(const ImuSample& s, const ros::Time& stamp) {
  sensor_msgs::Imu msg;
  msg.header.stamp = stamp;
  msg.orientation_covariance[0] = -1;  // REP 145: no orientation estimate
  msg.angular_velocity.x = s.gyro.x();
  msg.angular_velocity.y = s.gyro.y();
  msg.angular_velocity.z = s.gyro.z();
  msg.linear_acceleration.x = s.accel.x();
  msg.linear_acceleration.y = s.accel.y();
  msg.linear_acceleration.z = s.accel.z();
  return msg;
}

/// Plane ids as they are, everything else (our 0: not a plane, 255: nothing) 0.
cv::Mat planeIds(const cv::Mat& labels) {
  cv::Mat ids = labels.clone();
  ids.setTo(0, labels == 255);
  return ids;
}

}  // namespace

BagExportCounts exportBag(const std::string& rawlog_path, const std::string& bag_path,
                          const std::function<void(size_t)>& progress) {
  const fs::path bag_dir = existingOutputFolder(bag_path);
  const fs::path calib = fs::path(rawlog_path).parent_path() / "calib.ini";
  if (!fs::is_regular_file(calib))
    throw InputError(calib.string(), "", "missing (the rawlog's calibration is exported too)");
  BagExportCounts counts;
  Trajectory groundtruth;
  const std::string temporary = temporaryPathFor(bag_path);
  try {
    RawlogReader reader(rawlog_path);
    rosbag::Bag bag(temporary, rosbag::bagmode::Write);
    bag.setCompression(rosbag::compression::LZ4);
    for (auto obs = reader.next(); obs; obs = reader.next()) {
      const std::string& label = obs->sensorLabel;
      const std::string where = "entry " + std::to_string(reader.entriesRead());
      if (label == labels::kImu) {
        const auto* imu = dynamic_cast<const mrpt::obs::CObservationIMU*>(obs.get());
        if (!imu) throw InputError(rawlog_path, where, "an IMU entry of another type");
        const ImuSample s = toImuSample(*imu, reader);
        const sensor_msgs::Imu msg = imuMessage(s, rosStamp(obs->timestamp));
        bag.write("/imu", recordTime(msg.header.stamp), msg);
        ++counts.imu;
      } else if (label == labels::kCamera || label == labels::kPlaneMask) {
        const auto* image = dynamic_cast<const mrpt::obs::CObservationImage*>(obs.get());
        if (!image) throw InputError(rawlog_path, where, "a " + label + " entry not an image");
        const cv::Mat pixels = loadGrayImage(*image, reader);
        const bool mask = label == labels::kPlaneMask;
        const sensor_msgs::Image msg =
            mono8RosImage(mask ? planeIds(pixels) : pixels, rosStamp(obs->timestamp));
        bag.write(mask ? "/mask" : "/image", recordTime(msg.header.stamp), msg);
        ++(mask ? counts.masks : counts.images);
      } else if (label == labels::kGroundTruth) {
        const auto* pose = dynamic_cast<const mrpt::obs::CObservationRobotPose*>(obs.get());
        if (!pose) throw InputError(rawlog_path, where, "a ground-truth entry not a pose");
        groundtruth.push_back(toStampedPose(*pose));
        ++counts.groundtruth;
      }
      if (progress && reader.entriesRead() % 2000 == 0) progress(reader.entriesRead());
    }
    bag.close();
    // Beside the bag, for `rpvio-import rosbag --preset rpvio-sim` (which takes groundtruth.txt
    // when it is there: an older one must not stay).
    if (!groundtruth.empty())
      writeTum((bag_dir / "groundtruth.txt").string(), groundtruth);
    else
      fs::remove(bag_dir / "groundtruth.txt");
    if (!fs::exists(bag_dir / "calib.ini") || !fs::equivalent(calib, bag_dir / "calib.ini"))
      fs::copy_file(calib, bag_dir / "calib.ini", fs::copy_options::overwrite_existing);
    fs::rename(temporary, bag_path);
  } catch (const rosbag::BagException& e) {
    fs::remove(temporary);
    throw InputError(bag_path, "", std::string("cannot write the bag: ") + e.what());
  } catch (...) {
    fs::remove(temporary);
    throw;
  }
  return counts;
}

}  // namespace rpvio

#pragma once
// Writes an rpvio rawlog as a ROS1 bag in the RP-VIO authors' simulated-warehouse layout, so that
// other systems (the original RP-VIO, VINS-Mono, OpenVINS) run on the same data: CAM0 → /image
// (mono8), PLANE_MASK → /mask (mono8, value = plane id, 0 = none: our 0 and 255 both become 0),
// IMU → /imu (sensor_msgs/Imu, no orientation), header stamps = the rawlog's times, LZ4 chunks.
// Beside the bag: groundtruth.txt (TUM, when the rawlog has GROUND_TRUTH) and the rawlog's
// calib.ini, which `rpvio-import rosbag --calib` takes back.
#include <functional>
#include <string>

namespace rpvio {

struct BagExportCounts {
  size_t images = 0, masks = 0, imu = 0, groundtruth = 0;
};

/// Throws InputError on a bad rawlog; nothing appears under `bag_path` unless the export
/// completes.
BagExportCounts exportBag(const std::string& rawlog_path, const std::string& bag_path,
                          const std::function<void(size_t)>& progress = {});

}  // namespace rpvio

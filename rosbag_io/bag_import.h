#pragma once
// Converts a ROS1 bag into an rpvio rawlog + calib.ini (DESIGN.md §4), without ROS: an image
// topic → CAM0 (any encoding of ros_image.h, made grey), an optional mask topic → PLANE_MASK
// (mono8, value = plane id, 0 = none; paired with the image of identical header stamp), a
// sensor_msgs/Imu topic → IMU (optionally decimated by timestamp), an optional TUM file or
// nav_msgs/Odometry or geometry_msgs/PoseStamped topic → GROUND_TRUTH. Header stamps, not record
// times. Streams: only the IMU and the ground truth are held in memory, and images waiting for
// their mask.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "common/sensor_types.h"
#include "rosbag_io/ros_image.h"

namespace rpvio {

struct BagTopics {
  std::string image, imu, mask;  // mask "" = none
  std::string groundtruth;       // nav_msgs/Odometry or geometry_msgs/PoseStamped, "" = none
  // An accelerometer publishing apart from the gyroscope (`imu` then gives the angular velocity
  // only); merged into one stream, each sensor interpolated at the other's samples. "" = none.
  std::string accel;
};

/// What a dataset's bags contain: topics, calibration, IMU rate (docs/tools.md, rpvio-import).
struct BagPreset {
  BagTopics topics;
  std::optional<Calibration> calibration;  // none: --calib is required
  double imu_rate_hz = 0;                  // decimate to this rate; 0 = keep every sample
  std::string groundtruth_beside_bag;      // TUM file name looked for beside the bag
  std::vector<MaskColour> mask_colours;    // empty: masks are mono8 plane ids
};

/// "rpvio-sim" (the RP-VIO authors' simulated warehouse bags), "viode" (VIODE's simulated drone
/// bags, segmentation colours as planes), "openloris" (the official OpenLORIS-Scene bags' D435i:
/// separate accelerometer and gyroscope; the market scenes' calibration), "advio" (the RP-VIO
/// authors' ADVIO bags with masks; the iPhone calibration of sequences 1-12) or
/// "generic" (nothing preset). IMU noise: the RP-VIO authors' figures (imuNoiseFromVinsMono).
/// Throws std::invalid_argument on another name.
BagPreset bagPreset(const std::string& name);

struct BagImportOptions {
  std::string bag_path, output_rawlog;  // calib.ini is written beside the rawlog
  BagTopics topics;
  Calibration calibration;
  double imu_rate_hz = 0;
  double accel_scale = 1;        // the accelerations times this (a bag recorded in g: 9.80665)
  std::string groundtruth_file;  // TUM, optional
  std::vector<MaskColour> mask_colours;  // empty: masks are mono8 plane ids
};

struct BagImportCounts {
  size_t images = 0, masks = 0, imu = 0, groundtruth = 0;
  size_t unpaired_masks = 0;  // masks without an image of the same stamp: dropped
};

/// Throws InputError (bag + message position) on bad input: a missing topic (the message lists
/// the bag's topics), accelerations not in m/s^2 (median magnitude off gravity by 30 %), an
/// unsupported encoding, a mask of another size than its image, stamps going backwards. Nothing
/// appears under the output names unless the import completes.
BagImportCounts importBag(const BagImportOptions& options,
                          const std::function<void(size_t)>& progress = {});

}  // namespace rpvio

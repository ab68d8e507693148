#pragma once
// sensor_msgs/Image to and from OpenCV, by the message's `encoding`.
#include <sensor_msgs/Image.h>
#include <array>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace rpvio {

/// 8-bit grey image of a mono8, rgb8, bgr8, rgba8, bgra8 or mono16 (scaled by 1/256) message.
/// Throws InputError(file, where) on another encoding or a data size that does not match.
cv::Mat grayFromRosImage(const sensor_msgs::Image& msg, const std::string& file,
                         const std::string& where);
/// The labels of a mono8 message as they are. Throws InputError(file, where) otherwise.
cv::Mat labelsFromRosImage(const sensor_msgs::Image& msg, const std::string& file,
                           const std::string& where);
/// A semantic segmentation's class colour and the plane id it becomes.
struct MaskColour {
  std::array<uint8_t, 3> rgb;
  uint8_t plane_id;
};

/// Plane ids of an rgb8 or bgr8 segmentation: `colours` become their plane ids, every other
/// colour 0. Throws InputError(file, where) on another encoding.
cv::Mat labelsFromColours(const sensor_msgs::Image& msg, const std::vector<MaskColour>& colours,
                          const std::string& file, const std::string& where);
/// A mono8 message of an 8-bit single-channel image.
sensor_msgs::Image mono8RosImage(const cv::Mat& image, const ros::Time& stamp);

}  // namespace rpvio

#include "rosbag_io/ros_image.h"

#include <opencv2/imgproc.hpp>

#include "common/input_error.h"

namespace rpvio {
namespace {

/// The message's pixels as a cv::Mat of `type` (no copy), after checking the data's size.
cv::Mat pixels(const sensor_msgs::Image& msg, int type, const std::string& file,
               const std::string& where) {
  const size_t row_bytes = static_cast<size_t>(msg.width) * CV_ELEM_SIZE(type);
  if (msg.width == 0 || msg.height == 0 || msg.step < row_bytes ||
      msg.step % CV_ELEM_SIZE1(type) != 0 ||
      msg.data.size() < static_cast<size_t>(msg.step) * msg.height)
    throw InputError(file, where,
                     "image data of " + std::to_string(msg.data.size()) + " bytes does not hold " +
                         std::to_string(msg.width) + "x" + std::to_string(msg.height) + " " +
                         msg.encoding + " pixels");
  return cv::Mat(static_cast<int>(msg.height), static_cast<int>(msg.width), type,
                 const_cast<uint8_t*>(msg.data.data()), msg.step);
}

}  // namespace

cv::Mat grayFromRosImage(const sensor_msgs::Image& msg, const std::string& file,
                         const std::string& where) {
  const std::string& e = msg.encoding;
  cv::Mat gray;
  if (e == "mono8" || e == "8UC1") {
    gray = pixels(msg, CV_8UC1, file, where).clone();
  } else if (e == "rgb8" || e == "bgr8") {
    cv::cvtColor(pixels(msg, CV_8UC3, file, where), gray,
                 e == "rgb8" ? cv::COLOR_RGB2GRAY : cv::COLOR_BGR2GRAY);
  } else if (e == "rgba8" || e == "bgra8") {
    cv::cvtColor(pixels(msg, CV_8UC4, file, where), gray,
                 e == "rgba8" ? cv::COLOR_RGBA2GRAY : cv::COLOR_BGRA2GRAY);
  } else if (e == "mono16" || e == "16UC1") {
    if (msg.is_bigendian)
      throw InputError(file, where, "big-endian mono16 images are not supported");
    pixels(msg, CV_16UC1, file, where).convertTo(gray, CV_8U, 1.0 / 256);
  } else {
    throw InputError(
        file, where,
        "image encoding '" + e + "' is not supported (mono8, rgb8, bgr8, rgba8, bgra8, mono16)");
  }
  return gray;
}

cv::Mat labelsFromRosImage(const sensor_msgs::Image& msg, const std::string& file,
                           const std::string& where) {
  if (msg.encoding != "mono8" && msg.encoding != "8UC1")
    throw InputError(file, where,
                     "a plane mask must be mono8 (plane id per pixel), not '" + msg.encoding + "'");
  return pixels(msg, CV_8UC1, file, where).clone();
}

cv::Mat labelsFromColours(const sensor_msgs::Image& msg, const std::vector<MaskColour>& colours,
                          const std::string& file, const std::string& where) {
  if (msg.encoding != "rgb8" && msg.encoding != "bgr8")
    throw InputError(
        file, where,
        "a segmentation must be rgb8 or bgr8 (class colours), not '" + msg.encoding + "'");
  const cv::Mat image = pixels(msg, CV_8UC3, file, where);
  const bool rgb = msg.encoding == "rgb8";
  cv::Mat labels(image.size(), CV_8UC1, cv::Scalar(0));
  for (const MaskColour& c : colours) {
    const cv::Vec3b colour =
        rgb ? cv::Vec3b(c.rgb[0], c.rgb[1], c.rgb[2]) : cv::Vec3b(c.rgb[2], c.rgb[1], c.rgb[0]);
    cv::Mat is_class;
    cv::inRange(image, colour, colour, is_class);
    labels.setTo(c.plane_id, is_class);
  }
  return labels;
}

sensor_msgs::Image mono8RosImage(const cv::Mat& image, const ros::Time& stamp) {
  sensor_msgs::Image msg;
  msg.header.stamp = stamp;
  msg.height = static_cast<uint32_t>(image.rows);
  msg.width = static_cast<uint32_t>(image.cols);
  msg.encoding = "mono8";
  msg.step = msg.width;
  msg.data.resize(static_cast<size_t>(msg.step) * msg.height);
  for (int v = 0; v < image.rows; ++v)
    std::copy(image.ptr<uint8_t>(v), image.ptr<uint8_t>(v) + image.cols,
              msg.data.begin() + static_cast<ptrdiff_t>(v) * msg.step);
  return msg;
}

}  // namespace rpvio

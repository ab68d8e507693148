#include "rosbag_io/bag_import.h"

#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/Imu.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "common/atomic_file.h"
#include "common/input_error.h"
#include "rawlog_io/advio_import.h"
#include "rawlog_io/calibration.h"
#include "rawlog_io/imu_streams.h"
#include "rawlog_io/interleaved_writing.h"
#include "rawlog_io/rawlog_writer.h"
#include "rawlog_io/trajectory_io.h"
#include "rosbag_io/bag_records.h"
#include "rosbag_io/ros_image.h"
#include "rosbag_io/stamps.h"

namespace fs = std::filesystem;

namespace rpvio {
namespace {

// Images wait at most this many later images for their mask (in record order) before they are
// written without one.
constexpr size_t kMaxWaitingImages = 8;

std::string timeText(const ros::Time& t) {
  char text[48];
  std::snprintf(text, sizeof text, "t=%u.%09u s", t.sec, t.nsec);
  return text;
}

/// Every topic of the bag with its message type, for error messages.
std::string topicList(const rosbag::Bag& bag) {
  rosbag::View view(bag);
  std::string list;
  for (const rosbag::ConnectionInfo* c : view.getConnections())
    if (list.find(c->topic + " (") == std::string::npos)
      list += (list.empty() ? "" : ", ") + c->topic + " (" + c->datatype + ")";
  return list.empty() ? "no topics" : list;
}

/// InputError unless the bag has messages on `topic`, all of type `type` (or `other_type`).
void requireTopic(const rosbag::Bag& bag, const std::string& path, const std::string& topic,
                  const std::string& type, const std::string& other_type = "") {
  rosbag::View view(bag, rosbag::TopicQuery(topic));
  if (view.size() == 0)
    throw InputError(path, "",
                     "no messages on " + topic + " (the bag has: " + topicList(bag) + ")");
  for (const rosbag::ConnectionInfo* c : view.getConnections())
    if (c->datatype != type && c->datatype != other_type)
      throw InputError(path, "",
                       topic + " carries " + c->datatype + ", not " + type +
                           (other_type.empty() ? "" : " or " + other_type));
}

/// The message as a sensor_msgs/Image, its pixel array first checked to fit in the message:
/// deserializing trusts the array's length (a damaged one allocated up to 4 GB).
sensor_msgs::ImagePtr instantiateImage(const rosbag::MessageInstance& m, const std::string& path,
                                       const std::string& where) {
  if (!m.isType<sensor_msgs::Image>()) throw InputError(path, where, "not a sensor_msgs/Image");
  std::vector<uint8_t> bytes(m.size());
  ros::serialization::OStream out(bytes.data(), static_cast<uint32_t>(bytes.size()));
  m.write(out);
  ros::serialization::IStream in(bytes.data(), static_cast<uint32_t>(bytes.size()));
  sensor_msgs::Image fields;  // all but the pixels
  ros::serialization::deserialize(in, fields.header);
  in >> fields.height >> fields.width >> fields.encoding >> fields.is_bigendian >> fields.step;
  uint32_t pixel_bytes;
  in >> pixel_bytes;
  if (pixel_bytes > in.getLength())
    throw InputError(path, where,
                     "image data of " + std::to_string(pixel_bytes) + " bytes in a message of " +
                         std::to_string(bytes.size()));
  return m.instantiate<sensor_msgs::Image>();
}

/// Every sample of a sensor_msgs/Imu topic, stamps strictly increasing.
std::vector<ImuSample> readImuTopic(const rosbag::Bag& bag, const std::string& path,
                                    const std::string& topic) {
  std::vector<ImuSample> samples;
  size_t index = 0;
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery(topic))) {
    const std::string where = topic + " message " + std::to_string(++index);
    const auto msg = m.instantiate<sensor_msgs::Imu>();
    if (!msg) throw InputError(path, where, "not a sensor_msgs/Imu");
    ImuSample s;
    s.t = rawlogSeconds(msg->header.stamp);
    if (!samples.empty() && !(s.t > samples.back().t))
      throw InputError(path, where,
                       "stamp " + timeText(msg->header.stamp) + " is not after the previous one");
    s.gyro = {msg->angular_velocity.x, msg->angular_velocity.y, msg->angular_velocity.z};
    s.accel = {msg->linear_acceleration.x, msg->linear_acceleration.y, msg->linear_acceleration.z};
    if (!s.gyro.allFinite() || !s.accel.allFinite())
      throw InputError(path, where, "angular velocity or acceleration is not finite");
    samples.push_back(s);
  }
  return samples;
}

/// InputError unless the accelerations' median magnitude is about gravity: sensor_msgs/Imu is in
/// m/s^2, and a recorder that wrote g (or nothing) would otherwise give a run that cannot start.
void requireAccelerationInMetresPerSecondSquared(const std::vector<ImuSample>& imu, double gravity,
                                                 const std::string& path,
                                                 const std::string& topic) {
  if (imu.empty())
    throw InputError(path, topic, "no IMU sample (the gyroscope and accelerometer do not overlap)");
  std::vector<Eigen::Vector3d> accel;
  accel.reserve(imu.size());
  for (const ImuSample& s : imu) accel.push_back(s.accel);
  const double median = medianNorm(accel);
  if (std::abs(median / gravity - 1) > 0.3) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "median |linear_acceleration| is %.3f, not about gravity (%.2f m/s^2): "
                  "sensor_msgs/Imu is in m/s^2 (in g? --accel-scale 9.80665)",
                  median, gravity);
    throw InputError(path, topic, text);
  }
}

/// Ground-truth body poses from a nav_msgs/Odometry or geometry_msgs/PoseStamped topic.
Trajectory readGroundTruthTopic(const rosbag::Bag& bag, const std::string& path,
                                const std::string& topic) {
  Trajectory poses;
  size_t index = 0;
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery(topic))) {
    const std::string where = topic + " message " + std::to_string(++index);
    std_msgs::Header header;
    geometry_msgs::Pose p;
    if (const auto odometry = m.instantiate<nav_msgs::Odometry>()) {
      header = odometry->header;
      p = odometry->pose.pose;
    } else if (const auto stamped = m.instantiate<geometry_msgs::PoseStamped>()) {
      header = stamped->header;
      p = stamped->pose;
    } else {
      throw InputError(path, where, "not a nav_msgs/Odometry or geometry_msgs/PoseStamped");
    }
    StampedPose pose;
    pose.t = rawlogSeconds(header.stamp);
    if (!poses.empty() && !(pose.t > poses.back().t))
      throw InputError(path, where,
                       "stamp " + timeText(header.stamp) + " is not after the previous one");
    pose.p = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
    pose.q = Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z);
    if (!pose.p.allFinite() || !(std::abs(pose.q.norm() - 1) < 1e-3))
      throw InputError(path, where, "position not finite or orientation not a unit quaternion");
    pose.q.normalize();
    poses.push_back(pose);
  }
  return poses;
}

/// A distortion-free camera looking along body x (camera z = body x, x = body y, y = body z), as
/// the RP-VIO authors' configs mount it in their simulated datasets.
Calibration presetCalibration(int width, int height, double f, double cx, double cy) {
  Calibration c;
  c.camera.width = width;
  c.camera.height = height;
  c.camera.fx = c.camera.fy = f;
  c.camera.cx = cx;
  c.camera.cy = cy;
  c.T_BC.linear() << 0, 0, 1,  //
      1, 0, 0,                 //
      0, 1, 0;
  return c;
}

/// OpenLORIS-Scene's D435i colour camera and IMU (the market scenes), as the RP-VIO authors'
/// ol_market1_config.yaml gives the dataset's calibration.
Calibration openlorisCalibration() {
  Calibration c;
  c.camera.width = 848;
  c.camera.height = 480;
  c.camera.fx = 616.802734375;
  c.camera.fy = 616.7510375976562;
  c.camera.cx = 435.0341796875;
  c.camera.cy = 242.90113830566406;
  Eigen::Matrix3d R;  // imu^R_cam, printed to 9 digits: made orthonormal
  R << 9.99946615e-01, 5.27582295e-03, 8.88440156e-03,  //
      -5.28478975e-03, 9.99985549e-01, 9.86100143e-04,  //
      -8.87907068e-03, -1.03299969e-03, 9.99960047e-01;
  c.T_BC.linear() = nearestRotation(R);
  c.T_BC.translation() = Eigen::Vector3d(0.020096886903, -0.00507855368778, -0.0115051260218);
  c.imu = imuNoiseFromVinsMono(0.0163, 0.0032, 0.0049, 0.0004, 200, 9.81007);
  return c;
}

}  // namespace

BagPreset bagPreset(const std::string& name) {
  BagPreset preset;
  if (name == "generic") return preset;
  if (name == "viode") {
    preset.topics = {"/cam0/image_raw", "/imu0", "/cam0/segmentation", "/odometry", ""};
    preset.calibration = presetCalibration(752, 480, 376, 376, 240);
    // The authors' viode_config.yaml figures (for VIODE's 200 Hz IMU).
    preset.calibration->imu = imuNoiseFromVinsMono(0.2, 0.05, 0.02, 4.0e-5, 200, 9.81007);
    preset.mask_colours = {{{179, 217, 227}, 1}, {{167, 128, 147}, 2}, {{235, 152, 233}, 3}};
    return preset;  // ground, wall, road
  }
  if (name == "openloris") {  // masks: --mask-topic (the RP-VIO authors': /planes/segments_crf)
    preset.topics = {"/d400/color/image_raw", "/d400/gyro/sample", "", "/gt", "/d400/accel/sample"};
    preset.imu_rate_hz = 200;
    preset.calibration = openlorisCalibration();
    return preset;
  }
  if (name == "advio") {  // the RP-VIO authors' ADVIO bags (masks added), sequences 1-12
    preset.topics = {"/cam0/image_raw", "/imu0", "/cam0/mask", "", ""};
    preset.calibration = advioCalibration(12);
    return preset;
  }
  if (name != "rpvio-sim")
    throw std::invalid_argument("unknown preset '" + name +
                                "' (rpvio-sim, viode, openloris, advio or generic)");
  preset.topics = {"/image", "/imu", "/mask", "", ""};
  Calibration c = presetCalibration(640, 480, 320, 320, 240);
  c.T_BC.translation() = Eigen::Vector3d(0.5, 0, 0);
  c.time_offset = -0.0308;  // s, t_imu = t_cam + offset
  // The authors' rpvio_sim_config.yaml figures (for the 200 Hz kept here).
  c.imu = imuNoiseFromVinsMono(0.074427240, 0.002759607, 3.9471004e-7, 3.1538983e-8, 200, 9.80665);
  preset.calibration = c;
  preset.imu_rate_hz = 200;
  preset.groundtruth_beside_bag = "groundtruth.txt";
  return preset;
}

BagImportCounts importBag(const BagImportOptions& opt,
                          const std::function<void(size_t)>& progress) {
  const std::string& path = opt.bag_path;
  if (!fs::is_regular_file(path)) throw InputError(path, "", "file not found");
  const fs::path out_dir = existingOutputFolder(opt.output_rawlog);
  BagImportCounts counts;
  try {
    checkBagRecords(path);  // rosbag::Bag trusts every length and offset in the file
    // Opened apart from constructing: when open() throws on a damaged bag, ~Bag still frees the
    // connections it had read (a throwing constructor leaks them).
    rosbag::Bag bag;
    bag.open(path, rosbag::bagmode::Read);
    requireTopic(bag, path, opt.topics.image, "sensor_msgs/Image");
    requireTopic(bag, path, opt.topics.imu, "sensor_msgs/Imu");
    if (!opt.topics.mask.empty()) requireTopic(bag, path, opt.topics.mask, "sensor_msgs/Image");
    if (!opt.topics.groundtruth.empty())
      requireTopic(bag, path, opt.topics.groundtruth, "nav_msgs/Odometry",
                   "geometry_msgs/PoseStamped");
    if (!opt.topics.accel.empty()) requireTopic(bag, path, opt.topics.accel, "sensor_msgs/Imu");
    std::vector<ImuSample> imu = decimateImu(
        opt.topics.accel.empty() ? readImuTopic(bag, path, opt.topics.imu)
                                 : mergeSplitImu(readImuTopic(bag, path, opt.topics.imu),
                                                 readImuTopic(bag, path, opt.topics.accel)),
        opt.imu_rate_hz);
    for (ImuSample& sample : imu) sample.accel *= opt.accel_scale;
    requireAccelerationInMetresPerSecondSquared(
        imu, opt.calibration.imu.gravity, path,
        opt.topics.accel.empty() ? opt.topics.imu : opt.topics.accel);
    const Trajectory gt = !opt.groundtruth_file.empty() ? readTum(opt.groundtruth_file)
                          : !opt.topics.groundtruth.empty()
                              ? readGroundTruthTopic(bag, path, opt.topics.groundtruth)
                              : Trajectory{};

    RawlogWriter writer(opt.output_rawlog, opt.calibration);
    InterleavedSensorWriter sensors(writer, imu, gt);
    double last_image_t = -INFINITY;
    auto writeImage = [&](const ros::Time& stamp, const cv::Mat& image, const cv::Mat* mask) {
      const double t = rawlogSeconds(stamp);
      if (t <= last_image_t)
        throw InputError(path, opt.topics.image + " at " + timeText(stamp),
                         "image stamps go backwards or repeat (the previous one is not earlier)");
      last_image_t = t;
      sensors.writeUntil(t);
      writer.addImage(t, image);
      ++counts.images;
      if (!mask) return;
      if (mask->size() != image.size())
        throw InputError(path, opt.topics.mask + " at " + timeText(stamp),
                         "mask " + std::to_string(mask->cols) + "x" + std::to_string(mask->rows) +
                             " differs from its image " + std::to_string(image.cols) + "x" +
                             std::to_string(image.rows));
      writer.addMask(t, *mask);
      ++counts.masks;
    };
    // Images and masks in record order, paired by identical header stamp.
    std::map<ros::Time, cv::Mat> waiting_images, waiting_masks;
    auto writeImagesBefore = [&](const ros::Time& stamp) {
      while (!waiting_images.empty() && waiting_images.begin()->first < stamp) {
        writeImage(waiting_images.begin()->first, waiting_images.begin()->second, nullptr);
        waiting_images.erase(waiting_images.begin());
      }
    };
    std::vector<std::string> topics = {opt.topics.image};
    if (!opt.topics.mask.empty()) topics.push_back(opt.topics.mask);
    size_t done = 0, image_index = 0, mask_index = 0;
    for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery(topics))) {
      const bool is_image = m.getTopic() == opt.topics.image;
      const std::string where =
          m.getTopic() + " message " + std::to_string(is_image ? ++image_index : ++mask_index);
      const auto msg = instantiateImage(m, path, where);
      const ros::Time stamp = msg->header.stamp;
      if (is_image) {
        cv::Mat image = grayFromRosImage(*msg, path, where);
        if (opt.topics.mask.empty()) {
          writeImage(stamp, image, nullptr);
        } else if (const auto mask = waiting_masks.find(stamp); mask != waiting_masks.end()) {
          writeImagesBefore(stamp);
          writeImage(stamp, image, &mask->second);
          waiting_masks.erase(mask);
        } else if (!waiting_images.emplace(stamp, image).second) {
          throw InputError(path, where, "a second image stamped " + timeText(stamp));
        }
      } else {
        cv::Mat mask = opt.mask_colours.empty()
                           ? labelsFromRosImage(*msg, path, where)
                           : labelsFromColours(*msg, opt.mask_colours, path, where);
        if (const auto image = waiting_images.find(stamp); image != waiting_images.end()) {
          writeImagesBefore(stamp);
          writeImage(stamp, image->second, &mask);
          waiting_images.erase(stamp);
        } else {
          waiting_masks[stamp] = mask;
        }
      }
      while (waiting_images.size() > kMaxWaitingImages)
        writeImagesBefore(std::next(waiting_images.begin())->first);
      while (waiting_masks.size() > kMaxWaitingImages) {
        waiting_masks.erase(waiting_masks.begin());
        ++counts.unpaired_masks;
      }
      if (progress && ++done % 500 == 0) progress(done);
    }
    writeImagesBefore(ros::TIME_MAX);
    counts.unpaired_masks += waiting_masks.size();
    sensors.writeUntil(INFINITY);
    counts.imu = sensors.imuWritten();
    counts.groundtruth = sensors.groundTruthWritten();
    writer.close();  // then calib.ini: nothing is left behind if the rawlog fails
    saveCalibration((out_dir / "calib.ini").string(), opt.calibration);
  } catch (const rosbag::BagException& e) {
    throw InputError(path, "", std::string("not a readable ROS1 bag: ") + e.what());
  } catch (const ros::Exception& e) {  // a message body shorter than its type (truncated)
    throw InputError(path, "", std::string("a message cannot be read: ") + e.what());
  }
  return counts;
}

}  // namespace rpvio

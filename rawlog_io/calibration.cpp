#include "rawlog_io/calibration.h"

#include <Eigen/SVD>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>

#include "common/atomic_file.h"
#include "common/ini_file.h"
#include "common/input_error.h"
#include "common/input_file.h"

namespace rpvio {
namespace {

const char* modelName(DistortionModel m) {
  switch (m) {
    case DistortionModel::RadTan:
      return "radtan";
    case DistortionModel::Equidistant:
      return "equidistant";
    default:
      return "none";
  }
}

/// [camera] width or height: a whole number of pixels, positive and small enough for an int.
int pixelCount(const IniFile& ini, const std::string& key) {
  const double n = ini.number("camera", key);
  if (!(n >= 1 && n <= std::numeric_limits<int>::max()) || n != std::floor(n))
    throw InputError(ini.path(), "line " + std::to_string(ini.line("camera", key)),
                     "'" + key + "' must be a positive whole number of pixels");
  return static_cast<int>(n);
}

}  // namespace

Calibration loadCalibration(const std::string& path) {
  requireRegularFile(path, "calibration file");
  const IniFile ini(path);
  Calibration c;
  c.camera.width = pixelCount(ini, "width");
  c.camera.height = pixelCount(ini, "height");
  c.camera.fx = ini.number("camera", "fx");
  c.camera.fy = ini.number("camera", "fy");
  c.camera.cx = ini.number("camera", "cx");
  c.camera.cy = ini.number("camera", "cy");
  if (c.camera.fx <= 0 || c.camera.fy <= 0)
    throw InputError(path, "[camera]", "focal lengths must be positive");
  const std::string model = ini.text("camera", "distortion_model");
  if (model == "radtan") {
    c.camera.model = DistortionModel::RadTan;
  } else if (model == "equidistant") {
    c.camera.model = DistortionModel::Equidistant;
  } else if (model != "none") {
    throw InputError(path, "line " + std::to_string(ini.line("camera", "distortion_model")),
                     "distortion_model must be none, radtan or equidistant");
  }
  if (c.camera.model != DistortionModel::None) {
    const auto d = ini.numbers("camera", "distortion", 4);
    std::copy(d.begin(), d.end(), c.camera.distortion.begin());
  }
  const auto t = ini.numbers("T_BC", "translation", 3);
  const auto q = ini.numbers("T_BC", "rotation", 4);
  const Eigen::Quaterniond rotation(q[3], q[0], q[1], q[2]);
  if (std::abs(rotation.norm() - 1.0) > 1e-6)
    throw InputError(path, "line " + std::to_string(ini.line("T_BC", "rotation")),
                     "T_BC rotation is not a unit quaternion");
  c.T_BC = Eigen::Isometry3d::Identity();
  c.T_BC.linear() = rotation.normalized().toRotationMatrix();
  c.T_BC.translation() = Eigen::Vector3d(t[0], t[1], t[2]);
  c.time_offset = ini.numberOr("time", "offset", 0.0);
  c.camera_height = ini.numberOr("ground", "camera_height", 0.0);
  if (c.camera_height < 0)
    throw InputError(path, "line " + std::to_string(ini.line("ground", "camera_height")),
                     "camera_height must not be negative");
  c.imu.gyro_noise_density = ini.number("imu", "gyro_noise_density");
  c.imu.accel_noise_density = ini.number("imu", "accel_noise_density");
  c.imu.gyro_random_walk = ini.number("imu", "gyro_random_walk");
  c.imu.accel_random_walk = ini.number("imu", "accel_random_walk");
  c.imu.rate_hz = ini.number("imu", "rate_hz");
  c.imu.gravity = ini.number("imu", "gravity");
  return c;
}

void saveCalibration(const std::string& path, const Calibration& c) {
  writeFileAtomically(path, [&c](std::ostream& out) {
    out << std::setprecision(17);
    out << "# rpvio calibration (see rawlog_io/calibration.h for the meaning of every key)\n";
    out << "[camera]\nwidth = " << c.camera.width << "\nheight = " << c.camera.height
        << "\nfx = " << c.camera.fx << "\nfy = " << c.camera.fy << "\ncx = " << c.camera.cx
        << "\ncy = " << c.camera.cy << "\ndistortion_model = " << modelName(c.camera.model) << "\n";
    if (c.camera.model != DistortionModel::None)
      out << "distortion = " << c.camera.distortion[0] << " " << c.camera.distortion[1] << " "
          << c.camera.distortion[2] << " " << c.camera.distortion[3] << "\n";
    const Eigen::Quaterniond q(c.T_BC.linear());
    const Eigen::Vector3d& p = c.T_BC.translation();
    out << "\n[T_BC]\ntranslation = " << p.x() << " " << p.y() << " " << p.z()
        << "\nrotation = " << q.x() << " " << q.y() << " " << q.z() << " " << q.w() << "\n";
    out << "\n[time]\noffset = " << c.time_offset << "\n";
    out << "\n[imu]\ngyro_noise_density = " << c.imu.gyro_noise_density
        << "\naccel_noise_density = " << c.imu.accel_noise_density
        << "\ngyro_random_walk = " << c.imu.gyro_random_walk
        << "\naccel_random_walk = " << c.imu.accel_random_walk << "\nrate_hz = " << c.imu.rate_hz
        << "\ngravity = " << c.imu.gravity << "\n";
    if (c.camera_height > 0) out << "\n[ground]\ncamera_height = " << c.camera_height << "\n";
  });
}

Eigen::Matrix3d nearestRotation(const Eigen::Matrix3d& R) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return svd.matrixU() * svd.matrixV().transpose();
}

ImuNoise imuNoiseFromVinsMono(double acc_n, double gyr_n, double acc_w, double gyr_w,
                              double rate_hz, double gravity) {
  const double dt = 1.0 / rate_hz;
  ImuNoise n;
  n.accel_noise_density = acc_n * std::sqrt(dt / 2);
  n.gyro_noise_density = gyr_n * std::sqrt(dt / 2);
  n.accel_random_walk = acc_w * std::sqrt(dt);
  n.gyro_random_walk = gyr_w * std::sqrt(dt);
  n.rate_hz = rate_hz;
  n.gravity = gravity;
  return n;
}

}  // namespace rpvio

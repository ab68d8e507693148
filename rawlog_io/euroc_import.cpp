#include "rawlog_io/euroc_import.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <regex>
#include <sstream>

#include "common/atomic_file.h"
#include "common/input_error.h"
#include "common/input_file.h"
#include "common/text_table.h"
#include "rawlog_io/calibration.h"
#include "rawlog_io/euroc_csv.h"
#include "rawlog_io/nanosecond_stamps.h"
#include "rawlog_io/rawlog_writer.h"
#include "rawlog_io/trajectory_io.h"

namespace fs = std::filesystem;

namespace rpvio {
namespace {

/// The numbers of `key: [a, b, ...]` (possibly spanning lines) or `key: value`, in a sensor.yaml.
std::vector<double> yamlNumbers(const std::string& path, const std::string& key) {
  std::ifstream in = openInputFile(path);
  std::string line, collected;
  int line_no = 0, key_line = 0;
  bool in_list = false;
  while (std::getline(in, line)) {
    ++line_no;
    line = line.substr(0, line.find('#'));
    if (!in_list) {
      const auto pos = line.find(key + ":");  // the key, preceded by indentation only
      if (pos == std::string::npos || line.find_first_not_of(" \t") != pos) continue;
      key_line = line_no;
      collected = line.substr(pos + key.size() + 1);
      in_list = collected.find('[') != std::string::npos;
      if (!in_list) break;
    } else {
      collected += " " + line;
    }
    if (in_list && collected.find(']') != std::string::npos) break;
  }
  if (key_line == 0) throw InputError(path, "", "missing key '" + key + "'");
  std::string cleaned = collected;
  for (char& c : cleaned)
    if (c == '[' || c == ']' || c == ',') c = ' ';
  std::istringstream ss(cleaned);
  std::vector<double> values;
  for (std::string token; ss >> token;) values.push_back(parseFiniteNumber(token, path, key_line));
  return values;
}

std::vector<double> yamlNumbers(const std::string& path, const std::string& key, size_t count) {
  auto v = yamlNumbers(path, key);
  if (v.size() != count)
    throw InputError(path, "", "'" + key + "' needs " + std::to_string(count) + " numbers");
  return v;
}

std::string yamlWord(const std::string& path, const std::string& key) {
  std::ifstream in(path);
  std::regex pattern("^\\s*" + key + ":\\s*([A-Za-z_-]+)");
  std::smatch m;
  for (std::string line; std::getline(in, line);)
    if (std::regex_search(line, m, pattern)) return m[1];
  throw InputError(path, "", "missing key '" + key + "'");
}

Eigen::Isometry3d yamlTransform(const std::string& path) {
  // T_BS: { cols: 4, rows: 4, data: [16 numbers] } — the data list is the first list after T_BS.
  const auto d = yamlNumbers(path, "data", 16);
  Eigen::Matrix4d m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m(r, c) = d[4 * r + c];
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  // Re-orthonormalize the rotation (the files print ~12 digits); one written with every digit
  // (rpvio-export euroc) is kept as it is.
  const Eigen::Matrix3d R = m.topLeftCorner<3, 3>();
  T.linear() =
      (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-14 ? R : nearestRotation(R);
  T.translation() = m.topRightCorner<3, 1>();
  return T;
}

struct ImageEntry {
  double t;
  std::string file;
};

std::vector<ImageEntry> readImageList(const std::string& mav0) {
  const std::string csv = mav0 + "/cam0/data.csv";
  std::vector<ImageEntry> images;
  forEachTextRow(csv, [&](const std::vector<std::string>& f, int line) {
    if (f.size() != 2)
      throw InputError(csv, "line " + std::to_string(line), "expected 'timestamp,filename'");
    const double t = secondsOfNanosecondText(f[0], csv, line);
    if (!images.empty() && t <= images.back().t)
      throw InputError(csv, "line " + std::to_string(line), "timestamps not increasing");
    images.push_back({t, f[1]});
  });
  return images;
}

cv::Mat readGray(const std::string& file, const std::string& csv, size_t index) {
  // Checked first: OpenCV would print its own warning for a missing file.
  const cv::Mat img =
      fs::is_regular_file(file) ? cv::imread(file, cv::IMREAD_GRAYSCALE) : cv::Mat();
  if (img.empty())
    throw InputError(csv, "line " + std::to_string(index + 2),
                     "image missing or unreadable: " + file);
  return img;
}

}  // namespace

Calibration readEurocCalibration(const std::string& mav0) {
  const std::string cam_yaml = mav0 + "/cam0/sensor.yaml";
  const std::string imu_yaml = mav0 + "/imu0/sensor.yaml";
  Calibration c;
  const auto res = yamlNumbers(cam_yaml, "resolution", 2);
  const auto k = yamlNumbers(cam_yaml, "intrinsics", 4);
  c.camera.width = static_cast<int>(res[0]);
  c.camera.height = static_cast<int>(res[1]);
  c.camera.fx = k[0];
  c.camera.fy = k[1];
  c.camera.cx = k[2];
  c.camera.cy = k[3];
  const std::string model = yamlWord(cam_yaml, "distortion_model");
  if (model == "radial-tangential" || model == "radtan") {
    c.camera.model = DistortionModel::RadTan;
  } else if (model == "equidistant") {
    c.camera.model = DistortionModel::Equidistant;
  } else {
    throw InputError(cam_yaml, "", "unsupported distortion_model '" + model + "'");
  }
  const auto d = yamlNumbers(cam_yaml, "distortion_coefficients", 4);
  std::copy(d.begin(), d.end(), c.camera.distortion.begin());
  if (std::all_of(d.begin(), d.end(), [](double x) { return x == 0; }))
    c.camera.model = DistortionModel::None;  // the same camera, without the undistortion step
  // T_BC = T_B_imu^-1 * T_B_cam, both given in the MAV body frame.
  c.T_BC = yamlTransform(imu_yaml).inverse() * yamlTransform(cam_yaml);
  c.imu.gyro_noise_density = yamlNumbers(imu_yaml, "gyroscope_noise_density", 1)[0];
  c.imu.gyro_random_walk = yamlNumbers(imu_yaml, "gyroscope_random_walk", 1)[0];
  c.imu.accel_noise_density = yamlNumbers(imu_yaml, "accelerometer_noise_density", 1)[0];
  c.imu.accel_random_walk = yamlNumbers(imu_yaml, "accelerometer_random_walk", 1)[0];
  c.imu.rate_hz = yamlNumbers(imu_yaml, "rate_hz", 1)[0];
  return c;
}

EurocImportCounts importEuroc(const EurocImportOptions& opt,
                              const std::function<void(size_t, size_t)>& progress) {
  if (!fs::is_directory(opt.mav0_dir)) throw InputError(opt.mav0_dir, "", "folder not found");
  if (!opt.masks_dir.empty() && !fs::is_directory(opt.masks_dir))
    throw InputError(opt.masks_dir, "", "masks folder not found");
  const fs::path out_dir = existingOutputFolder(opt.output_rawlog);
  const Calibration calib = readEurocCalibration(opt.mav0_dir);
  const auto images = readImageList(opt.mav0_dir);
  const auto imu = readEurocImuCsv(opt.mav0_dir + "/imu0/data.csv");
  const Trajectory gt =
      opt.groundtruth_file.empty() ? Trajectory{} : readTrajectory(opt.groundtruth_file);

  const std::string calib_path = (out_dir / "calib.ini").string();
  const std::string cam_csv = opt.mav0_dir + "/cam0/data.csv";
  EurocImportCounts counts;
  RawlogWriter writer(opt.output_rawlog, calib);
  size_t i_img = 0, i_imu = 0, i_gt = 0;
  const size_t total = images.size() + imu.size() + gt.size();
  // Merge the three time-ordered streams; at equal stamps IMU first, then ground truth, then
  // images.
  while (i_img < images.size() || i_imu < imu.size() || i_gt < gt.size()) {
    const double t_img = i_img < images.size() ? images[i_img].t : INFINITY;
    const double t_imu = i_imu < imu.size() ? imu[i_imu].t : INFINITY;
    const double t_gt = i_gt < gt.size() ? gt[i_gt].t : INFINITY;
    if (t_imu <= t_gt && t_imu <= t_img) {
      writer.addImu(imu[i_imu++]);
      ++counts.imu;
    } else if (t_gt <= t_img) {
      writer.addGroundTruth(gt[i_gt++]);
      ++counts.groundtruth;
    } else {
      const ImageEntry& e = images[i_img];
      const cv::Mat img = readGray(opt.mav0_dir + "/cam0/data/" + e.file, cam_csv, i_img);
      writer.addImage(e.t, img);
      ++counts.images;
      if (!opt.masks_dir.empty()) {
        const std::string mask_file = opt.masks_dir + "/" + e.file;
        const cv::Mat mask = fs::is_regular_file(mask_file)
                                 ? cv::imread(mask_file, cv::IMREAD_UNCHANGED)
                                 : cv::Mat();
        if (mask.empty()) throw InputError(mask_file, "", "mask missing or unreadable");
        if (mask.type() != CV_8UC1)
          throw InputError(mask_file, "", "mask is not an 8-bit label image");
        if (mask.size() != img.size())
          throw InputError(mask_file, "",
                           "mask size " + std::to_string(mask.cols) + "x" +
                               std::to_string(mask.rows) + " differs from its image " +
                               std::to_string(img.cols) + "x" + std::to_string(img.rows));
        writer.addMask(e.t, mask);
        ++counts.masks;
      }
      ++i_img;
    }
    const size_t done = i_img + i_imu + i_gt;
    if (progress && (done % 2000 == 0 || done == total)) progress(done, total);
  }
  writer.close();  // then calib.ini: nothing is left behind if the rawlog fails
  saveCalibration(calib_path, calib);
  return counts;
}

}  // namespace rpvio

#include "rawlog_io/euroc_export.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "common/atomic_file.h"
#include "common/input_error.h"
#include "common/options.h"
#include "rawlog_io/calibration.h"
#include "rawlog_io/nanosecond_stamps.h"
#include "rawlog_io/rawlog_labels.h"
#include "rawlog_io/rawlog_reader.h"

namespace fs = std::filesystem;

namespace rpvio {
namespace {

std::string numbers(std::initializer_list<double> values) {
  std::string text;
  for (double v : values) text += (text.empty() ? "" : ", ") + exactNumberText(v);
  return text;
}

std::string matrixYaml(const Eigen::Isometry3d& T) {
  const Eigen::Matrix4d m = T.matrix();
  std::string rows;
  for (int r = 0; r < 4; ++r)
    rows += (r ? ",\n         " : "") + numbers({m(r, 0), m(r, 1), m(r, 2), m(r, 3)});
  return "T_BS:\n  cols: 4\n  rows: 4\n  data: [" + rows + "]\n";
}

void writeText(const fs::path& path, const std::string& text) {
  writeFileAtomically(path.string(), [&](std::ostream& out) { out << text; });
}

std::string cameraYaml(const Calibration& c, double rate_hz) {
  const CameraIntrinsics& k = c.camera;
  const std::array<double, 4>& d = k.distortion;
  return "%YAML:1.0\nsensor_type: camera\ncomment: exported by rpvio-export\n" +
         matrixYaml(c.T_BC) + "rate_hz: " + exactNumberText(rate_hz) + "\nresolution: [" +
         numbers({double(k.width), double(k.height)}) + "]\ncamera_model: pinhole\nintrinsics: [" +
         numbers({k.fx, k.fy, k.cx, k.cy}) + "]\ndistortion_model: " +
         (k.model == DistortionModel::Equidistant ? "equidistant" : "radial-tangential") +
         "\ndistortion_coefficients: [" + numbers({d[0], d[1], d[2], d[3]}) + "]\n";
}

std::string imuYaml(const ImuNoise& n) {
  return "%YAML:1.0\nsensor_type: imu\ncomment: exported by rpvio-export\n" +
         matrixYaml(Eigen::Isometry3d::Identity()) + "rate_hz: " + exactNumberText(n.rate_hz) +
         "\ngyroscope_noise_density: " + exactNumberText(n.gyro_noise_density) +
         "\ngyroscope_random_walk: " + exactNumberText(n.gyro_random_walk) +
         "\naccelerometer_noise_density: " + exactNumberText(n.accel_noise_density) +
         "\naccelerometer_random_walk: " + exactNumberText(n.accel_random_walk) + "\n";
}

struct TimedPose {
  int64_t ns;
  StampedPose pose;
};

std::string groundTruthCsv(const std::vector<TimedPose>& poses) {
  std::string text =
      "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], "
      "q_RS_z [], v_RS_R_x [m s^-1], v_RS_R_y [m s^-1], v_RS_R_z [m s^-1], b_w_RS_S_x [rad s^-1], "
      "b_w_RS_S_y [rad s^-1], b_w_RS_S_z [rad s^-1], b_a_RS_S_x [m s^-2], b_a_RS_S_y [m s^-2], "
      "b_a_RS_S_z [m s^-2]\n";
  for (size_t i = 0; i < poses.size(); ++i) {
    const size_t a = i > 0 ? i - 1 : i, b = i + 1 < poses.size() ? i + 1 : i;
    const double dt = poses[b].pose.t - poses[a].pose.t;
    const Eigen::Vector3d v = dt > 0 ? Eigen::Vector3d((poses[b].pose.p - poses[a].pose.p) / dt)
                                     : Eigen::Vector3d::Zero();
    const StampedPose& p = poses[i].pose;
    text += std::to_string(poses[i].ns) + ", " +
            numbers({p.p.x(), p.p.y(), p.p.z(), p.q.w(), p.q.x(), p.q.y(), p.q.z(), v.x(), v.y(),
                     v.z(), 0, 0, 0, 0, 0, 0}) +
            "\n";
  }
  return text;
}

}  // namespace

EurocExportCounts exportEuroc(const std::string& rawlog_path, const std::string& out_dir,
                              const std::function<void(size_t)>& progress) {
  fs::path out = fs::path(out_dir).lexically_normal();
  if (out.filename().empty()) out = out.parent_path();  // "DIR/"
  if (fs::exists(out)) throw InputError(out_dir, "", "exists (the export makes a new folder)");
  const fs::path calib_path = fs::path(rawlog_path).parent_path() / "calib.ini";
  const Calibration calib = loadCalibration(calib_path.string());
  // EuRoC has no camera-IMU time offset: the camera stamps go onto the IMU clock
  // (t_imu = t_cam + offset) and the folder describes a synchronized sensor.
  const int64_t camera_shift_ns = std::llround(calib.time_offset * 1e9);
  const fs::path tmp = out.string() + ".partial";
  fs::remove_all(tmp);
  const fs::path cam = tmp / "mav0" / "cam0", imu_dir = tmp / "mav0" / "imu0",
                 masks = tmp / "masks";
  EurocExportCounts counts;
  try {
    for (const fs::path& d : {cam / "data", imu_dir, masks}) fs::create_directories(d);
    RawlogReader reader(rawlog_path);
    std::ofstream images_csv(cam / "data.csv"), imu_csv(imu_dir / "data.csv");
    images_csv << "#timestamp [ns],filename\n";
    imu_csv << "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
               "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n";
    std::vector<TimedPose> groundtruth;
    int64_t first_image = 0, last_image = 0;
    for (auto obs = reader.next(); obs; obs = reader.next()) {
      const std::string& label = obs->sensorLabel;
      const bool camera = label == labels::kCamera || label == labels::kPlaneMask;
      const int64_t ns = toNanoseconds(obs->timestamp) + (camera ? camera_shift_ns : 0);
      const std::string where = "entry " + std::to_string(reader.entriesRead());
      if (label == labels::kImu) {
        const auto* imu_obs = dynamic_cast<const mrpt::obs::CObservationIMU*>(obs.get());
        if (!imu_obs) throw InputError(rawlog_path, where, "an IMU entry of another type");
        const ImuSample s = toImuSample(*imu_obs, reader);
        imu_csv << ns << ","
                << numbers(
                       {s.gyro.x(), s.gyro.y(), s.gyro.z(), s.accel.x(), s.accel.y(), s.accel.z()})
                << "\n";
        ++counts.imu;
      } else if (camera) {
        const auto* image = dynamic_cast<const mrpt::obs::CObservationImage*>(obs.get());
        if (!image) throw InputError(rawlog_path, where, "a " + label + " entry not an image");
        const cv::Mat pixels = loadGrayImage(*image, reader);
        const bool mask = label == labels::kPlaneMask;
        const fs::path file = (mask ? masks : cam / "data") / (std::to_string(ns) + ".png");
        if (!cv::imwrite(file.string(), pixels))
          throw std::runtime_error(file.string() + ": cannot write");
        if (mask) {
          ++counts.masks;
        } else {
          images_csv << ns << "," << ns << ".png\n";
          if (counts.images++ == 0) first_image = ns;
          last_image = ns;
        }
      } else if (label == labels::kGroundTruth) {
        const auto* pose = dynamic_cast<const mrpt::obs::CObservationRobotPose*>(obs.get());
        if (!pose) throw InputError(rawlog_path, where, "a ground-truth entry not a pose");
        groundtruth.push_back({ns, toStampedPose(*pose)});
        ++counts.groundtruth;
      }
      if (progress && reader.entriesRead() % 2000 == 0) progress(reader.entriesRead());
    }
    if (!images_csv || !imu_csv) throw std::runtime_error(out_dir + ": cannot write the CSVs");
    const double camera_rate =
        counts.images > 1 ? (counts.images - 1) / ((last_image - first_image) * 1e-9) : 0;
    writeText(cam / "sensor.yaml", cameraYaml(calib, camera_rate));
    writeText(imu_dir / "sensor.yaml", imuYaml(calib.imu));
    if (!groundtruth.empty()) {
      fs::create_directories(tmp / "mav0" / "state_groundtruth_estimate0");
      writeText(tmp / "mav0" / "state_groundtruth_estimate0" / "data.csv",
                groundTruthCsv(groundtruth));
    }
    if (counts.masks == 0) fs::remove(masks);
    fs::rename(tmp, out);
  } catch (...) {
    fs::remove_all(tmp);
    throw;
  }
  return counts;
}

}  // namespace rpvio

#include "rawlog_io/advio_import.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <regex>
#include <stdexcept>

#include "common/atomic_file.h"
#include "common/input_error.h"
#include "common/text_table.h"
#include "rawlog_io/calibration.h"
#include "rawlog_io/imu_streams.h"
#include "rawlog_io/interleaved_writing.h"
#include "rawlog_io/rawlog_writer.h"

namespace fs = std::filesystem;

namespace rpvio {
namespace {

constexpr double kStandardGravity = 9.80665;  // m/s^2, CoreMotion's "g"

/// One of ADVIO's four recording batches (the dataset's calibration/README.md and yaml files).
struct AdvioBatch {
  int first_sequence, last_sequence;
  double fx, fy, cx, cy;
  std::array<double, 4> radtan;           // k1 k2 p1 p2
  Eigen::Vector3d accel_bias, gyro_bias;  // approximate, additive, in the files' units
};

// One batch per row, as the dataset's table prints them.
// clang-format off
const AdvioBatch kBatches[] = {
    // sequences, fx, fy, cx, cy, k1 k2 p1 p2; then the accelerometer and gyroscope biases
    {1, 12,   1077.2, 1079.3, 362.145,  636.3873, {0.0478, 0.0339,  -0.00033,  -0.00091},
     {0.0407, -0.0623, 0.1017}, {-0.0067, 0.0070, -0.0065}},
    {13, 17,  1082.4, 1084.4, 364.6778, 643.3080, {0.0366, 0.0803,  0.000783,  -0.000215},
     {0.0415, -0.0617, 0.1008}, {-0.0065, 0.0055, -0.0064}},
    {18, 19,  1076.9, 1078.5, 360.96,   639.31,   {0.0510, -0.0354, -0.0054,   0.0473},
     {0.0393, -0.0635, 0.1024}, {-0.0069, 0.0062, -0.0067}},
    {20, 23,  1081.1, 1082.1, 359.59,   640.79,   {0.0556, -0.0454, 0.0009,    -0.0018},
     {0.0405, -0.0620, 0.1012}, {-0.0066, 0.0065, -0.0063}},
};
// clang-format on

const AdvioBatch& batchOf(int sequence) {
  for (const AdvioBatch& b : kBatches)
    if (sequence >= b.first_sequence && sequence <= b.last_sequence) return b;
  throw std::invalid_argument("ADVIO has sequences 1-23, not " + std::to_string(sequence));
}

/// NN of a folder named advio-NN, 0 when the name is another.
int sequenceNumber(const fs::path& dir) {
  const std::string name = (dir.has_filename() ? dir : dir.parent_path()).filename().string();
  std::smatch m;
  static const std::regex pattern("advio-(\\d{1,2})");
  return std::regex_match(name, m, pattern) ? std::stoi(m[1]) : 0;
}

/// The first of `names` that exists in `dir`; InputError naming them all otherwise.
std::string existingFile(const fs::path& dir, std::initializer_list<const char*> names) {
  for (const char* name : names)
    if (fs::is_regular_file(dir / name)) return (dir / name).string();
  std::string list;
  for (const char* name : names) list += (list.empty() ? "" : " or ") + std::string(name);
  throw InputError(dir.string(), "", "missing " + list);
}

struct TimedRow {
  double t;
  std::vector<double> values;
  int line;  // in the file
};

/// `t, v1 .. vn` rows with strictly increasing t.
std::vector<TimedRow> readTimedCsv(const std::string& path, size_t values) {
  std::vector<TimedRow> rows;
  forEachTextRow(path, [&](const std::vector<std::string>& fields, int line) {
    auto v = parseNumberRow(fields, values + 1, values + 1, path, line);
    if (!rows.empty() && !(v[0] > rows.back().t))
      throw InputError(path, "line " + std::to_string(line), "timestamps not increasing");
    rows.push_back({v[0], std::vector<double>(v.begin() + 1, v.end()), line});
  });
  return rows;
}

Eigen::Vector3d vec3(const TimedRow& row) { return {row.values[0], row.values[1], row.values[2]}; }

cv::Mat turned(const cv::Mat& gray, FrameRotation rotation) {
  if (rotation == FrameRotation::None) return gray;
  cv::Mat out;
  cv::rotate(gray, out,
             rotation == FrameRotation::Clockwise          ? cv::ROTATE_90_CLOCKWISE
             : rotation == FrameRotation::CounterClockwise ? cv::ROTATE_90_COUNTERCLOCKWISE
                                                           : cv::ROTATE_180);
  return out;
}

}  // namespace

FrameRotation frameRotationFromName(const std::string& name) {
  if (name == "none") return FrameRotation::None;
  if (name == "cw") return FrameRotation::Clockwise;
  if (name == "ccw") return FrameRotation::CounterClockwise;
  if (name == "180") return FrameRotation::HalfTurn;
  throw std::invalid_argument("'" + name + "' is not none, cw, ccw or 180");
}

Calibration advioCalibration(int sequence) {
  const AdvioBatch& b = batchOf(sequence);
  Calibration c;
  c.camera.width = 720;  // portrait, once turned upright
  c.camera.height = 1280;
  c.camera.fx = b.fx;
  c.camera.fy = b.fy;
  c.camera.cx = b.cx;
  c.camera.cy = b.cy;
  c.camera.model = DistortionModel::RadTan;
  std::copy(b.radtan.begin(), b.radtan.end(), c.camera.distortion.begin());
  // Camera in the iPhone's IMU frame, from the RP-VIO authors' advio_12_config.yaml (imu^R_cam,
  // imu^T_cam): about diag(1, -1, -1), the back camera of a phone held upright.
  Eigen::Matrix3d R;
  R << 0.9999763379093255, -0.004079205042965442, -0.005539287650170447,  //
      -0.004066386342107199, -0.9999890330121858, 0.0023234365646622014,  //
      -0.00554870467502187, -0.0023008567036498766, -0.9999819588046867;
  c.T_BC.linear() = nearestRotation(R);  // printed to 16 digits
  c.T_BC.translation() =
      Eigen::Vector3d(-0.008977668364731128, 0.07557012320238939, -0.005545773942541918);
  // The same configuration's figures, for the IMU's 100 Hz.
  c.imu = imuNoiseFromVinsMono(0.1517, 0.0758, 6.6407e-6, 1.6127e-6, 100, 9.8067);
  return c;
}

double detectAccelScale(const std::vector<Eigen::Vector3d>& accel, const Eigen::Matrix3d& R_BC,
                        const std::string& path, std::string& reason) {
  if (accel.empty()) throw InputError(path, "", "no accelerometer sample");
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& a : accel) sum += a;
  const double median = medianNorm(accel);
  char text[160];
  double unit;
  if (std::abs(median - 1) < 0.3) {
    unit = kStandardGravity;
  } else if (std::abs(median / kStandardGravity - 1) < 0.3) {
    unit = 1;
  } else {
    std::snprintf(text, sizeof text,
                  "cannot tell the units: median |a| = %.3f is neither about 1 (g) nor about 9.8 "
                  "(m/s^2); give --accel-scale",
                  median);
    throw InputError(path, "", text);
  }
  // At rest the specific force points up; in an upright image "up" is the camera's -y.
  const double image_down = (R_BC.transpose() * sum.normalized()).y();
  if (std::abs(image_down) < 0.5) {
    std::snprintf(text, sizeof text,
                  "cannot tell the sign: the mean reading is %.0f deg from the image's vertical "
                  "(the camera's y axis in the calibration); give --accel-scale",
                  std::acos(std::abs(image_down)) * 180 / M_PI);
    throw InputError(path, "", text);
  }
  const double scale = image_down < 0 ? unit : -unit;
  std::snprintf(text, sizeof text, "median |a| = %.3f, mean reading towards the image's %s", median,
                image_down < 0 ? "top" : "bottom (CoreMotion's sign)");
  reason = text;
  return scale;
}

AdvioImportCounts importAdvio(const AdvioImportOptions& opt,
                              const std::function<void(size_t)>& progress) {
  const fs::path dir(opt.sequence_dir);
  if (!fs::is_directory(dir / "iphone"))
    throw InputError(opt.sequence_dir, "", "not an ADVIO sequence folder (no iphone/ in it)");
  if (opt.every < 1)
    throw InputError(opt.sequence_dir, "", "keeping every N-th frame needs N >= 1");
  const fs::path out_dir = existingOutputFolder(opt.output_rawlog);

  AdvioImportCounts counts;
  Calibration calib;
  const AdvioBatch* batch = nullptr;
  if (const int sequence = sequenceNumber(dir);
      !opt.calibration && sequence >= 1 && sequence <= 23) {
    batch = &batchOf(sequence);
    counts.batch = static_cast<int>(batch - kBatches) + 1;
  }
  if (opt.calibration) {
    calib = *opt.calibration;
  } else if (batch) {
    calib = advioCalibration(batch->first_sequence);
  } else {
    throw InputError(opt.sequence_dir, "",
                     "the folder is not named advio-01 .. advio-23, so its calibration batch is "
                     "unknown; give --calib calib.ini");
  }

  const fs::path iphone = dir / "iphone";
  const std::string frames_csv = (iphone / "frames.csv").string();
  const std::string accel_csv = existingFile(iphone, {"accelerometer.csv"});
  const std::vector<TimedRow> frames = readTimedCsv(frames_csv, 1);
  // Row k stamps video frame k, as the dataset's own tools read it (the second column is not used).
  const std::vector<TimedRow> accel_rows = readTimedCsv(accel_csv, 3);
  const std::vector<TimedRow> gyro_rows =
      readTimedCsv(existingFile(iphone, {"gyro.csv", "gyroscope.csv"}), 3);

  const bool unbias = batch && opt.subtract_batch_bias;  // no batch with --calib
  std::vector<Eigen::Vector3d> accel_readings;
  for (const TimedRow& r : accel_rows)
    accel_readings.push_back(vec3(r) - (unbias ? batch->accel_bias : Eigen::Vector3d::Zero()));
  if (opt.accel_scale) {
    counts.accel_scale = *opt.accel_scale;
    counts.accel_scale_reason = "given";
  } else {
    counts.accel_scale =
        detectAccelScale(accel_readings, calib.T_BC.linear(), accel_csv, counts.accel_scale_reason);
  }
  std::vector<ImuSample> gyro(gyro_rows.size()), accel(accel_rows.size());
  for (size_t i = 0; i < gyro_rows.size(); ++i) {
    gyro[i].t = gyro_rows[i].t;
    gyro[i].gyro = vec3(gyro_rows[i]) - (unbias ? batch->gyro_bias : Eigen::Vector3d::Zero());
  }
  for (size_t i = 0; i < accel_rows.size(); ++i) {
    accel[i].t = accel_rows[i].t;
    accel[i].accel = counts.accel_scale * accel_readings[i];
  }
  const std::vector<ImuSample> imu = mergeSplitImu(gyro, accel);

  Trajectory gt;
  if (fs::is_directory(dir / "ground-truth")) {
    const std::string pose_csv = existingFile(dir / "ground-truth", {"pose.csv", "poses.csv"});
    for (const TimedRow& r : readTimedCsv(pose_csv, 7)) {
      StampedPose p;
      p.t = r.t;
      p.p = vec3(r);  // then the orientation as w x y z
      p.q = unitQuaternion(r.values[3], r.values[4], r.values[5], r.values[6], pose_csv, r.line);
      gt.push_back(p);
    }
  }

  const std::string video = (iphone / "frames.mov").string();
  if (!fs::is_regular_file(video)) throw InputError(video, "", "file not found");
  setenv("OPENCV_FFMPEG_LOGLEVEL", "-8", 0);  // FFmpeg quiet: errors are ours, on one line
  cv::VideoCapture capture(video, cv::CAP_FFMPEG);
  if (!capture.isOpened()) throw InputError(video, "", "OpenCV (FFmpeg) cannot open the video");
  capture.set(cv::CAP_PROP_ORIENTATION_AUTO, 0);  // turned by --rotate only

  RawlogWriter writer(opt.output_rawlog, calib);
  InterleavedSensorWriter sensors(writer, imu, gt);
  size_t frame = 0;
  for (cv::Mat bgr; capture.grab(); ++frame) {
    if (frame >= frames.size()) {
      ++counts.frames_without_stamp;
      continue;
    }
    if (frame % opt.every != 0) continue;
    if (!capture.retrieve(bgr) || bgr.empty())
      throw InputError(video, "frame " + std::to_string(frame + 1), "cannot be decoded");
    cv::Mat gray = bgr;
    if (bgr.channels() == 3) cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
    gray = turned(gray, opt.rotation);
    if (gray.cols != calib.camera.width || gray.rows != calib.camera.height)
      throw InputError(video, "frame " + std::to_string(frame + 1),
                       std::to_string(gray.cols) + "x" + std::to_string(gray.rows) +
                           " once turned, the calibration says " +
                           std::to_string(calib.camera.width) + "x" +
                           std::to_string(calib.camera.height) + " (see --rotate)");
    sensors.writeUntil(frames[frame].t);
    writer.addImage(frames[frame].t, gray);
    ++counts.images;
    if (progress && counts.images % 100 == 0) progress(frame + 1);
  }
  const double frames_in_file = capture.get(cv::CAP_PROP_FRAME_COUNT);
  if (frame < frames.size() && frames_in_file > static_cast<double>(frame))
    throw InputError(video, "frame " + std::to_string(frame + 1),
                     "cannot be decoded (the file says it has " +
                         std::to_string(static_cast<long long>(frames_in_file)) + " frames)");
  if (counts.images == 0) throw InputError(video, "", "no frame could be decoded");
  counts.stamps_without_frame = frames.size() - std::min(frame, frames.size());
  sensors.writeUntil(INFINITY);
  counts.imu = sensors.imuWritten();
  counts.groundtruth = sensors.groundTruthWritten();
  writer.close();  // then calib.ini: nothing is left behind if the rawlog fails
  saveCalibration((out_dir / "calib.ini").string(), calib);
  return counts;
}

}  // namespace rpvio

#pragma once
// Converts an ADVIO sequence in its raw layout (Cortés et al., ECCV 2018) into an rpvio rawlog +
// calib.ini: `iphone/frames.mov` (H.264, 60 Hz, stored landscape 1280x720) with the stamps of
// `iphone/frames.csv` → CAM0 (grey, turned upright), `iphone/accelerometer.csv` and
// `iphone/gyro.csv` (100 Hz each, sampled apart) merged → IMU, `ground-truth/pose.csv` (optional)
// → GROUND_TRUTH. Streams the video: memory does not grow with the sequence's length.
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "common/sensor_types.h"

namespace rpvio {

/// How a stored video frame is turned before use (the calibration's width and height are those
/// after turning). OpenCV's own turning from the file's metadata is always off.
enum class FrameRotation { None, Clockwise, CounterClockwise, HalfTurn };

/// "none", "cw", "ccw", "180"; std::invalid_argument otherwise.
FrameRotation frameRotationFromName(const std::string& name);

struct AdvioImportOptions {
  std::string sequence_dir;                           // advio-NN, holding iphone/ and ground-truth/
  std::string output_rawlog;                          // calib.ini is written beside it
  int every = 1;                                      // keep every N-th video frame (60 Hz / N)
  FrameRotation rotation = FrameRotation::Clockwise;  // ADVIO's iPhone video is stored sideways
  // Default: the published calibration of the sequence's batch, chosen by the NN of the folder
  // name (advio-01 .. advio-23).
  std::optional<Calibration> calibration;
  // f = accel_scale * (a - bias) gives the specific force in m/s^2. Default: detected (units from
  // the median magnitude, sign from gravity's direction in the upright image).
  std::optional<double> accel_scale;
  bool subtract_batch_bias = true;  // the batch's published approximate additive IMU biases
};

struct AdvioImportCounts {
  size_t images = 0, imu = 0, groundtruth = 0;
  size_t frames_without_stamp = 0;  // video frames past the end of frames.csv (dropped)
  size_t stamps_without_frame = 0;  // frames.csv rows past the end of the video
  int batch = 0;                    // 1-4; 0 when --calib was given
  double accel_scale = 0;           // as used
  std::string accel_scale_reason;   // how it was chosen, for the report
};

/// The calibration of ADVIO's iPhone for sequence 1-23: intrinsics and radial-tangential
/// distortion of the sequence's batch (the dataset's calibration/ folder), the camera-IMU pose and
/// IMU noise of the RP-VIO authors' ADVIO configuration. std::invalid_argument outside 1-23.
Calibration advioCalibration(int sequence);

/// The factor that turns the accelerometer's readings into specific force in m/s^2: ±1 or
/// ±9.80665 from the median magnitude (about 1 g or about 9.8 m/s^2) and from the mean reading's
/// direction in the camera (specific force points up, i.e. towards the image's top, when the
/// images are upright). InputError(path) when either is unclear; `reason` says what was seen.
double detectAccelScale(const std::vector<Eigen::Vector3d>& accel, const Eigen::Matrix3d& R_BC,
                        const std::string& path, std::string& reason);

/// Throws InputError (file + line or frame) on bad input; nothing appears under the output names
/// unless the import completes. `progress(frames_read)` is called now and then.
AdvioImportCounts importAdvio(const AdvioImportOptions& options,
                              const std::function<void(size_t)>& progress = {});

}  // namespace rpvio

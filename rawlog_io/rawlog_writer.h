#pragma once
// Writes a dataset in the rawlog conventions of DESIGN.md §4: observation-only, gz-compressed,
// stock MRPT classes only; CAM0 and PLANE_MASK images stored externally as PNG in
// `<dir>/<stem>_Images/`. Observations must be added in non-decreasing time order.
#include <Eigen/Geometry>
#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "common/sensor_types.h"

namespace rpvio {

class RawlogWriter {
 public:
  /// Opens `<path>.tmp`; the rawlog appears under `path` only after close().
  /// `calib` fills cameraParams and cameraPose (T_BC) of the image observations.
  RawlogWriter(const std::string& path, const Calibration& calib);
  ~RawlogWriter();  // without close(): the temporary file is removed, nothing under `path`
  RawlogWriter(const RawlogWriter&) = delete;
  RawlogWriter& operator=(const RawlogWriter&) = delete;

  void addImage(double t, const cv::Mat& gray8);   // CAM0, CV_8UC1
  void addMask(double t, const cv::Mat& labels8);  // PLANE_MASK, CV_8UC1, lossless PNG
  void addImu(const ImuSample& sample);            // IMU
  void addGroundTruth(const StampedPose& pose);    // GROUND_TRUTH, body pose in the world
  void close();

  std::string imagesDir() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rpvio

#pragma once
// The IMU samples and ground-truth poses of a dataset, held in memory, written into a rawlog
// between its streamed images in time order (DESIGN.md §4: observations in non-decreasing time).
#include <vector>

#include "common/sensor_types.h"
#include "rawlog_io/rawlog_writer.h"

namespace rpvio {

class InterleavedSensorWriter {
 public:
  /// Keeps references: `writer`, `imu` and `groundtruth` must outlive this object.
  InterleavedSensorWriter(RawlogWriter& writer, const std::vector<ImuSample>& imu,
                          const Trajectory& groundtruth)
      : writer_(writer), imu_(imu), groundtruth_(groundtruth) {}

  /// Writes every sample and pose stamped up to t (INFINITY: the rest); at equal stamps IMU
  /// first, then ground truth, so that an image of stamp t written next comes after both.
  void writeUntil(double t);

  size_t imuWritten() const { return next_imu_; }
  size_t groundTruthWritten() const { return next_gt_; }

 private:
  RawlogWriter& writer_;
  const std::vector<ImuSample>& imu_;
  const Trajectory& groundtruth_;
  size_t next_imu_ = 0, next_gt_ = 0;
};

}  // namespace rpvio

#include "rawlog_io/interleaved_writing.h"

#include <algorithm>
#include <cmath>

namespace rpvio {

void InterleavedSensorWriter::writeUntil(double t) {
  for (;;) {
    const double t_imu = next_imu_ < imu_.size() ? imu_[next_imu_].t : INFINITY;
    const double t_gt = next_gt_ < groundtruth_.size() ? groundtruth_[next_gt_].t : INFINITY;
    if ((next_imu_ == imu_.size() && next_gt_ == groundtruth_.size()) || std::min(t_imu, t_gt) > t)
      return;
    if (t_imu <= t_gt)
      writer_.addImu(imu_[next_imu_++]);
    else
      writer_.addGroundTruth(groundtruth_[next_gt_++]);
  }
}

}  // namespace rpvio

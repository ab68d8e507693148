#pragma once
// Faults injected into a simulated sequence (issue 10), to test that the estimator keeps working,
// detects what it cannot bridge, re-initializes and says so. All off by default. Times are in
// seconds of the sequence (IMU clock); an interval is [start, start + duration).
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "common/sensor_types.h"

namespace rpvio::sim {

struct TimeInterval {
  double start = 0, duration = 0;
  bool contains(double t) const { return t >= start && t < start + duration; }
};

struct FaultInjection {
  std::vector<double> dropped_frames;        // single frames (nearest frame to each time) lost
  std::vector<TimeInterval> dropped_bursts;  // every frame in the interval lost
  std::vector<TimeInterval> imu_gaps;        // no IMU sample in the interval
  std::vector<TimeInterval> blackouts;       // black image, mask all 0 (nothing recognized)
  std::vector<TimeInterval> motion_blur;     // images blurred along the image x axis ...
  double blur_px = 15;                       // ... over this length
  std::vector<TimeInterval> no_planes;  // mask all 0: no static plane visible (as when a character
                                        // fills the view), image unchanged
  double accel_saturation = 0;          // m/s², |component| clipped to this (0: off)
  double gyro_saturation = 0;           // rad/s, likewise

  /// Whether the frame at time t (frame period `period`) is dropped.
  bool dropsFrame(double t, double period) const;
  bool dropsImu(double t) const;
  /// Blackout, blur and no-plane faults at time t, applied in place.
  void applyToFrame(double t, cv::Mat& image, cv::Mat& mask) const;
  /// Saturation applied to one sample.
  ImuSample saturate(const ImuSample& sample) const;
};

/// "START:DURATION" (seconds); throws std::invalid_argument naming `what` on a malformed value.
TimeInterval parseTimeInterval(const std::string& text, const std::string& what);

}  // namespace rpvio::sim

#include "sim/fault_injection.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace rpvio::sim {
namespace {

bool inAny(const std::vector<TimeInterval>& intervals, double t) {
  for (const auto& i : intervals)
    if (i.contains(t)) return true;
  return false;
}

double clip(double value, double limit) {
  return limit > 0 ? std::clamp(value, -limit, limit) : value;
}

}  // namespace

bool FaultInjection::dropsFrame(double t, double period) const {
  for (double d : dropped_frames)
    if (std::abs(t - d) < 0.5 * period) return true;
  return inAny(dropped_bursts, t);
}

bool FaultInjection::dropsImu(double t) const { return inAny(imu_gaps, t); }

void FaultInjection::applyToFrame(double t, cv::Mat& image, cv::Mat& mask) const {
  if (inAny(blackouts, t)) {
    image.setTo(0);
    mask.setTo(0);
    return;
  }
  if (inAny(motion_blur, t) && blur_px > 1) {
    const int length = static_cast<int>(std::lround(blur_px));
    const cv::Mat kernel = cv::Mat::ones(1, length, CV_32F) / static_cast<float>(length);
    cv::filter2D(image, image, -1, kernel, cv::Point(-1, -1), 0, cv::BORDER_REFLECT);
  }
  if (inAny(no_planes, t)) mask.setTo(0);
}

ImuSample FaultInjection::saturate(const ImuSample& sample) const {
  ImuSample out = sample;
  for (int i = 0; i < 3; ++i) {
    out.accel[i] = clip(sample.accel[i], accel_saturation);
    out.gyro[i] = clip(sample.gyro[i], gyro_saturation);
  }
  return out;
}

TimeInterval parseTimeInterval(const std::string& text, const std::string& what) {
  const auto colon = text.find(':');
  try {
    if (colon == std::string::npos) throw std::invalid_argument("no colon");
    size_t used_start = 0, used_duration = 0;
    TimeInterval i;
    i.start = std::stod(text.substr(0, colon), &used_start);
    i.duration = std::stod(text.substr(colon + 1), &used_duration);
    if (used_start != colon || used_duration != text.size() - colon - 1 || i.start < 0 ||
        !(i.duration > 0) || !std::isfinite(i.start + i.duration))
      throw std::invalid_argument("bad numbers");
    return i;
  } catch (const std::exception&) {
    throw std::invalid_argument(what + " expects START:DURATION in seconds (e.g. 10:2), got '" +
                                text + "'");
  }
}

}  // namespace rpvio::sim

#include "rosbag_io/stamps.h"

#include <cmath>
#include <stdexcept>

#include "rawlog_io/rawlog_reader.h"

namespace rpvio {
namespace {

const mrpt::Clock::time_point kUnixEpoch = fromSeconds(0.0);
constexpr int64_t kNanosecondsPerTick = 100, kNanosecondsPerSecond = 1000000000;

}  // namespace

ros::Time rosStamp(const mrpt::Clock::time_point& t) {
  const int64_t ns = (t - kUnixEpoch).count() * kNanosecondsPerTick;
  if (ns < 0) throw std::invalid_argument("a time before 1970 has no ROS stamp");
  return ros::Time(static_cast<uint32_t>(ns / kNanosecondsPerSecond),
                   static_cast<uint32_t>(ns % kNanosecondsPerSecond));
}

double rawlogSeconds(const ros::Time& stamp) {
  const auto ns = static_cast<int64_t>(stamp.toNSec());
  const mrpt::Clock::time_point tick =
      kUnixEpoch + mrpt::Clock::duration((ns + kNanosecondsPerTick / 2) / kNanosecondsPerTick);
  // The writer converts seconds to ticks by truncation: nudge the seconds onto the tick.
  double t = toSeconds(tick);
  while (fromSeconds(t) < tick) t = std::nextafter(t, INFINITY);
  while (fromSeconds(t) > tick) t = std::nextafter(t, -INFINITY);
  return t;
}

}  // namespace rpvio

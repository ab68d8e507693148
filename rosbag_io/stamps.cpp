#include "rosbag_io/stamps.h"

#include <stdexcept>

#include "rawlog_io/nanosecond_stamps.h"

namespace rpvio {

ros::Time rosStamp(const mrpt::Clock::time_point& t) {
  const int64_t ns = toNanoseconds(t);
  if (ns < 0) throw std::invalid_argument("a time before 1970 has no ROS stamp");
  ros::Time stamp;
  stamp.fromNSec(static_cast<uint64_t>(ns));
  return stamp;
}

double rawlogSeconds(const ros::Time& stamp) {
  return secondsOfNanoseconds(static_cast<int64_t>(stamp.toNSec()));
}

}  // namespace rpvio

#pragma once
// Exact stamps between ROS (integer nanoseconds) and rawlogs (MRPT's 100 ns ticks, written from
// seconds): a sequence exported to a bag and imported back has the same ticks, hence the same
// rpvio-slam run.
#include <mrpt/core/Clock.h>
#include <ros/time.h>

namespace rpvio {

/// The rawlog time as a ROS stamp, exactly. Throws std::invalid_argument before 1970.
ros::Time rosStamp(const mrpt::Clock::time_point& t);
/// Seconds that the rawlog writer stores as the tick nearest to the stamp.
double rawlogSeconds(const ros::Time& stamp);

}  // namespace rpvio

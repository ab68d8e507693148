#pragma once
// Integer-nanosecond stamps (EuRoC CSVs, ROS messages) and rawlog times (MRPT's 100 ns ticks,
// written from seconds by truncation), converted without losing a tick: a 19-digit EuRoC stamp
// read as a double would be rounded to 256 ns, and seconds a hair below a tick would truncate to
// the previous one.
#include <mrpt/core/Clock.h>

#include <cstdint>
#include <string>

namespace rpvio {

/// Nanoseconds since 1970 of a rawlog time, exactly.
int64_t toNanoseconds(const mrpt::Clock::time_point& t);
/// Seconds that the rawlog writer stores as the tick nearest to `ns` nanoseconds since 1970.
/// Exact for simulated times; past 9e8 s (1998) the writer's seconds reach even ticks only, so a
/// real stamp may land one tick (100 ns) early — and then round-trips exactly.
double secondsOfNanoseconds(int64_t ns);
/// The same of a decimal integer; InputError(path, "line N") on anything else.
double secondsOfNanosecondText(const std::string& text, const std::string& path, int line);

}  // namespace rpvio

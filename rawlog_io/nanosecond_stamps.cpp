#include "rawlog_io/nanosecond_stamps.h"

#include <cmath>
#include <limits>

#include "common/input_error.h"
#include "rawlog_io/rawlog_reader.h"

namespace rpvio {
namespace {

constexpr int64_t kNanosecondsPerTick = 100;

const mrpt::Clock::time_point& unixEpoch() {
  static const mrpt::Clock::time_point epoch = fromSeconds(0.0);
  return epoch;
}

}  // namespace

int64_t toNanoseconds(const mrpt::Clock::time_point& t) {
  return (t - unixEpoch()).count() * kNanosecondsPerTick;
}

double secondsOfNanoseconds(int64_t ns) {
  const auto ticks =
      (ns >= 0 ? ns + kNanosecondsPerTick / 2 : ns - kNanosecondsPerTick / 2) / kNanosecondsPerTick;
  const mrpt::Clock::time_point tick = unixEpoch() + mrpt::Clock::duration(ticks);
  // The writer converts seconds to ticks by truncation: nudge the seconds onto the tick.
  double t = toSeconds(tick);
  while (fromSeconds(t) < tick) t = std::nextafter(t, INFINITY);
  while (fromSeconds(t) > tick) t = std::nextafter(t, -INFINITY);
  return t;
}

double secondsOfNanosecondText(const std::string& text, const std::string& path, int line) {
  size_t used = 0;
  long long ns = 0;
  try {
    ns = std::stoll(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || text.find_first_not_of(" \t\r", used) != std::string::npos || ns < 0 ||
      ns > std::numeric_limits<int64_t>::max() / 2)
    throw InputError(path, "line " + std::to_string(line),
                     "'" + text + "' is not a timestamp in nanoseconds since 1970");
  return secondsOfNanoseconds(ns);
}

}  // namespace rpvio

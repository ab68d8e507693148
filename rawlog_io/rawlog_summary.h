#pragma once
// Streams a whole rawlog, loading every image and IMU sample the way a consumer would, and counts
// the observations per sensor label: a check that a dataset is complete and readable.
#include <map>
#include <string>

namespace rpvio {

struct RawlogSummary {
  std::map<std::string, size_t> observations_per_label;
  double first_t = 0, last_t = 0;
};

/// Throws InputError naming the file and entry at the first problem.
RawlogSummary summarizeRawlog(const std::string& path);

}  // namespace rpvio

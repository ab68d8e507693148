#pragma once
#include <cstddef>
#include <vector>

namespace rpvio::eval {

struct ErrorStats {
  double rmse = 0, mean = 0, median = 0, std = 0, min = 0, max = 0;
  size_t count = 0;
};

/// Statistics of a list of non-negative errors (std is the population standard deviation).
ErrorStats computeStats(std::vector<double> errors);

}  // namespace rpvio::eval

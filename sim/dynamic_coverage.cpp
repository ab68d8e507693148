#include "sim/dynamic_coverage.h"

#include <algorithm>
#include <cmath>

namespace rpvio::sim {
namespace {

double percentile(const std::vector<double>& sorted, double q) {
  const double x = q * static_cast<double>(sorted.size() - 1);
  const auto i = static_cast<size_t>(std::floor(x));
  const size_t j = std::min(i + 1, sorted.size() - 1);
  return sorted[i] + (x - static_cast<double>(i)) * (sorted[j] - sorted[i]);
}

}  // namespace

CoverageSummary summarizeCoverage(const std::vector<CoverageSample>& samples) {
  CoverageSummary s;
  if (samples.empty()) return s;
  std::vector<double> sorted;
  double first_sum = 0;
  int first_count = 0;
  for (const CoverageSample& c : samples) {
    sorted.push_back(c.fraction);
    s.mean += c.fraction;
    if (c.t - samples.front().t < 2.0) first_sum += c.fraction, ++first_count;
  }
  std::sort(sorted.begin(), sorted.end());
  s.mean /= static_cast<double>(samples.size());
  s.median = percentile(sorted, 0.5);
  s.p90 = percentile(sorted, 0.9);
  s.peak = sorted.back();
  s.first_2s_mean = first_sum / first_count;
  return s;
}

}  // namespace rpvio::sim

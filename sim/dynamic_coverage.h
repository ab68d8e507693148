#pragma once
// How much of the image moving things cover, frame by frame, and the figures a sequence is
// described by (sequence.json): median, 90th percentile, peak, and the mean over the first 2 s
// (the initialization window).
#include <vector>

namespace rpvio::sim {

struct CoverageSample {
  double t;         // s, camera timestamp
  double fraction;  // 0..1 of the pixels
};

struct CoverageSummary {
  double mean = 0, median = 0, p90 = 0, peak = 0, first_2s_mean = 0;
};

/// Percentiles by linear interpolation between order statistics.
CoverageSummary summarizeCoverage(const std::vector<CoverageSample>& samples);

}  // namespace rpvio::sim

#pragma once
// rpvio-bench's figures: one record per (sequence, mode, run), and the report files made of them
// (results.md: the paper's Table I layout, modes x sequences; results.json: every figure).
#include <map>
#include <string>
#include <vector>

namespace rpvio::apps {

struct BenchRun {
  std::string sequence, mode;
  int run = 0;
  std::string dir;     // the run's rpvio-slam output folder
  int exit_code = -1;  // of rpvio-slam
  bool evaluated = false;
  std::string error;  // why it was not evaluated
  double ate_rmse = 0, ate_rotation_deg = 0, coverage = 0;
  double refined_ate_rmse = -1;  // of trajectory_refined.tum (its keyframes); -1: none
  // From the run's summary.json.
  double initialized_at = -1, resets = 0;
  double frontend_ms_median = 0, frontend_ms_p95 = 0, optimization_ms_median = 0,
         optimization_ms_p95 = 0, total_ms_median = 0, total_ms_p95 = 0, load_ms_median = 0,
         processing_ms_median = 0, processing_ms_p95 = 0;
  double real_time_factor = 0, peak_memory_mb = 0, wall_s = 0;
};

struct BenchSetup {
  std::string suite_dir;
  std::vector<std::string> modes, sequences;
  int runs = 1, jobs = 1;
  double min_coverage = 0.9;  // below: tracking lost, "X" in the table
  double wall_s = 0;          // of the whole benchmark
  /// Per sequence: median fraction of the image moving things cover (its sequence.json; NaN when
  /// the sequence has none).
  std::map<std::string, double> dynamic_fraction;
};

/// A run counts in the ATE table when it was evaluated and covered the sequence.
bool tracked(const BenchRun& run, const BenchSetup& setup);

std::string resultsMarkdown(const BenchSetup& setup, const std::vector<BenchRun>& runs);
std::string resultsJson(const BenchSetup& setup, const std::vector<BenchRun>& runs);

}  // namespace rpvio::apps

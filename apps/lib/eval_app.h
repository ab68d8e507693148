#pragma once
// rpvio-eval: ATE/RPE of one or more estimates against ground truth, table + JSON + plot.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "evaluation/plane_map_accuracy.h"
#include "evaluation/plane_visibility.h"
#include "evaluation/trajectory_metrics.h"
#include "mrpt_modules/frontend/feature_tracker.h"

namespace rpvio::apps {

struct EvalAppOptions {
  std::string gt_file;
  std::vector<std::string> est_files, labels;
  std::string format;  // "" = detect from content
  eval::EvalOptions eval;
  std::string plot_png, json_file;
  // Plane map (planes.yaml of rpvio-slam) against true planes (groundtruth_planes.yaml of
  // rpvio-sim), moved by the first estimate's alignment.
  std::string planes_file, gt_planes_file;
  // The sequence's rawlog: its plane masks say which true planes were seen and trackable for more
  // than 2 s (eval::PlaneVisibility), and the report names those without a map entry.
  std::string masks_rawlog;
  // ... trackable by the front-end of the run's mode: its KLT window and margin (px).
  int tracker_klt_window = TrackerOptions{}.klt_window;
  int tracker_window_margin = TrackerOptions{}.window_margin;
};

struct EvalAppResult {
  std::vector<std::string> labels;
  std::vector<eval::EvalResult> results;
  std::optional<eval::PlaneMapAccuracy> plane_map;
  std::optional<std::map<int, eval::LabelVisibility>> visible_s;  // per label, with masks_rawlog
  eval::MissingPlanes missing_planes;
};

/// Reads the files (InputError on bad content or no overlap, naming the estimate file), evaluates,
/// writes the optional plot and JSON.
EvalAppResult runEvaluation(const EvalAppOptions& options);

/// `ATE_RMSE <m>` lines (first estimate first) and a readable table.
std::string formatEvaluationReport(const EvalAppOptions& options, const EvalAppResult& result);

int evalMain(int argc, char** argv);

}  // namespace rpvio::apps

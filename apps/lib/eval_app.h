#pragma once
// rpvio-eval: ATE/RPE of one or more estimates against ground truth, table + JSON + plot.
#include <string>
#include <vector>

#include "apps/evaluation/trajectory_metrics.h"

namespace rpvio::apps {

struct EvalAppOptions {
  std::string gt_file;
  std::vector<std::string> est_files, labels;
  std::string format;  // "" = detect from content
  eval::EvalOptions eval;
  std::string plot_png, json_file;
};

struct EvalAppResult {
  std::vector<std::string> labels;
  std::vector<eval::EvalResult> results;
};

/// Reads the files (InputError on bad content or no overlap, naming the estimate file), evaluates,
/// writes the optional plot and JSON.
EvalAppResult runEvaluation(const EvalAppOptions& options);

/// `ATE_RMSE <m>` lines (first estimate first) and a readable table.
std::string formatEvaluationReport(const EvalAppOptions& options, const EvalAppResult& result);

int evalMain(int argc, char** argv);

}  // namespace rpvio::apps

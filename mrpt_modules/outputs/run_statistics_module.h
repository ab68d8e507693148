#pragma once
// Output module: the run's statistics, written into the pipeline's output folder at the end.
//   stats.csv     per frame (FeatureFrame): t, load_ms (FrameDecoding), frontend_ms (the wall
//                 time since the previous frame, without decoding and estimator work),
//                 optimization_ms, features, planes, state (the frame's EstimatorFrame, in
//                 order), total_ms (their sum: the frame's cost)
//   summary.json  frames, poses, completeness (RunEnd), the estimator's summary (initialization,
//                 time offset, resets, last status), the map's (MapSummary: size, batch
//                 refinement), the loop closure's (LoopClosureSummary: revisits found, accepted,
//                 rejected and why), timing medians and 95th percentiles, real-time factor,
//                 peak memory.
// Listed after the modules it records: it sees each frame once they have processed it.
#include <chrono>
#include <optional>

#include "mrpt_modules/core/module.h"
#include "mrpt_modules/core/run_messages.h"
#include "mrpt_modules/estimator/estimator_types.h"
#include "mrpt_modules/estimator/map_sink.h"
#include "mrpt_modules/loop/loop_closure_module.h"

namespace rpvio {

/// The q-quantile (0..1) of `values`, nearest rank below; 0 when empty.
double percentile(std::vector<double> values, double q);
/// Peak resident memory of this process (MB).
double peakMemoryMb();

class RunStatisticsModule : public Module {
  DEFINE_MRPT_OBJECT(RunStatisticsModule, rpvio)

 public:
  void initialize(const IniFile& config, const std::string& section,
                  PipelineContext& context) override;
  void finish() override;

 private:
  using Clock = std::chrono::steady_clock;
  /// Per-frame wall times: the whole pipeline since the previous frame, the part spent decoding
  /// the frame's image files, and the part the estimator spent.
  struct FrameRow {
    double t = 0, wall_ms = 0, load_ms = 0, estimator_ms = 0;
  };
  void onFrame(double t);
  void write(double wall_s) const;

  std::string output_dir_;
  Clock::time_point start_, frame_start_;
  std::vector<FrameRow> rows_;
  std::vector<FrameReport> reports_;
  size_t reports_counted_ = 0;
  double load_ms_ = 0;
  size_t poses_ = 0;
  RunEnd end_;
  std::optional<EstimatorSummary> estimator_;
  std::optional<MapSummary> map_;
  std::optional<LoopClosureSummary> loops_;
};

}  // namespace rpvio

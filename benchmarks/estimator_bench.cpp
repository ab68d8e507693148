// Per-frame time of the sliding-window estimator without the images: 20 s of simulated C4
// (640x480, 20 Hz) tracked once with a mode's front-end settings (masks or none), then fed with the
// simulator's IMU to the estimator with that mode's settings (config/<mode>.ini), and the batch
// refinement at the end. The front-end's time on such frames is bench_frontend's.
// Run from the repository root: build/bin/bench_estimator --benchmark_repetitions=3
// --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <algorithm>
#include <chrono>
#include <map>
#include <string>

#include "common/ini_file.h"
#include "common/options.h"
#include "mrpt_modules/estimator/map_builder.h"
#include "mrpt_modules/estimator/sliding_window_estimator.h"
#include "mrpt_modules/frontend/feature_tracker.h"
#include "sim/simulator.h"

namespace {

struct Recorded {
  rpvio::Calibration calibration;
  std::vector<rpvio::FeatureFrame> frames;
  std::vector<std::vector<rpvio::ImuSample>> imu;  // samples since the previous frame
};

std::string configPath(const std::string& mode) { return "config/" + mode + ".ini"; }

const Recorded& recorded(const std::string& mode) {
  static std::map<std::string, Recorded> by_mode;
  if (const auto it = by_mode.find(mode); it != by_mode.end()) return it->second;
  rpvio::sim::SimConfig config;
  config.scene.characters = 4;
  config.duration = 20.0;
  rpvio::sim::Simulator sim(config);
  const rpvio::IniFile ini(configPath(mode));
  rpvio::FeatureTracker tracker(sim.calibration().camera,
                                rpvio::TrackerOptions::load(ini, "FeatureTrackerModule"));
  Recorded r;
  r.calibration = sim.calibration();
  const std::vector<rpvio::ImuSample> stream = sim.imuStream();
  const auto times = sim.frameTimes();
  size_t first = 0;  // the last sample at or before the previous frame
  for (size_t k = 0; k < times.size(); ++k) {
    const auto image = sim.render(times[k], static_cast<int>(k));
    r.frames.push_back(tracker.track(times[k], image.image, image.mask));
    std::vector<rpvio::ImuSample> since;
    if (k > 0) {
      while (first + 1 < stream.size() && stream[first + 1].t <= times[k - 1]) ++first;
      for (size_t i = first; i < stream.size() && stream[i].t <= times[k]; ++i)
        since.push_back(stream[i]);
    }
    r.imu.push_back(since);
  }
  return by_mode.emplace(mode, std::move(r)).first->second;
}

double percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0;
  const auto at = values.begin() + static_cast<std::ptrdiff_t>(p * (values.size() - 1));
  std::nth_element(values.begin(), at, values.end());
  return *at;
}

void runEstimator(benchmark::State& state, const std::string& mode) {
  const Recorded& r = recorded(mode);
  const rpvio::IniFile ini(configPath(mode));
  const auto options =
      rpvio::loadOptions<rpvio::EstimatorOptions>(ini, "SlidingWindowEstimatorModule");
  std::vector<double> tracking_s, waiting_s, refinement_s, keyframe_s, between_keyframes_s;
  for (auto _ : state) {
    // One iteration = the whole 20 s from a fresh estimator, then the batch refinement.
    rpvio::MapBuilder map(rpvio::PlanesMapOptions::load(ini, "PlanesMap"),
                          rpvio::loadOptions<rpvio::MapBuilderOptions>(ini, "MapBuilderModule"));
    rpvio::SlidingWindowEstimator estimator(r.calibration, options, map);
    for (size_t k = 0; k < r.frames.size(); ++k) {
      const bool initialized = estimator.initialized();
      const auto start = std::chrono::steady_clock::now();
      const auto states = estimator.addFrame(r.frames[k], r.imu[k]);
      const double s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      // The initialization's frame (a late one tracks its frames since too) counts as waiting.
      (initialized ? tracking_s : waiting_s).push_back(s);
      if (initialized && !states.empty())
        (states.back().keyframe ? keyframe_s : between_keyframes_s).push_back(s);
    }
    estimator.finishMap();
    refinement_s.push_back(map.refinementSeconds());
  }
  // Seconds per frame (printed with an SI prefix: 6.7m = 6.7 ms) over every iteration's frames.
  state.counters["tracking_median_s"] = percentile(tracking_s, 0.5);
  state.counters["tracking_p95_s"] = percentile(tracking_s, 0.95);
  state.counters["tracking_max_s"] = percentile(tracking_s, 1.0);
  state.counters["waiting_median_s"] = percentile(waiting_s, 0.5);
  // Frames whose second newest became a keyframe (the whole window solved, the oldest keyframe
  // marginalized) and the others (motion-only solve by default).
  state.counters["keyframe_median_s"] = percentile(keyframe_s, 0.5);
  state.counters["between_keyframes_median_s"] = percentile(between_keyframes_s, 0.5);
  state.counters["refinement_s"] = percentile(refinement_s, 0.5);
  state.counters["tracking_frames"] =
      static_cast<double>(tracking_s.size()) / static_cast<double>(state.iterations());
}

void BM_EstimatorRpvioSingle(benchmark::State& state) { runEstimator(state, "rpvio-single"); }
void BM_EstimatorRpvioMulti(benchmark::State& state) { runEstimator(state, "rpvio-multi"); }
void BM_EstimatorMaskVins(benchmark::State& state) { runEstimator(state, "mask-vins"); }
void BM_EstimatorVinsMono(benchmark::State& state) { runEstimator(state, "vins-mono"); }
BENCHMARK(BM_EstimatorRpvioSingle)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_EstimatorRpvioMulti)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_EstimatorMaskVins)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_EstimatorVinsMono)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

}  // namespace

// Per-frame time of the plane discovery (rpvio-auto) on the feature frames of simulated 640x480
// C4 frames tracked without masks (the arguments: features per image, 150 by default, 250 in
// rpvio-auto; adopt_young on or off), with the simulator's camera rotations standing in for the
// gyroscope; the front-end's time on the same frames is bench_frontend's BM_FrontendNoMasks.
// Run: build/bin/bench_plane_discovery --benchmark_repetitions=5
// --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <algorithm>
#include <chrono>
#include <map>

#include "mrpt_modules/estimator/plane_discovery.h"
#include "mrpt_modules/frontend/feature_tracker.h"
#include "sim/simulator.h"

namespace {

struct Recorded {
  std::vector<rpvio::FeatureFrame> frames;
  std::vector<Eigen::Quaterniond> rotations;  // camera k in camera k−1
};

Recorded record(int max_features) {
  rpvio::sim::SimConfig config;
  config.scene.characters = 4;
  config.duration = 5.0;
  rpvio::sim::Simulator sim(config);
  rpvio::TrackerOptions options;
  options.use_masks = false;
  options.max_features = max_features;
  rpvio::FeatureTracker tracker(sim.calibration().camera, options);
  const Eigen::Matrix3d R_BC = sim.calibration().T_BC.linear();
  Recorded out;
  Eigen::Matrix3d previous = Eigen::Matrix3d::Identity();
  const auto times = sim.frameTimes();
  for (size_t k = 0; k < times.size(); ++k) {
    const auto image = sim.render(times[k], static_cast<int>(k));
    out.frames.push_back(tracker.track(times[k], image.image, image.mask));
    const Eigen::Matrix3d R_wc = sim.state(times[k]).R_wb * R_BC;
    out.rotations.emplace_back(k == 0 ? Eigen::Matrix3d::Identity()
                                      : Eigen::Matrix3d(previous.transpose() * R_wc));
    previous = R_wc;
  }
  return out;
}

const Recorded& recorded(int max_features) {
  static std::map<int, Recorded> cache;
  auto it = cache.find(max_features);
  if (it == cache.end()) it = cache.emplace(max_features, record(max_features)).first;
  return it->second;
}

void BM_PlaneDiscovery(benchmark::State& state) {
  const Recorded& r = recorded(static_cast<int>(state.range(0)));
  rpvio::PlaneDiscoveryOptions options;
  options.enabled = true;
  options.adopt_young = state.range(1) != 0;
  std::vector<double> frame_seconds;
  size_t labelled = 0, frames = 0;
  for (auto _ : state) {
    rpvio::PlaneDiscovery discovery(options);  // one iteration = the whole 5 s sequence
    for (size_t k = 0; k < r.frames.size(); ++k) {
      const auto start = std::chrono::steady_clock::now();
      const auto out = discovery.label(r.frames[k], r.rotations[k]);
      frame_seconds.push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      labelled += out.features.size();
      ++frames;
    }
  }
  const auto middle = frame_seconds.begin() + static_cast<std::ptrdiff_t>(frame_seconds.size() / 2);
  std::nth_element(frame_seconds.begin(), middle, frame_seconds.end());
  state.counters["median_s_per_frame"] = *middle;
  state.counters["labelled_per_frame"] = static_cast<double>(labelled) / frames;
}
BENCHMARK(BM_PlaneDiscovery)
    ->Args({150, 1})
    ->Args({250, 1})
    ->Args({250, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

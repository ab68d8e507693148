// Per-frame time of the front-end on simulated 640x480 C4 frames with 150 features.
// Run: build/bin/bench_frontend --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <algorithm>
#include <chrono>

#include "mrpt_modules/frontend/feature_tracker.h"
#include "sim/simulator.h"

namespace {

const std::vector<rpvio::sim::RenderedFrame>& frames() {
  static const std::vector<rpvio::sim::RenderedFrame> rendered = [] {
    rpvio::sim::SimConfig config;
    config.scene.characters = 4;
    config.duration = 3.0;
    rpvio::sim::Simulator sim(config);
    std::vector<rpvio::sim::RenderedFrame> out;
    const auto times = sim.frameTimes();
    for (size_t k = 0; k < times.size(); ++k)
      out.push_back(sim.render(times[k], static_cast<int>(k)));
    return out;
  }();
  return rendered;
}

void trackSequence(benchmark::State& state, bool masks, int detection_level = 0,
                   int min_plane_features = rpvio::TrackerOptions{}.min_plane_features) {
  const auto& images = frames();
  rpvio::sim::SimConfig config;
  rpvio::TrackerOptions options;
  options.use_masks = masks;
  options.detection_level = detection_level;
  options.min_plane_features = min_plane_features;
  const rpvio::CameraIntrinsics camera = config.calibration().camera;
  size_t features = 0, tracked = 0;
  std::vector<double> frame_seconds;
  for (auto _ : state) {
    // One iteration = the whole 3 s sequence from a fresh tracker (detection + tracking mix).
    rpvio::FeatureTracker tracker(camera, options);
    for (size_t k = 0; k < images.size(); ++k) {
      const auto start = std::chrono::steady_clock::now();
      const auto f = tracker.track(k * 0.05, images[k].image, images[k].mask);
      frame_seconds.push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      features += f.features.size();
      ++tracked;
    }
  }
  // Seconds per frame, mean and median over every frame tracked (printed with an SI prefix:
  // 6.7m = 6.7 ms).
  state.counters["s_per_frame"] = benchmark::Counter(
      static_cast<double>(tracked), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  const auto middle = frame_seconds.begin() + static_cast<std::ptrdiff_t>(frame_seconds.size() / 2);
  std::nth_element(frame_seconds.begin(), middle, frame_seconds.end());
  state.counters["median_s_per_frame"] = *middle;
  state.counters["features_per_frame"] = static_cast<double>(features) / tracked;
}

void BM_FrontendPlaneMasks(benchmark::State& state) { trackSequence(state, true); }
void BM_FrontendNoMasks(benchmark::State& state) { trackSequence(state, false); }
// Corners detected on the half-resolution image (the `detection_level = 1` option).
void BM_FrontendPlaneMasksHalfResolutionCorners(benchmark::State& state) {
  trackSequence(state, true, 1);
}
// One spacing for every plane (`min_plane_features = 0`, mask-vins' detector).
void BM_FrontendPlaneMasksOneSpacing(benchmark::State& state) { trackSequence(state, true, 0, 0); }
BENCHMARK(BM_FrontendPlaneMasks)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FrontendNoMasks)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FrontendPlaneMasksHalfResolutionCorners)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FrontendPlaneMasksOneSpacing)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

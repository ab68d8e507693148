// Per-frame time of the front-end on simulated 640x480 C4 frames with 150 features, and on the
// handheld profile's 1280x720 C4 frames (fast turns, the gyroscope's rotation prediction on).
// Run: build/bin/bench_frontend --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <algorithm>
#include <chrono>
#include <map>
#include <string>

#include "mrpt_modules/frontend/feature_tracker.h"
#include "mrpt_modules/imu/gyro_rotation.h"
#include "sim/simulator.h"

namespace {

/// 3 s of C4 frames of a simulator profile, with the gyroscope's camera rotation between
/// consecutive frames (what FeatureTrackerModule hands the tracker).
struct Sequence {
  rpvio::sim::SimConfig config;
  std::vector<rpvio::sim::RenderedFrame> frames;
  std::vector<double> times;
  std::vector<Eigen::Matrix3d> R_cur_prev;  // [k]: from frame k−1 to k ([0]: identity)
};

const Sequence& sequence(const std::string& profile) {
  static std::map<std::string, Sequence> rendered;
  auto found = rendered.find(profile);
  if (found != rendered.end()) return found->second;
  Sequence s;
  s.config = rpvio::sim::SimConfig::profile(profile);
  s.config.scene.characters = 4;
  s.config.duration = 3.0;
  rpvio::sim::Simulator sim(s.config);
  const std::vector<rpvio::ImuSample> imu = sim.imuStream();
  const Eigen::Matrix3d R_BC = s.config.camera.T_BC().linear();
  s.times = sim.frameTimes();
  for (size_t k = 0; k < s.times.size(); ++k) {
    s.frames.push_back(sim.render(s.times[k], static_cast<int>(k)));
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    if (k > 0) {
      std::vector<rpvio::ImuSample> before;
      for (const auto& sample : imu)
        if (sample.t < s.times[k]) before.push_back(sample);
      R = rpvio::cameraRotationBetween(before, s.times[k - 1], s.times[k], R_BC);
    }
    s.R_cur_prev.push_back(R);
  }
  return rendered.emplace(profile, std::move(s)).first->second;
}

void trackSequence(benchmark::State& state, bool masks,
                   int detection_level = rpvio::TrackerOptions{}.detection_level,
                   int min_plane_features = rpvio::TrackerOptions{}.min_plane_features,
                   const std::string& profile = "paper",
                   int max_features = rpvio::TrackerOptions{}.max_features) {
  const Sequence& sequence_ = sequence(profile);
  const auto& images = sequence_.frames;
  const rpvio::sim::SimConfig& config = sequence_.config;
  rpvio::TrackerOptions options;
  options.use_masks = masks;
  options.detection_level = detection_level;
  options.min_plane_features = min_plane_features;
  options.max_features = max_features;
  const rpvio::CameraIntrinsics camera = config.calibration().camera;
  size_t features = 0, tracked = 0;
  std::vector<double> frame_seconds;
  for (auto _ : state) {
    // One iteration = the whole 3 s sequence from a fresh tracker (detection + tracking mix).
    rpvio::FeatureTracker tracker(camera, options);
    for (size_t k = 0; k < images.size(); ++k) {
      const auto start = std::chrono::steady_clock::now();
      const auto f = tracker.track(sequence_.times[k], images[k].image, images[k].mask,
                                   k > 0 ? &sequence_.R_cur_prev[k] : nullptr);
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
// rpvio-auto's front-end: no masks, 250 features.
void BM_FrontendNoMasks250Features(benchmark::State& state) {
  const rpvio::TrackerOptions defaults;
  trackSequence(state, false, defaults.detection_level, defaults.min_plane_features, "paper", 250);
}
// Corners detected on the half-resolution image (the `detection_level = 1` option).
void BM_FrontendPlaneMasksHalfResolutionCorners(benchmark::State& state) {
  trackSequence(state, true, 1);
}
// One spacing for every plane (`min_plane_features = 0`, mask-vins' detector).
void BM_FrontendPlaneMasksOneSpacing(benchmark::State& state) { trackSequence(state, true, 0, 0); }
// The handheld profile: 1280x720 at 30 Hz, 60° field of view, head turns up to 3 rad/s; corners
// on the half-resolution image (the default detection level at this width) and, for comparison,
// on the full one.
void BM_FrontendPlaneMasksHandheld1280x720(benchmark::State& state) {
  trackSequence(state, true, rpvio::TrackerOptions{}.detection_level,
                rpvio::TrackerOptions{}.min_plane_features, "handheld");
}
void BM_FrontendPlaneMasksHandheld1280x720FullResolutionCorners(benchmark::State& state) {
  trackSequence(state, true, 0, rpvio::TrackerOptions{}.min_plane_features, "handheld");
}
BENCHMARK(BM_FrontendPlaneMasks)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FrontendPlaneMasksHandheld1280x720)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FrontendPlaneMasksHandheld1280x720FullResolutionCorners)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_FrontendNoMasks)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FrontendNoMasks250Features)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FrontendPlaneMasksHalfResolutionCorners)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FrontendPlaneMasksOneSpacing)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

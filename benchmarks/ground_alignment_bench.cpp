// Time of one ground alignment (ground_alignment.h) between two real 1226x370 street images of
// ../shared/data/kitti07_vio (frames 60 and 61, 8 m/s), the pyramids built, with and without the
// last pair's motion as guess. Run from the repository root:
//   build/bin/bench_ground_alignment --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <opencv2/imgcodecs.hpp>

#include "mrpt_modules/frontend/ground_alignment.h"

namespace {

const std::string kImages = "../shared/data/kitti07_vio/mav0/cam0/data/";

void alignPair(benchmark::State& state, bool with_guess) {
  const cv::Mat previous = cv::imread(kImages + "1600000006235023104.png", cv::IMREAD_GRAYSCALE);
  const cv::Mat current = cv::imread(kImages + "1600000006339024896.png", cv::IMREAD_GRAYSCALE);
  if (previous.empty() || current.empty()) {
    state.SkipWithError("kitti07_vio images not found (run from the repository root)");
    return;
  }
  const rpvio::CameraIntrinsics camera{1226, 370, 707.0912, 707.0912, 601.8873, 183.1104};
  rpvio::GroundAligner aligner(camera, {});
  const rpvio::GroundMotion guess{Eigen::Vector3d(0, 0.01, -0.45), Eigen::Vector3d::UnitY()};
  for (auto _ : state) {
    const auto previous_levels = rpvio::buildGreyPyramid(previous, 5);
    const auto current_levels = rpvio::buildGreyPyramid(current, 5);
    const auto result = aligner.align(previous_levels, current_levels, Eigen::Matrix3d::Identity(),
                                      Eigen::Vector3d::UnitY(), with_guess ? &guess : nullptr);
    benchmark::DoNotOptimize(result);
  }
}
void BM_GroundAlignmentKitti07(benchmark::State& state) { alignPair(state, true); }
void BM_GroundAlignmentKitti07NoGuess(benchmark::State& state) { alignPair(state, false); }
BENCHMARK(BM_GroundAlignmentKitti07)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_GroundAlignmentKitti07NoGuess)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

// The main() of every benchmark here: OpenCV on one thread, as rpvio-slam runs by default.
#include <benchmark/benchmark.h>
#include <opencv2/core/utility.hpp>

int main(int argc, char** argv) {
  cv::setNumThreads(1);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

// A real static start (EuRoC V1_01: the MAV sits still for 95 frames): the initializer must wait
// and say why, never invent motion. Both methods; for the planar one every feature is treated as
// lying on one plane so that only the parallax gate can stop it.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "common/text_table.h"
#include "mrpt_modules/frontend/feature_tracker.h"
#include "mrpt_modules/initialization/initializer.h"
#include "rawlog_io/euroc_csv.h"
#include "rawlog_io/euroc_import.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

class StaticStart : public ::testing::TestWithParam<InitializerMethod> {};

TEST_P(StaticStart, WaitsOnARealStaticStart) {
  const std::string mav0 = test::dataDir() + "/euroc_v101_static/mav0";
  const Calibration calib = readEurocCalibration(mav0);
  const auto imu = readEurocImuCsv(mav0 + "/imu0/data.csv");
  TrackerOptions options;
  options.use_masks = false;
  FeatureTracker tracker(calib.camera, options);
  InitializerOptions init;
  init.method = GetParam();
  Initializer initializer(calib, init);
  initializer.setMinLoggingLevel(mrpt::system::LVL_WARN);
  std::vector<FeatureFrame> frames;
  std::vector<std::shared_ptr<ImuPreintegration>> preintegrations;
  size_t imu_index = 0;
  InitializationResult result;
  forEachTextRow(mav0 + "/cam0/data.csv", [&](const std::vector<std::string>& f, int line) {
    const double t = parseFiniteNumber(f[0], "data.csv", line) * 1e-9;
    FeatureFrame frame =
        tracker.track(t, cv::imread(mav0 + "/cam0/data/" + f[1], cv::IMREAD_GRAYSCALE), {});
    for (auto& feature : frame.features) feature.plane_id = 1;
    while (imu_index + 1 < imu.size() && imu[imu_index + 1].t <= t) ++imu_index;
    std::shared_ptr<ImuPreintegration> from_previous;
    if (!frames.empty()) {
      size_t j = imu_index;
      while (j > 0 && imu[j - 1].t > frames.back().t) --j;
      const ImuSample& first = imu[j > 0 ? j - 1 : 0];
      from_previous = std::make_shared<ImuPreintegration>(
          first.accel, first.gyro, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), calib.imu);
      for (; j <= imu_index; ++j)
        if (j > 0) from_previous->push(imu[j].t - imu[j - 1].t, imu[j].accel, imu[j].gyro);
    }
    frames.push_back(frame);
    preintegrations.push_back(from_previous);
    result = initializer.tryInitialize(frames, preintegrations);
    EXPECT_FALSE(result.ok()) << "initialized on a static start at frame " << frames.size();
  });
  EXPECT_EQ(frames.size(), 95u);
  EXPECT_EQ(result.status, InitStatus::kTooLittleParallax) << result.reason;
}

INSTANTIATE_TEST_SUITE_P(Methods, StaticStart,
                         ::testing::Values(InitializerMethod::kPlanarHomography,
                                           InitializerMethod::kEssentialMatrix));

}  // namespace
}  // namespace rpvio

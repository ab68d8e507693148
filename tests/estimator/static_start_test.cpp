// A real static start (EuRoC V1_01: the MAV sits still for 95 frames): the initializer must wait
// and say why, never invent motion. Every feature is treated as lying on one plane so that only
// the parallax gate can stop it.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "mrpt_modules/estimator/planar_initializer.h"
#include "mrpt_modules/frontend/feature_tracker.h"
#include "rawlog_io/euroc_csv.h"
#include "rawlog_io/euroc_import.h"
#include "rawlog_io/text_table.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

TEST(PlanarInitializer, WaitsOnARealStaticStart) {
  const std::string mav0 = test::dataDir() + "/euroc_v101_static/mav0";
  const Calibration calib = readEurocCalibration(mav0);
  const auto imu = readEurocImuCsv(mav0 + "/imu0/data.csv");
  TrackerOptions options;
  options.use_masks = false;
  FeatureTracker tracker(calib.camera, options);
  std::vector<WindowFrame> window;
  size_t imu_index = 0, attempts = 0;
  std::string why;
  forEachTextRow(mav0 + "/cam0/data.csv", [&](const std::vector<std::string>& f, int line) {
    const double t = parseFiniteNumber(f[0], "data.csv", line) * 1e-9;
    WindowFrame frame;
    frame.features =
        tracker.track(t, cv::imread(mav0 + "/cam0/data/" + f[1], cv::IMREAD_GRAYSCALE), {});
    for (auto& feature : frame.features.features) feature.plane_id = 1;
    while (imu_index + 1 < imu.size() && imu[imu_index + 1].t <= t) ++imu_index;
    if (!window.empty()) {
      size_t j = imu_index;
      while (j > 0 && imu[j - 1].t > window.back().features.t) --j;
      frame.imu_from_previous = std::make_shared<ImuPreintegration>(
          imu[j > 0 ? j - 1 : 0].accel, imu[j > 0 ? j - 1 : 0].gyro, Eigen::Vector3d::Zero(),
          Eigen::Vector3d::Zero(), calib.imu);
      for (; j <= imu_index; ++j)
        if (j > 0)
          frame.imu_from_previous->push(imu[j].t - imu[j - 1].t, imu[j].accel, imu[j].gyro);
    }
    window.push_back(frame);
    std::vector<WindowFrame> attempt = window;
    ++attempts;
    EXPECT_FALSE(initializeFromPlane(attempt, calib, {}, &why)) << "initialized on a static start";
  });
  EXPECT_EQ(attempts, 95u);
  EXPECT_EQ(why, "too little parallax");
}

}  // namespace
}  // namespace rpvio

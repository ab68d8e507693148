// The plane discovery on a real static start (EuRoC V1_01: the MAV sits still on the floor for
// 95 frames, real gyroscope): without translation no plane can be told from the scene by its
// motion, and none may be invented from tracking noise.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "common/text_table.h"
#include "mrpt_modules/estimator/plane_discovery.h"
#include "mrpt_modules/frontend/feature_tracker.h"
#include "mrpt_modules/imu/imu_preintegration.h"
#include "rawlog_io/euroc_csv.h"
#include "rawlog_io/euroc_import.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

TEST(PlaneDiscoveryOnRealImages, FindsNothingWhileTheCameraSitsStill) {
  const std::string mav0 = test::dataDir() + "/euroc_v101_static/mav0";
  const Calibration calib = readEurocCalibration(mav0);
  const auto imu = readEurocImuCsv(mav0 + "/imu0/data.csv");
  TrackerOptions tracking;
  tracking.use_masks = false;
  FeatureTracker tracker(calib.camera, tracking);
  PlaneDiscoveryOptions options;
  options.enabled = true;
  PlaneDiscovery discovery(options);
  const Eigen::Quaterniond q_BC(calib.T_BC.linear());
  size_t frames = 0, features = 0, labelled = 0, next_sample = 0;
  double previous_t = -1;
  forEachTextRow(mav0 + "/cam0/data.csv", [&](const std::vector<std::string>& f, int line) {
    const double t = parseFiniteNumber(f[0], "data.csv", line) * 1e-9;
    const FeatureFrame frame =
        tracker.track(t, cv::imread(mav0 + "/cam0/data/" + f[1], cv::IMREAD_GRAYSCALE), {});
    // The body's rotation since the previous frame from the gyroscope, in the camera.
    Eigen::Quaterniond q_body = Eigen::Quaterniond::Identity();
    if (previous_t >= 0) {
      ImuPreintegration rotation(imu[next_sample].accel, imu[next_sample].gyro,
                                 Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), calib.imu);
      for (; next_sample + 1 < imu.size() && imu[next_sample + 1].t <= t; ++next_sample)
        rotation.push(imu[next_sample + 1].t - imu[next_sample].t, imu[next_sample + 1].accel,
                      imu[next_sample + 1].gyro);
      q_body = rotation.deltaQ();
    }
    while (next_sample + 1 < imu.size() && imu[next_sample + 1].t <= t) ++next_sample;
    const Eigen::Quaterniond R_previous_current = q_BC.inverse() * q_body * q_BC;
    const FeatureFrame out = discovery.label(frame, R_previous_current);
    ++frames;
    features += frame.features.size();
    labelled += out.features.size();
    previous_t = t;
  });
  EXPECT_EQ(frames, 95u);
  EXPECT_GT(features, 95u * 50);  // tracked, just not moving
  EXPECT_EQ(labelled, 0u);
  EXPECT_EQ(discovery.segmentsFound(), 0u);
  EXPECT_TRUE(discovery.events().empty());
}

}  // namespace
}  // namespace rpvio

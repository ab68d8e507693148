// Fault injection (issue 10): each fault changes exactly what it says in the written rawlog —
// frames lost, IMU samples missing or clipped, black or blurred images, empty masks — and nothing
// else; malformed intervals are refused.
#include <gtest/gtest.h>

#include <mrpt/obs/CObservationIMU.h>
#include <mrpt/obs/CObservationImage.h>

#include <map>
#include <opencv2/core.hpp>

#include "rawlog_io/rawlog_labels.h"
#include "rawlog_io/rawlog_reader.h"
#include "sim/sequence_writer.h"
#include "tests/test_util.h"

namespace rpvio::sim {
namespace {

struct Contents {
  std::map<double, cv::Mat> images, masks;  // by stamp
  std::vector<ImuSample> imu;
};

Contents writeAndRead(const FaultInjection& faults) {
  SimConfig config;
  config.duration = 1.0;
  config.scene.characters = 1;
  config.scene.texel_size = 0.05;
  config.faults = faults;
  test::TempDir dir;
  writeSequence(config, dir.path().string());
  Contents c;
  RawlogReader reader(dir.file("seq.rawlog"));
  while (const auto obs = reader.next()) {
    if (const auto* imu = dynamic_cast<const mrpt::obs::CObservationIMU*>(obs.get())) {
      c.imu.push_back(toImuSample(*imu, reader));
    } else if (const auto* image = dynamic_cast<const mrpt::obs::CObservationImage*>(obs.get())) {
      const double t = std::round(toSeconds(obs->timestamp) * 1000) / 1000;
      (obs->sensorLabel == labels::kCamera ? c.images : c.masks)[t] = loadGrayImage(*image, reader);
    }
  }
  return c;
}

bool hasFrame(const Contents& c, double t) { return c.images.count(t) && c.masks.count(t); }

TEST(FaultInjection, EachFaultDoesWhatItSays) {
  const Contents clean = writeAndRead({});
  ASSERT_EQ(clean.images.size(), 21u);
  ASSERT_EQ(clean.imu.size(), 201u);

  FaultInjection drops;
  drops.dropped_frames = {0.2};
  drops.dropped_bursts = {{0.5, 0.2}};  // 0.5, 0.55, 0.6, 0.65
  const Contents dropped = writeAndRead(drops);
  EXPECT_EQ(dropped.images.size(), 16u);
  EXPECT_FALSE(hasFrame(dropped, 0.2));
  EXPECT_FALSE(hasFrame(dropped, 0.65));
  EXPECT_TRUE(hasFrame(dropped, 0.7));
  EXPECT_EQ(cv::norm(dropped.images.at(0.7), clean.images.at(0.7)), 0.0);
  EXPECT_EQ(dropped.imu.size(), 201u);

  FaultInjection gap;
  gap.imu_gaps = {{0.3, 0.1}};
  const Contents gapped = writeAndRead(gap);
  EXPECT_EQ(gapped.imu.size(), 181u);
  for (const ImuSample& s : gapped.imu) EXPECT_FALSE(s.t >= 0.3 - 1e-9 && s.t < 0.4 - 1e-9) << s.t;
  EXPECT_EQ(gapped.images.size(), 21u);

  FaultInjection image_faults;
  image_faults.blackouts = {{0.1, 0.1}};
  image_faults.motion_blur = {{0.4, 0.1}};
  image_faults.no_planes = {{0.8, 0.1}};
  const Contents faulty = writeAndRead(image_faults);
  EXPECT_EQ(cv::countNonZero(faulty.images.at(0.1)), 0);
  EXPECT_EQ(cv::countNonZero(faulty.masks.at(0.15)), 0);
  EXPECT_GT(cv::countNonZero(faulty.images.at(0.2)), 0);
  // Blur: same mean brightness, less gradient energy.
  const cv::Mat& sharp = clean.images.at(0.4);
  const cv::Mat& blurred = faulty.images.at(0.4);
  EXPECT_NEAR(cv::mean(blurred)[0], cv::mean(sharp)[0], 2.0);
  auto gradientEnergy = [](const cv::Mat& m) {
    cv::Mat f;
    m.convertTo(f, CV_32F);
    cv::Mat shifted = f(cv::Rect(1, 0, f.cols - 1, f.rows)) - f(cv::Rect(0, 0, f.cols - 1, f.rows));
    return cv::norm(shifted);
  };
  EXPECT_LT(gradientEnergy(blurred), 0.5 * gradientEnergy(sharp));
  EXPECT_EQ(cv::norm(faulty.masks.at(0.4), clean.masks.at(0.4)), 0.0);
  EXPECT_EQ(cv::countNonZero(faulty.masks.at(0.8)), 0);
  EXPECT_EQ(cv::norm(faulty.images.at(0.8), clean.images.at(0.8)), 0.0);

  FaultInjection saturation;
  saturation.accel_saturation = 9.0;
  saturation.gyro_saturation = 0.01;
  const Contents clipped = writeAndRead(saturation);
  ASSERT_EQ(clipped.imu.size(), clean.imu.size());
  size_t changed = 0;
  for (size_t k = 0; k < clipped.imu.size(); ++k) {
    EXPECT_LE(clipped.imu[k].accel.cwiseAbs().maxCoeff(), 9.0);
    EXPECT_LE(clipped.imu[k].gyro.cwiseAbs().maxCoeff(), 0.01);
    changed += clipped.imu[k].accel != clean.imu[k].accel;
  }
  EXPECT_GT(changed, 100u);  // gravity alone exceeds 9 m/s² on the z axis
}

TEST(FaultInjection, MalformedIntervalsAreRefused) {
  EXPECT_NEAR(parseTimeInterval("10:2", "--blackout").duration, 2.0, 1e-12);
  for (const char* bad : {"10", "10:", ":2", "a:2", "10:-1", "10:0", "-1:2", "1:2x"})
    EXPECT_THROW(parseTimeInterval(bad, "--blackout"), std::invalid_argument) << bad;
}

TEST(FaultInjection, SimulatorAppRejectsBadFaultOptions) {
  test::TempDir dir;
  std::string out;
  EXPECT_EQ(
      test::runCommand(
          test::binDir() + "/rpvio-sim --characters 0 --blackout 3 --out " + dir.file("x"), out),
      2);
  EXPECT_NE(out.find("--blackout expects START:DURATION"), std::string::npos) << out;
  EXPECT_EQ(test::runCommand(test::binDir() + "/rpvio-sim --characters 0 --drop-frame soon --out " +
                                 dir.file("x"),
                             out),
            2);
  EXPECT_NE(out.find("--drop-frame expects a time"), std::string::npos) << out;
}

}  // namespace
}  // namespace rpvio::sim

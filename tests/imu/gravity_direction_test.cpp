// The front-end's gravity direction (gravity_direction.h) against the true attitude.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "mrpt_modules/imu/gravity_direction.h"

namespace rpvio {
namespace {

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180 / M_PI;
}

/// 200 Hz samples of a body turning at `rate` (rad/s, body frame) with no acceleration but
/// `extra` (world frame, m/s²), starting level with a 10° roll.
void simulate(GravityDirection& filter, const Eigen::Vector3d& rate, const Eigen::Vector3d& extra,
              double seconds, Eigen::Matrix3d& R_wb) {
  R_wb = Eigen::AngleAxisd(10 * M_PI / 180, Eigen::Vector3d::UnitX()).matrix();
  const Eigen::Vector3d g(0, 0, -9.81);
  for (int k = 0; k <= seconds * 200; ++k) {
    if (k > 0) R_wb = R_wb * Eigen::AngleAxisd(rate.norm() / 200, rate.normalized()).matrix();
    filter.add({k / 200.0, rate, R_wb.transpose() * (extra - g)});
  }
}

TEST(GravityDirection, FollowsTheBodyThroughATurn) {
  GravityDirection filter(9.81, 3);
  Eigen::Matrix3d R_wb;
  simulate(filter, Eigen::Vector3d(0.3, -0.2, 0.5), Eigen::Vector3d::Zero(), 20, R_wb);
  ASSERT_TRUE(filter.down());
  EXPECT_LT(angleDeg(*filter.down(), R_wb.transpose() * -Eigen::Vector3d::UnitZ()), 0.5);
}

TEST(GravityDirection, ACarsTurnTiltsItByLessThanItsOwnShare) {
  // 3 s of a 3 m/s² centripetal acceleration (17° if taken as gravity) after 5 s of driving level.
  GravityDirection filter(9.81, 3);
  Eigen::Matrix3d R_wb;
  simulate(filter, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 5, R_wb);
  const Eigen::Vector3d down_true = R_wb.transpose() * -Eigen::Vector3d::UnitZ();
  EXPECT_LT(angleDeg(*filter.down(), down_true), 0.5);
  GravityDirection turning = filter;
  for (int k = 1; k <= 600; ++k)
    turning.add(
        {5 + k / 200.0, Eigen::Vector3d::Zero(), R_wb.transpose() * Eigen::Vector3d(0, 3, 9.81)});
  const double tilt = angleDeg(*turning.down(), down_true);
  EXPECT_GT(tilt, 5);   // it does lean: the filter has no other source
  EXPECT_LT(tilt, 12);  // 1 − e^(−3/3) of the 17°
}

}  // namespace
}  // namespace rpvio

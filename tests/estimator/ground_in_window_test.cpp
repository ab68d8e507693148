// The window's ground plane for the camera-height factor: the level plane below the camera at
// about its height, not a ceiling, a wall, a table top or a slope.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "mrpt_modules/estimator/ground_in_window.h"

namespace rpvio {
namespace {

PlaneEstimate plane(const Eigen::Vector3d& n, double d) {
  PlaneEstimate e;
  const Eigen::Vector3d unit = n.normalized();
  for (int k = 0; k < 3; ++k) e.normal[k] = unit[k];
  e.distance[0] = d;
  return e;
}

TEST(GroundInWindow, TheLevelPlaneBelowTheCameraAtItsHeight) {
  const Eigen::Vector3d camera(3, -2, 1.65);
  PlaneEstimates planes;
  planes[1] = plane({1, 0, 0}, 10);     // a wall
  planes[2] = plane({0, 0, 1}, 5);      // the ceiling, above
  planes[3] = plane({0, 0, -1}, -0.8);  // a table top at z = 0.8, normal down
  planes[4] = plane({0, 0, -1}, 0.02);  // the floor at z = −0.02, normal down
  const double slope = std::tan(15 * M_PI / 180);
  planes[5] = plane({slope, 0, 1}, slope * 3);  // a 15° ramp through (3, ·, 0)
  const std::set<int> all{1, 2, 3, 4, 5};
  const auto ground = groundInWindow(planes, all, camera, 1.65, 10);
  ASSERT_TRUE(ground);
  EXPECT_EQ(ground->plane, 4);
  // Its normal points down: the camera is on its negative side.
  EXPECT_EQ(ground->side, -1.0);
  // Without the floor: no plane is the ground (the table is 0.85 m below, the ramp too steep).
  EXPECT_FALSE(groundInWindow(planes, {1, 2, 3, 5}, camera, 1.65, 10));
  // The ramp passes with a wider tilt; the floor is nearer the height all the same.
  const auto with_ramp = groundInWindow(planes, all, camera, 1.65, 20);
  ASSERT_TRUE(with_ramp);
  EXPECT_EQ(with_ramp->plane, 4);
  EXPECT_EQ(groundInWindow(planes, {1, 2, 3, 5}, camera, 1.65, 20)->plane, 5);
  // A window whose scale drifted 20 %: still the floor; 40 %: no ground (without the table, which
  // would then be as near the height).
  EXPECT_EQ(groundInWindow(planes, all, camera, 1.67 / 1.2, 10)->plane, 4);
  EXPECT_FALSE(groundInWindow(planes, {1, 2, 4, 5}, camera, 1.67 / 1.4, 10));
}

}  // namespace
}  // namespace rpvio

// The plane map following the pose graph: each plane moved by the correction of the keyframe
// nearest to when it was first seen; a saved map's planes merged with a run's.
#include <gtest/gtest.h>

#include "mrpt_modules/loop/planes_in_graph_frame.h"

namespace rpvio {
namespace {

Eigen::Isometry3d shift(double x) { return Eigen::Isometry3d(Eigen::Translation3d(x, 0, 0)); }

Plane wallAt(double x, double first_seen) {
  Plane p;
  p.normal = Eigen::Vector3d::UnitX();
  p.distance = x;
  p.first_seen = first_seen;
  p.observations = 3;
  for (double y : {0.0, 1.0, 2.0})
    for (double z : {0.0, 1.0}) p.support.emplace_back(x, y, z);
  p.updatePolygon();
  return p;
}

TEST(PlanesInGraphFrame, EachPlaneMovesWithTheKeyframeNearestItsFirstSighting) {
  const KeyframeCorrections corrections = {{10.0, shift(1)}, {20.0, shift(2)}, {30.0, shift(3)}};
  const auto moved = planesInGraphFrame(
      {wallAt(0, 5), wallAt(0, 14.9), wallAt(0, 15.1), wallAt(0, 29), wallAt(0, 40)}, corrections);
  ASSERT_EQ(moved.size(), 5u);
  const double expected[] = {1, 1, 2, 3, 3};
  for (size_t k = 0; k < 5; ++k) {
    EXPECT_NEAR(moved[k].distance, expected[k], 1e-12) << k;
    EXPECT_NEAR(moved[k].support.front().x(), expected[k], 1e-12) << k;
  }
  EXPECT_EQ(planesInGraphFrame({wallAt(4, 1)}, {}).front().distance, 4);
}

TEST(PlanesInGraphFrame, ARunsPlanesMergeIntoTheSavedOnesAndNewOnesAreAdded) {
  // The saved map keeps outlines only (planes.yaml): the same wall seen again merges with it,
  // a wall 3 m away stays apart, and so do two saved planes in one plane but far apart.
  Plane saved = wallAt(0, 1);
  saved.support.clear();
  Plane far_twin = wallAt(0, 1);
  for (auto& x : far_twin.support) x.y() += 20;
  far_twin.updatePolygon();
  far_twin.support.clear();
  const auto merged = mergedPlanes({saved, far_twin}, {wallAt(0.02, 50), wallAt(3, 50)});
  ASSERT_EQ(merged.size(), 3u);
  EXPECT_EQ(merged[0].observations, 6u);
  EXPECT_NEAR(merged[0].distance, 0.01, 0.011);
  EXPECT_EQ(merged[1].observations, 3u);
  EXPECT_NEAR(merged[2].distance, 3, 1e-12);
}

}  // namespace
}  // namespace rpvio

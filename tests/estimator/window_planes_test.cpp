// WindowPlanes::choose: the labels whose features get homography factors, among every plane or
// among those a verification found static.
#include <gtest/gtest.h>

#include <set>
#include <utility>

#include "mrpt_modules/estimator/window_planes.h"

namespace rpvio {
namespace {

/// One frame with 5 tracks on plane 1, 20 on plane 2 and 10 on plane 3.
FeatureManager threePlanes() {
  FeatureFrame frame;
  int id = 0;
  for (const auto& [plane, tracks] : {std::pair{1, 5}, {2, 20}, {3, 10}})
    for (int i = 0; i < tracks; ++i) {
      TrackedFeature f;
      f.id = id++;
      f.plane_id = plane;
      frame.features.push_back(f);
    }
  FeatureManager features;
  features.addFrame(0, frame);
  return features;
}

TEST(WindowPlanes, OnlyEligiblePlanesAreChosen) {
  const FeatureManager features = threePlanes();
  const std::set<int> eligible{1, 3};  // plane 2 never judged static

  WindowPlanes all(HomographyPlanes::kAll);
  all.choose(features);
  EXPECT_EQ(all.chosen(), (std::set<int>{1, 2, 3}));
  all.choose(features, &eligible);
  EXPECT_EQ(all.chosen(), eligible);

  WindowPlanes largest(HomographyPlanes::kLargest);
  largest.choose(features);
  EXPECT_EQ(largest.chosen(), std::set<int>{2});
  // The current plane is no longer eligible: the largest eligible one takes over.
  largest.choose(features, &eligible);
  EXPECT_EQ(largest.chosen(), std::set<int>{3});

  const std::set<int> none;
  largest.choose(features, &none);
  EXPECT_TRUE(largest.chosen().empty());
}

}  // namespace
}  // namespace rpvio

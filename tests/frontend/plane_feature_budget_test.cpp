// densePlanes: which planes get a tighter feature spacing, and which spacing.
#include <gtest/gtest.h>

#include <cmath>

#include "mrpt_modules/frontend/plane_feature_budget.h"

namespace rpvio {
namespace {

TEST(PlaneFeatureBudget, SmallPlanesGetTheSpacingThatHoldsTheirShare) {
  cv::Mat mask(480, 640, CV_8U, cv::Scalar(1));  // a large plane...
  mask(cv::Rect(400, 300, 180, 60)).setTo(2);    // ... a small one (10800 px) ...
  mask(cv::Rect(50, 50, 40, 20)).setTo(3);       // ... a tiny one (800 px) ...
  mask(cv::Rect(100, 400, 400, 50)).setTo(0);    // ... and a character (no plane)
  cv::Mat detectable(mask.size(), CV_8U, cv::Scalar(255));
  detectable(cv::Rect(400, 300, 10, 60)).setTo(0);  // 600 px of plane 2 not detectable
  const auto dense = densePlanes(mask, detectable, 20, 30, 21);
  ASSERT_EQ(dense.size(), 2u);  // plane 1 holds 20 features at 30 px
  ASSERT_TRUE(dense.count(2) && dense.count(3));
  EXPECT_NEAR(dense.at(2).spacing, std::sqrt(10200 / 20.0), 1e-9);
  EXPECT_EQ(dense.at(2).box, cv::Rect(410, 300, 170, 60));
  EXPECT_EQ(dense.at(3).spacing, 21);  // √(800 / 20) = 6.3, below one KLT window
  EXPECT_EQ(dense.at(3).box, cv::Rect(50, 50, 40, 20));
}

TEST(PlaneFeatureBudget, NoneWhenOffOrWhenEveryPlaneHoldsItsShare) {
  cv::Mat mask(480, 640, CV_8U, cv::Scalar(1));
  mask(cv::Rect(0, 0, 320, 480)).setTo(2);
  mask(cv::Rect(600, 0, 40, 40)).setTo(255);  // unknown: never a plane
  const cv::Mat detectable(mask.size(), CV_8U, cv::Scalar(255));
  EXPECT_TRUE(densePlanes(mask, detectable, 20, 30, 21).empty());
  mask(cv::Rect(0, 0, 40, 40)).setTo(4);
  EXPECT_TRUE(densePlanes(mask, detectable, 0, 30, 21).empty());
  EXPECT_EQ(densePlanes(mask, detectable, 20, 30, 21).size(), 1u);
  // Not detectable at all: no plane to hold features.
  EXPECT_TRUE(densePlanes(mask, cv::Mat::zeros(mask.size(), CV_8U), 20, 30, 21).empty());
}

}  // namespace
}  // namespace rpvio

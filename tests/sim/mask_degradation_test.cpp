// CNN-like mask degradation: each option does what it says, and nothing happens by default.
#include <gtest/gtest.h>

#include "sim/mask_degradation.h"

namespace rpvio::sim {
namespace {

/// Plane 1 on the left half, plane 2 on the right, a "character" (0) square in the middle.
cv::Mat groundTruthMask() {
  cv::Mat m(100, 200, CV_8U, cv::Scalar(1));
  m(cv::Rect(100, 0, 100, 100)).setTo(2);
  m(cv::Rect(80, 30, 40, 40)).setTo(0);
  return m;
}

TEST(MaskDegradation, OffByDefault) {
  cv::Mat m = groundTruthMask();
  const MaskDegradation none;
  EXPECT_FALSE(none.enabled());
  degradeMask(m, none, 1);
  EXPECT_EQ(cv::countNonZero(m != groundTruthMask()), 0);
}

TEST(MaskDegradation, BoundaryBleedsOntoCharacters) {
  cv::Mat m = groundTruthMask();
  MaskDegradation d;
  d.boundary_bleed_px = 3;
  degradeMask(m, d, 1);
  // The 40x40 character shrinks by 3 px on each side; planes are untouched elsewhere.
  EXPECT_EQ(cv::countNonZero(m == 0), 34 * 34);
  EXPECT_EQ(m.at<uint8_t>(50, 81), 1);
  EXPECT_EQ(m.at<uint8_t>(50, 100), 0);
}

TEST(MaskDegradation, MissedSplitAndSpuriousPlanes) {
  MaskDegradation missed;
  missed.missed_plane_rate = 1.0;
  cv::Mat m = groundTruthMask();
  degradeMask(m, missed, 1);
  EXPECT_EQ(cv::countNonZero(m), 0);  // every plane missed

  MaskDegradation split;
  split.split_plane_id = 1;
  m = groundTruthMask();
  m(cv::Rect(0, 80, 200, 20)).setTo(1);  // plane 1 reaches the right half at the bottom
  degradeMask(m, split, 1);
  EXPECT_EQ(m.at<uint8_t>(90, 150), 101);
  EXPECT_EQ(m.at<uint8_t>(90, 20), 1);

  MaskDegradation spurious;
  spurious.spurious_blob_rate = 1.0;
  m = groundTruthMask();
  degradeMask(m, spurious, 7);
  EXPECT_LT(cv::countNonZero(m == 0), 40 * 40);  // part of the character now carries a plane id
}

}  // namespace
}  // namespace rpvio::sim

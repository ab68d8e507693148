// The neighbours' local affine motion (local_warps): exact on an affine motion field, and none
// where the neighbours lie along a line (the motion across it is unobserved) or are too few.
#include <gtest/gtest.h>

#include <cmath>

#include "mrpt_modules/frontend/local_image_motion.h"

namespace rpvio {
namespace {

const cv::Matx22d kAffine(1.08, 0.05, -0.03, 0.95);
const cv::Point2f kShift(6.5f, -2.0f);

PixelMotion moved(float x, float y) {
  const cv::Vec2d p = kAffine * cv::Vec2d(x, y);
  return {{x, y}, cv::Point2f(static_cast<float>(p[0]), static_cast<float>(p[1])) + kShift};
}

TEST(LocalImageMotion, RecoversAnAffineMotionFieldFromScatteredNeighbours) {
  std::vector<PixelMotion> motions = {moved(100, 100)};
  for (double angle = 0; angle < 2 * M_PI - 1e-9; angle += M_PI / 4)
    motions.push_back(moved(static_cast<float>(100 + 20 * std::cos(angle)),
                            static_cast<float>(100 + 12 * std::sin(angle))));
  const auto A = localImageMotion(motions, 0, 8, 60);
  ASSERT_TRUE(A.has_value());
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c) EXPECT_NEAR((*A)(r, c), kAffine(r, c), 1e-4);
}

TEST(LocalImageMotion, NoneAlongALineOrWithTooFewNeighbours) {
  // Eight neighbours along an edge, 1 px off it at most: spread ratio ~1e-3.
  std::vector<PixelMotion> along = {moved(100, 100)};
  for (int k = 1; k <= 8; ++k)
    along.push_back(moved(static_cast<float>(100 + 5 * k), static_cast<float>(100 + (k % 2))));
  EXPECT_FALSE(localImageMotion(along, 0, 8, 60).has_value());
  // The same neighbours 10 px either side of the line: spread ratio 0.15, observed.
  for (int k = 1; k <= 8; ++k)
    along[k] = moved(static_cast<float>(100 + 5 * k), static_cast<float>(k % 2 ? 90 : 110));
  EXPECT_TRUE(localImageMotion(along, 0, 8, 60).has_value());
  // Two neighbours within reach.
  const std::vector<PixelMotion> few = {moved(100, 100), moved(110, 100), moved(100, 110),
                                        moved(300, 300)};
  EXPECT_FALSE(localImageMotion(few, 0, 8, 60).has_value());
}

}  // namespace
}  // namespace rpvio

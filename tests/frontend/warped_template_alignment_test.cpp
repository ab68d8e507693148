// The anchored alignment against a known plane motion: a textured image and its exact warp by a
// homography (strong perspective and scale change); the birth patch warped by the homography's
// Jacobian finds the true position, a translational match does not.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "mrpt_modules/frontend/warped_template_alignment.h"

namespace rpvio {
namespace {

cv::Mat smoothTexture() {
  cv::Mat noise(480, 640, CV_32F);
  cv::RNG rng(7);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 2.0);
  cv::normalize(noise, noise, 0, 255, cv::NORM_MINMAX);
  cv::Mat out;
  noise.convertTo(out, CV_8U);
  return out;
}

cv::Point2f apply(const cv::Matx33d& H, cv::Point2f p) {
  const cv::Vec3d q = H * cv::Vec3d(p.x, p.y, 1);
  return {static_cast<float>(q[0] / q[2]), static_cast<float>(q[1] / q[2])};
}

// A floor-like motion: the image rows below the horizon stretch and shear, by up to ~1.6x.
const cv::Matx33d kHomography(1.25, 0.18, -40, 0.02, 1.35, -60, 0.0, 0.0006, 1);

TEST(WarpedTemplateAlignment, FindsThePointUnderAHomography) {
  const cv::Mat birth = smoothTexture();
  cv::Mat current;
  cv::warpPerspective(birth, current, cv::Mat(kHomography), birth.size(), cv::INTER_CUBIC);
  std::vector<double> warped_errors, translational_errors;
  for (int y = 120; y <= 320; y += 40)
    for (int x = 160; x <= 420; x += 40) {
      const cv::Point2f p(x, y), truth = apply(kHomography, p);
      const cv::Point2f guess = truth + cv::Point2f(0.6f, -0.4f);
      const auto warped =
          alignWarpedTemplate(birth, p, homographyJacobian(kHomography, p), current, guess);
      ASSERT_TRUE(warped) << "at " << p;
      warped_errors.push_back(cv::norm(*warped - truth));
      const auto translational = alignWarpedTemplate(birth, p, cv::Matx22d::eye(), current, guess);
      // No match (uncorrelated after alignment) counts as an infinite error.
      translational_errors.push_back(translational ? cv::norm(*translational - truth) : INFINITY);
    }
  std::sort(warped_errors.begin(), warped_errors.end());
  std::sort(translational_errors.begin(), translational_errors.end());
  const size_t mid = warped_errors.size() / 2;
  std::printf(
      "error median %.3f px, max %.3f px (translational: median %.3f px, %zu of %zu not "
      "matched)\n",
      warped_errors[mid], warped_errors.back(), translational_errors[mid],
      static_cast<size_t>(
          std::count(translational_errors.begin(), translational_errors.end(), INFINITY)),
      translational_errors.size());
  // The warp is the homography's local affine map: its perspective curvature over the 21x21
  // patch is what is left (measured 0.02 px median, 0.06 px max; translational 0.19 / 0.65 px).
  EXPECT_LT(warped_errors[mid], 0.05);
  EXPECT_LT(warped_errors.back(), 0.1);
  EXPECT_GT(translational_errors[mid], 5 * warped_errors[mid]);
}

TEST(WarpedTemplateAlignment, ContrastChangeDoesNotMoveTheMatch) {
  const cv::Mat birth = smoothTexture();
  cv::Mat current;
  const cv::Matx33d shift(1, 0, 3.4, 0, 1, -2.2, 0, 0, 1);
  cv::warpPerspective(birth, current, cv::Mat(shift), birth.size(), cv::INTER_CUBIC);
  current.convertTo(current, CV_8U, 0.7, 30);
  const cv::Point2f p(300, 200);
  const auto found =
      alignWarpedTemplate(birth, p, cv::Matx22d::eye(), current, p + cv::Point2f(3, -2));
  ASSERT_TRUE(found);
  EXPECT_LT(cv::norm(*found - apply(shift, p)), 0.05);
}

TEST(WarpedTemplateAlignment, PatchLeavingTheImageIsNoMatch) {
  const cv::Mat birth = smoothTexture();
  EXPECT_FALSE(alignWarpedTemplate(birth, {5, 5}, cv::Matx22d::eye(), birth, {5, 5}));
  EXPECT_FALSE(alignWarpedTemplate(birth, {300, 200}, cv::Matx22d::eye(), birth, {635, 200}));
  EXPECT_FALSE(alignWarpedTemplate(birth, {300, 200}, cv::Matx22d::zeros(), birth, {300, 200}));
  // The true match lies where its patch would cross the right border; the guess is still inside.
  cv::Mat current;
  const cv::Matx33d shift(1, 0, 3.5, 0, 1, 0, 0, 0, 1);
  cv::warpPerspective(birth, current, cv::Mat(shift), birth.size(), cv::INTER_CUBIC);
  EXPECT_FALSE(alignWarpedTemplate(birth, {626, 200}, cv::Matx22d::eye(), current, {628, 200}));
}

TEST(WarpedTemplateAlignment, HomographyJacobianMatchesNumericDerivative) {
  const cv::Vec2d p(250.5, 330.25);
  const cv::Matx22d J = homographyJacobian(kHomography, cv::Point2f(p[0], p[1]));
  auto map = [](const cv::Vec2d& x) {
    const cv::Vec3d q = kHomography * cv::Vec3d(x[0], x[1], 1);
    return cv::Vec2d(q[0] / q[2], q[1] / q[2]);
  };
  const double h = 1e-4;
  for (int axis = 0; axis < 2; ++axis) {
    const cv::Vec2d dp(axis == 0 ? h : 0, axis == 1 ? h : 0);
    const cv::Vec2d numeric = (map(p + dp) - map(p - dp)) / (2 * h);
    EXPECT_NEAR(J(0, axis), numeric[0], 1e-7);
    EXPECT_NEAR(J(1, axis), numeric[1], 1e-7);
  }
}

}  // namespace
}  // namespace rpvio

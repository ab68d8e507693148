// The homography fit and RANSAC of the per-plane outlier rejection, on synthetic matches of a
// known homography (the real pair is in homography_graf_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "mrpt_modules/frontend/homography_ransac.h"

namespace rpvio {
namespace {

// A plane seen from two poses of a 460 px camera: rotation, translation and perspective terms.
Eigen::Matrix3d trueHomography() {
  Eigen::Matrix3d H;
  H << 1.02, 0.03, 12.0, -0.02, 0.98, -7.0, 4e-5, -3e-5, 1.0;
  return H;
}

struct Matches {
  PointList from, to;
  std::vector<bool> outlier;
};

/// n matches in a 640x480 image; every `outlier_every`-th one moved 5–40 px off the homography,
/// the others with Gaussian noise `sigma`.
Matches makeMatches(size_t n, double sigma, size_t outlier_every) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> x(0, 640), y(0, 480), off(5, 40), sign(-1, 1);
  std::normal_distribution<double> noise(0, sigma);
  Matches m;
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d p(x(rng), y(rng));
    Eigen::Vector2d q = (trueHomography() * p.homogeneous()).hnormalized();
    const bool outlier = outlier_every && i % outlier_every == 0;
    if (outlier)
      q += off(rng) * Eigen::Vector2d(sign(rng), sign(rng)).normalized();
    else
      q += Eigen::Vector2d(noise(rng), noise(rng));
    m.from.push_back(p);
    m.to.push_back(q);
    m.outlier.push_back(outlier);
  }
  return m;
}

TEST(HomographyFit, ExactMatchesGiveTheHomography) {
  const Matches m = makeMatches(20, 0, 0);
  const auto H = fitHomography(m.from, m.to);
  ASSERT_TRUE(H);
  EXPECT_LT((*H - trueHomography()).norm(), 1e-9);
}

TEST(HomographyFit, FourMatchesAreEnoughAndThreeAreNot) {
  const Matches m = makeMatches(4, 0, 0);
  const auto H = fitHomography(m.from, m.to);
  ASSERT_TRUE(H);
  EXPECT_LT((*H - trueHomography()).norm(), 1e-8);
  const PointList three_from(m.from.begin(), m.from.begin() + 3);
  const PointList three_to(m.to.begin(), m.to.begin() + 3);
  EXPECT_FALSE(fitHomography(three_from, three_to));
}

TEST(HomographyFit, CollinearMatchesAreDegenerate) {
  PointList from, to;
  for (int i = 0; i < 10; ++i) {
    from.emplace_back(10.0 * i, 5.0 * i + 3);
    to.push_back((trueHomography() * from.back().homogeneous()).hnormalized());
  }
  EXPECT_FALSE(fitHomography(from, to));
  EXPECT_TRUE(homographyRansacInliers(from, to, {}).empty());
}

TEST(AffineFit, ExactMatchesGiveTheMapAndALineDoesNot) {
  Eigen::Matrix3d A;
  A << 0.97, 0.05, -3.0, -0.04, 1.03, 8.5, 0, 0, 1;
  PointList from = {{100, 50}, {400, 80}, {250, 300}}, to;
  for (const auto& p : from) to.push_back((A * p.homogeneous()).hnormalized());
  const auto three = fitAffine(from, to);
  ASSERT_TRUE(three);
  EXPECT_LT((*three - A).norm(), 1e-9);
  // Least squares: a noisy fourth match moves the fit by a fraction of its offset.
  from.emplace_back(500, 400);
  to.push_back((A * from.back().homogeneous()).hnormalized() + Eigen::Vector2d(0.4, 0));
  const auto four = fitAffine(from, to);
  ASSERT_TRUE(four);
  EXPECT_GT((*four - A).norm(), 1e-6);
  EXPECT_LT(((*four) * from.back().homogeneous() - A * from.back().homogeneous()).norm(), 0.4);
  const PointList line = {{0, 0}, {1, 1}, {2, 2}, {3, 3}};
  EXPECT_FALSE(fitAffine(line, line));
}

TEST(HomographyRansac, FindsEveryPlantedOutlierAndKeepsTheInliers) {
  // A quarter of the matches are outliers; inlier noise 0.1 px against a 1 px threshold.
  const Matches m = makeMatches(120, 0.1, 4);
  const auto count = [&](const std::vector<bool>& flags, bool outliers) {
    size_t n = 0;
    for (size_t i = 0; i < flags.size(); ++i) n += flags[i] && m.outlier[i] == outliers;
    return n;
  };
  HomographyRansacOptions refined;
  refined.refine = true;
  const auto minimal = homographyRansacInliers(m.from, m.to, {});
  const auto grown = homographyRansacInliers(m.from, m.to, refined);
  ASSERT_EQ(minimal.size(), m.from.size());
  ASSERT_EQ(grown.size(), m.from.size());
  EXPECT_EQ(count(minimal, true), 0u);
  EXPECT_EQ(count(grown, true), 0u);
  // Of 90 inliers: a minimal model carries its four points' noise and may lose a few near the
  // threshold; the refit of its inliers does not.
  EXPECT_GE(count(minimal, false), 80u);
  EXPECT_EQ(count(grown, false), 90u);
}

TEST(HomographyRansac, SameInputSameFlags) {
  const Matches m = makeMatches(60, 0.3, 3);
  EXPECT_EQ(homographyRansacInliers(m.from, m.to, {}), homographyRansacInliers(m.from, m.to, {}));
}

TEST(HomographyRansac, ThresholdIsInTheUnitsOfTheSecondImage) {
  const Matches m = makeMatches(60, 0.1, 4);
  // `to` in units 100 times larger (pixels → hundreds of pixels): the same threshold scaled by
  // 1/100 gives the same flags; left at 1 (100 px) it accepts the 5–40 px outliers too.
  PointList to_scaled;
  for (const auto& q : m.to) to_scaled.push_back(q / 100);
  HomographyRansacOptions scaled;
  scaled.threshold = 0.01;
  EXPECT_EQ(homographyRansacInliers(m.from, to_scaled, scaled),
            homographyRansacInliers(m.from, m.to, {}));
  const auto loose = homographyRansacInliers(m.from, to_scaled, {});
  EXPECT_EQ(std::count(loose.begin(), loose.end(), true), 60);
}

}  // namespace
}  // namespace rpvio

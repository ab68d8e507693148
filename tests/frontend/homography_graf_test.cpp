// The per-plane homography routine on a real planar pair with a large viewpoint change:
// Mikolajczyk's graf1 → graf3 (../shared/data/graf, ground truth H1to3p).
#include <gtest/gtest.h>

#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>

#include "mrpt_modules/frontend/outlier_rejection.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

TEST(HomographyRansac, RecoversGrafGroundTruth) {
  const std::string dir = test::dataDir() + "/graf/";
  const cv::Mat img1 = cv::imread(dir + "graf1.png", cv::IMREAD_GRAYSCALE);
  const cv::Mat img3 = cv::imread(dir + "graf3.png", cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(img1.empty());
  ASSERT_FALSE(img3.empty());
  cv::Mat H_true;
  cv::FileStorage(dir + "H1to3p.xml", cv::FileStorage::READ)["H13"] >> H_true;
  ASSERT_EQ(H_true.rows, 3);

  // Putative matches from SIFT with Lowe's ratio test; the RANSAC must cope with their outliers.
  auto sift = cv::SIFT::create(4000);
  std::vector<cv::KeyPoint> k1, k3;
  cv::Mat d1, d3;
  sift->detectAndCompute(img1, cv::noArray(), k1, d1);
  sift->detectAndCompute(img3, cv::noArray(), k3, d3);
  std::vector<std::vector<cv::DMatch>> knn;
  cv::BFMatcher(cv::NORM_L2).knnMatch(d1, d3, knn, 2);
  // The routine works on normalized coordinates: use an arbitrary camera (f = 600, centre).
  const double f = 600, cx = img1.cols / 2.0, cy = img1.rows / 2.0;
  std::vector<cv::Point2f> from, to;
  for (const auto& m : knn) {
    if (m.size() < 2 || m[0].distance > 0.8f * m[1].distance) continue;
    const cv::Point2f a = k1[m[0].queryIdx].pt, b = k3[m[0].trainIdx].pt;
    from.emplace_back(static_cast<float>((a.x - cx) / f), static_cast<float>((a.y - cy) / f));
    to.emplace_back(static_cast<float>((b.x - cx) / f), static_cast<float>((b.y - cy) / f));
  }
  ASSERT_GT(from.size(), 50u);
  RansacOptions options;
  options.threshold_px = 2.0;
  options.virtual_focal = f;  // virtual camera = the arbitrary one: pixels of the images again
  // An accurate H from half outliers: the inliers of a minimal model (312 here) give 2.2 px,
  // refitted ones 1.1 px.
  options.refine_homography = true;
  cv::Mat H_virtual;
  const auto inliers = homographyInliers(from, to, options, &H_virtual);
  ASSERT_FALSE(H_virtual.empty());
  // Back to image pixels: H = T⁻¹ H_virtual T with T the shift by the centre.
  const cv::Mat T = (cv::Mat_<double>(3, 3) << 1, 0, -cx, 0, 1, -cy, 0, 0, 1);
  const cv::Mat H = T.inv() * H_virtual * T;
  double error = 0;
  const std::vector<cv::Point2d> corners = {
      {0, 0}, {img1.cols - 1.0, 0}, {img1.cols - 1.0, img1.rows - 1.0}, {0, img1.rows - 1.0}};
  for (const auto& c : corners) {
    const cv::Mat p = (cv::Mat_<double>(3, 1) << c.x, c.y, 1);
    const cv::Mat a = H * p, b = H_true * p;
    error +=
        cv::norm(cv::Point2d(a.at<double>(0) / a.at<double>(2), a.at<double>(1) / a.at<double>(2)) -
                 cv::Point2d(b.at<double>(0) / b.at<double>(2), b.at<double>(1) / b.at<double>(2)));
  }
  error /= corners.size();
  std::printf("graf1->graf3: %zu matches, %ld inliers, mean corner transfer error %.3f px\n",
              from.size(), std::count(inliers.begin(), inliers.end(), true), error);
  EXPECT_LT(error, 2.0);
}

TEST(HomographyRansac, FewMatchesAreAllKept) {
  const std::vector<cv::Point2f> a = {{0, 0}, {1, 0}, {0, 1}};
  const auto flags = homographyInliers(a, a, RansacOptions{});
  EXPECT_EQ(std::count(flags.begin(), flags.end(), true), 3);
}

}  // namespace
}  // namespace rpvio

// CornerDetector selects exactly the corners of cv::goodFeaturesToTrack, in the same order, on
// real and simulated images, with masks, with tied responses, and with its buffers reused across
// image sizes.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "mrpt_modules/frontend/corner_detector.h"
#include "sim/simulator.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

std::vector<cv::Point2f> opencvCorners(const cv::Mat& image, const cv::Mat& allowed, int max,
                                       double min_distance) {
  std::vector<cv::Point2f> corners;
  cv::goodFeaturesToTrack(image, corners, max, 0.01, min_distance, allowed);
  return corners;
}

void expectSameCorners(CornerDetector& detector, const cv::Mat& image, const cv::Mat& allowed,
                       int max, double min_distance) {
  const auto expected = opencvCorners(image, allowed, max, min_distance);
  ASSERT_FALSE(expected.empty());
  const auto got = detector.detect(image, allowed, max, 0.01, min_distance);
  ASSERT_EQ(got.size(), expected.size()) << "max " << max << ", min distance " << min_distance;
  for (size_t i = 0; i < got.size(); ++i)
    ASSERT_EQ(got[i], expected[i]) << "corner " << i << " of " << got.size();
}

cv::Mat graf() {
  const cv::Mat image = cv::imread(test::dataDir() + "/graf/graf1.png", cv::IMREAD_GRAYSCALE);
  EXPECT_FALSE(image.empty()) << "missing " << test::dataDir() << "/graf/graf1.png";
  return image;
}

TEST(CornerDetector, SameCornersAsOpenCvOnARealImage) {
  const cv::Mat image = graf();
  ASSERT_FALSE(image.empty());
  cv::Mat allowed(image.size(), CV_8U, cv::Scalar(255));
  CornerDetector detector;
  for (const int max : {20, 150, 2000})
    for (const double min_distance : {1.0, 10.0, 30.0})
      expectSameCorners(detector, image, allowed, max, min_distance);
  // A mask with holes: the quality threshold is relative to the strongest allowed response.
  for (int k = 0; k < 40; ++k)
    cv::circle(allowed, {(k * 97) % image.cols, (k * 61) % image.rows}, 45, cv::Scalar(0),
               cv::FILLED);
  expectSameCorners(detector, image, allowed, 150, 30.0);
}

TEST(CornerDetector, SameCornersAsOpenCvOnAMaskedSimulatedFrame) {
  sim::SimConfig config;
  config.scene.characters = 4;
  config.duration = 1.0;
  sim::Simulator simulator(config);
  const auto frame = simulator.render(0.5, 10);
  // Plane pixels only, minus the neighbourhoods of 60 tracked features (the tracker's mask).
  cv::Mat allowed = (frame.mask > 0) & (frame.mask < 255);
  for (int k = 0; k < 60; ++k)
    cv::circle(allowed, {(k * 131) % 640, (k * 71) % 480}, 30, cv::Scalar(0), cv::FILLED);
  ASSERT_GT(cv::countNonZero(allowed), 10000);
  CornerDetector detector;
  expectSameCorners(detector, frame.image, allowed, 90, 30.0);
  expectSameCorners(detector, frame.image, allowed, 1000, 5.0);
}

TEST(CornerDetector, EqualResponsesAreTakenInOpenCvsOrder) {
  // Every inner corner of a checkerboard has the same response: the order decides which ones a
  // min distance larger than the squares keeps.
  cv::Mat board(240, 320, CV_8U);
  for (int y = 0; y < board.rows; ++y)
    for (int x = 0; x < board.cols; ++x) board.at<uint8_t>(y, x) = ((x / 16 + y / 16) % 2) * 200;
  const cv::Mat allowed(board.size(), CV_8U, cv::Scalar(255));
  CornerDetector detector;
  expectSameCorners(detector, board, allowed, 40, 25.0);
  expectSameCorners(detector, board, allowed, 500, 1.0);
}

TEST(CornerDetector, BuffersFollowTheImageSize) {
  const cv::Mat big = graf();
  ASSERT_FALSE(big.empty());
  cv::Mat small;
  cv::resize(big, small, cv::Size(320, 256), 0, 0, cv::INTER_AREA);
  CornerDetector detector;
  for (const cv::Mat& image : {big, small, big, small})
    expectSameCorners(detector, image, cv::Mat(image.size(), CV_8U, cv::Scalar(255)), 150, 20.0);
}

TEST(CornerDetector, MasksThatChangeBetweenCallsAndTouchTheBorder) {
  // Responses are computed only near allowed pixels: masks that move between calls on one
  // detector, allowed pixels in the first and last rows and columns, a width that is not a
  // multiple of the 16-column chunks.
  const cv::Mat full = graf();
  ASSERT_FALSE(full.empty());
  const cv::Mat image = full(cv::Rect(101, 67, 333, 247)).clone();
  cv::Mat edges(image.size(), CV_8U, cv::Scalar(0));
  edges.colRange(0, 9) = 255;
  edges.colRange(image.cols - 5, image.cols) = 255;
  edges.rowRange(0, 3) = 255;
  edges.rowRange(image.rows - 7, image.rows) = 255;
  cv::Mat islands(image.size(), CV_8U, cv::Scalar(0));
  for (int k = 0; k < 25; ++k)
    cv::circle(islands, {(k * 97) % image.cols, (k * 61) % image.rows}, 5 + k % 13, cv::Scalar(255),
               cv::FILLED);
  // Single allowed columns on both sides of chunk edges: their neighbours are in other chunks.
  cv::Mat columns(image.size(), CV_8U, cv::Scalar(0));
  for (const int x : {15, 48, 111, 144, 200, image.cols - 1}) columns.col(x) = 255;
  CornerDetector detector;
  for (const cv::Mat& allowed : {edges, islands, columns, edges, columns, islands})
    for (const double min_distance : {1.0, 12.0})
      expectSameCorners(detector, image, allowed, 300, min_distance);
}

TEST(CornerDetector, NoCornerOnAFlatOrFullyMaskedImage) {
  CornerDetector detector;
  const cv::Mat flat(480, 640, CV_8U, cv::Scalar(90));
  const cv::Mat everywhere(flat.size(), CV_8U, cv::Scalar(255));
  EXPECT_TRUE(detector.detect(flat, everywhere, 150, 0.01, 30).empty());
  const cv::Mat image = graf();
  ASSERT_FALSE(image.empty());
  EXPECT_TRUE(
      detector.detect(image, cv::Mat(image.size(), CV_8U, cv::Scalar(0)), 150, 0.01, 30).empty());
  EXPECT_TRUE(
      detector.detect(image, cv::Mat(image.size(), CV_8U, cv::Scalar(255)), 0, 0.01, 30).empty());
}

}  // namespace
}  // namespace rpvio

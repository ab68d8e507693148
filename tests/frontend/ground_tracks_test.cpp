// The ground's tracks (ground_tracks.h) on a synthetic ground: carried by the true homography,
// labelled kGroundLabel, ending where the alignment fails and after max_length frames.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <map>
#include <opencv2/imgproc.hpp>

#include "mrpt_modules/frontend/ground_tracks.h"

namespace rpvio {
namespace {

const CameraIntrinsics kCamera{640, 240, 400, 400, 320, 60};

cv::Mat texture() {
  cv::Mat noise(240, 640, CV_8U), image;
  cv::RNG(3).fill(noise, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(noise, image, cv::Size(0, 0), 3.0);
  cv::normalize(image, image, 0, 255, cv::NORM_MINMAX);
  return image;
}

cv::Mat warped(const cv::Mat& image, const Eigen::Matrix3d& H_normalized) {
  Eigen::Matrix3d K;
  K << kCamera.fx, 0, kCamera.cx, 0, kCamera.fy, kCamera.cy, 0, 0, 1;
  const Eigen::Matrix3d H = K * H_normalized * K.inverse();
  cv::Matx33d h;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) h(r, c) = H(r, c);
  cv::Mat out;
  cv::warpPerspective(image, out, h, image.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  return out;
}

TEST(GroundTracks, FollowTheGroundsHomographyAndEndWhenItIsLost) {
  const GroundMotion truth{Eigen::Vector3d(0, 0, -0.2), Eigen::Vector3d::UnitY()};
  const Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  const Eigen::Vector3d down = Eigen::Vector3d::UnitY();
  GroundTrackOptions options;
  options.max_length = 3;
  GroundTracks tracks(kCamera, options, GroundAlignmentOptions{});
  int next_id = 100;
  const cv::Mat first = texture();
  const auto born = tracks.track(0.0, first, nullptr, &down, next_id);
  // As many as fit below the horizon at spacing_px (14 of 16 in this 640x240 view).
  ASSERT_GE(born.size(), 8u);
  ASSERT_LE(born.size(), static_cast<size_t>(options.features));
  for (const TrackedFeature& f : born) {
    EXPECT_EQ(f.plane_id, kGroundLabel);
    EXPECT_GE(f.id, 100);
  }
  // The second image: the first moved by the ground's homography; every track that stays in view
  // is where the homography puts it.
  const Eigen::Matrix3d H = truth.homography(R);
  const auto carried = tracks.track(0.1, warped(first, H), &R, &down, next_id);
  ASSERT_TRUE(tracks.lastAlignment() && tracks.lastAlignment()->ok);
  std::map<int, Eigen::Vector2d> before;
  for (const TrackedFeature& f : born) before[f.id] = f.normalized;
  int followed = 0;
  for (const TrackedFeature& f : carried) {
    if (!before.count(f.id)) continue;
    ++followed;
    const Eigen::Vector2d expected = (H * before[f.id].homogeneous()).hnormalized();
    EXPECT_LT((f.normalized - expected).norm() * kCamera.fx, 0.5) << "track " << f.id;
    EXPECT_EQ(f.track_length, 2);
  }
  EXPECT_GE(followed, static_cast<int>(born.size()) / 2);
  // An image of something else: the alignment fails and every track ends (new ones start).
  cv::Mat other(240, 640, CV_8U);
  cv::RNG(5).fill(other, cv::RNG::UNIFORM, 0, 255);
  const auto after_loss = tracks.track(0.2, other, &R, &down, next_id);
  EXPECT_FALSE(tracks.lastAlignment()->ok);
  for (const TrackedFeature& f : after_loss) EXPECT_EQ(f.track_length, 1);
}

}  // namespace
}  // namespace rpvio

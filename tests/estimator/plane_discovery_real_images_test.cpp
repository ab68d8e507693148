// The plane discovery on real images (../shared/data/vamr_checkerboard: 736 hand-held frames of
// a checkerboard on a desk, every camera pose known; no IMU, so the poses' rotations stand in for
// the gyroscope). Issue #34's target: the board plane is found, and the homographies of its
// features between frames k and k+5 agree with the poses' (H = K [r1 r2 t]) to a median transfer
// error of at most 1 px over the sequence.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <fstream>
#include <map>
#include <opencv2/imgcodecs.hpp>

#include "mrpt_modules/estimator/plane_discovery.h"
#include "mrpt_modules/frontend/feature_tracker.h"
#include "mrpt_modules/frontend/homography_ransac.h"
#include "tests/vamr_checkerboard.h"

namespace rpvio {
namespace {

const std::string kDir = test::vamrDir();
constexpr int kFrames = 736, kGap = 5;
constexpr double kRate = 30;  // Hz: assumed (no timestamps); only the check's span depends on it

/// K.txt, and D.txt's radial model in pixel units, (1 + k1 r² + k2 r⁴) with r in pixels, as
/// radtan's normalized k1 f², k2 f⁴ (fx and fy differ by 0.025 %).
CameraIntrinsics intrinsics() {
  CameraIntrinsics c;
  c.width = 752;
  c.height = 480;
  std::ifstream k(kDir + "/K.txt"), d(kDir + "/D.txt");
  double skip, k1, k2;
  k >> c.fx >> skip >> c.cx >> skip >> c.fy >> c.cy;
  d >> k1 >> k2;
  c.model = DistortionModel::RadTan;
  c.distortion = {k1 * c.fx * c.fx, k2 * std::pow(c.fx, 4), 0, 0};
  return c;
}

/// Normalized-coordinate homography of the board plane (world Z = 0) from frame a to frame b.
Eigen::Matrix3d boardHomography(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const auto plane_to_image = [](const Eigen::Isometry3d& T) {
    Eigen::Matrix3d H;
    H << T.linear().col(0), T.linear().col(1), T.translation();
    return H;
  };
  return plane_to_image(b) * plane_to_image(a).inverse();
}

TEST(PlaneDiscoveryOnRealImages, FindsTheCheckerboardWithItsTrueHomographies) {
  const CameraIntrinsics camera = intrinsics();
  const std::vector<Eigen::Isometry3d> poses = test::vamrCameraFromWorld();
  ASSERT_EQ(poses.size(), static_cast<size_t>(kFrames)) << kDir;
  TrackerOptions tracking;
  tracking.use_masks = false;
  FeatureTracker tracker(camera, tracking);
  PlaneDiscoveryOptions options;
  options.enabled = true;
  PlaneDiscovery discovery(options);
  std::vector<FeatureFrame> labelled;
  for (int k = 0; k < kFrames; ++k) {
    char name[64];
    std::snprintf(name, sizeof name, "/images/img_%04d.jpg", k + 1);
    const cv::Mat image = cv::imread(kDir + name, cv::IMREAD_GRAYSCALE);
    ASSERT_FALSE(image.empty()) << kDir + name;
    const FeatureFrame frame = tracker.track(k / kRate, image, cv::Mat());
    // Camera k in camera k−1: R_{k−1,w} R_{w,k}.
    const Eigen::Quaterniond R_previous_current(
        k == 0 ? Eigen::Matrix3d::Identity()
               : Eigen::Matrix3d(poses[k - 1].linear() * poses[k].linear().transpose()));
    labelled.push_back(discovery.label(frame, R_previous_current));
  }
  // The board (and the desk it lies on) is the scene's one plane: one accepted plane holds
  // nearly every labelled feature.
  std::map<int, size_t> features_of;
  for (const FeatureFrame& f : labelled)
    for (const TrackedFeature& x : f.features) ++features_of[x.plane_id];
  ASSERT_FALSE(features_of.empty()) << "no plane discovered";
  const auto board = std::max_element(features_of.begin(), features_of.end(),
                                      [](auto& a, auto& b) { return a.second < b.second; });
  size_t total = 0;
  for (const auto& [plane, n] : features_of) total += n;
  std::printf("%zu discovered planes; the largest holds %zu of %zu labelled observations\n",
              features_of.size(), board->second, total);
  EXPECT_GE(board->second, 0.9 * total);

  // Its homographies from k to k+5 (fitted to its features there) against the poses'.
  std::vector<double> frame_errors;
  size_t frames_with_board = 0;
  for (int k = 0; k + kGap < kFrames; ++k) {
    std::map<int, Eigen::Vector2d> at_k;
    for (const TrackedFeature& x : labelled[k].features)
      if (x.plane_id == board->first) at_k[x.id] = x.normalized;
    PointList from, to;
    for (const TrackedFeature& x : labelled[k + kGap].features)
      if (const auto it = at_k.find(x.id); x.plane_id == board->first && it != at_k.end())
        from.push_back(it->second), to.push_back(x.normalized);
    if (from.size() < 10) continue;
    ++frames_with_board;
    const auto H = fitHomography(from, to);
    ASSERT_TRUE(H.has_value());
    const Eigen::Matrix3d H_true = boardHomography(poses[k], poses[k + kGap]);
    std::vector<double> errors;
    for (const Eigen::Vector2d& u : from) {
      const Eigen::Vector2d d =
          (*H * u.homogeneous()).hnormalized() - (H_true * u.homogeneous()).hnormalized();
      errors.push_back(std::hypot(camera.fx * d.x(), camera.fy * d.y()));
    }
    std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
    frame_errors.push_back(errors[errors.size() / 2]);
  }
  ASSERT_FALSE(frame_errors.empty());
  std::vector<double> sorted = frame_errors;
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted[sorted.size() / 2], p90 = sorted[sorted.size() * 9 / 10];
  std::printf(
      "board homographies k -> k+%d on %zu of %d frame pairs: transfer error median "
      "%.3f px, p90 %.3f px\n",
      kGap, frames_with_board, kFrames - kGap, median, p90);
  EXPECT_GE(frames_with_board, 0.9 * (kFrames - kGap));  // found early and kept
  EXPECT_LE(median, 1.0);
}

}  // namespace
}  // namespace rpvio

// The ground's homography by direct alignment (ground_alignment.h): on an image warped by a known
// ground motion, and on real street images (../shared/data/kitti07_vio: KITTI 07, the road in the
// lower half of every frame, the camera 1.65 m above it) against the ground truth's motion.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "mrpt_modules/frontend/ground_alignment.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180 / M_PI;
}

TEST(GroundAlignment, RecoversAKnownGroundMotionOfASyntheticImage) {
  // A 640x240 camera 1.5 m above a textured ground, moving 0.6 m forward and turning 2°.
  const CameraIntrinsics camera{640, 240, 400, 400, 320, 60};
  cv::Mat noise(240, 640, CV_8U);
  cv::RNG(3).fill(noise, cv::RNG::UNIFORM, 0, 255);
  cv::Mat previous;
  cv::GaussianBlur(noise, previous, cv::Size(0, 0), 3.0);
  cv::normalize(previous, previous, 0, 255, cv::NORM_MINMAX);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(2 * M_PI / 180, Eigen::Vector3d::UnitY()).matrix();
  GroundMotion truth{Eigen::Vector3d(0.02, 0.01, -0.6) / 1.5, Eigen::Vector3d(0, 1, 0.05)};
  truth.n.normalize();
  Eigen::Matrix3d K;
  K << camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1;
  const Eigen::Matrix3d H = K * truth.homography(R) * K.inverse();
  cv::Matx33d Hcv;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) Hcv(r, c) = H(r, c);
  cv::Mat current;
  cv::warpPerspective(previous, current, Hcv, previous.size(), cv::INTER_LINEAR,
                      cv::BORDER_REFLECT);
  current = current * 0.9 + 10;  // auto-exposure

  GroundAligner aligner(camera, {});
  const auto result = aligner.align(buildGreyPyramid(previous, 5), buildGreyPyramid(current, 5), R,
                                    Eigen::Vector3d(0, 1, 0), nullptr);
  ASSERT_TRUE(result.ok) << result.residual_grey << " grey, " << result.pixels << " px, "
                         << result.inlier_share;
  EXPECT_LT((result.motion.a - truth.a).norm(), 0.02 * truth.a.norm()) << result.motion.a;
  EXPECT_LT(angleDeg(result.motion.n, truth.n), 0.5);
}

TEST(GroundAlignment, FindsNoGroundInImagesOfNoise) {
  // Two unrelated images of noise, five draws: no motion explains one by the other.
  const CameraIntrinsics camera{640, 240, 400, 400, 320, 60};
  GroundAligner aligner(camera, {});
  cv::RNG rng(7);
  for (int draw = 0; draw < 5; ++draw) {
    cv::Mat previous(240, 640, CV_8U), current(240, 640, CV_8U);
    rng.fill(previous, cv::RNG::UNIFORM, 0, 255);
    rng.fill(current, cv::RNG::UNIFORM, 0, 255);
    const auto result =
        aligner.align(buildGreyPyramid(previous, 5), buildGreyPyramid(current, 5),
                      Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 1, 0), nullptr);
    EXPECT_FALSE(result.ok) << "draw " << draw << ": " << result.residual_grey << " grey, "
                            << result.pixels << " px, " << result.inlier_share << " inliers, "
                            << result.still_cost_ratio << " of the rotation's cost";
  }
}

/// KITTI 07 as shipped in shared/data: images and the body's true poses.
struct Kitti07 {
  std::string dir = test::dataDir() + "/kitti07_vio";
  std::vector<std::string> images;
  std::vector<Eigen::Isometry3d> body;  // in the world
  Eigen::Isometry3d T_BC = Eigen::Isometry3d::Identity();
  CameraIntrinsics camera{1226, 370, 707.0912, 707.0912, 601.8873, 183.1104};
  Kitti07() {
    std::ifstream gt(dir + "/groundtruth.tum");
    std::string line;
    while (std::getline(gt, line)) {
      if (line.empty() || line[0] == '#') continue;
      std::istringstream in(line);
      double t, x, y, z, qx, qy, qz, qw;
      in >> t >> x >> y >> z >> qx >> qy >> qz >> qw;
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
      pose.linear() = Eigen::Quaterniond(qw, qx, qy, qz).normalized().toRotationMatrix();
      pose.translation() = Eigen::Vector3d(x, y, z);
      body.push_back(pose);
    }
    std::ifstream csv(dir + "/mav0/cam0/data.csv");
    std::getline(csv, line);
    while (std::getline(csv, line))
      images.push_back(dir + "/mav0/cam0/data/" + line.substr(line.find(',') + 1));
    Eigen::Matrix4d m;  // sensor.yaml's T_BS
    m << 0, 0, 1, 0.2, -1, 0, 0, 0, 0, -1, 0, 0.1, 0, 0, 0, 1;
    T_BC.matrix() = m;
  }
  Eigen::Isometry3d cameraPose(size_t k) const { return body[k] * T_BC; }
};

TEST(GroundAlignment, FollowsTheRoadOfRealStreetImages) {
  // All 159 pairs of consecutive frames (10 Hz, up to 8 m/s: the road moves 30-100 px) in order,
  // each aligned with the true rotation and, as GroundTracks does, the last pair's motion as its
  // guess; a = t/d against the true translation over the camera's 1.65 m, n against the true
  // vertical.
  const Kitti07 kitti;
  ASSERT_EQ(kitti.images.size(), 160u);
  ASSERT_EQ(kitti.body.size(), 160u);
  GroundAligner aligner(kitti.camera, {});
  int aligned = 0, pairs = 0;
  std::vector<double> a_errors, n_errors;
  std::optional<GroundMotion> guess;
  GreyPyramid previous = buildGreyPyramid(cv::imread(kitti.images[0], cv::IMREAD_GRAYSCALE), 5);
  for (size_t k = 0; k + 1 < 160; ++k) {
    const GreyPyramid current =
        buildGreyPyramid(cv::imread(kitti.images[k + 1], cv::IMREAD_GRAYSCALE), 5);
    const Eigen::Isometry3d cur_prev = kitti.cameraPose(k + 1).inverse() * kitti.cameraPose(k);
    const Eigen::Vector3d down =
        kitti.cameraPose(k).linear().transpose() * -Eigen::Vector3d::UnitZ();
    std::optional<GroundMotion> start;
    if (guess) start = GroundMotion{cur_prev.linear() * guess->a, guess->n};
    const auto result =
        aligner.align(previous, current, cur_prev.linear(), down, start ? &*start : nullptr);
    previous = current;
    guess.reset();
    const Eigen::Vector3d a_true = cur_prev.translation() / 1.65;
    if (!result.ok) continue;
    const Eigen::Vector3d n_cur = cur_prev.linear() * result.motion.n;
    guess = GroundMotion{result.motion.a / (1 + n_cur.dot(result.motion.a)), n_cur};
    if (a_true.norm() < 0.05) continue;  // too slow for n to be observable
    ++pairs;
    ++aligned;
    a_errors.push_back((result.motion.a - a_true).norm() / a_true.norm());
    n_errors.push_back(angleDeg(result.motion.n, down));
  }
  ASSERT_GE(aligned, 140) << "aligned " << aligned;
  std::sort(a_errors.begin(), a_errors.end());
  std::sort(n_errors.begin(), n_errors.end());
  const double a_median = a_errors[a_errors.size() / 2], n_median = n_errors[n_errors.size() / 2];
  // Measured: 12 % and 2.1° (the road seen a few degrees below the horizon, at a grazing angle).
  EXPECT_LT(a_median, 0.15) << "median relative error of t/d";
  EXPECT_LT(n_median, 3.0) << "median error of the normal (deg)";
  std::cout << "aligned " << aligned << ", t/d median error " << a_median << ", normal " << n_median
            << " deg, 90 %: " << a_errors[a_errors.size() * 9 / 10] << " / "
            << n_errors[n_errors.size() * 9 / 10] << " deg\n";
}

}  // namespace
}  // namespace rpvio

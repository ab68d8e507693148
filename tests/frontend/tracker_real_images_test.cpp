// The tracker on real hand-held images (../shared/data/vamr_checkerboard: 736 frames of a
// checkerboard on a desk, every camera pose known). Issue #36's target: the tracker keeps >= 90 %
// of the board's tracks frame to frame, and their positions agree with the ground-truth
// homography (the poses') to <= 1 px median. No IMU: the poses' rotations stand in for the
// gyroscope's prediction.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <fstream>
#include <map>
#include <opencv2/imgcodecs.hpp>

#include "mrpt_modules/frontend/feature_tracker.h"
#include "tests/vamr_checkerboard.h"

namespace rpvio {
namespace {

const std::string kDir = test::vamrDir();
constexpr int kFrames = 736;

struct Camera {
  double fx, fy, cx, cy, k1, k2;  // D.txt's radial model, in pixel units
  CameraIntrinsics intrinsics() const {
    CameraIntrinsics c{752, 480, fx, fy, cx, cy};
    c.model = DistortionModel::RadTan;  // the same model, normalized
    c.distortion = {k1 * fx * fx, k2 * std::pow(fx, 4), 0, 0};
    return c;
  }
  /// Distorted pixel of a point in camera coordinates.
  Eigen::Vector2d project(const Eigen::Vector3d& X) const {
    const Eigen::Vector2d ideal(fx * X.x() / X.z() + cx, fy * X.y() / X.z() + cy);
    const Eigen::Vector2d c(cx, cy);
    const double r2 = (ideal - c).squaredNorm();
    return c + (1 + k1 * r2 + k2 * r2 * r2) * (ideal - c);
  }
};

Camera camera() {
  Camera c;
  std::ifstream k(kDir + "/K.txt"), d(kDir + "/D.txt");
  double skip;
  k >> c.fx >> skip >> c.cx >> skip >> c.fy >> c.cy;
  d >> c.k1 >> c.k2;
  return c;
}

TEST(TrackerOnRealImages, KeepsTheBoardsTracksAtTheirTrueHomographies) {
  const Camera cam = camera();
  const std::vector<Eigen::Isometry3d> poses = test::vamrCameraFromWorld();
  ASSERT_EQ(poses.size(), static_cast<size_t>(kFrames)) << kDir;
  TrackerOptions options;
  options.use_masks = false;
  FeatureTracker tracker(cam.intrinsics(), options);
  // A track's point on the board plane, from its ray at birth; board tracks are those whose
  // next five positions lie within 2 px of the point's projections (off-plane points do not).
  struct Track {
    Eigen::Vector3d X_w;
    int born = 0;
    bool board = false;
  };
  std::map<int, Track> tracks;
  std::map<int, Eigen::Vector2d> previous;  // the previous frame's features
  std::vector<double> errors;
  size_t offered = 0, kept = 0;
  const double margin = 0.5 * options.klt_window;
  auto inside = [&](const Eigen::Vector2d& u) {
    return u.x() > margin && u.y() > margin && u.x() < 752 - margin && u.y() < 480 - margin;
  };
  for (int k = 0; k < kFrames; ++k) {
    char name[64];
    std::snprintf(name, sizeof name, "/images/img_%04d.jpg", k + 1);
    const cv::Mat image = cv::imread(kDir + name, cv::IMREAD_GRAYSCALE);
    ASSERT_FALSE(image.empty()) << kDir + name;
    const Eigen::Matrix3d R_cur_prev =
        k == 0 ? Eigen::Matrix3d::Identity()
               : Eigen::Matrix3d(poses[k].linear() * poses[k - 1].linear().transpose());
    const FeatureFrame frame = tracker.track(k / 30.0, image, cv::Mat(), k ? &R_cur_prev : nullptr);
    const Eigen::Isometry3d w_T_c = poses[k].inverse();
    std::map<int, Eigen::Vector2d> current;
    for (const TrackedFeature& f : frame.features) {
      current[f.id] = f.pixel;
      if (f.track_length == 1) {
        // Ray x through the camera centre o, in the world: where it meets Z = 0.
        const Eigen::Vector3d o = w_T_c.translation(),
                              x = w_T_c.linear() * f.normalized.homogeneous();
        const double lambda = -o.z() / x.z();
        if (lambda > 0) tracks[f.id] = {o + lambda * x, k, false};
        continue;
      }
      const auto t = tracks.find(f.id);
      if (t == tracks.end()) continue;
      const Eigen::Vector2d truth = cam.project(poses[k] * t->second.X_w);
      const double error = (f.pixel - truth).norm();
      if (k - t->second.born <= 5) {
        if (error > 2)
          tracks.erase(t);  // off the plane
        else if (k - t->second.born == 5)
          t->second.board = true;
        continue;
      }
      if (t->second.board) errors.push_back(error);
    }
    // Of the board tracks of frame k−1 whose point is still in view, the share tracked into k.
    for (const auto& [id, pixel] : previous) {
      const auto t = tracks.find(id);
      if (t == tracks.end() || !t->second.board || k - t->second.born <= 5) continue;
      if (!inside(cam.project(poses[k] * t->second.X_w))) continue;
      ++offered;
      kept += current.count(id);
    }
    previous = current;
  }
  ASSERT_GT(offered, 10000u);
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  const double median = errors[errors.size() / 2];
  std::printf(
      "board tracks: %.1f%% kept frame to frame (%zu offered), error against the poses' "
      "homography median %.3f px over %zu positions\n",
      100.0 * kept / offered, offered, median, errors.size());
  EXPECT_GE(static_cast<double>(kept) / offered, 0.9);
  EXPECT_LE(median, 1.0);
}

}  // namespace
}  // namespace rpvio

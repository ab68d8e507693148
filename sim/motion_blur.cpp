#include "sim/motion_blur.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "sim/parallel_rows.h"

namespace rpvio::sim {
namespace {

/// How every part of every character moves from its pose now to its pose at t.
std::vector<std::vector<PartMotion>> partMotion(const std::vector<Character>& now, double t) {
  std::vector<std::vector<PartMotion>> motion;
  for (const Character& c : now) {
    Character then = c;
    then.pose(t);
    motion.push_back(c.figure().motionTo(then.figure()));
  }
  return motion;
}

/// T_WO(t_other) T_WO(t)⁻¹ of every moving object: where its points go.
std::vector<Eigen::Isometry3d> objectMotion(const std::vector<MovingPlanarObject>& objects,
                                            double t, double t_other) {
  std::vector<Eigen::Isometry3d> motion;
  for (const MovingPlanarObject& m : objects)
    motion.push_back(m.pose(t_other) * m.pose(t).inverse());
  return motion;
}

/// Bilinear sample of a CV_32F image, coordinates clamped to the image.
float bilinear(const cv::Mat& image, double x, double y) {
  x = std::clamp(x, 0.0, image.cols - 1.0);
  y = std::clamp(y, 0.0, image.rows - 1.0);
  const int x0 = std::min(static_cast<int>(x), image.cols - 2);
  const int y0 = std::min(static_cast<int>(y), image.rows - 2);
  const float fx = static_cast<float>(x - x0), fy = static_cast<float>(y - y0);
  const float* r0 = image.ptr<float>(y0);
  const float* r1 = image.ptr<float>(y0 + 1);
  return (1 - fy) * ((1 - fx) * r0[x0] + fx * r0[x0 + 1]) +
         fy * ((1 - fx) * r1[x0] + fx * r1[x0 + 1]);
}

}  // namespace

cv::Mat motionBlur(const SceneRadiance& sharp, const WarehouseScene& scene,
                   const PinholeCamera& cam, const Eigen::Isometry3d& T_WC,
                   const ShutterInterval& shutter, int threads) {
  const auto character_open = partMotion(scene.characters(), shutter.t_open);
  const auto character_close = partMotion(scene.characters(), shutter.t_close);
  const double t = 0.5 * (shutter.t_open + shutter.t_close);
  const auto object_open = objectMotion(scene.movingObjects(), t, shutter.t_open);
  const auto object_close = objectMotion(scene.movingObjects(), t, shutter.t_close);
  // Static points move with the camera only: camera frame at t → camera frames at the shutter.
  const Eigen::Isometry3d C_open = shutter.T_WC_open.inverse(),
                          C_close = shutter.T_WC_close.inverse();
  const Eigen::Isometry3d open_from_now = C_open * T_WC, close_from_now = C_close * T_WC;
  auto project = [&](const Eigen::Vector3d& Xc, Eigen::Vector2d& px) {
    if (Xc.z() <= 1e-6) return false;
    px = Eigen::Vector2d(cam.fx * Xc.x() / Xc.z() + cam.cx, cam.fy * Xc.y() / Xc.z() + cam.cy);
    return true;
  };
  constexpr double kFar = 1e6;  // m: where a ray that hits nothing ends (direction only)
  cv::Mat blurred(sharp.radiance.size(), CV_32F);
  parallelRows(cam.height, threads, [&](int r) {
    for (int c = 0; c < cam.width; ++c) {
      const float depth = sharp.depth.at<float>(r, c);
      const Eigen::Vector3d Xc = (depth > 0 ? depth : kFar) *
                                 Eigen::Vector3d((c - cam.cx) / cam.fx, (r - cam.cy) / cam.fy, 1);
      Eigen::Vector3d Xc_open = open_from_now * Xc, Xc_close = close_from_now * Xc;
      const int mover = sharp.mover.at<int16_t>(r, c);
      if (mover >= kMoverObjectBase) {  // a point of a moving object moves with it
        const Eigen::Vector3d X = T_WC * Xc;
        Xc_open = C_open * (object_open[mover - kMoverObjectBase] * X);
        Xc_close = C_close * (object_close[mover - kMoverObjectBase] * X);
      } else if (mover >= 0) {  // a character's point moves with its limb
        const Eigen::Vector3d X = T_WC * Xc;
        const int part = sharp.part.at<int8_t>(r, c);
        Xc_open = C_open * character_open[mover][part].apply(X);
        Xc_close = C_close * character_close[mover][part].apply(X);
      }
      Eigen::Vector2d p_open, p_close;
      if (!project(Xc_open, p_open) || !project(Xc_close, p_close)) {
        blurred.at<float>(r, c) = sharp.radiance.at<float>(r, c);
        continue;
      }
      const Eigen::Vector2d step = p_close - p_open;
      const int n = std::max(1, static_cast<int>(std::ceil(step.norm())));
      float sum = 0;
      for (int i = 0; i < n; ++i) {
        const Eigen::Vector2d p = p_open + (i + 0.5) / n * step;
        sum += bilinear(sharp.radiance, p.x(), p.y());
      }
      blurred.at<float>(r, c) = sum / n;
    }
  });
  return blurred;
}

}  // namespace rpvio::sim

#include "sim/motion_blur.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "sim/parallel_rows.h"

namespace rpvio::sim {
namespace {

std::vector<DancingCharacter> posedAt(const std::vector<DancingCharacter>& characters, double t) {
  std::vector<DancingCharacter> posed = characters;
  for (DancingCharacter& c : posed) c.pose(t);
  return posed;
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
  const std::vector<DancingCharacter>& now = scene.characters();
  const std::vector<DancingCharacter> open = posedAt(now, shutter.t_open);
  const std::vector<DancingCharacter> close = posedAt(now, shutter.t_close);
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
      if (sharp.mask.at<uint8_t>(r, c) == kMaskCharacter) {
        const Eigen::Vector3d X = T_WC * Xc;
        size_t k = 0;  // the character whose surface X is on
        for (size_t j = 1; j < now.size(); ++j)
          if (std::abs(now[j].signedDistance(X)) < std::abs(now[k].signedDistance(X))) k = j;
        Xc_open = C_open * now[k].follow(X, open[k]);
        Xc_close = C_close * now[k].follow(X, close[k]);
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

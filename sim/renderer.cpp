#include "sim/renderer.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "sim/parallel_rows.h"

namespace rpvio::sim {
namespace {

constexpr int kTile = 16;  // px, the renderer culls the scene per tile

}  // namespace

std::pair<Eigen::Vector3d, Eigen::Vector3d> pixelRay(const PinholeCamera& cam,
                                                     const Eigen::Isometry3d& T_WC, double u,
                                                     double v) {
  const Eigen::Vector3d d_c((u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, 1.0);
  return {T_WC.translation(), T_WC.linear() * d_c};
}

SceneRadiance renderRadiance(const WarehouseScene& scene, const PinholeCamera& cam,
                             const Eigen::Isometry3d& T_WC, const RenderOptions& opt) {
  const int W = cam.width, H = cam.height;
  cv::Mat intensity(H, W, CV_32F), labels(H, W, CV_8U), dynamic(H, W, CV_8U), depth(H, W, CV_32F);
  cv::Mat mover(H, W, CV_16S), part(H, W, CV_8S);
  const double footprint_per_depth = 1.0 / cam.fx;  // one pixel at depth 1 m
  const int k = std::max(1, opt.supersampling);
  // What each kTile x kTile tile can see (its rays' pyramid, 1 px wider than the tile so that it
  // holds every sample ray).
  const WarehouseScene::PlanesInView view = scene.planesInView(T_WC.translation());
  const int tiles_x = (W + kTile - 1) / kTile, tiles_y = (H + kTile - 1) / kTile;
  std::vector<WarehouseScene::PlanesInView> tile_views;
  for (int ty = 0; ty < tiles_y; ++ty)
    for (int tx = 0; tx < tiles_x; ++tx) {
      const double u0 = tx * kTile - 1.0, u1 = std::min(W, (tx + 1) * kTile) + 0.0;
      const double v0 = ty * kTile - 1.0, v1 = std::min(H, (ty + 1) * kTile) + 0.0;
      auto ray = [&](double u, double v) { return pixelRay(cam, T_WC, u, v).second; };
      tile_views.push_back(
          scene.cullToPyramid(view, {ray(u0, v0), ray(u1, v0), ray(u1, v1), ray(u0, v1)}));
    }
  auto shade = [&](double u, double v, int r, int c) {
    const auto& tile = tile_views[(r / kTile) * tiles_x + c / kTile];
    return scene.cast(tile, pixelRay(cam, T_WC, u, v).second, footprint_per_depth / k);
  };

  // Pass 1: one ray per pixel centre (labels), or k x k rays everywhere.
  parallelRows(H, opt.threads, [&](int r) {
    for (int c = 0; c < W; ++c) {
      const SceneHit centre = shade(c, r, r, c);
      labels.at<uint8_t>(r, c) = static_cast<uint8_t>(centre.label);
      dynamic.at<uint8_t>(r, c) = centre.dynamic ? 255 : 0;
      depth.at<float>(r, c) = static_cast<float>(centre.t);
      part.at<int8_t>(r, c) = static_cast<int8_t>(centre.part);
      mover.at<int16_t>(r, c) =
          static_cast<int16_t>(centre.character >= 0       ? centre.character
                               : centre.moving_object >= 0 ? kMoverObjectBase + centre.moving_object
                                                           : -1);
      if (opt.supersampling <= 0) {
        intensity.at<float>(r, c) = centre.intensity;
        continue;
      }
      float sum = 0;
      for (int i = 0; i < k; ++i)
        for (int j = 0; j < k; ++j)
          sum += shade(c - 0.5 + (j + 0.5) / k, r - 0.5 + (i + 0.5) / k, r, c).intensity;
      intensity.at<float>(r, c) = sum / (k * k);
    }
  });
  // Pass 2 (adaptive): 2x2 rotated-grid samples where a neighbour has another label (edges).
  if (opt.supersampling <= 0) {
    parallelRows(H, opt.threads, [&](int r) {
      for (int c = 0; c < W; ++c) {
        const uint8_t l = labels.at<uint8_t>(r, c);
        const bool edge = (c > 0 && labels.at<uint8_t>(r, c - 1) != l) ||
                          (c + 1 < W && labels.at<uint8_t>(r, c + 1) != l) ||
                          (r > 0 && labels.at<uint8_t>(r - 1, c) != l) ||
                          (r + 1 < H && labels.at<uint8_t>(r + 1, c) != l);
        if (!edge) continue;
        static const double kOffsets[4][2] = {
            {-0.125, -0.375}, {0.375, -0.125}, {0.125, 0.375}, {-0.375, 0.125}};
        float sum = 0;
        for (const auto& o : kOffsets) sum += shade(c + o[0], r + o[1], r, c).intensity;
        intensity.at<float>(r, c) = sum / 4;
      }
    });
  }
  return {intensity, labels, dynamic, depth, mover, part};
}

cv::Mat exposeImage(const cv::Mat& radiance, const PinholeCamera& cam, const RenderOptions& opt,
                    double gain, uint64_t noise_seed) {
  const int W = cam.width, H = cam.height;
  cv::Mat intensity(H, W, CV_32F);
  // Vignetting: darkening growing with the squared distance from the principal point.
  const double r_max2 = cam.cx * cam.cx + cam.cy * cam.cy;
  for (int r = 0; r < H; ++r) {
    const float* in = radiance.ptr<float>(r);
    float* out = intensity.ptr<float>(r);
    for (int c = 0; c < W; ++c) {
      const double d2 = (c - cam.cx) * (c - cam.cx) + (r - cam.cy) * (r - cam.cy);
      out[c] = in[c] * static_cast<float>(gain * (1.0 - opt.vignetting * d2 / r_max2));
    }
  }
  if (opt.noise_sigma > 0) {
    cv::Mat noise(H, W, CV_32F);
    cv::RNG rng(noise_seed);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, opt.noise_sigma);
    intensity += noise;
  }
  cv::Mat image;
  intensity.convertTo(image, CV_8U);  // rounds and saturates to 0..255
  return image;
}

RenderedFrame renderFrame(const WarehouseScene& scene, const PinholeCamera& cam,
                          const Eigen::Isometry3d& T_WC, const RenderOptions& opt,
                          uint64_t noise_seed) {
  const SceneRadiance sharp = renderRadiance(scene, cam, T_WC, opt);
  return {exposeImage(sharp.radiance, cam, opt, 1.0, noise_seed), sharp.mask, sharp.dynamic};
}

}  // namespace rpvio::sim

#pragma once
// Ray-casting renderer of the warehouse for a pinhole camera: image (8-bit, filtered textures,
// anti-aliased edges, vignetting, Gaussian noise) and the plane-instance label mask of the same
// instant. Two stages: the scene's radiance at the pixels (renderRadiance), then the sensor
// (exposeImage), so that camera effects (motion_blur.h, auto_exposure.h) can act in between.
// Pixel (u, v) integer coordinates are pixel centres (OpenCV convention).
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "sim/warehouse_scene.h"

namespace rpvio::sim {

struct PinholeCamera {
  int width = 640, height = 480;
  double fx = 320, fy = 320, cx = 319.5, cy = 239.5;  // 90° horizontal field of view
};

struct RenderOptions {
  double noise_sigma = 2.0;  // grey levels, Gaussian
  double vignetting = 0.25;  // relative darkening at the image corners
  int supersampling = 0;     // 0: 2x2 only where labels change (edges); k > 0: k x k everywhere
  int threads = 0;           // 0: all hardware threads (not an INI key: rendering is deterministic)

  template <class Visitor>
  void fields(Visitor& v) {
    RPVIO_OPTION(v, noise_sigma);
    RPVIO_OPTION(v, vignetting);
    RPVIO_OPTION(v, supersampling);
  }
};

struct RenderedFrame {
  cv::Mat image;    // CV_8UC1
  cv::Mat mask;     // CV_8UC1 labels (see warehouse_scene.h)
  cv::Mat dynamic;  // CV_8UC1, 255 where the pixel centre sees a moving thing (ground truth)
};

constexpr int16_t kMoverObjectBase = 1000;

/// What reaches the sensor from the scene as posed, at one instant.
struct SceneRadiance {
  cv::Mat radiance;  // CV_32F, shaded intensity (0..255 on surfaces; more on light panels)
  cv::Mat mask;      // CV_8UC1 labels
  cv::Mat dynamic;   // CV_8UC1, 255 on moving things
  cv::Mat depth;     // CV_32F, camera-z depth of the point at the pixel centre (0: nothing hit)
  cv::Mat mover;     // CV_16S, what moving thing the pixel centre sees: character k as k, moving
                     // object j as kMoverObjectBase + j, -1 nothing that moves
  cv::Mat part;      // CV_8S, the character's part there (-1: none)
};

/// The scene as posed (WarehouseScene::setTime) seen from camera pose T_WC (camera in world).
SceneRadiance renderRadiance(const WarehouseScene& scene, const PinholeCamera& camera,
                             const Eigen::Isometry3d& T_WC, const RenderOptions& options);

/// The sensor: radiance × gain × vignetting, plus Gaussian noise, rounded and saturated to 8 bits.
cv::Mat exposeImage(const cv::Mat& radiance, const PinholeCamera& camera,
                    const RenderOptions& options, double gain, uint64_t noise_seed);

/// renderRadiance then exposeImage at gain 1: the sharp image of an instant.
/// (WarehouseScene::setTime) from camera pose T_WC (camera in world). Deterministic for a given
/// noise_seed, whatever the thread count.
RenderedFrame renderFrame(const WarehouseScene& scene, const PinholeCamera& camera,
                          const Eigen::Isometry3d& T_WC, const RenderOptions& options,
                          uint64_t noise_seed);

/// World ray of pixel (u, v): origin and direction with unit camera-z component (t = depth).
std::pair<Eigen::Vector3d, Eigen::Vector3d> pixelRay(const PinholeCamera& camera,
                                                     const Eigen::Isometry3d& T_WC, double u,
                                                     double v);

}  // namespace rpvio::sim

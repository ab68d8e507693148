#pragma once
// Motion blur of a finite exposure: the frame at time t integrates the scene over the shutter
// interval [t − e/2, t + e/2] following the true camera motion and the characters' motion.
//
// Method: a per-pixel motion-vector post-process of the sharp radiance at t, not an average of
// sub-frame renders. Each pixel's scene point (its depth; on a character the same point of the
// moving limb, CapsuleFigure::follow; on a moving object, the object's motion) is projected with
// the camera poses at the shutter's opening and closing, p− and p+, and the pixel is the box
// integral of the sharp radiance along the segment p− → p+: B(p) = (1/n) Σ_i I(p− + (i + ½)/n (p+ −
// p−)), n = ⌈|p+ − p−|⌉ (samples ≤ 1 px apart, bilinear). Its cost is one projection per pixel plus
// about one sample per pixel of blur, a fraction of a render, whereas sub-frames spaced ≤ 1 px cost
// one full render per pixel of blur. Approximation: the motion is the pixel's own, so a moving
// character smears over the background only inside its own silhouette (its outer half-smear is
// missing), and occlusion changes during the exposure are ignored.
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "sim/renderer.h"

namespace rpvio::sim {

/// Where the camera is at the shutter's opening and closing (the sharp frame's pose is T_WC).
struct ShutterInterval {
  double t_open = 0, t_close = 0;  // s; the frame's time is their middle
  Eigen::Isometry3d T_WC_open = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_WC_close = Eigen::Isometry3d::Identity();
};

/// Blurred radiance (CV_32F) of `sharp`, rendered from T_WC with `scene` posed at the frame's
/// time. `threads`: 0 = all hardware threads.
cv::Mat motionBlur(const SceneRadiance& sharp, const WarehouseScene& scene,
                   const PinholeCamera& camera, const Eigen::Isometry3d& T_WC,
                   const ShutterInterval& shutter, int threads);

}  // namespace rpvio::sim

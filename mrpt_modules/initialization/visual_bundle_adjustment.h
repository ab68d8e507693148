#pragma once
// Visual bundle adjustment of the initialization window (up to scale): reprojection residuals of
// every triangulated track (3D points) and, for the features of the planes in `window.planes`,
// RP-VIO's homography residual between consecutive observations (plane normal on the unit
// sphere). Both residuals are weighted sqrt_info (= focal / sigma_px) under a Cauchy loss.
#include "mrpt_modules/initialization/sfm_window.h"

namespace rpvio {

struct BundleAdjustmentOptions {
  double sqrt_info = 460.0 / 1.5;
  double cauchy_scale = 1.0;  // in units of sigma_px
  int max_iterations = 30;
  bool homography_residuals = true;
};

/// What fixes the gauge: the pose of `fixed_frame` (6 DoF) and the scale, either by the distance
/// of `fixed_distance_plane` or by the position of `fixed_position_frame` (VINS-style).
struct BundleAdjustmentGauge {
  size_t fixed_frame = 0;
  std::optional<int> fixed_distance_plane;
  std::optional<size_t> fixed_position_frame;
};

struct BundleAdjustmentReport {
  bool converged = false;
  double initial_rms_px = 0, final_rms_px = 0;  // residual RMS in px at the focal length 460
  size_t residuals = 0;
};

/// Refines the solved cameras, the triangulated points and the planes' normals (and distances not
/// fixed by the gauge) in place.
BundleAdjustmentReport bundleAdjust(SfmWindow& window, const BundleAdjustmentGauge& gauge,
                                    const BundleAdjustmentOptions& options = {});

}  // namespace rpvio

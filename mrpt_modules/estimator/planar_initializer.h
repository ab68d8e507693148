#pragma once
// RP-VIO's initialization (DESIGN.md §1 step 3) over a window of frames: the largest plane seen
// in the first and last frames, its homography decomposed and disambiguated by the gyroscope,
// every frame's camera pose by PnP on the plane's points (up to the plane distance), then the
// visual-inertial alignment for scale, gravity, velocities and biases. The world frame is
// gravity-aligned (z up) with its origin at the first camera.
#include <optional>
#include <string>
#include <vector>

#include "mrpt_modules/estimator/estimator_types.h"
#include "rawlog_io/calibration.h"

namespace rpvio {

struct PlanarInitOptions {
  double min_window_s = 2.0;    // enough IMU excitation and baseline for the alignment
  double min_parallax_px = 30;  // at the virtual focal length 460, between first and last frame
  size_t min_plane_features = 15;
  // Wider than the front-end's frame-to-frame 1 px: over the window's baseline tracks drift.
  double ransac_threshold_px = 2.5;
  double virtual_focal = 460;
};

/// On success, fills the states of `frames` (and repropagates their preintegrations with the
/// estimated biases) and returns the plane's id and estimate; otherwise `why_not` says why.
std::optional<std::pair<int, PlaneEstimate>> initializeFromPlane(std::vector<WindowFrame>& frames,
                                                                 const Calibration& calibration,
                                                                 const PlanarInitOptions& options,
                                                                 std::string* why_not);

}  // namespace rpvio

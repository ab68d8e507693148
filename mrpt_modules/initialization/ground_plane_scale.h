#pragma once
// Metric scale of an up-to-scale initialization window from the camera's known height above a
// flat ground (ground robots, cars), for when the IMU's accelerations do not make the scale
// observable. The ground is the labelled plane whose points, fitted in the window's reference
// camera frame r, have a normal within max_tilt of gravity; its distance from camera r's centre
// in SfM units is d, so the scale is height / d.
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <vector>

#include "mrpt_modules/imu/imu_preintegration.h"
#include "mrpt_modules/initialization/sfm_window.h"

namespace rpvio {

struct GroundPlane {
  int plane_id = 0;
  Eigen::Vector3d n_r = Eigen::Vector3d::UnitZ();  // unit, from camera r's centre towards the plane
  double d = 0;                                    // SfM units
  double tilt_deg = 0;                             // normal against gravity's direction
};

/// Gravity's direction in frame r from the preintegrated velocity changes, Σ_k R_r_b(k−1) Δv_k =
/// R_r_w (v_n − v_0 − g T): the platform's own change of velocity over the window is the error
/// (a car gaining 3 m/s in 2 s: ~9°). `R_r_b[k]`: body orientations in r; `imu[k]` from k−1 to k.
Eigen::Vector3d gravityDirection(const std::vector<Eigen::Matrix3d>& R_r_b,
                                 const std::vector<std::shared_ptr<ImuPreintegration>>& imu);

/// The ground among the window's labelled planes with at least `min_points` points: the one
/// most nearly perpendicular to `down_r`, if within `max_tilt_deg` and below the camera.
std::optional<GroundPlane> findGroundPlane(const SfmWindow& window, const Eigen::Vector3d& down_r,
                                           double max_tilt_deg, size_t min_points);

}  // namespace rpvio

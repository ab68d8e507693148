#pragma once
// Points of the initial structure: two-view triangulation of a feature and the intersection of a
// viewing ray with a known plane (RP-VIO's plane features), both in the reference frame.
#include <optional>

#include "mrpt_modules/initialization/camera_pose.h"

namespace rpvio {

/// Linear (DLT) triangulation of the normalized observations u_a, u_b of two cameras; nullopt when
/// the point is not in front of both cameras (depth > min_depth) or the rays are parallel.
std::optional<Eigen::Vector3d> triangulateTwoView(const CameraPose& a, const Eigen::Vector2d& u_a,
                                                  const CameraPose& b, const Eigen::Vector2d& u_b,
                                                  double min_depth = 1e-3);

/// Where the ray of the normalized point u of `camera` meets the plane n·X = d (reference frame);
/// nullopt when it meets it behind the camera or not at all.
std::optional<Eigen::Vector3d> intersectRayWithPlane(const CameraPose& camera,
                                                     const Eigen::Vector2d& u,
                                                     const Eigen::Vector3d& n, double d);

}  // namespace rpvio

#include "mrpt_modules/estimator/ground_in_window.h"

#include <cmath>

namespace rpvio {

std::optional<GroundInWindow> groundInWindow(const PlaneEstimates& planes,
                                             const std::set<int>& candidates,
                                             const Eigen::Vector3d& camera_centre, double height,
                                             double max_tilt_deg, double max_relative_error) {
  std::optional<GroundInWindow> ground;
  double best = max_relative_error * height;
  for (int id : candidates) {
    const auto it = planes.find(id);
    if (it == planes.end()) continue;
    const Eigen::Vector3d n(it->second.normal);
    if (std::abs(n.z()) < std::cos(max_tilt_deg * M_PI / 180)) continue;
    const double signed_distance = n.dot(camera_centre) - it->second.distance[0];
    if (signed_distance * n.z() <= 0) continue;  // the camera is below it
    const double error = std::abs(std::abs(signed_distance) - height);
    if (error > best) continue;
    best = error;
    ground = GroundInWindow{id, signed_distance > 0 ? 1.0 : -1.0};
  }
  return ground;
}

}  // namespace rpvio

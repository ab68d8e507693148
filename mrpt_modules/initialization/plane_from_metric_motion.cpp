#include "mrpt_modules/initialization/plane_from_metric_motion.h"

namespace rpvio {

std::optional<CameraPlane> planeFromMetricMotion(const std::vector<Eigen::Vector2d>& points_i,
                                                 const std::vector<Eigen::Vector2d>& points_j,
                                                 const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                                                 const HomographyInitOptions& options,
                                                 std::string* why_not) {
  std::vector<PlaneMotion> candidates;
  if (!planeMotionFromHomography(points_i, points_j, R, options, why_not, &candidates))
    return std::nullopt;
  // Among the solutions, the rotation closest to the metric one, then t/d along t.
  const PlaneMotion* best = nullptr;
  double best_cost = 0;
  for (const auto& c : candidates) {
    const double alignment = c.t_over_d.normalized().dot(t.normalized());
    const double cost = c.rotation_error_deg + 10.0 * (1.0 - alignment);
    if (!best || cost < best_cost) best = &c, best_cost = cost;
  }
  const double d = t.dot(best->t_over_d) / best->t_over_d.squaredNorm();
  if (!(d > 0)) {
    if (why_not) *why_not = "plane distance from the metric translation is not positive";
    return std::nullopt;
  }
  return CameraPlane{best->n, d};
}

}  // namespace rpvio

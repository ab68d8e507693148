#include "mrpt_modules/initialization/ground_plane_scale.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>

namespace rpvio {

Eigen::Vector3d gravityDirection(const std::vector<Eigen::Matrix3d>& R_r_b,
                                 const std::vector<std::shared_ptr<ImuPreintegration>>& imu) {
  // The specific force integrates to −g T when the velocity does not change: gravity points
  // against the sum.
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (size_t k = 1; k < imu.size(); ++k)
    if (imu[k]) sum += R_r_b[k - 1] * imu[k]->deltaV();
  return -sum.normalized();
}

std::optional<GroundPlane> findGroundPlane(const SfmWindow& window, const Eigen::Vector3d& down_r,
                                           double max_tilt_deg, size_t min_points) {
  std::map<int, std::vector<Eigen::Vector3d>> points;
  for (const SfmTrack& track : window.tracks)
    if (track.plane_id > 0 && track.X_r) points[track.plane_id].push_back(*track.X_r);
  std::optional<GroundPlane> best;
  for (const auto& [id, X] : points) {
    if (X.size() < min_points) continue;
    // Least-squares plane: through the centroid, normal the direction of least spread.
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const auto& x : X) centroid += x / static_cast<double>(X.size());
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
    for (const auto& x : X) scatter += (x - centroid) * (x - centroid).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(scatter);
    Eigen::Vector3d n = eigen.eigenvectors().col(0);
    if (n.dot(centroid) < 0) n = -n;  // n·X = d > 0: from the camera towards the plane
    const double tilt = std::acos(std::clamp(n.dot(down_r), -1.0, 1.0)) * 180 / M_PI;
    if (tilt > max_tilt_deg || (best && tilt >= best->tilt_deg)) continue;
    best = GroundPlane{id, n, n.dot(centroid), tilt};
  }
  return best;
}

}  // namespace rpvio

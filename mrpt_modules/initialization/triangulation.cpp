#include "mrpt_modules/initialization/triangulation.h"

#include <Eigen/Dense>

namespace rpvio {

std::optional<Eigen::Vector3d> triangulateTwoView(const CameraPose& a, const Eigen::Vector2d& u_a,
                                                  const CameraPose& b, const Eigen::Vector2d& u_b,
                                                  double min_depth) {
  // Each view gives x P X − z P X = 0 and y P X − z P X = 0 with P = [Rᵀ | −Rᵀ p] (Hartley &
  // Zisserman §12.2); the solution is the right singular vector of the smallest singular value.
  Eigen::Matrix4d A;
  int row = 0;
  for (const auto& [cam, u] : {std::pair{&a, u_a}, std::pair{&b, u_b}}) {
    Eigen::Matrix<double, 3, 4> P;
    P << cam->R_r_c.transpose(), -cam->R_r_c.transpose() * cam->p_r_c;
    A.row(row++) = u.x() * P.row(2) - P.row(0);
    A.row(row++) = u.y() * P.row(2) - P.row(1);
  }
  const Eigen::Vector4d X =
      Eigen::JacobiSVD<Eigen::Matrix4d>(A, Eigen::ComputeFullV).matrixV().col(3);
  if (std::abs(X.w()) < 1e-12) return std::nullopt;
  const Eigen::Vector3d point = X.head<3>() / X.w();
  if (a.toCamera(point).z() <= min_depth || b.toCamera(point).z() <= min_depth) return std::nullopt;
  return point;
}

std::optional<Eigen::Vector3d> intersectRayWithPlane(const CameraPose& camera,
                                                     const Eigen::Vector2d& u,
                                                     const Eigen::Vector3d& n, double d) {
  // X = p + λ r with n·X = d → λ = (d − n·p) / (n·r); λ is the depth along the camera's z axis.
  const Eigen::Vector3d ray = camera.R_r_c * u.homogeneous();
  const double denominator = n.dot(ray);
  if (std::abs(denominator) < 1e-9) return std::nullopt;
  const double depth = (d - n.dot(camera.p_r_c)) / denominator;
  if (depth <= 0) return std::nullopt;
  return camera.p_r_c + depth * ray;
}

}  // namespace rpvio

// A plane moved into another frame (Plane::transformed): its points stay on it, its covariance is
// carried by the Jacobian of (n', d') in (n, d), checked against numeric derivatives.
#include <gtest/gtest.h>

#include "planes_map/plane.h"

namespace rpvio {
namespace {

Eigen::Isometry3d someMotion() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.2, -0.4, 1).normalized()).matrix();
  T.translation() = Eigen::Vector3d(3, -2, 0.5);
  return T;
}

TEST(PlaneTransform, PointsOnThePlaneStayOnIt) {
  Plane plane;
  plane.normal = Eigen::Vector3d(0.1, 0.2, 1).normalized();
  plane.distance = 1.3;
  Eigen::Vector3d origin, u, v;
  plane.planeFrame(origin, u, v);
  for (int k = 0; k < 5; ++k) plane.support.push_back(origin + k * u - 2 * k * v);
  plane.polygon = plane.support;
  const Eigen::Isometry3d T = someMotion();
  const Plane moved = plane.transformed(T);
  EXPECT_NEAR(moved.normal.norm(), 1, 1e-12);
  for (size_t k = 0; k < plane.support.size(); ++k) {
    EXPECT_NEAR(moved.signedDistance(T * plane.support[k]), 0, 1e-12);
    EXPECT_LT((moved.support[k] - T * plane.support[k]).norm(), 1e-12);
    EXPECT_LT((moved.polygon[k] - T * plane.polygon[k]).norm(), 1e-12);
  }
  // And back.
  const Plane back = moved.transformed(T.inverse());
  EXPECT_LT((back.normal - plane.normal).norm(), 1e-12);
  EXPECT_NEAR(back.distance, plane.distance, 1e-12);
}

TEST(PlaneTransform, TheCovarianceIsCarriedByTheNumericJacobian) {
  Plane plane;
  plane.normal = Eigen::Vector3d(-0.3, 0.1, 0.9).normalized();
  plane.distance = -2.1;
  Eigen::Matrix4d A = Eigen::Matrix4d::Random();
  plane.covariance = A * A.transpose() * 1e-3;
  const Eigen::Isometry3d T = someMotion();
  // (n, d) -> (n', d') taken as a function of the four numbers, differentiated numerically.
  const auto f = [&](const Eigen::Vector4d& x) {
    Plane p;
    p.normal = x.head<3>();
    p.distance = x(3);
    const Plane m = p.transformed(T);
    return Eigen::Vector4d(m.normal.x(), m.normal.y(), m.normal.z(), m.distance);
  };
  Eigen::Vector4d x0;
  x0 << plane.normal, plane.distance;
  Eigen::Matrix4d J;
  const double h = 1e-6;
  for (int c = 0; c < 4; ++c) {
    Eigen::Vector4d dx = Eigen::Vector4d::Zero();
    dx(c) = h;
    J.col(c) = (f(x0 + dx) - f(x0 - dx)) / (2 * h);
  }
  const Eigen::Matrix4d expected = J * plane.covariance * J.transpose();
  EXPECT_LT((plane.transformed(T).covariance - expected).norm(), 1e-9 * expected.norm());
}

}  // namespace
}  // namespace rpvio

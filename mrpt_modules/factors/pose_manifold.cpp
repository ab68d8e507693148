#include "mrpt_modules/factors/pose_manifold.h"

#include <Eigen/Geometry>

#include "mrpt_modules/factors/parameter_blocks.h"
#include "mrpt_modules/imu/so3.h"

namespace rpvio {

bool PoseManifold::Plus(const double* x, const double* delta, double* out) const {
  const Eigen::Quaterniond q =
      (poseRotation(x) * expQuaternion(Eigen::Vector3d(delta[3], delta[4], delta[5]))).normalized();
  for (int i = 0; i < 3; ++i) out[i] = x[i] + delta[i];
  out[3] = q.x(), out[4] = q.y(), out[5] = q.z(), out[6] = q.w();
  return true;
}

Eigen::Matrix<double, 7, 6> posePlusJacobian(const double* x) {
  // d(q ⊗ [½δθ, 1])/dδθ in (x, y, z, w) order: ½ [w I + [v]× ; −vᵀ].
  const Eigen::Quaterniond q = poseRotation(x);
  Eigen::Matrix<double, 7, 6> J = Eigen::Matrix<double, 7, 6>::Zero();
  J.topLeftCorner<3, 3>().setIdentity();
  J.block<3, 3>(3, 3) = 0.5 * (q.w() * Eigen::Matrix3d::Identity() + hat(q.vec()));
  J.block<1, 3>(6, 3) = -0.5 * q.vec().transpose();
  return J;
}

bool PoseManifold::PlusJacobian(const double* x, double* jacobian) const {
  Eigen::Map<Eigen::Matrix<double, 7, 6, Eigen::RowMajor>> J(jacobian);
  J = posePlusJacobian(x);
  return true;
}

bool PoseManifold::Minus(const double* y, const double* x, double* out) const {
  const Eigen::AngleAxisd d(poseRotation(x).inverse() * poseRotation(y));
  const Eigen::Vector3d w = d.angle() * d.axis();
  for (int i = 0; i < 3; ++i) out[i] = y[i] - x[i], out[3 + i] = w[i];
  return true;
}

bool PoseManifold::MinusJacobian(const double* x, double* jacobian) const {
  Eigen::Matrix<double, 6, 6> I = Eigen::Matrix<double, 6, 6>::Identity();
  Eigen::Map<Eigen::Matrix<double, 6, 7, Eigen::RowMajor>> J(jacobian);
  J = tangentToAmbient<6>(I, x);
  return true;
}

namespace {

/// d(Exp(δ) ⊗ q)/dδ at δ = 0 for world-frame δ, in (x, y, z, w) order: ½ [w I − [v]× ; −vᵀ].
Eigen::Matrix<double, 4, 3> leftPerturbationJacobian(const Eigen::Quaterniond& q) {
  Eigen::Matrix<double, 4, 3> J;
  J.topRows<3>() = 0.5 * (q.w() * Eigen::Matrix3d::Identity() - hat(q.vec()));
  J.bottomRows<1>() = -0.5 * q.vec().transpose();
  return J;
}

}  // namespace

bool TiltOnlyPoseManifold::Plus(const double* x, const double* delta, double* out) const {
  const Eigen::Quaterniond q =
      (expQuaternion(Eigen::Vector3d(delta[0], delta[1], 0)) * poseRotation(x)).normalized();
  for (int i = 0; i < 3; ++i) out[i] = x[i];
  out[3] = q.x(), out[4] = q.y(), out[5] = q.z(), out[6] = q.w();
  return true;
}

bool TiltOnlyPoseManifold::PlusJacobian(const double* x, double* jacobian) const {
  Eigen::Map<Eigen::Matrix<double, 7, 2, Eigen::RowMajor>> J(jacobian);
  J.setZero();
  J.bottomRows<4>() = leftPerturbationJacobian(poseRotation(x)).leftCols<2>();
  return true;
}

bool TiltOnlyPoseManifold::Minus(const double* y, const double* x, double* out) const {
  const Eigen::AngleAxisd d(poseRotation(y) * poseRotation(x).inverse());
  const Eigen::Vector3d w = d.angle() * d.axis();
  out[0] = w.x(), out[1] = w.y();
  return true;
}

bool TiltOnlyPoseManifold::MinusJacobian(const double* x, double* jacobian) const {
  // The Plus Jacobian's columns are orthogonal with norm ½: its pseudo-inverse is 4 Jᵀ.
  Eigen::Map<Eigen::Matrix<double, 2, 7, Eigen::RowMajor>> J(jacobian);
  J.setZero();
  J.rightCols<4>() = 4 * leftPerturbationJacobian(poseRotation(x)).leftCols<2>().transpose();
  return true;
}

}  // namespace rpvio

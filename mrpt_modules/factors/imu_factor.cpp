#include "mrpt_modules/factors/imu_factor.h"

#include <Eigen/Cholesky>

#include "mrpt_modules/factors/parameter_blocks.h"
#include "mrpt_modules/factors/pose_manifold.h"
#include "mrpt_modules/imu/so3.h"

namespace rpvio {
namespace {

using P = ImuPreintegration;

/// Vector-part blocks of the quaternion product matrices: (a ⊗ b).vec w.r.t. b.vec is
/// a.w I + [a.v]×; w.r.t. a.vec it is b.w I − [b.v]×.
Eigen::Matrix3d leftVec(const Eigen::Quaterniond& a) {
  return a.w() * Eigen::Matrix3d::Identity() + hat(a.vec());
}
Eigen::Matrix3d rightVec(const Eigen::Quaterniond& b) {
  return b.w() * Eigen::Matrix3d::Identity() - hat(b.vec());
}

/// 4x4 matrices of q ⊗ p in [w, x, y, z] order: q ⊗ p = left(q) p = right(p) q.
Eigen::Matrix4d leftProduct(const Eigen::Quaterniond& q) {
  Eigen::Matrix4d m;
  m(0, 0) = q.w();
  m.block<1, 3>(0, 1) = -q.vec().transpose();
  m.block<3, 1>(1, 0) = q.vec();
  m.block<3, 3>(1, 1) = leftVec(q);
  return m;
}
Eigen::Matrix4d rightProduct(const Eigen::Quaterniond& p) {
  Eigen::Matrix4d m;
  m(0, 0) = p.w();
  m.block<1, 3>(0, 1) = -p.vec().transpose();
  m.block<3, 1>(1, 0) = p.vec();
  m.block<3, 3>(1, 1) = rightVec(p);
  return m;
}

}  // namespace

ImuFactor::ImuFactor(std::shared_ptr<const ImuPreintegration> preintegration,
                     const Eigen::Vector3d& g_w)
    : pre_(std::move(preintegration)), g_w_(g_w) {
  // Whitening W with WᵀW = P⁻¹ (upper Cholesky factor of the information).
  const Eigen::Matrix<double, 15, 15> information = pre_->covariance().inverse();
  sqrt_information_ = Eigen::LLT<Eigen::Matrix<double, 15, 15>>(information).matrixL().transpose();
}

bool ImuFactor::Evaluate(double const* const* x, double* residuals, double** jacobians) const {
  const Eigen::Vector3d Pi = posePosition(x[0]), Pj = posePosition(x[2]);
  const Eigen::Quaterniond Qi = poseRotation(x[0]), Qj = poseRotation(x[2]);
  const Eigen::Map<const Eigen::Matrix<double, 9, 1>> sbi(x[1]), sbj(x[3]);
  const Eigen::Vector3d Vi = sbi.segment<3>(0), Bai = sbi.segment<3>(3), Bgi = sbi.segment<3>(6);
  const Eigen::Vector3d Vj = sbj.segment<3>(0), Baj = sbj.segment<3>(3), Bgj = sbj.segment<3>(6);

  Eigen::Map<Eigen::Matrix<double, 15, 1>> r(residuals);
  r = sqrt_information_ * pre_->evaluate(Pi, Qi, Vi, Bai, Bgi, Pj, Qj, Vj, Baj, Bgj, g_w_);
  if (!jacobians) return true;

  const double T = pre_->sumDt();
  const auto& J = pre_->jacobian();
  const Eigen::Matrix3d RiT = Qi.toRotationMatrix().transpose();
  const Eigen::Vector3d dbg = Bgi - pre_->linearizedBg();
  const Eigen::Quaterniond q_corr =
      pre_->deltaQ() * expQuaternion(J.block<3, 3>(P::kR, P::kBg) * dbg);
  const Eigen::Quaterniond Qij = Qi.inverse() * Qj;

  if (jacobians[0]) {  // pose_i: (δp_i, δθ_i)
    Eigen::Matrix<double, 15, 6> Jt = Eigen::Matrix<double, 15, 6>::Zero();
    Jt.block<3, 3>(P::kP, 0) = -RiT;
    Jt.block<3, 3>(P::kP, 3) = hat(RiT * (Pj - Pi - Vi * T - 0.5 * g_w_ * T * T));
    // r_q = 2 vec(q_corr⁻¹ ⊗ Exp(−δθ) ⊗ Qi⁻¹Qj)
    Jt.block<3, 3>(P::kR, 3) =
        -(rightProduct(Qij) * leftProduct(q_corr.inverse())).bottomRightCorner<3, 3>();
    Jt.block<3, 3>(P::kV, 3) = hat(RiT * (Vj - Vi - g_w_ * T));
    Eigen::Map<Eigen::Matrix<double, 15, 7, Eigen::RowMajor>> out(jacobians[0]);
    out = tangentToAmbient<15>(sqrt_information_ * Jt, x[0]);
  }
  if (jacobians[1]) {  // speed_bias_i
    Eigen::Matrix<double, 15, 9> Jb = Eigen::Matrix<double, 15, 9>::Zero();
    Jb.block<3, 3>(P::kP, 0) = -RiT * T;
    Jb.block<3, 3>(P::kP, 3) = -J.block<3, 3>(P::kP, P::kBa);
    Jb.block<3, 3>(P::kP, 6) = -J.block<3, 3>(P::kP, P::kBg);
    // r_q = 2 vec(Exp(φ) ⊗ Δq⁻¹ Qi⁻¹ Qj), φ = −J_q δbg; Exp(φ + ε) = Exp(φ) Exp(J_r(φ) ε).
    const Eigen::Vector3d phi = -J.block<3, 3>(P::kR, P::kBg) * dbg;
    Jb.block<3, 3>(P::kR, 6) =
        -(rightProduct(pre_->deltaQ().inverse() * Qij) * leftProduct(expQuaternion(phi)))
             .bottomRightCorner<3, 3>() *
        rightJacobian(phi) * J.block<3, 3>(P::kR, P::kBg);
    Jb.block<3, 3>(P::kV, 0) = -RiT;
    Jb.block<3, 3>(P::kV, 3) = -J.block<3, 3>(P::kV, P::kBa);
    Jb.block<3, 3>(P::kV, 6) = -J.block<3, 3>(P::kV, P::kBg);
    Jb.block<3, 3>(P::kBa, 3) = -Eigen::Matrix3d::Identity();
    Jb.block<3, 3>(P::kBg, 6) = -Eigen::Matrix3d::Identity();
    Eigen::Map<Eigen::Matrix<double, 15, 9, Eigen::RowMajor>> out(jacobians[1]);
    out = sqrt_information_ * Jb;
  }
  if (jacobians[2]) {  // pose_j
    Eigen::Matrix<double, 15, 6> Jt = Eigen::Matrix<double, 15, 6>::Zero();
    Jt.block<3, 3>(P::kP, 0) = RiT;
    Jt.block<3, 3>(P::kR, 3) = leftVec(q_corr.inverse() * Qij);
    Eigen::Map<Eigen::Matrix<double, 15, 7, Eigen::RowMajor>> out(jacobians[2]);
    out = tangentToAmbient<15>(sqrt_information_ * Jt, x[2]);
  }
  if (jacobians[3]) {  // speed_bias_j
    Eigen::Matrix<double, 15, 9> Jb = Eigen::Matrix<double, 15, 9>::Zero();
    Jb.block<3, 3>(P::kV, 0) = RiT;
    Jb.block<3, 3>(P::kBa, 3) = Eigen::Matrix3d::Identity();
    Jb.block<3, 3>(P::kBg, 6) = Eigen::Matrix3d::Identity();
    Eigen::Map<Eigen::Matrix<double, 15, 9, Eigen::RowMajor>> out(jacobians[3]);
    out = sqrt_information_ * Jb;
  }
  return true;
}

}  // namespace rpvio

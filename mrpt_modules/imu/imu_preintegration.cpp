#include "mrpt_modules/imu/imu_preintegration.h"

#include "mrpt_modules/imu/so3.h"

namespace rpvio {

ImuPreintegration::ImuPreintegration(const Eigen::Vector3d& acc0, const Eigen::Vector3d& gyr0,
                                     const Eigen::Vector3d& ba, const Eigen::Vector3d& bg,
                                     const ImuNoise& noise)
    : noise_(noise),
      acc0_(acc0),
      gyr0_(gyr0),
      first_acc_(acc0),
      first_gyr_(gyr0),
      ba_(ba),
      bg_(bg) {}

void ImuPreintegration::push(double dt, const Eigen::Vector3d& acc, const Eigen::Vector3d& gyr) {
  samples_.push_back({dt, acc, gyr});
  integrate(dt, acc, gyr);
}

void ImuPreintegration::repropagate(const Eigen::Vector3d& ba, const Eigen::Vector3d& bg) {
  ba_ = ba;
  bg_ = bg;
  acc0_ = first_acc_;
  gyr0_ = first_gyr_;
  sum_dt_ = 0;
  delta_p_.setZero();
  delta_v_.setZero();
  delta_q_.setIdentity();
  jacobian_.setIdentity();
  covariance_.setZero();
  for (const Sample& s : samples_) integrate(s.dt, s.acc, s.gyr);
}

// One midpoint step from the previous sample (acc0_, gyr0_) to (acc1, gyr1), with the exact
// linearization of this discrete step for the error state [δp δθ δv δba δbg] (right perturbation
// of the rotation) and the noise of the two samples and of the bias random walks.
void ImuPreintegration::integrate(double dt, const Eigen::Vector3d& acc1,
                                  const Eigen::Vector3d& gyr1) {
  const Eigen::Vector3d w = 0.5 * (gyr0_ + gyr1) - bg_;
  const Eigen::Vector3d a0 = acc0_ - ba_, a1 = acc1 - ba_;
  const Eigen::Quaterniond dq = expQuaternion(w * dt);
  const Eigen::Quaterniond q1 = (delta_q_ * dq).normalized();
  const Eigen::Matrix3d R0 = delta_q_.toRotationMatrix(), R1 = q1.toRotationMatrix();
  const Eigen::Vector3d acc_mid = 0.5 * (R0 * a0 + R1 * a1);

  // δθ₁ = Exp(w dt)ᵀ δθ₀ − J_r(w dt) dt δbg;  δa = ½(−R0 [a0]× δθ₀ − R1 [a1]× δθ₁ − (R0 + R1) δba).
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d dth_dth = dq.toRotationMatrix().transpose();
  const Eigen::Matrix3d dth_dbg = -rightJacobian(w * dt) * dt;
  const Eigen::Matrix3d A0 = R0 * hat(a0), A1 = R1 * hat(a1);
  const Eigen::Matrix3d da_dth = -0.5 * (A0 + A1 * dth_dth);
  const Eigen::Matrix3d da_dba = -0.5 * (R0 + R1);
  const Eigen::Matrix3d da_dbg = -0.5 * A1 * dth_dbg;

  Matrix15 F = Matrix15::Identity();
  F.block<3, 3>(kP, kR) = 0.5 * dt * dt * da_dth;
  F.block<3, 3>(kP, kV) = I * dt;
  F.block<3, 3>(kP, kBa) = 0.5 * dt * dt * da_dba;
  F.block<3, 3>(kP, kBg) = 0.5 * dt * dt * da_dbg;
  F.block<3, 3>(kR, kR) = dth_dth;
  F.block<3, 3>(kR, kBg) = dth_dbg;
  F.block<3, 3>(kV, kR) = dt * da_dth;
  F.block<3, 3>(kV, kBa) = dt * da_dba;
  F.block<3, 3>(kV, kBg) = dt * da_dbg;

  // Noise inputs [n_a0 n_g0 n_a1 n_g1 n_ba n_bg]: each gyro sample enters w with weight ½.
  Eigen::Matrix<double, 15, 18> V = Eigen::Matrix<double, 15, 18>::Zero();
  const Eigen::Matrix3d dth_dng = 0.5 * rightJacobian(w * dt) * dt;
  const Eigen::Matrix3d da_dng = -0.5 * A1 * dth_dng;
  for (int k = 0; k < 2; ++k) {
    const Eigen::Matrix3d da_dna = 0.5 * (k == 0 ? R0 : R1);
    V.block<3, 3>(kP, 6 * k) = 0.5 * dt * dt * da_dna;
    V.block<3, 3>(kV, 6 * k) = dt * da_dna;
    V.block<3, 3>(kP, 6 * k + 3) = 0.5 * dt * dt * da_dng;
    V.block<3, 3>(kR, 6 * k + 3) = dth_dng;
    V.block<3, 3>(kV, 6 * k + 3) = dt * da_dng;
  }
  V.block<3, 3>(kBa, 12) = I * dt;
  V.block<3, 3>(kBg, 15) = I * dt;
  // Sample noise: discrete variance σ²/dt (σ the density). Each sample is shared by two midpoint
  // steps with weight ½; treating the two as independent with twice that variance gives each step
  // the continuous-time variance σ² dt. Random walks: σ_rw² dt after the dt in V, hence σ_rw²/dt.
  Eigen::Matrix<double, 18, 1> q;
  const double na = 2 * noise_.accel_noise_density * noise_.accel_noise_density / dt;
  const double ng = 2 * noise_.gyro_noise_density * noise_.gyro_noise_density / dt;
  const double nba = noise_.accel_random_walk * noise_.accel_random_walk / dt;
  const double nbg = noise_.gyro_random_walk * noise_.gyro_random_walk / dt;
  q << na, na, na, ng, ng, ng, na, na, na, ng, ng, ng, nba, nba, nba, nbg, nbg, nbg;

  delta_p_ += delta_v_ * dt + 0.5 * acc_mid * dt * dt;
  delta_v_ += acc_mid * dt;
  delta_q_ = q1;
  jacobian_ = F * jacobian_;
  covariance_ = F * covariance_ * F.transpose() + V * q.asDiagonal() * V.transpose();
  sum_dt_ += dt;
  acc0_ = acc1;
  gyr0_ = gyr1;
}

ImuPreintegration::Vector15 ImuPreintegration::evaluate(
    const Eigen::Vector3d& Pi, const Eigen::Quaterniond& Qi, const Eigen::Vector3d& Vi,
    const Eigen::Vector3d& Bai, const Eigen::Vector3d& Bgi, const Eigen::Vector3d& Pj,
    const Eigen::Quaterniond& Qj, const Eigen::Vector3d& Vj, const Eigen::Vector3d& Baj,
    const Eigen::Vector3d& Bgj, const Eigen::Vector3d& g_w) const {
  const Eigen::Vector3d dba = Bai - ba_, dbg = Bgi - bg_;
  // First-order bias correction of the preintegrated terms (Forster et al. 2017, Eq. 44).
  const Eigen::Quaterniond q_corr = delta_q_ * expQuaternion(jacobian_.block<3, 3>(kR, kBg) * dbg);
  const Eigen::Vector3d v_corr =
      delta_v_ + jacobian_.block<3, 3>(kV, kBa) * dba + jacobian_.block<3, 3>(kV, kBg) * dbg;
  const Eigen::Vector3d p_corr =
      delta_p_ + jacobian_.block<3, 3>(kP, kBa) * dba + jacobian_.block<3, 3>(kP, kBg) * dbg;
  const double T = sum_dt_;
  const Eigen::Matrix3d RiT = Qi.toRotationMatrix().transpose();
  Vector15 r;
  r.segment<3>(kP) = RiT * (Pj - Pi - Vi * T - 0.5 * g_w * T * T) - p_corr;
  r.segment<3>(kR) = 2 * (q_corr.inverse() * (Qi.inverse() * Qj)).vec();
  r.segment<3>(kV) = RiT * (Vj - Vi - g_w * T) - v_corr;
  r.segment<3>(kBa) = Baj - Bai;
  r.segment<3>(kBg) = Bgj - Bgi;
  return r;
}

}  // namespace rpvio

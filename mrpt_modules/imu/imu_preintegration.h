#pragma once
// IMU preintegration between two frames i and j (midpoint rule), with the Jacobians of the
// preintegrated terms w.r.t. the biases and the propagated 15x15 covariance (Forster et al. 2017;
// Qin et al. 2018, VINS-Mono §IV-B). Error-state order: [dp, dtheta, dv, dba, dbg].
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "common/sensor_types.h"

namespace rpvio {

class ImuPreintegration {
 public:
  static constexpr int kP = 0, kR = 3, kV = 6, kBa = 9, kBg = 12;
  using Matrix15 = Eigen::Matrix<double, 15, 15>;
  using Vector15 = Eigen::Matrix<double, 15, 1>;

  /// acc0/gyr0: the sample at t_i (interpolated if needed); biases are the linearization point.
  ImuPreintegration(const Eigen::Vector3d& acc0, const Eigen::Vector3d& gyr0,
                    const Eigen::Vector3d& ba, const Eigen::Vector3d& bg, const ImuNoise& noise);

  /// Adds the sample `dt` seconds after the previous one (midpoint integration).
  void push(double dt, const Eigen::Vector3d& acc, const Eigen::Vector3d& gyr);
  /// Re-integrates all samples with new linearization biases.
  void repropagate(const Eigen::Vector3d& ba, const Eigen::Vector3d& bg);

  double sumDt() const { return sum_dt_; }
  const Eigen::Vector3d& deltaP() const { return delta_p_; }
  const Eigen::Quaterniond& deltaQ() const { return delta_q_; }
  const Eigen::Vector3d& deltaV() const { return delta_v_; }
  const Eigen::Vector3d& linearizedBa() const { return ba_; }
  const Eigen::Vector3d& linearizedBg() const { return bg_; }
  const Matrix15& jacobian() const { return jacobian_; }  // d(state_j error)/d(state_i error)
  const Matrix15& covariance() const { return covariance_; }

  /// Residual [rp, rq(3, vector part *2), rv, rba, rbg] of the states at i and j (world frame,
  /// gravity vector g_w e.g. (0,0,-9.81)), bias change applied to first order.
  Vector15 evaluate(const Eigen::Vector3d& Pi, const Eigen::Quaterniond& Qi,
                    const Eigen::Vector3d& Vi, const Eigen::Vector3d& Bai,
                    const Eigen::Vector3d& Bgi, const Eigen::Vector3d& Pj,
                    const Eigen::Quaterniond& Qj, const Eigen::Vector3d& Vj,
                    const Eigen::Vector3d& Baj, const Eigen::Vector3d& Bgj,
                    const Eigen::Vector3d& g_w) const;

 private:
  struct Sample {
    double dt;
    Eigen::Vector3d acc, gyr;
  };
  void integrate(double dt, const Eigen::Vector3d& acc1, const Eigen::Vector3d& gyr1);

  ImuNoise noise_;
  Eigen::Vector3d acc0_, gyr0_, first_acc_, first_gyr_;
  Eigen::Vector3d ba_, bg_;
  double sum_dt_ = 0;
  Eigen::Vector3d delta_p_ = Eigen::Vector3d::Zero(), delta_v_ = Eigen::Vector3d::Zero();
  Eigen::Quaterniond delta_q_ = Eigen::Quaterniond::Identity();
  Matrix15 jacobian_ = Matrix15::Identity();
  Matrix15 covariance_ = Matrix15::Zero();
  std::vector<Sample> samples_;
};

}  // namespace rpvio

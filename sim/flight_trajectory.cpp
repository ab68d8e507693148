#include "sim/flight_trajectory.h"

#include <cmath>

namespace rpvio::sim {
namespace {

/// A scalar function with its first two derivatives.
struct Jet {
  double f, d1, d2;
};

Eigen::Matrix3d skew(const Eigen::Vector3d& w) {
  Eigen::Matrix3d m;
  m << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return m;
}

Eigen::Vector3d vee(const Eigen::Matrix3d& m) {
  return 0.5 * Eigen::Vector3d(m(2, 1) - m(1, 2), m(0, 2) - m(2, 0), m(1, 0) - m(0, 1));
}

}  // namespace

FlightState FlightTrajectory::at(double t) const {
  const FlightParams& P = params_;
  const double w0 = P.speed / P.radius;
  // Azimuth: starts from rest, φ' = w0 (1 − e^{−t/τ}).
  const double e = std::exp(-t / P.speed_ramp);
  const Jet phi{P.start_angle + w0 * (t - P.speed_ramp * (1 - e)), w0 * (1 - e),
                w0 / P.speed_ramp * e};
  // Height: a wave starting at its lowest point (at rest), plus the start push J (1 − e^{−u²}),
  // u = t / T.
  const double k = 2 * M_PI / P.height_period;
  const double u = t / P.start_push_time, g = std::exp(-u * u);
  const Jet z{
      P.height - P.height_amplitude * std::cos(k * t) + P.start_push * (1 - g),
      P.height_amplitude * k * std::sin(k * t) + P.start_push * 2 * u / P.start_push_time * g,
      P.height_amplitude * k * k * std::cos(k * t) +
          P.start_push * 2 / (P.start_push_time * P.start_push_time) * (1 - 2 * u * u) * g};

  FlightState s;
  const double c = std::cos(phi.f), sn = std::sin(phi.f), R = P.radius;
  s.p = {R * c, R * sn, z.f};
  s.v = {-R * sn * phi.d1, R * c * phi.d1, z.d1};
  s.a = {-R * c * phi.d1 * phi.d1 - R * sn * phi.d2, -R * sn * phi.d1 * phi.d1 + R * c * phi.d2,
         z.d2};

  // Attitude R = Rz(ψ) Ry(θ) Rx(ρ): yaw towards the centre, small pitch/roll oscillations.
  const Jet yaw{phi.f + M_PI, phi.d1, phi.d2};
  const double a = P.tilt_amplitude, f_pitch = 2 * M_PI * 0.23, f_roll = 2 * M_PI * 0.17;
  const Jet pitch{a * std::sin(f_pitch * t), a * f_pitch * std::cos(f_pitch * t), 0};
  const Jet roll{a * std::sin(f_roll * t + 1.0), a * f_roll * std::cos(f_roll * t + 1.0), 0};
  const Eigen::Matrix3d Rz = Eigen::AngleAxisd(yaw.f, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Matrix3d Ry =
      Eigen::AngleAxisd(pitch.f, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Matrix3d Rx = Eigen::AngleAxisd(roll.f, Eigen::Vector3d::UnitX()).toRotationMatrix();
  s.R_wb = Rz * Ry * Rx;
  // Ṙ = Rz [ez]ψ' Ry Rx + Rz Ry [ey]θ' Rx + Rz Ry Rx [ex]ρ';  ω_b = vee(Rᵀ Ṙ).
  const Eigen::Matrix3d R_dot = Rz * skew(Eigen::Vector3d::UnitZ() * yaw.d1) * Ry * Rx +
                                Rz * Ry * skew(Eigen::Vector3d::UnitY() * pitch.d1) * Rx +
                                s.R_wb * skew(Eigen::Vector3d::UnitX() * roll.d1);
  s.omega_b = vee(s.R_wb.transpose() * R_dot);
  return s;
}

}  // namespace rpvio::sim

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

/// A square wave of period 2π and amplitude 1 as its Fourier series to the fifth harmonic with
/// Lanczos' σ factors (σ_k = sinc(k / 7): no overshoot, flat stretches),
/// q(x) = 4/π Σ_{k=1,3,5} σ_k sin(kx) / k, with q', q'' (a Jet in x), and ∫₀ˣ q. Its steepest
/// slope is q'(0) = 4/π Σ σ_k = 2.60.
constexpr double kLanczos[3] = {0.9667664, 0.7241014, 0.3484106};  // sinc(1/7), (3/7), (5/7)
Jet squareWave(double x) {
  Jet q{0, 0, 0};
  for (int i = 0; i < 3; ++i) {
    const double k = 2 * i + 1, c = 4 / M_PI * kLanczos[i];
    q = {q.f + c * std::sin(k * x) / k, q.d1 + c * std::cos(k * x), q.d2 - c * k * std::sin(k * x)};
  }
  return q;
}
double squareWaveIntegral(double x) {
  double sum = 0;
  for (int i = 0; i < 3; ++i) {
    const double k = 2 * i + 1;
    sum += 4 / M_PI * kLanczos[i] * (1 - std::cos(k * x)) / (k * k);
  }
  return sum;
}

/// Quintic smoothstep S(x) = 6x⁵ − 15x⁴ + 10x³ on [0, 1] (0 before, 1 after) with S', S''.
Jet smoothStep(double x) {
  if (x <= 0) return {0, 0, 0};
  if (x >= 1) return {1, 0, 0};
  return {x * x * x * (10 + x * (-15 + 6 * x)), 30 * x * x * (1 + x * (-2 + x)),
          60 * x * (1 + x * (-3 + 2 * x))};
}

/// The road's heading ψ(s) at arc length s (ψ', ψ'' per metre): 0, a smooth 90° left turn over
/// [turn_after, turn_after + turn_length], then π/2.
Jet roadHeading(const FlightParams& P, double s) {
  const Jet S = smoothStep((s - P.turn_after) / P.turn_length);
  const double L = P.turn_length;
  return {M_PI / 2 * S.f, M_PI / 2 * S.d1 / L, M_PI / 2 * S.d2 / (L * L)};
}

/// Road position at arc length s: ∫₀ˢ (cos ψ, sin ψ) from (road_start, road_start); the turn by
/// composite Simpson's rule (256 intervals: error below 1e-8 m for the default turn).
Eigen::Vector2d roadPosition(const FlightParams& P, double s) {
  const Eigen::Vector2d start(P.road_start, P.road_start);
  if (s <= P.turn_after) return start + Eigen::Vector2d(s, 0);
  const double turn = std::min(s, P.turn_after + P.turn_length) - P.turn_after;
  constexpr int kIntervals = 256;
  const double h = turn / kIntervals;
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (int i = 0; i <= kIntervals; ++i) {
    const double psi = roadHeading(P, P.turn_after + i * h).f;
    const double weight = (i == 0 || i == kIntervals) ? 1 : (i % 2 ? 4 : 2);
    sum += weight * Eigen::Vector2d(std::cos(psi), std::sin(psi));
  }
  const Eigen::Vector2d after_turn(0, std::max(0.0, s - P.turn_after - P.turn_length));
  return start + Eigen::Vector2d(P.turn_after, 0) + h / 3 * sum + after_turn;
}

}  // namespace

FlightState FlightTrajectory::at(double t) const {
  const FlightParams& P = params_;
  // Arc length (speed / R on the circle): from rest, s' = v (1 − e^{−t/τ}) + Δv q(2π t / T).
  const double e = std::exp(-t / P.speed_ramp);
  const double w_swing = 2 * M_PI / P.speed_swing_period;
  const Jet swing = squareWave(w_swing * t);
  const Jet arc{P.speed_swing * squareWaveIntegral(w_swing * t) / w_swing, P.speed_swing * swing.f,
                P.speed_swing * w_swing * swing.d1};
  // Height: a wave starting at its lowest point (at rest), plus the start push J (1 − e^{−u²}),
  // u = t / T, plus the walking bob.
  const double k = 2 * M_PI / P.height_period, kb = 2 * M_PI * P.bob_frequency;
  const double u = t / P.start_push_time, g = std::exp(-u * u);
  const Jet z{P.height - P.height_amplitude * std::cos(k * t) + P.start_push * (1 - g) +
                  P.bob_amplitude * std::sin(kb * t),
              P.height_amplitude * k * std::sin(k * t) +
                  P.start_push * 2 * u / P.start_push_time * g +
                  P.bob_amplitude * kb * std::cos(kb * t),
              P.height_amplitude * k * k * std::cos(k * t) +
                  P.start_push * 2 / (P.start_push_time * P.start_push_time) * (1 - 2 * u * u) * g -
                  P.bob_amplitude * kb * kb * std::sin(kb * t)};

  FlightState s;
  Jet yaw;
  if (P.path == PathShape::Circle) {
    // Azimuth φ = φ0 + arc / R.
    const double w0 = P.speed / P.radius, R = P.radius;
    const Jet phi{P.start_angle + w0 * (t - P.speed_ramp * (1 - e)) + arc.f / R,
                  w0 * (1 - e) + arc.d1 / R, w0 / P.speed_ramp * e + arc.d2 / R};
    const double c = std::cos(phi.f), sn = std::sin(phi.f);
    s.p = {R * c, R * sn, z.f};
    s.v = {-R * sn * phi.d1, R * c * phi.d1, z.d1};
    s.a = {-R * c * phi.d1 * phi.d1 - R * sn * phi.d2, -R * sn * phi.d1 * phi.d1 + R * c * phi.d2,
           z.d2};
    const double towards = P.look == LookDirection::Centre ? M_PI : M_PI / 2;
    yaw = {phi.f + towards, phi.d1, phi.d2};
  } else {
    const Jet along{P.speed * (t - P.speed_ramp * (1 - e)) + arc.f, P.speed * (1 - e) + arc.d1,
                    P.speed / P.speed_ramp * e + arc.d2};
    // ψ(s(t)): ψ̇ = ψ' ṡ, ψ̈ = ψ'' ṡ² + ψ' s̈; the velocity ṡ (cos ψ, sin ψ).
    const Jet psi = roadHeading(P, along.f);
    yaw = {psi.f, psi.d1 * along.d1, psi.d2 * along.d1 * along.d1 + psi.d1 * along.d2};
    const Eigen::Vector2d p = roadPosition(P, along.f), dir(std::cos(psi.f), std::sin(psi.f)),
                          normal(-dir.y(), dir.x());
    const Eigen::Vector2d a = along.d2 * dir + along.d1 * yaw.d1 * normal;
    s.p = {p.x(), p.y(), z.f};
    s.v = {along.d1 * dir.x(), along.d1 * dir.y(), z.d1};
    s.a = {a.x(), a.y(), z.d2};
  }
  // Head turns: the yaw swings by ± yaw_swing.
  const double w_yaw = 2 * M_PI / P.yaw_swing_period;
  const Jet turn = squareWave(w_yaw * t);
  yaw = {yaw.f + P.yaw_swing * turn.f, yaw.d1 + P.yaw_swing * w_yaw * turn.d1,
         yaw.d2 + P.yaw_swing * w_yaw * w_yaw * turn.d2};

  // Attitude R = Rz(ψ) Ry(θ) Rx(ρ): the yaw above, small pitch/roll oscillations.
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

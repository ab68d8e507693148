#pragma once
// IMU measurements of the analytic flight: gyro = ω_b + b_g + n_g, accel = R_wbᵀ (a_w − g_w) + b_a
// + n_a, with white noise of density σ (discrete σ_d = σ √rate) and biases following a random walk
// of density σ_b (discrete step σ_b √dt) — the Kalibr/EuRoC IMU noise model.
#include <random>
#include <vector>

#include "common/sensor_types.h"
#include "rawlog_io/rawlog_writer.h"
#include "sim/flight_trajectory.h"

namespace rpvio::sim {

struct ImuBiasState {
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero(), accel = Eigen::Vector3d::Zero();
};

/// The noise-free sample at time t (gravity (0, 0, −gravity) in the world).
ImuSample idealImuSample(const FlightTrajectory& flight, double t, double gravity);

/// The whole noisy stream at the IMU rate over [0, duration]; `biases` (optional) receives the true
/// bias at every sample. Deterministic for a given seed.
std::vector<ImuSample> simulateImu(const FlightTrajectory& flight, const ImuNoise& noise,
                                   const ImuBiasState& initial_bias, double duration, bool noisy,
                                   uint64_t seed, std::vector<ImuBiasState>* biases = nullptr);

}  // namespace rpvio::sim

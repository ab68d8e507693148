#include "sim/imu_simulator.h"

#include <cmath>

namespace rpvio::sim {

ImuSample idealImuSample(const FlightTrajectory& flight, double t, double gravity) {
  const FlightState s = flight.at(t);
  ImuSample m;
  m.t = t;
  m.gyro = s.omega_b;
  m.accel = s.R_wb.transpose() * (s.a - Eigen::Vector3d(0, 0, -gravity));
  return m;
}

std::vector<ImuSample> simulateImu(const FlightTrajectory& flight, const ImuNoise& noise,
                                   const ImuBiasState& initial_bias, double duration, bool noisy,
                                   uint64_t seed, std::vector<ImuBiasState>* biases) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  auto gaussian3 = [&] { return Eigen::Vector3d(normal(rng), normal(rng), normal(rng)); };
  const double dt = 1.0 / noise.rate_hz;
  const double gyro_sigma = noise.gyro_noise_density / std::sqrt(dt);
  const double accel_sigma = noise.accel_noise_density / std::sqrt(dt);
  const double gyro_walk = noise.gyro_random_walk * std::sqrt(dt);
  const double accel_walk = noise.accel_random_walk * std::sqrt(dt);

  const auto count = static_cast<size_t>(std::floor(duration * noise.rate_hz + 1e-9)) + 1;
  std::vector<ImuSample> samples;
  samples.reserve(count);
  ImuBiasState bias = initial_bias;
  for (size_t k = 0; k < count; ++k) {
    ImuSample m = idealImuSample(flight, k * dt, noise.gravity);
    if (noisy) {
      m.gyro += bias.gyro + gyro_sigma * gaussian3();
      m.accel += bias.accel + accel_sigma * gaussian3();
    }
    samples.push_back(m);
    if (biases) biases->push_back(bias);
    if (noisy) {
      bias.gyro += gyro_walk * gaussian3();
      bias.accel += accel_walk * gaussian3();
    }
  }
  return samples;
}

}  // namespace rpvio::sim

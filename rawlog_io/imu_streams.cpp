#include "rawlog_io/imu_streams.h"

#include <algorithm>
#include <cmath>

namespace rpvio {

std::vector<ImuSample> mergeSplitImu(const std::vector<ImuSample>& gyro,
                                     const std::vector<ImuSample>& accel) {
  std::vector<ImuSample> merged;
  if (gyro.empty() || accel.empty()) return merged;
  const double begin = std::max(gyro.front().t, accel.front().t),
               end = std::min(gyro.back().t, accel.back().t);
  size_t g = 0, a = 0;  // the next sample of each
  auto interpolate = [](const std::vector<ImuSample>& v, size_t next, double t,
                        Eigen::Vector3d ImuSample::*value) -> Eigen::Vector3d {
    if (next == 0) return v[0].*value;
    if (next == v.size()) return v.back().*value;
    const double w = (t - v[next - 1].t) / (v[next].t - v[next - 1].t);
    return (1 - w) * (v[next - 1].*value) + w * (v[next].*value);
  };
  while (g < gyro.size() || a < accel.size()) {
    const double t =
        std::min(g < gyro.size() ? gyro[g].t : INFINITY, a < accel.size() ? accel[a].t : INFINITY);
    const bool gyro_here = g < gyro.size() && gyro[g].t == t,
               accel_here = a < accel.size() && accel[a].t == t;
    if (t >= begin && t <= end) {
      ImuSample s;
      s.t = t;
      s.gyro = gyro_here ? gyro[g].gyro : interpolate(gyro, g, t, &ImuSample::gyro);
      s.accel = accel_here ? accel[a].accel : interpolate(accel, a, t, &ImuSample::accel);
      merged.push_back(s);
    }
    g += gyro_here;
    a += accel_here;
  }
  return merged;
}

std::vector<ImuSample> decimateImu(const std::vector<ImuSample>& samples, double rate_hz) {
  if (rate_hz <= 0 || samples.empty()) return samples;
  std::vector<ImuSample> kept;
  long long last_slot = -1;
  for (const ImuSample& s : samples) {
    const auto slot =
        static_cast<long long>(std::floor((s.t - samples.front().t) * rate_hz + 1e-3));
    if (slot <= last_slot) continue;
    last_slot = slot;
    kept.push_back(s);
  }
  return kept;
}

double medianNorm(const std::vector<Eigen::Vector3d>& vectors) {
  if (vectors.empty()) return 0;
  std::vector<double> norms;
  norms.reserve(vectors.size());
  for (const Eigen::Vector3d& v : vectors) norms.push_back(v.norm());
  std::nth_element(norms.begin(), norms.begin() + norms.size() / 2, norms.end());
  return norms[norms.size() / 2];
}

}  // namespace rpvio

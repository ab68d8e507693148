// Preintegration on real EuRoC IMU data (../shared/data, ETH Zurich ASL): 1 s windows propagated
// from the ground-truth state and compared with the ground truth at the window's end.
#include <gtest/gtest.h>

#include <algorithm>

#include "mrpt_modules/imu/imu_preintegration.h"
#include "rawlog_io/euroc_csv.h"
#include "rawlog_io/trajectory_io.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

const Eigen::Vector3d kGravity(0, 0, -9.81);

struct WindowErrors {
  std::vector<double> position, rotation_deg;
};

double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(q * (v.size() - 1))];
}

void report(const char* name, const WindowErrors& e) {
  std::printf(
      "%s: %zu windows; position error median %.4f p90 %.4f max %.4f m; rotation error "
      "median %.4f p90 %.4f max %.4f deg\n",
      name, e.position.size(), percentile(e.position, 0.5), percentile(e.position, 0.9),
      percentile(e.position, 1.0), percentile(e.rotation_deg, 0.5), percentile(e.rotation_deg, 0.9),
      percentile(e.rotation_deg, 1.0));
}

/// Propagates the state at imu[first] over `count` samples; returns (p, q) at imu[first + count].
std::pair<Eigen::Vector3d, Eigen::Quaterniond> propagate(
    const std::vector<ImuSample>& imu, size_t first, size_t count, const Eigen::Vector3d& p,
    const Eigen::Quaterniond& q, const Eigen::Vector3d& v, const Eigen::Vector3d& ba,
    const Eigen::Vector3d& bg) {
  ImuPreintegration pre(imu[first].accel, imu[first].gyro, ba, bg, ImuNoise{});
  for (size_t k = first + 1; k <= first + count; ++k)
    pre.push(imu[k].t - imu[k - 1].t, imu[k].accel, imu[k].gyro);
  const double T = pre.sumDt();
  return {p + v * T + 0.5 * kGravity * T * T + q * pre.deltaP(), q * pre.deltaQ()};
}

/// Index of the IMU sample closest to t.
size_t nearestImu(const std::vector<ImuSample>& imu, double t) {
  auto it = std::lower_bound(imu.begin(), imu.end(), t,
                             [](const ImuSample& s, double x) { return s.t < x; });
  if (it == imu.end()) return imu.size() - 1;
  if (it != imu.begin() && t - std::prev(it)->t < it->t - t) --it;
  return static_cast<size_t>(it - imu.begin());
}

TEST(EurocPropagation, V102WindowsFromGroundTruthStates) {
  const std::string dir = test::dataDir() + "/euroc_v102_imu_gt/mav0/";
  const auto imu = readEurocImuCsv(dir + "imu0/data.csv");
  const auto gt = readEurocStateCsv(dir + "gt0/data.csv");
  WindowErrors errors;
  for (size_t i = 0; i < gt.size(); i += 20) {  // a window every 0.5 s (ground truth at 40 Hz)
    const size_t first = nearestImu(imu, gt[i].t);
    if (std::abs(imu[first].t - gt[i].t) > 1e-3 || first + 200 >= imu.size()) continue;
    const double t_end = imu[first + 200].t;
    const auto end = std::find_if(gt.begin(), gt.end(),
                                  [&](const auto& s) { return std::abs(s.t - t_end) < 1e-3; });
    if (end == gt.end()) continue;
    const auto [p, q] =
        propagate(imu, first, 200, gt[i].p, gt[i].q, gt[i].v, gt[i].accel_bias, gt[i].gyro_bias);
    errors.position.push_back((p - end->p).norm());
    errors.rotation_deg.push_back(q.angularDistance(end->q) * 180 / M_PI);
  }
  ASSERT_GT(errors.position.size(), 50u);
  report("V1_02 1 s windows", errors);
  EXPECT_LT(percentile(errors.position, 0.5), 0.05);
  EXPECT_LT(percentile(errors.rotation_deg, 0.5), 0.3);
}

/// Mean IMU bias over the ground-truth poses gt[a..b): gyro − ω_gt and accel − R_gtᵀ (a_gt − g),
/// with ω_gt and a_gt from differences of the ground-truth poses 50 ms apart.
std::pair<Eigen::Vector3d, Eigen::Vector3d> biasesFromGroundTruth(const std::vector<ImuSample>& imu,
                                                                  const Trajectory& gt, size_t a,
                                                                  size_t b) {
  Eigen::Vector3d bg = Eigen::Vector3d::Zero(), ba = Eigen::Vector3d::Zero();
  int n = 0;
  for (size_t i = std::max<size_t>(a, 10); i + 10 < std::min(b, gt.size()); i += 5) {
    const double h = gt[i + 10].t - gt[i].t;
    const Eigen::AngleAxisd turn(gt[i - 10].q.inverse() * gt[i + 10].q);
    const Eigen::Vector3d omega = turn.angle() * turn.axis() / (2 * h);
    const Eigen::Vector3d acc_w = (gt[i + 10].p - 2 * gt[i].p + gt[i - 10].p) / (h * h);
    const size_t k = nearestImu(imu, gt[i].t);
    bg += imu[k].gyro - omega;
    ba += imu[k].accel - gt[i].q.inverse() * (acc_w - kGravity);
    ++n;
  }
  return {ba / n, bg / n};
}

TEST(EurocPropagation, V101WholeSequenceWindows) {
  // V1_01's ground truth (TUM) has poses only: velocities by a central difference over ±50 ms,
  // biases as the mean IMU error against the ground-truth motion over ±5 s around each window.
  const std::string dir = test::dataDir() + "/euroc_v101_static/";
  const auto imu = readEurocImuCsv(dir + "mav0/imu0/data.csv");
  const Trajectory gt = readTum(dir + "groundtruth_v101_full.tum");
  WindowErrors errors;
  for (size_t i = 20; i + 220 < gt.size(); i += 100) {
    const size_t first = nearestImu(imu, gt[i].t);
    if (std::abs(imu[first].t - gt[i].t) > 2.5e-3 || first + 200 >= imu.size()) continue;
    const Eigen::Vector3d v = (gt[i + 10].p - gt[i - 10].p) / (gt[i + 10].t - gt[i - 10].t);
    const auto [ba, bg] = biasesFromGroundTruth(imu, gt, i < 1000 ? 0 : i - 1000, i + 1000);
    const auto [p, q] = propagate(imu, first, 200, gt[i].p, gt[i].q, v, ba, bg);
    const double t_end = imu[first + 200].t;
    size_t j = i;
    while (j + 1 < gt.size() && std::abs(gt[j + 1].t - t_end) < std::abs(gt[j].t - t_end)) ++j;
    errors.position.push_back((p - gt[j].p).norm());
    errors.rotation_deg.push_back(q.angularDistance(gt[j].q) * 180 / M_PI);
  }
  ASSERT_GT(errors.position.size(), 200u);
  report("V1_01 1 s windows, whole sequence", errors);
  EXPECT_LT(percentile(errors.position, 0.5), 0.05);
  EXPECT_LT(percentile(errors.rotation_deg, 0.5), 0.3);
}

}  // namespace
}  // namespace rpvio

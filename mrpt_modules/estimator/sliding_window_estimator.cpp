#include "mrpt_modules/estimator/sliding_window_estimator.h"

#include <ceres/ceres.h>
#include <ceres/sphere_manifold.h>
#include <cmath>
#include <set>
#include <unordered_map>

#include "mrpt_modules/core/parameter_blocks.h"
#include "mrpt_modules/factors/homography_factor.h"
#include "mrpt_modules/factors/imu_factor.h"
#include "mrpt_modules/factors/pose_manifold.h"
#include "mrpt_modules/frontend/feature_tracker.h"

namespace rpvio {
namespace {

Eigen::Vector3d speed(const WindowFrame& f) { return Eigen::Vector3d(f.speed_bias); }
Eigen::Vector3d accelBias(const WindowFrame& f) { return Eigen::Vector3d(f.speed_bias + 3); }
Eigen::Vector3d gyroBias(const WindowFrame& f) { return Eigen::Vector3d(f.speed_bias + 6); }

/// Appends samples, skipping one equal to the last already there (frames share boundary samples).
void appendSamples(std::vector<ImuSample>& to, const std::vector<ImuSample>& from) {
  for (const auto& s : from)
    if (to.empty() || s.t > to.back().t) to.push_back(s);
}

/// Stand-in for the marginalization prior: the oldest keyframe stays near its last estimate with
/// fixed standard deviations (position, rotation, velocity, biases).
struct OldestStatePrior {
  OldestStatePrior(const double* pose, const double* speed_bias) {
    std::copy(pose, pose + 7, pose0);
    std::copy(speed_bias, speed_bias + 9, sb0);
  }
  template <typename T>
  bool operator()(const T* pose, const T* sb, T* r) const {
    const Eigen::Quaternion<T> q(pose[6], pose[3], pose[4], pose[5]);
    const Eigen::Quaternion<T> q0{T(pose0[6]), T(pose0[3]), T(pose0[4]), T(pose0[5])};
    const Eigen::Quaternion<T> dq = q0.conjugate() * q;
    for (int i = 0; i < 3; ++i) {
      r[i] = (pose[i] - T(pose0[i])) / T(kSigmaPosition);
      r[3 + i] = T(2) * dq.vec()[i] / T(kSigmaRotation);
      r[6 + i] = (sb[i] - T(sb0[i])) / T(kSigmaVelocity);
      r[9 + i] = (sb[3 + i] - T(sb0[3 + i])) / T(kSigmaAccelBias);
      r[12 + i] = (sb[6 + i] - T(sb0[6 + i])) / T(kSigmaGyroBias);
    }
    return true;
  }
  static constexpr double kSigmaPosition = 0.1, kSigmaRotation = 0.02, kSigmaVelocity = 0.2,
                          kSigmaAccelBias = 0.05, kSigmaGyroBias = 0.002;
  double pose0[7], sb0[9];
};

}  // namespace

SlidingWindowEstimator::SlidingWindowEstimator(const Calibration& calibration,
                                               const EstimatorOptions& options)
    : calib_(calibration), options_(options) {}

std::shared_ptr<ImuPreintegration> SlidingWindowEstimator::preintegrate(
    const std::vector<ImuSample>& samples, const Eigen::Vector3d& ba,
    const Eigen::Vector3d& bg) const {
  auto pre = std::make_shared<ImuPreintegration>(samples.front().accel, samples.front().gyro, ba,
                                                 bg, calib_.imu);
  for (size_t k = 1; k < samples.size(); ++k)
    pre->push(samples[k].t - samples[k - 1].t, samples[k].accel, samples[k].gyro);
  return pre;
}

StateEstimate SlidingWindowEstimator::predict(double t) const {
  const WindowFrame& last = window_.back();
  StateEstimate s;
  s.t = t;
  std::copy(last.pose, last.pose + 7, s.pose);
  if (pending_imu_.size() < 2) return s;
  const auto pre = preintegrate(pending_imu_, accelBias(last), gyroBias(last));
  const Eigen::Vector3d g(0, 0, -calib_.imu.gravity);
  const double T = pre->sumDt();
  const Eigen::Quaterniond q = poseRotation(last.pose);
  const Eigen::Vector3d p =
      posePosition(last.pose) + speed(last) * T + 0.5 * g * T * T + q * pre->deltaP();
  const Eigen::Quaterniond q_new = (q * pre->deltaQ()).normalized();
  s.pose[0] = p.x(), s.pose[1] = p.y(), s.pose[2] = p.z();
  s.pose[3] = q_new.x(), s.pose[4] = q_new.y(), s.pose[5] = q_new.z(), s.pose[6] = q_new.w();
  return s;
}

void SlidingWindowEstimator::tryInitialize() {
  std::vector<WindowFrame> frames;
  for (size_t k = 0; k < init_buffer_.size(); ++k) {
    WindowFrame f;
    f.features = init_buffer_[k].features;
    if (k > 0 && init_buffer_[k].imu.size() >= 2)
      f.imu_from_previous =
          preintegrate(init_buffer_[k].imu, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
    else if (k > 0)
      return;  // a frame without IMU: wait for a clean window
    frames.push_back(f);
  }
  const auto plane = initializeFromPlane(frames, calib_, options_.init, &status_);
  if (!plane) return;
  // Keyframes: evenly spaced over the initialization window, ending at its newest frame.
  const size_t n = frames.size();
  const size_t step =
      std::max<size_t>(1, (n - 1 + options_.window_size - 2) / (options_.window_size - 1));
  std::vector<size_t> chosen;
  for (long k = static_cast<long>(n) - 1; k >= 0; k -= static_cast<long>(step))
    chosen.insert(chosen.begin(), k);
  window_.clear();
  for (size_t c = 0; c < chosen.size(); ++c) {
    WindowFrame kf = frames[chosen[c]];
    kf.imu_from_previous = nullptr;
    if (c > 0) {
      std::vector<ImuSample> samples;
      for (size_t k = chosen[c - 1] + 1; k <= chosen[c]; ++k)
        appendSamples(samples, init_buffer_[k].imu);
      kf.imu_from_previous = preintegrate(samples, accelBias(kf), gyroBias(kf));
    }
    window_.push_back(kf);
  }
  planes_.clear();
  planes_[plane->first] = plane->second;
  pending_imu_ = {init_buffer_.back().imu.back()};
  init_buffer_.clear();
  initialized_ = true;
  status_ = "tracking";
  optimize();
}

void SlidingWindowEstimator::initializeMissingPlanes() {
  // Planes seen in both the first and the newest keyframe get parameters from the features
  // triangulated with the window's poses (midpoint of the two rays) and a least-squares plane.
  const WindowFrame& a = window_.front();
  const WindowFrame& b = window_.back();
  std::unordered_map<int, const TrackedFeature*> in_a;
  for (const auto& f : a.features.features) in_a[f.id] = &f;
  std::map<int, std::vector<Eigen::Vector3d>> points;
  const Eigen::Isometry3d T_BC = calib_.T_BC;
  auto camera = [&](const WindowFrame& f) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = poseRotation(f.pose).toRotationMatrix();
    T.translation() = posePosition(f.pose);
    return T * T_BC;
  };
  const Eigen::Isometry3d Ca = camera(a), Cb = camera(b);
  for (const auto& f : b.features.features) {
    if (f.plane_id <= 0 || planes_.count(f.plane_id) || !in_a.count(f.id)) continue;
    const Eigen::Vector3d da =
        Ca.linear() * Eigen::Vector3d(in_a[f.id]->normalized.x(), in_a[f.id]->normalized.y(), 1);
    const Eigen::Vector3d db = Cb.linear() * Eigen::Vector3d(f.normalized.x(), f.normalized.y(), 1);
    const Eigen::Vector3d oa = Ca.translation(), ob = Cb.translation();
    // Closest points of the two rays: solve [da −db] [s t]ᵀ ≈ ob − oa.
    Eigen::Matrix<double, 3, 2> A;
    A << da, -db;
    const Eigen::Vector2d st = A.colPivHouseholderQr().solve(ob - oa);
    if (st.x() <= 0 || st.y() <= 0) continue;
    const double angle = std::acos(std::clamp(da.normalized().dot(db.normalized()), -1.0, 1.0));
    if (angle < 0.5 * M_PI / 180) continue;  // too little parallax for this point
    points[f.plane_id].push_back(0.5 * (oa + st.x() * da + ob + st.y() * db));
  }
  for (const auto& [id, pts] : points) {
    if (pts.size() < 10) continue;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& p : pts) mean += p / pts.size();
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const auto& p : pts) cov += (p - mean) * (p - mean).transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    const Eigen::Vector3d n = eig.eigenvectors().col(0);
    if (eig.eigenvalues()(0) / pts.size() > 0.05 * 0.05) continue;  // not flat enough (σ > 5 cm)
    PlaneEstimate e;
    e.normal[0] = n.x(), e.normal[1] = n.y(), e.normal[2] = n.z();
    e.distance[0] = n.dot(mean);
    planes_[id] = e;
  }
}

void SlidingWindowEstimator::optimize() {
  // Planes used: every known plane (multi) or the known plane with most features (single).
  std::map<int, int> count;
  for (const auto& kf : window_)
    for (const auto& f : kf.features.features)
      if (planes_.count(f.plane_id)) ++count[f.plane_id];
  std::set<int> used;
  for (const auto& [id, c] : count)
    if (options_.all_planes) used.insert(id);
  if (!options_.all_planes && !count.empty())
    used.insert(std::max_element(count.begin(), count.end(), [](const auto& x, const auto& y) {
                  return x.second < y.second;
                })->first);

  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.loss_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  PoseManifold pose_manifold;
  ceres::SphereManifold<3> sphere;
  double mount[7];
  {
    const Eigen::Quaterniond q(calib_.T_BC.linear());
    const Eigen::Vector3d t = calib_.T_BC.translation();
    const double m[7] = {t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w()};
    std::copy(m, m + 7, mount);
  }
  problem.AddParameterBlock(mount, 7);
  problem.SetParameterBlockConstant(mount);
  for (auto& kf : window_) {
    problem.AddParameterBlock(kf.pose, 7, &pose_manifold);
    problem.AddParameterBlock(kf.speed_bias, 9);
  }
  const Eigen::Vector3d g(0, 0, -calib_.imu.gravity);
  for (size_t k = 1; k < window_.size(); ++k)
    problem.AddResidualBlock(new ImuFactor(window_[k].imu_from_previous, g), nullptr,
                             window_[k - 1].pose, window_[k - 1].speed_bias, window_[k].pose,
                             window_[k].speed_bias);
  const double weight = options_.init.virtual_focal / options_.pixel_sigma;
  std::unordered_map<int, std::pair<size_t, Eigen::Vector2d>> last_seen;
  for (size_t k = 0; k < window_.size(); ++k)
    for (const auto& f : window_[k].features.features) {
      if (!used.count(f.plane_id)) continue;
      const auto it = last_seen.find(f.id);
      if (it != last_seen.end()) {
        PlaneEstimate& plane = planes_[f.plane_id];
        problem.AddResidualBlock(
            HomographyResidual::create(it->second.second, f.normalized, weight),
            new ceres::CauchyLoss(options_.cauchy_scale), window_[it->second.first].pose,
            window_[k].pose, mount, plane.normal, plane.distance);
      }
      last_seen[f.id] = {k, f.normalized};
    }
  for (int id : used)
    if (problem.HasParameterBlock(planes_[id].normal))
      problem.SetManifold(planes_[id].normal, &sphere);
  problem.AddResidualBlock(
      new ceres::AutoDiffCostFunction<OldestStatePrior, 15, 7, 9>(
          new OldestStatePrior(window_.front().pose, window_.front().speed_bias)),
      nullptr, window_.front().pose, window_.front().speed_bias);
  ceres::Solver::Options solver;
  solver.trust_region_strategy_type = ceres::DOGLEG;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = options_.max_iterations;
  solver.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
}

bool SlidingWindowEstimator::healthy() const {
  const WindowFrame& f = window_.back();
  for (double x : f.pose)
    if (!std::isfinite(x)) return false;
  return speed(f).norm() < 30 && accelBias(f).norm() < 2.0 && gyroBias(f).norm() < 0.5;
}

void SlidingWindowEstimator::reset(const std::string& cause) {
  ++resets_;
  status_ = "reset: " + cause;
  initialized_ = false;
  window_.clear();
  pending_imu_.clear();
  init_buffer_.clear();
  planes_.clear();
}

std::optional<StateEstimate> SlidingWindowEstimator::addFrame(
    const FeatureFrame& frame, const std::vector<ImuSample>& imu_since_previous) {
  if (!initialized_) {
    init_buffer_.push_back({frame, imu_since_previous});
    if (init_buffer_.size() > options_.init_window_frames) init_buffer_.pop_front();
    tryInitialize();
    if (!initialized_) return std::nullopt;
    StateEstimate s;
    s.t = frame.t;
    std::copy(window_.back().pose, window_.back().pose + 7, s.pose);
    s.keyframe = true;
    return s;
  }
  appendSamples(pending_imu_, imu_since_previous);
  StateEstimate predicted = predict(frame.t);
  const WindowFrame& last = window_.back();
  const bool keyframe = averageParallax(last.features, frame, options_.init.virtual_focal) >=
                            options_.keyframe_parallax_px ||
                        frame.t - last.features.t >= options_.max_keyframe_gap_s;
  if (!keyframe || pending_imu_.size() < 2) return predicted;

  WindowFrame kf;
  kf.features = frame;
  kf.imu_from_previous = preintegrate(pending_imu_, accelBias(last), gyroBias(last));
  std::copy(predicted.pose, predicted.pose + 7, kf.pose);
  const Eigen::Vector3d v =
      speed(last) + Eigen::Vector3d(0, 0, -calib_.imu.gravity) * kf.imu_from_previous->sumDt() +
      poseRotation(last.pose) * kf.imu_from_previous->deltaV();
  for (int i = 0; i < 3; ++i) kf.speed_bias[i] = v[i];
  std::copy(last.speed_bias + 3, last.speed_bias + 9, kf.speed_bias + 3);
  window_.push_back(kf);
  pending_imu_ = {pending_imu_.back()};
  if (window_.size() > options_.window_size) {
    window_.pop_front();
    window_.front().imu_from_previous = nullptr;
  }
  initializeMissingPlanes();
  optimize();
  if (!healthy()) {
    reset("implausible state (speed or biases)");
    return std::nullopt;
  }
  StateEstimate s;
  s.t = frame.t;
  std::copy(window_.back().pose, window_.back().pose + 7, s.pose);
  s.keyframe = true;
  return s;
}

}  // namespace rpvio

#include "mrpt_modules/estimator/planar_initializer.h"

#include <ceres/ceres.h>
#include <ceres/rotation.h>
#include <ceres/sphere_manifold.h>
#include <array>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <unordered_map>

#include "mrpt_modules/factors/homography_factor.h"
#include "mrpt_modules/factors/pose_manifold.h"
#include "mrpt_modules/initialization/plane_motion_from_homography.h"
#include "mrpt_modules/initialization/visual_inertial_alignment.h"

namespace rpvio {
namespace {

/// Features of `plane` common to two frames (normalized coordinates, same order).
void commonPlaneFeatures(const FeatureFrame& a, const FeatureFrame& b, int plane,
                         std::vector<Eigen::Vector2d>& in_a, std::vector<Eigen::Vector2d>& in_b) {
  std::unordered_map<int, Eigen::Vector2d> first;
  for (const auto& f : a.features)
    if (f.plane_id == plane) first[f.id] = f.normalized;
  for (const auto& f : b.features)
    if (f.plane_id == plane && first.count(f.id)) {
      in_a.push_back(first[f.id]);
      in_b.push_back(f.normalized);
    }
}

/// The plane label with the most features in a frame.
int largestPlane(const FeatureFrame& frame) {
  std::map<int, int> count;
  for (const auto& f : frame.features)
    if (f.plane_id > 0) ++count[f.plane_id];
  int best = -1, best_count = 0;
  for (const auto& [plane, c] : count)
    if (c > best_count) best = plane, best_count = c;
  return best;
}

/// Camera rotation X_cj = R X_c0 predicted by the gyroscope from frame 0 to frame j.
Eigen::Matrix3d gyroCameraRotation(const std::vector<WindowFrame>& frames, size_t j,
                                   const Eigen::Matrix3d& R_BC) {
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  for (size_t k = 1; k <= j; ++k) q = q * frames[k].imu_from_previous->deltaQ();
  return cameraRotationFromBody(q.toRotationMatrix(), R_BC);
}

/// Mean displacement (px at `focal`) left once the rotation R is compensated.
double translationalParallax(const std::vector<Eigen::Vector2d>& a,
                             const std::vector<Eigen::Vector2d>& b, const Eigen::Matrix3d& R,
                             double focal) {
  double sum = 0;
  for (size_t k = 0; k < a.size(); ++k) {
    const Eigen::Vector3d r = R * Eigen::Vector3d(a[k].x(), a[k].y(), 1);
    sum += (b[k] - r.head<2>() / r.z()).norm();
  }
  return a.empty() ? 0 : focal * sum / a.size();
}

/// The gyroscope's relative rotation between two consecutive camera frames, its bias correction
/// estimated jointly: r = 2 vec((R_BCᵀ ΔR(bg) R_BC)⁻¹ ⊗ R_c,k-1ᵀ R_c,k) / sigma, with
/// ΔR(bg) = ΔR Exp(J_bg δbg) (first-order bias correction of the preintegration).
struct GyroRotationResidual {
  GyroRotationResidual(const ImuPreintegration& pre, const Eigen::Quaterniond& q_BC, double sigma)
      : delta_q(pre.deltaQ()),
        J_bg(pre.jacobian().block<3, 3>(ImuPreintegration::kR, ImuPreintegration::kBg)),
        q_BC(q_BC),
        sigma(sigma) {}

  template <typename T>
  bool operator()(const T* cam_a, const T* cam_b, const T* dbg, T* residual) const {
    const Eigen::Quaternion<T> qa(cam_a[6], cam_a[3], cam_a[4], cam_a[5]);
    const Eigen::Quaternion<T> qb(cam_b[6], cam_b[3], cam_b[4], cam_b[5]);
    const Eigen::Matrix<T, 3, 1> phi =
        J_bg.cast<T>() * Eigen::Matrix<T, 3, 1>(dbg[0], dbg[1], dbg[2]);
    T aa[3] = {phi.x(), phi.y(), phi.z()}, qc[4];
    ceres::AngleAxisToQuaternion(aa, qc);  // (w, x, y, z)
    const Eigen::Quaternion<T> correction(qc[0], qc[1], qc[2], qc[3]);
    const Eigen::Quaternion<T> body = delta_q.cast<T>() * correction;
    const Eigen::Quaternion<T> camera = q_BC.cast<T>().conjugate() * body * q_BC.cast<T>();
    const Eigen::Quaternion<T> error = camera.conjugate() * (qa.conjugate() * qb);
    for (int i = 0; i < 3; ++i) residual[i] = T(2) * error.vec()[i] / T(sigma);
    return true;
  }

  Eigen::Quaterniond delta_q;
  Eigen::Matrix3d J_bg;
  Eigen::Quaterniond q_BC;
  double sigma;
};

/// Visual bundle adjustment of the camera poses (c0 frame, plane units), the plane normal and a
/// gyroscope bias correction: homography residuals of every plane feature between consecutive
/// observations (tracks drift over longer baselines) and the gyroscope's relative rotations
/// (camera 0 fixed: gauge; plane distance fixed to 1: scale).
void refineWithHomographies(const std::vector<WindowFrame>& frames, int plane,
                            std::vector<UpToScaleFrame>& poses, Eigen::Vector3d& n, double focal,
                            const Eigen::Quaterniond& q_BC, Eigen::Vector3d& gyro_bias_change) {
  std::vector<std::array<double, 7>> blocks(poses.size());
  for (size_t k = 0; k < poses.size(); ++k) {
    const Eigen::Quaterniond q(poses[k].R_c0_c);
    blocks[k] = {
        poses[k].p_c0_c.x(), poses[k].p_c0_c.y(), poses[k].p_c0_c.z(), q.x(), q.y(), q.z(), q.w()};
  }
  std::array<double, 7> identity = {0, 0, 0, 0, 0, 0, 1};
  double normal[3] = {n.x(), n.y(), n.z()}, distance[1] = {1.0};
  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  PoseManifold pose_manifold;
  ceres::SphereManifold<3> sphere;
  std::unordered_map<int, std::pair<size_t, Eigen::Vector2d>> first_seen;
  for (size_t k = 0; k < frames.size(); ++k)
    for (const auto& f : frames[k].features.features) {
      if (f.plane_id != plane) continue;
      const auto it = first_seen.find(f.id);
      if (it == first_seen.end()) {
        first_seen[f.id] = {k, f.normalized};
        continue;
      }
      problem.AddResidualBlock(HomographyResidual::create(it->second.second, f.normalized, focal),
                               new ceres::CauchyLoss(1.0), blocks[it->second.first].data(),
                               blocks[k].data(), identity.data(), normal, distance);
      it->second = {k, f.normalized};  // consecutive observations: drift does not accumulate
    }
  // Gyroscope rotations between consecutive frames, with a shared bias correction.
  double dbg[3] = {0, 0, 0};
  for (size_t k = 1; k < frames.size(); ++k) {
    const ImuPreintegration& pre = *frames[k].imu_from_previous;
    const double sigma = std::sqrt(
        pre.covariance().block<3, 3>(ImuPreintegration::kR, ImuPreintegration::kR).trace() / 3);
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<GyroRotationResidual, 3, 7, 7, 3>(
                                 new GyroRotationResidual(pre, q_BC, std::max(sigma, 1e-5))),
                             nullptr, blocks[k - 1].data(), blocks[k].data(), dbg);
  }
  for (auto& b : blocks)
    if (problem.HasParameterBlock(b.data())) problem.SetManifold(b.data(), &pose_manifold);
  if (problem.HasParameterBlock(blocks[0].data()))
    problem.SetParameterBlockConstant(blocks[0].data());
  if (!problem.HasParameterBlock(normal)) return;
  problem.SetParameterBlockConstant(identity.data());
  problem.SetParameterBlockConstant(distance);
  problem.SetManifold(normal, &sphere);
  ceres::Solver::Options solver;
  solver.max_num_iterations = 20;
  solver.linear_solver_type = ceres::DENSE_QR;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  for (size_t k = 0; k < poses.size(); ++k) {
    const Eigen::Quaterniond q(blocks[k][6], blocks[k][3], blocks[k][4], blocks[k][5]);
    poses[k].R_c0_c = q.normalized().toRotationMatrix();
    poses[k].p_c0_c = Eigen::Vector3d(blocks[k][0], blocks[k][1], blocks[k][2]);
  }
  n = Eigen::Vector3d(normal[0], normal[1], normal[2]).normalized();
  gyro_bias_change = Eigen::Vector3d(dbg[0], dbg[1], dbg[2]);
}

}  // namespace

std::optional<std::pair<int, PlaneEstimate>> initializeFromPlane(std::vector<WindowFrame>& frames,
                                                                 const Calibration& calib,
                                                                 const PlanarInitOptions& options,
                                                                 std::string* why_not) {
  auto fail = [&](const std::string& reason) {
    if (why_not) *why_not = reason;
    return std::nullopt;
  };
  if (frames.size() < 5 ||
      frames.back().features.t - frames.front().features.t < options.min_window_s)
    return fail("collecting frames");
  const Eigen::Matrix3d R_BC = calib.T_BC.linear();
  const int plane = largestPlane(frames.front().features);
  if (plane < 0) return fail("no plane features");

  // The frame pair (0, m) of the largest translational parallax with enough common plane features.
  size_t pair = 0;
  double best_parallax = 0;
  std::vector<Eigen::Vector2d> pts0, ptsm;
  for (size_t m = 1; m < frames.size(); ++m) {
    std::vector<Eigen::Vector2d> a, b;
    commonPlaneFeatures(frames.front().features, frames[m].features, plane, a, b);
    if (a.size() < options.min_plane_features) break;
    // Features must really move (a still camera with a biased gyroscope would otherwise show
    // "parallax" after compensation), and not only by rotation.
    const double raw =
        translationalParallax(a, b, Eigen::Matrix3d::Identity(), options.virtual_focal);
    const double p = std::min(raw, translationalParallax(a, b, gyroCameraRotation(frames, m, R_BC),
                                                         options.virtual_focal));
    if (p > best_parallax) best_parallax = p, pair = m, pts0 = a, ptsm = b;
  }
  if (pair == 0) return fail("too few plane features");
  if (best_parallax < options.min_parallax_px) return fail("too little parallax");

  HomographyInitOptions h_options;
  h_options.min_inliers = options.min_plane_features;
  h_options.ransac_threshold_px = options.ransac_threshold_px;
  h_options.virtual_focal = options.virtual_focal;
  std::string why;
  const auto motion = planeMotionFromHomography(pts0, ptsm, gyroCameraRotation(frames, pair, R_BC),
                                                h_options, &why);
  if (!motion) return fail(why);
  if (motion->rotation_error_deg > 5)
    return fail("homography rotation disagrees with the gyroscope");

  // Plane-based visual odometry in units of the plane distance from camera 0 (n·X = 1 in c0):
  // every frame by PnP on the plane points already known, new plane features added by
  // intersecting their rays with the plane.
  Eigen::Vector3d n = motion->n;
  std::unordered_map<int, Eigen::Vector3d> points;  // c0 frame
  std::vector<UpToScaleFrame> up_to_scale(frames.size());
  for (size_t k = 0; k < frames.size(); ++k) {
    Eigen::Matrix3d R_c0_c = Eigen::Matrix3d::Identity();
    Eigen::Vector3d p_c0_c = Eigen::Vector3d::Zero();
    if (k > 0) {
      std::vector<cv::Point3d> object;
      std::vector<cv::Point2d> image;
      for (const auto& f : frames[k].features.features)
        if (f.plane_id == plane && points.count(f.id)) {
          const Eigen::Vector3d& X = points[f.id];
          object.emplace_back(X.x(), X.y(), X.z());
          image.emplace_back(f.normalized.x(), f.normalized.y());
        }
      if (object.size() < 8) return fail("plane lost during the window");
      // Start from the previous pose; refine on all points (Levenberg-Marquardt).
      const Eigen::Matrix3d R_prev = up_to_scale[k - 1].R_c0_c.transpose();
      const Eigen::Vector3d t_prev = -R_prev * up_to_scale[k - 1].p_c0_c;
      cv::Mat R_cv, rvec, tvec;
      cv::eigen2cv(R_prev, R_cv);
      cv::Rodrigues(R_cv, rvec);
      cv::eigen2cv(t_prev, tvec);
      cv::solvePnPRefineLM(object, image, cv::Mat::eye(3, 3, CV_64F), cv::Mat(), rvec, tvec);
      cv::Rodrigues(rvec, R_cv);
      Eigen::Matrix3d R;
      Eigen::Vector3d t;
      cv::cv2eigen(R_cv, R);
      cv::cv2eigen(tvec, t);
      R_c0_c = R.transpose();
      p_c0_c = -R.transpose() * t;
    }
    for (const auto& f : frames[k].features.features) {
      if (f.plane_id != plane || points.count(f.id)) continue;
      const Eigen::Vector3d ray = R_c0_c * Eigen::Vector3d(f.normalized.x(), f.normalized.y(), 1);
      const double denom = n.dot(ray);
      if (denom <= 1e-3) continue;
      points[f.id] = p_c0_c + (1 - n.dot(p_c0_c)) / denom * ray;
    }
    up_to_scale[k] = {R_c0_c, p_c0_c, frames[k].imu_from_previous};
  }
  Eigen::Vector3d dbg;
  refineWithHomographies(frames, plane, up_to_scale, n, options.virtual_focal,
                         Eigen::Quaterniond(R_BC), dbg);
  for (size_t k = 1; k < frames.size(); ++k) {
    auto& pre = *frames[k].imu_from_previous;
    pre.repropagate(pre.linearizedBa(), pre.linearizedBg() + dbg);
  }
  const auto aligned = alignVisualInertial(up_to_scale, calib.T_BC, calib.imu.gravity, &why);
  if (!aligned) return fail(why);

  // World: gravity along −z, origin at camera 0.
  const Eigen::Matrix3d R_w_c0 =
      Eigen::Quaterniond::FromTwoVectors(aligned->gravity_c0, Eigen::Vector3d(0, 0, -1))
          .toRotationMatrix();
  const Eigen::Vector3d ba = frames[1].imu_from_previous->linearizedBa() + aligned->accel_bias;
  for (size_t k = 0; k < frames.size(); ++k) {
    const Eigen::Matrix3d R_wb = R_w_c0 * up_to_scale[k].R_c0_c * R_BC.transpose();
    const Eigen::Vector3d p_wb =
        R_w_c0 * (aligned->scale * up_to_scale[k].p_c0_c) - R_wb * calib.T_BC.translation();
    const Eigen::Quaterniond q(R_wb);
    const Eigen::Vector3d v = R_w_c0 * aligned->velocity_c0[k];
    double* pose = frames[k].pose;
    pose[0] = p_wb.x(), pose[1] = p_wb.y(), pose[2] = p_wb.z();
    pose[3] = q.x(), pose[4] = q.y(), pose[5] = q.z(), pose[6] = q.w();
    double* sb = frames[k].speed_bias;
    for (int i = 0; i < 3; ++i) sb[i] = v[i], sb[3 + i] = ba[i], sb[6 + i] = aligned->gyro_bias[i];
    if (frames[k].imu_from_previous)
      frames[k].imu_from_previous->repropagate(ba, aligned->gyro_bias);
  }
  PlaneEstimate estimate;
  const Eigen::Vector3d n_w = R_w_c0 * n;
  estimate.normal[0] = n_w.x(), estimate.normal[1] = n_w.y(), estimate.normal[2] = n_w.z();
  estimate.distance[0] = aligned->scale;  // n_c0·X = 1 plane unit; camera 0 at the origin
  return std::make_pair(plane, estimate);
}

}  // namespace rpvio

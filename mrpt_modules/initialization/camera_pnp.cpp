#include "mrpt_modules/initialization/camera_pnp.h"

#include <Eigen/Eigenvalues>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include "mrpt_modules/imu/so3.h"

namespace rpvio {
namespace {

/// Least squares of [u; 1]× Rᵀ (X − p) = 0 over the chosen points; nullopt when their rays do not
/// fix p (fewer than two distinct directions).
std::optional<Eigen::Vector3d> positionFromRays(const std::vector<Eigen::Vector3d>& points_r,
                                                const std::vector<Eigen::Vector2d>& u,
                                                const Eigen::Matrix3d& R_r_c,
                                                const std::vector<size_t>& chosen) {
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (size_t k : chosen) {
    const Eigen::Matrix3d A = hat(u[k].homogeneous().normalized()) * R_r_c.transpose();
    normal += A.transpose() * A;
    rhs += A.transpose() * A * points_r[k];
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(normal);
  if (eig.eigenvalues()(0) < 1e-9 * std::max(1.0, eig.eigenvalues()(2))) return std::nullopt;
  return normal.ldlt().solve(rhs);
}

std::vector<size_t> agreeing(const std::vector<Eigen::Vector3d>& points_r,
                             const std::vector<Eigen::Vector2d>& u, const CameraPose& camera,
                             double threshold) {
  std::vector<size_t> agree;
  for (size_t k = 0; k < u.size(); ++k) {
    const Eigen::Vector3d X_c = camera.toCamera(points_r[k]);
    if (X_c.z() > 0 && (X_c.hnormalized() - u[k]).norm() < threshold) agree.push_back(k);
  }
  return agree;
}

}  // namespace

std::optional<CameraPose> cameraPoseFromPnp(const std::vector<Eigen::Vector3d>& points_r,
                                            const std::vector<Eigen::Vector2d>& u,
                                            const std::optional<CameraPose>& guess,
                                            const PnpOptions& options, std::vector<bool>* inlier) {
  if (points_r.size() < options.min_points || points_r.size() != u.size()) return std::nullopt;
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  for (size_t k = 0; k < u.size(); ++k) {
    object.emplace_back(points_r[k].x(), points_r[k].y(), points_r[k].z());
    image.emplace_back(u[k].x(), u[k].y());
  }
  // OpenCV wants the reference-to-camera transform: X_c = Rᵀ X_r − Rᵀ p.
  cv::Mat rvec, tvec;
  if (guess) {
    cv::Mat R_cv;
    cv::eigen2cv(Eigen::Matrix3d(guess->R_r_c.transpose()), R_cv);
    cv::Rodrigues(R_cv, rvec);
    cv::eigen2cv(Eigen::Vector3d(-guess->R_r_c.transpose() * guess->p_r_c), tvec);
  }
  std::vector<int> inliers;
  const cv::Mat K = cv::Mat::eye(3, 3, CV_64F);
  if (!cv::solvePnPRansac(object, image, K, cv::Mat(), rvec, tvec, guess.has_value(), 100,
                          options.ransac_threshold_px / options.virtual_focal, 0.99, inliers,
                          guess ? cv::SOLVEPNP_ITERATIVE : cv::SOLVEPNP_EPNP))
    return std::nullopt;
  if (inliers.size() < options.min_points ||
      inliers.size() < options.min_inlier_ratio * object.size())
    return std::nullopt;
  if (inlier) {
    inlier->assign(object.size(), false);
    for (int k : inliers) (*inlier)[k] = true;
  }
  std::vector<cv::Point3d> object_in;
  std::vector<cv::Point2d> image_in;
  for (int k : inliers) object_in.push_back(object[k]), image_in.push_back(image[k]);
  cv::solvePnPRefineLM(object_in, image_in, K, cv::Mat(), rvec, tvec);
  cv::Mat R_cv;
  cv::Rodrigues(rvec, R_cv);
  Eigen::Matrix3d R_c_r;
  Eigen::Vector3d t_c_r;
  cv::cv2eigen(R_cv, R_c_r);
  cv::cv2eigen(tvec, t_c_r);
  return CameraPose{R_c_r.transpose(), -R_c_r.transpose() * t_c_r};
}

std::optional<CameraPose> cameraPositionFromKnownRotation(
    const std::vector<Eigen::Vector3d>& points_r, const std::vector<Eigen::Vector2d>& u,
    const Eigen::Matrix3d& R_r_c, size_t min_points, const PnpOptions& options,
    std::vector<bool>* inlier) {
  const size_t n = points_r.size();
  if (n < std::max<size_t>(min_points, 2) || n != u.size()) return std::nullopt;
  const double threshold = options.ransac_threshold_px / options.virtual_focal;
  std::vector<size_t> best;
  const size_t m = std::min(n, kMaxKnownRotationHypothesisPoints);
  for (size_t a = 0; a < m; ++a)
    for (size_t b = a + 1; b < m; ++b)
      if (const auto p = positionFromRays(points_r, u, R_r_c, {a, b})) {
        auto agree = agreeing(points_r, u, CameraPose{R_r_c, *p}, threshold);
        if (agree.size() > best.size()) best = std::move(agree);
      }
  if (best.size() < std::max<size_t>(min_points, 2) || best.size() < options.min_inlier_ratio * n)
    return std::nullopt;
  const auto p = positionFromRays(points_r, u, R_r_c, best);
  if (!p) return std::nullopt;
  if (inlier) {
    inlier->assign(n, false);
    for (size_t k : agreeing(points_r, u, CameraPose{R_r_c, *p}, threshold)) (*inlier)[k] = true;
  }
  return CameraPose{R_r_c, *p};
}

}  // namespace rpvio

#include "mrpt_modules/initialization/camera_pnp.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

namespace rpvio {

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

}  // namespace rpvio
